// The analytic leg model of method/leg_ik.h measured on the host's robot, so that
// the planner and the safety filter work for any URDF quadruped whose legs have
// the Unitree form (abduction about x, then two pitch joints), with no
// per-robot constants in the plugin.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "method/leg_ik.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// Lengths from the host's forward kinematics at three poses of each leg
// (straight, knee at -90 deg, abduction at +90 deg), limits from joint_limits;
// then checked against the host at further poses. std::nullopt, with `why`
// set, when the robot does not have four legs of that form (within 0.1 mm).
// Leg i is the host's foot i (the scenario's foot order must be FR FL RR RL for
// the leg names to mean anything; the geometry itself does not depend on it).
std::optional<std::array<jump::LegGeometry, jump::kLegCount>> legGeometryFromHost(const pronk_host_api* host,
                                                                                    std::string* why);

}  // namespace pronk::guided_jump
