// Thrust trajectory, Bezier part: the whole-body centre of mass (CoM), not the
// trunk, follows a cubic Bezier from rest at c0 to the Bezier lift-off state
// (c_lo, v_lo) over the thrust duration T_th (paper, "Trajectory
// parametrization"; docs/method-trajectories.md).
//
// Frame. Everything here is in one frame with z up (against gravity): the start
// frame S, origin on the take-off surface directly below the start CoM, x along
// the robot's initial heading, y to its left. The robot starts at yaw 0 in S,
// like the reference code's env frame. Target displacements, the jump-plane
// azimuth and the lift-off yaw are all measured in S; a caller that prefers a
// world-aligned start frame only has to express those three in it.
//
// Bezier over [0, T], s = t / T, control points P0..P3:
//   B(t)   = (1-s)^3 P0 + 3 (1-s)^2 s P1 + 3 (1-s) s^2 P2 + s^3 P3
//   B'(t)  = 3/T   [ (1-s)^2 (P1-P0) + 2 (1-s) s (P2-P1) + s^2 (P3-P2) ]
//   B''(t) = 6/T^2 [ (1-s) (P2 - 2 P1 + P0) + s (P3 - 2 P2 + P1) ]
// all evaluated in closed form, never by finite differences.
#pragma once

#include <Eigen/Core>
#include <array>

#include "method/action_mapping.h"

namespace pronk::jump {

// A point's position and velocity (m, m/s) in the start frame.
struct PointState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// A cubic Bezier curve in R^3 over t in [0, duration]. Evaluation clamps t to
// that interval: before 0 it returns the start (position, velocity and
// acceleration at t = 0), after the end the end values. It never extrapolates
// the polynomial.
class CubicBezier {
 public:
  // duration must be finite and > 0, control points finite (else std::invalid_argument).
  CubicBezier(const std::array<Eigen::Vector3d, 4>& control_points, double duration);

  // The Hermite form: the curve from (p_start, v_start) at t = 0 to (p_end, v_end)
  // at t = duration: P0 = p_start, P1 = p_start + T/3 v_start,
  // P2 = p_end - T/3 v_end, P3 = p_end.
  static CubicBezier fromBoundaryStates(const PointState& start, const PointState& end, double duration);

  Eigen::Vector3d position(double t) const;
  Eigen::Vector3d velocity(double t) const;
  Eigen::Vector3d acceleration(double t) const;

  double duration() const { return duration_; }
  const std::array<Eigen::Vector3d, 4>& controlPoints() const { return points_; }

 private:
  double normalizedTime(double t) const;

  std::array<Eigen::Vector3d, 4> points_;
  double duration_;
};

// (r cos(el) cos(az), r cos(el) sin(az), r sin(el)): a vector of length r at
// elevation el above the horizontal, in the vertical plane at azimuth az.
Eigen::Vector3d jumpPlaneVector(double radius, double elevation, double azimuth);

// The Bezier lift-off state of an action in the jump plane at `azimuth`:
//   c_lo = polar_origin + jumpPlaneVector(r_p, theta_p, azimuth)
//   v_lo = jumpPlaneVector(r_v, theta_v, azimuth)
// polar_origin is the point on the take-off surface directly below the start
// CoM (in S: (0, 0, 0)), so r_p sin(theta_p) is the lift-off CoM height above
// that surface.
PointState bezierLiftOffState(const JumpAction& action, double azimuth, const Eigen::Vector3d& polar_origin);

// The CoM thrust Bezier from rest at com_start to `liftoff` over thrust_duration:
// P0 = P1 = com_start, P2 = c_lo - T_th/3 v_lo, P3 = c_lo.
CubicBezier comThrustBezier(const Eigen::Vector3d& com_start, const PointState& liftoff, double thrust_duration);

}  // namespace pronk::jump
