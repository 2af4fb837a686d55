// The paper's landing reward term: R = exp(-e / sigma_e), e the horizontal
// distance (m) between where the robot landed and the target, sigma_e = 0.1 m.
#pragma once

#include <Eigen/Core>

namespace pronk::guided_jump {

constexpr double kLandingErrorScale = 0.1;  // m, the paper's sigma_e

// The start-relative horizontal displacement of the CoM expressed in the robot's
// initial heading frame (x forward, y left), where targets are given.
Eigen::Vector2d displacementInHeadingFrame(const Eigen::Vector3d& com_start_world, const Eigen::Vector3d& com_end_world,
                                           double start_yaw);

// Horizontal landing error, m: |displacement - target_xy|.
double landingError(const Eigen::Vector2d& displacement_heading, const Eigen::Vector2d& target_xy);

// exp(-error / scale).
double landingReward(double error, double scale = kLandingErrorScale);

// Yaw (rad) of a (w, x, y, z) quaternion: rotation about world z of the body x axis.
double yawOf(const double quaternion_wxyz[4]);

}  // namespace pronk::guided_jump
