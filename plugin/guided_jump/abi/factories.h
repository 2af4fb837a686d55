// The factories this plugin registers (plugin_entry.cpp lists them).
#pragma once

#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// controller `guided_jump` (guided_jump_controller.cpp)
const pronk_factory* guidedJumpControllerFactory();
// environment `jump` (jump_environment.cpp)
const pronk_factory* jumpEnvironmentFactory();

// The control period both factories declare, s.
constexpr double kControlPeriod = 0.001;

}  // namespace pronk::guided_jump
