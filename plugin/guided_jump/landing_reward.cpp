#include "landing_reward.h"

#include <cmath>

namespace pronk::guided_jump {

Eigen::Vector2d displacementInHeadingFrame(const Eigen::Vector3d& com_start_world, const Eigen::Vector3d& com_end_world,
                                           double start_yaw) {
  const Eigen::Vector2d d_world = (com_end_world - com_start_world).head<2>();
  const double c = std::cos(start_yaw), s = std::sin(start_yaw);
  return {c * d_world.x() + s * d_world.y(), -s * d_world.x() + c * d_world.y()};
}

double landingError(const Eigen::Vector2d& displacement_heading, const Eigen::Vector2d& target_xy) {
  return (displacement_heading - target_xy).norm();
}

double landingReward(double error, double scale) { return std::exp(-error / scale); }

double yawOf(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
}

}  // namespace pronk::guided_jump
