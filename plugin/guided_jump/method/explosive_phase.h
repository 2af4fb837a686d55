// Thrust trajectory, explosive part: after the Bezier, the CoM moves on a
// straight line along the Bezier lift-off velocity with uniformly accelerated
// rectilinear motion (UARM), from speed v0 = |v_lo| to k v0 over the distance d
// (paper, "Explosive Thrust"; docs/method-trajectories.md). With u = v_lo / v0
// and tau = t - T_th in [0, T_e]:
//   T_e    = 2 d / ((1 + k) v0)               (d = (v0 + k v0) / 2 * T_e)
//   a      = (k - 1) v0 / T_e = (k^2 - 1) v0^2 / (2 d)
//   c(tau) = c_lo + (v0 tau + a tau^2 / 2) u
//   v(tau) = (v0 + a tau) u,   acc(tau) = a u
// so position and velocity join the Bezier's at T_th, and the motion ends at
// c_lo + d u with velocity k v_lo. d = 0 is no extension (T_e = 0); k = 1 is
// constant speed (a = 0, T_e = d / v0). Both are ordinary values of the formulas
// above, with no clamp.
#pragma once

#include <Eigen/Core>

#include "method/action_mapping.h"
#include "method/thrust_trajectory.h"

namespace pronk::jump {

class ExplosivePhase {
 public:
  // start: the Bezier lift-off state (c_lo, v_lo). Throws std::invalid_argument
  // unless speed_ratio (k) >= 0 and distance (d) >= 0, all finite, and
  // |v_lo| > 0 when d > 0 (with no speed there is no direction to extend along).
  ExplosivePhase(const PointState& start, double speed_ratio, double distance);

  double duration() const { return duration_; }            // T_e, s
  double speedRatio() const { return speed_ratio_; }       // k
  double distance() const { return distance_; }            // d, m
  double startSpeed() const { return start_speed_; }       // v0 = |v_lo|, m/s
  double accelerationAlongPath() const { return accel_; }  // a, m/s^2 (signed, along u); 0 when d = 0
  const Eigen::Vector3d& direction() const { return direction_; }  // u (zero when v_lo = 0)

  // tau is the time since the phase began, clamped to [0, T_e].
  Eigen::Vector3d position(double tau) const;
  Eigen::Vector3d velocity(double tau) const;
  Eigen::Vector3d acceleration(double tau) const;

  const PointState& startState() const { return start_; }
  // The state at tau = T_e: (c_lo + d u, k v_lo) when d > 0; (c_lo, v_lo) when
  // d = 0, since a motion of zero length cannot change the speed.
  const PointState& endState() const { return end_; }

 private:
  double normalizedTime(double tau) const;  // tau / T_e clamped to [0, 1]

  PointState start_;
  PointState end_;
  Eigen::Vector3d direction_ = Eigen::Vector3d::Zero();
  double speed_ratio_;
  double distance_;
  double start_speed_ = 0.0;
  double duration_ = 0.0;
  double accel_ = 0.0;
};

// The whole CoM thrust reference: the Bezier over [0, T_th], then the UARM over
// (T_th, T_th + T_e]. Position and velocity are continuous at T_th; the
// acceleration generally jumps there (at exactly t = T_th the Bezier's value is
// returned). t is clamped to [0, duration()].
class ThrustPlan {
 public:
  // From an action: Bezier lift-off state from the polar parameters in the jump
  // plane at `azimuth` about `polar_origin` (bezierLiftOffState), CoM at rest at
  // com_start. All in the start frame (thrust_trajectory.h).
  ThrustPlan(const JumpAction& action, double azimuth, const Eigen::Vector3d& com_start,
             const Eigen::Vector3d& polar_origin);
  // From a Cartesian Bezier lift-off state (for planners that work in Cartesian space).
  ThrustPlan(const Eigen::Vector3d& com_start, const PointState& bezier_liftoff, double thrust_duration,
             double speed_ratio, double explosive_distance);

  double bezierDuration() const { return bezier_.duration(); }       // T_th
  double explosiveDuration() const { return explosive_.duration(); }  // T_e
  double duration() const { return bezier_.duration() + explosive_.duration(); }

  Eigen::Vector3d position(double t) const;
  Eigen::Vector3d velocity(double t) const;
  Eigen::Vector3d acceleration(double t) const;

  const Eigen::Vector3d& comStart() const { return bezier_.controlPoints()[0]; }
  const PointState& bezierLiftOff() const { return explosive_.startState(); }  // (c_lo_b, v_lo_b)
  const PointState& liftOff() const { return explosive_.endState(); }         // actual lift-off (c_lo_e, v_lo_e)

  const CubicBezier& bezier() const { return bezier_; }
  const ExplosivePhase& explosive() const { return explosive_; }

 private:
  CubicBezier bezier_;
  ExplosivePhase explosive_;
};

}  // namespace pronk::jump
