#include "method/explosive_phase.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pronk::jump {

ExplosivePhase::ExplosivePhase(const PointState& start, double speed_ratio, double distance)
    : start_(start), end_(start), speed_ratio_(speed_ratio), distance_(distance) {
  if (!start.position.allFinite() || !start.velocity.allFinite()) {
    throw std::invalid_argument("explosive phase: start state is not finite");
  }
  if (!(std::isfinite(speed_ratio) && speed_ratio >= 0.0)) {
    std::ostringstream msg;
    msg << "explosive phase: speed ratio k must be finite and >= 0, got " << speed_ratio;
    throw std::invalid_argument(msg.str());
  }
  if (!(std::isfinite(distance) && distance >= 0.0)) {
    std::ostringstream msg;
    msg << "explosive phase: distance d must be finite and >= 0 m, got " << distance;
    throw std::invalid_argument(msg.str());
  }
  start_speed_ = start.velocity.norm();
  if (start_speed_ > 0.0) direction_ = start.velocity / start_speed_;
  if (distance_ == 0.0) return;  // no extension: T_e = 0, the end is the start
  if (!(start_speed_ > 0.0)) {
    std::ostringstream msg;
    msg << "explosive phase: d = " << distance << " m needs a non-zero Bezier lift-off velocity to extend along";
    throw std::invalid_argument(msg.str());
  }
  duration_ = 2.0 * distance_ / ((1.0 + speed_ratio_) * start_speed_);
  if (!(duration_ > 0.0)) {  // d so small that T_e underflows: no extension
    duration_ = 0.0;
    return;
  }
  accel_ = (speed_ratio_ * speed_ratio_ - 1.0) * start_speed_ * start_speed_ / (2.0 * distance_);
  end_.position = start.position + distance_ * direction_;
  end_.velocity = speed_ratio_ * start.velocity;
}

// In normalized time rho = tau / T_e the UARM reads s = d rho (2 + (k - 1) rho) / (1 + k)
// and |v| = v0 (1 + (k - 1) rho): the same motion as v0 tau + a tau^2 / 2, but
// bounded for any small d (where a itself grows without bound).
double ExplosivePhase::normalizedTime(double tau) const { return std::clamp(tau / duration_, 0.0, 1.0); }

Eigen::Vector3d ExplosivePhase::position(double tau) const {
  if (duration_ <= 0.0) return start_.position;
  const double rho = normalizedTime(tau);
  if (rho >= 1.0) return end_.position;
  const double arc = distance_ * rho * (2.0 + (speed_ratio_ - 1.0) * rho) / (1.0 + speed_ratio_);
  return start_.position + arc * direction_;
}

Eigen::Vector3d ExplosivePhase::velocity(double tau) const {
  if (duration_ <= 0.0) return start_.velocity;
  const double rho = normalizedTime(tau);
  if (rho <= 0.0) return start_.velocity;
  if (rho >= 1.0) return end_.velocity;
  return (start_speed_ * (1.0 + (speed_ratio_ - 1.0) * rho)) * direction_;
}

Eigen::Vector3d ExplosivePhase::acceleration(double /*tau*/) const { return accel_ * direction_; }

ThrustPlan::ThrustPlan(const JumpAction& action, double azimuth, const Eigen::Vector3d& com_start,
                       const Eigen::Vector3d& polar_origin)
    : ThrustPlan(com_start, bezierLiftOffState(action, azimuth, polar_origin), action.thrust_duration_s,
                 action.speed_ratio, action.explosive_distance_m) {}

ThrustPlan::ThrustPlan(const Eigen::Vector3d& com_start, const PointState& bezier_liftoff, double thrust_duration,
                       double speed_ratio, double explosive_distance)
    : bezier_(comThrustBezier(com_start, bezier_liftoff, thrust_duration)),
      explosive_(bezier_liftoff, speed_ratio, explosive_distance) {}

Eigen::Vector3d ThrustPlan::position(double t) const {
  const double tb = bezier_.duration();
  return t <= tb ? bezier_.position(t) : explosive_.position(t - tb);
}

Eigen::Vector3d ThrustPlan::velocity(double t) const {
  const double tb = bezier_.duration();
  return t <= tb ? bezier_.velocity(t) : explosive_.velocity(t - tb);
}

Eigen::Vector3d ThrustPlan::acceleration(double t) const {
  const double tb = bezier_.duration();
  if (t <= tb || explosive_.duration() <= 0.0) return bezier_.acceleration(t);
  return explosive_.acceleration(t - tb);
}

}  // namespace pronk::jump
