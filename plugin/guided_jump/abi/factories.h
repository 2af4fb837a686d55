// The factories this plugin registers (plugin_entry.cpp lists them).
#pragma once

#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// controller `guided_jump` (guided_jump_controller.cpp)
const pronk_factory* guidedJumpControllerFactory();
// environment `jump` (jump_environment.cpp)
const pronk_factory* jumpEnvironmentFactory();

// The minor ABI version the host negotiated (pronk_plugin_query sets it):
// what the plugin may answer with (1.4: prior_action's PRONK_REJECTED).
void setNegotiatedAbiMinor(uint32_t minor);
uint32_t negotiatedAbiMinor();

}  // namespace pronk::guided_jump
