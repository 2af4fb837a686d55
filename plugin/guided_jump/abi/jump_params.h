// The parameters of controller `guided_jump` and environment `jump`, each
// declared once (name, type, range, default, unit, doc) in jump_params.cpp, and
// the readers of the settings both factories share. Each factory's list keeps
// its own order; a parameter both take is the same declaration in both.
#pragma once

#include <string>
#include <vector>

#include "abi/plugin_params.h"
#include "control/hold_controller.h"
#include "control/jump_phases.h"
#include "method/motor_model.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// Controller `guided_jump`: the stance's parameters, then the jump's.
const std::vector<pronk_param_decl>& controllerParamDecls();
// Environment `jump`: the stance's, the phase machine's, then the episode's,
// the action ranges', the reward's and the safety filter's.
const std::vector<pronk_param_decl>& environmentParamDecls();

// kp, kd, stance, gravity_compensation, motor (throws InvalidArgument).
HoldSettings readHoldSettings(const ParamReader& read);
// The phase machine's parameters both factories take: start_delay, feedforward,
// flight_kp_division, momentum_gain (throws InvalidArgument).
void readCommonJumpSettings(const ParamReader& read, JumpSettings* settings);

// "dc" or "effort"; throws InvalidArgument naming the parameter for any other name.
jump::MotorModel motorModelFromName(const std::string& name);
// "gravity", "dynamic", "dynamic_angular"; throws InvalidArgument naming the
// parameter for any other name.
Feedforward feedforwardFromName(const std::string& name);

}  // namespace pronk::guided_jump
