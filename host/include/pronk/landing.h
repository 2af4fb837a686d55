// Where a jump ended, read from its trace alone: the host's view, the same for
// any environment (it needs no event or metric the environment reports).
#pragma once

#include <string>

#include <Eigen/Core>

#include "pronk/scenario.h"
#include "pronk/trace.h"

namespace pronk {

// A jump ends standing when every foot is down and the trunk's z axis is within
// this angle of the vertical.
constexpr double kUprightAngle = 30.0 * M_PI / 180.0;
// Beyond this tilt at the episode's end the robot has turned over, even when no
// body but a foot touched the terrain (it may still be tumbling in the air).
constexpr double kTippedAngle = 60.0 * M_PI / 180.0;

struct Landing {
  Eigen::Vector3d displacement = Eigen::Vector3d::Constant(NAN);  // trunk, in the start heading frame
  double yaw = NAN;        // rad, heading change
  double error_xy = NAN;   // m
  // The height of the surface the feet stand on at the end, relative to the
  // one they took off from (the mean of the feet down, m), and the landing
  // error as the paper counts it: error_xy for a target without height; for
  // one with a height, 3-D, the trunk's xy and the feet's height.
  double height = NAN;
  double error = NAN;
  double error_yaw = NAN;  // rad, |wrapped|
  double tilt = NAN;       // rad, trunk z axis from the vertical at the end
  bool standing = false;
  // Non-empty when the episode ended in a state that is no landing at all:
  // "airborne: ..." (no foot on the ground) or "tipped_over: ...".
  std::string end_failure;
};

Landing landingOf(const Trace& trace, const TargetSpec& target);

// Heading of a w-x-y-z quaternion (rad).
double yawOf(const Eigen::Vector4d& q_wxyz);

}  // namespace pronk
