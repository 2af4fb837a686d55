// The parameters of controller `guided_jump` and environment `jump`: the
// phases' own (each declared by its phase in control/, the same declaration in
// both factories), then each factory's. Each factory's list keeps its own order.
#pragma once

#include <vector>

#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// Controller `guided_jump`: the phases', then action and landing_height.
const std::vector<pronk_param_decl>& controllerParamDecls();
// Environment `jump`: the phases', then the episode's, the action ranges', the
// reward's, the safety filter's and the planner's.
const std::vector<pronk_param_decl>& environmentParamDecls();

}  // namespace pronk::guided_jump
