#include "method/thrust_trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pronk::jump {

CubicBezier::CubicBezier(const std::array<Eigen::Vector3d, 4>& control_points, double duration)
    : points_(control_points), duration_(duration) {
  if (!(std::isfinite(duration) && duration > 0.0)) {
    std::ostringstream msg;
    msg << "Bezier duration must be finite and > 0 s, got " << duration;
    throw std::invalid_argument(msg.str());
  }
  for (int i = 0; i < 4; ++i) {
    if (!points_[i].allFinite()) {
      std::ostringstream msg;
      msg << "Bezier control point P" << i << " is not finite: (" << points_[i].transpose() << ")";
      throw std::invalid_argument(msg.str());
    }
  }
}

CubicBezier CubicBezier::fromBoundaryStates(const PointState& start, const PointState& end, double duration) {
  const double third = duration / 3.0;
  return CubicBezier({start.position, start.position + third * start.velocity, end.position - third * end.velocity,
                      end.position},
                     duration);
}

double CubicBezier::normalizedTime(double t) const { return std::clamp(t / duration_, 0.0, 1.0); }

Eigen::Vector3d CubicBezier::position(double t) const {
  const double s = normalizedTime(t);
  const double u = 1.0 - s;
  return (u * u * u) * points_[0] + (3.0 * u * u * s) * points_[1] + (3.0 * u * s * s) * points_[2] +
         (s * s * s) * points_[3];
}

Eigen::Vector3d CubicBezier::velocity(double t) const {
  const double s = normalizedTime(t);
  const double u = 1.0 - s;
  return (3.0 / duration_) *
         ((u * u) * (points_[1] - points_[0]) + (2.0 * u * s) * (points_[2] - points_[1]) +
          (s * s) * (points_[3] - points_[2]));
}

Eigen::Vector3d CubicBezier::acceleration(double t) const {
  const double s = normalizedTime(t);
  const double u = 1.0 - s;
  return (6.0 / (duration_ * duration_)) *
         (u * (points_[2] - 2.0 * points_[1] + points_[0]) + s * (points_[3] - 2.0 * points_[2] + points_[1]));
}

Eigen::Vector3d jumpPlaneVector(double radius, double elevation, double azimuth) {
  const double horizontal = radius * std::cos(elevation);
  return {horizontal * std::cos(azimuth), horizontal * std::sin(azimuth), radius * std::sin(elevation)};
}

PointState bezierLiftOffState(const JumpAction& action, double azimuth, const Eigen::Vector3d& polar_origin) {
  PointState s;
  s.position = polar_origin + jumpPlaneVector(action.liftoff_radius_m, action.liftoff_elevation_rad, azimuth);
  s.velocity = jumpPlaneVector(action.liftoff_speed_mps, action.velocity_elevation_rad, azimuth);
  return s;
}

CubicBezier comThrustBezier(const Eigen::Vector3d& com_start, const PointState& liftoff, double thrust_duration) {
  PointState rest;
  rest.position = com_start;
  return CubicBezier::fromBoundaryStates(rest, liftoff, thrust_duration);
}

}  // namespace pronk::jump
