// What the thrust's start fixes for the rest of the jump: the start frame S,
// the thrust plan and the orientation plan in it, the standing height, where
// the feet stood and where the stance puts them. The thrust tracks it; the
// flight and the landing read it.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "control/leg_drive.h"
#include "method/action_mapping.h"
#include "method/orientation_trajectory.h"
#include "method/explosive_phase.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

struct JumpPlan {
  // S: origin on the ground below the CoM at the thrust start, z up, x along the
  // trunk's heading then.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();        // world
  Eigen::Matrix3d heading = Eigen::Matrix3d::Identity();   // S -> world
  double start_time = 0;                                   // s: the thrust began
  double standing_height = 0;                              // m: CoM above the ground at the start
  double landing_height = 0;                               // m: the landing surface above the take-off one
  std::unique_ptr<jump::ThrustPlan> thrust;                // in S
  std::unique_ptr<jump::OrientationTrajectory> orientation;
  double flight_time = 0.2;                                // s: planned, lift-off to touchdown
  double touchdown_yaw = 0;                                // rad, world: lift-off yaw + yaw rate x flight time
  Eigen::Vector3d stance_offset = Eigen::Vector3d::Zero();  // trunk - feet centroid at the start, trunk frame
  Eigen::Matrix3Xd start_feet;                             // feet at the start, world
  Eigen::Matrix3Xd stance_feet;                            // feet at the stance joints, trunk frame

  // The CoM's height above the take-off surface where it lands standing.
  double landingComHeight() const { return origin.z() + landing_height + standing_height; }
};

// The plan for `action` from the state at the thrust start, the jump plane at
// `azimuth` (rad, in S) and the landing surface `landing_height` above the
// take-off one. Throws std::invalid_argument for an action the method refuses.
JumpPlan makeJumpPlan(const LegDrive& drive, const pronk_robot_state& s, const jump::JumpAction& action,
                      double azimuth, double landing_height);

}  // namespace pronk::guided_jump
