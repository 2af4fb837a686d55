#include "method/ballistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pronk::jump {

namespace {

constexpr double kPi = 3.14159265358979323846;


bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

void requireFinite(const Eigen::Vector3d& v, const char* what) {
  if (!finite(v)) {
    throw std::invalid_argument(fmt::format("ballistics: {} ({:g}, {:g}, {:g}) is not finite", what, v.x(), v.y(), v.z()));
  }
}

// |g_z| after checking that gravity points down.
double downwardGravity(const Eigen::Vector3d& gravity) {
  requireFinite(gravity, "gravity");
  if (!(gravity.z() < 0.0)) {
    throw std::invalid_argument(fmt::format("ballistics: gravity ({:g}, {:g}, {:g}) m/s^2 must have a negative z component",
                                       gravity.x(), gravity.y(), gravity.z()));
  }
  return -gravity.z();
}

// The planar inverse (horizontal speed, hyperbola) assumes uniform horizontal motion.
double verticalGravity(const Eigen::Vector3d& gravity, const char* who) {
  const double g = downwardGravity(gravity);
  if (std::hypot(gravity.x(), gravity.y()) > 1e-12 * gravity.norm()) {
    throw std::invalid_argument(
        fmt::format("{}: needs gravity along -z, got ({:g}, {:g}, {:g}) m/s^2", who, gravity.x(), gravity.y(), gravity.z()));
  }
  return g;
}

// Tolerance for "still rising" at the target, m/s.
constexpr double kDescendingTolerance = 1e-12;

LiftOffVelocity makeSolution(const Eigen::Vector3d& velocity, double flight_time, const Eigen::Vector3d& gravity) {
  LiftOffVelocity solution;
  solution.velocity = velocity;
  solution.flight_time = flight_time;
  solution.arrives_descending = velocity.z() + gravity.z() * flight_time <= kDescendingTolerance;
  return solution;
}

}  // namespace

Eigen::Vector3d standardGravity() { return Eigen::Vector3d(0.0, 0.0, -9.81); }

// ---------------------------------------------------------------------------
// Forward flight

BallisticFlight::BallisticFlight(const FlightState& lift_off, const Eigen::Vector3d& gravity)
    : lift_off_(lift_off), gravity_(gravity), g_down_(downwardGravity(gravity)) {
  requireFinite(lift_off.position, "lift-off position");
  requireFinite(lift_off.velocity, "lift-off velocity");
}

Eigen::Vector3d BallisticFlight::position(double t) const {
  return lift_off_.position + lift_off_.velocity * t + 0.5 * gravity_ * t * t;
}

Eigen::Vector3d BallisticFlight::velocity(double t) const { return lift_off_.velocity + gravity_ * t; }

FlightState BallisticFlight::state(double t) const { return FlightState{position(t), velocity(t)}; }

double BallisticFlight::apexTime() const { return std::max(lift_off_.velocity.z(), 0.0) / g_down_; }

double BallisticFlight::apexHeight() const {
  const double vz = std::max(lift_off_.velocity.z(), 0.0);
  return lift_off_.position.z() + vz * vz / (2.0 * g_down_);
}

Eigen::Vector3d BallisticFlight::apexPoint() const { return position(apexTime()); }

std::optional<double> BallisticFlight::landingTime(double surface_height) const {
  if (!std::isfinite(surface_height) || surface_height > apexHeight()) return std::nullopt;
  // z(t) = h  <=>  (a/2) t^2 - vz t - (z0 - h) = 0 with a = |g_z|; the later root
  // is (vz + sqrt(D)) / a, D = vz^2 + 2 a (z0 - h). For vz < 0 that form cancels,
  // so it is rewritten through the product of the roots.
  const double vz = lift_off_.velocity.z();
  const double drop = lift_off_.position.z() - surface_height;
  const double root = std::sqrt(std::max(vz * vz + 2.0 * g_down_ * drop, 0.0));
  const double t = vz >= 0.0 ? (vz + root) / g_down_ : 2.0 * drop / (root - vz);
  if (t < 0.0) return std::nullopt;
  return t;
}

std::optional<Eigen::Vector3d> BallisticFlight::landingPoint(double surface_height) const {
  const auto t = landingTime(surface_height);
  if (!t) return std::nullopt;
  Eigen::Vector3d p = position(*t);
  p.z() = surface_height;  // exact by construction; removes the rounding of z(t)
  return p;
}

std::optional<FlightState> BallisticFlight::landingState(double surface_height) const {
  const auto t = landingTime(surface_height);
  if (!t) return std::nullopt;
  FlightState s = state(*t);
  s.position.z() = surface_height;
  return s;
}

// ---------------------------------------------------------------------------
// Heuristic event times

double heuristicApexTime(double lift_off_time, const FlightState& lift_off, const Eigen::Vector3d& gravity) {
  return lift_off_time + BallisticFlight(lift_off, gravity).apexTime();
}

std::optional<double> heuristicTouchdownTime(double lift_off_time, const FlightState& lift_off,
                                             double touchdown_com_height, const Eigen::Vector3d& gravity) {
  const auto t = BallisticFlight(lift_off, gravity).landingTime(touchdown_com_height);
  if (!t) return std::nullopt;
  return lift_off_time + *t;
}

// ---------------------------------------------------------------------------
// Inverse problems

LiftOffVelocity liftOffVelocityForFlightTime(const Eigen::Vector3d& lift_off_position, const Eigen::Vector3d& target,
                                             double flight_time, const Eigen::Vector3d& gravity) {
  requireFinite(lift_off_position, "lift-off position");
  requireFinite(target, "target");
  downwardGravity(gravity);
  if (!(flight_time > 0.0) || !std::isfinite(flight_time)) {
    throw std::invalid_argument(
        fmt::format("liftOffVelocityForFlightTime: flight time {:g} s must be positive and finite", flight_time));
  }
  const Eigen::Vector3d v = (target - lift_off_position - 0.5 * gravity * flight_time * flight_time) / flight_time;
  return makeSolution(v, flight_time, gravity);
}

std::optional<LiftOffVelocity> liftOffVelocityForHorizontalSpeed(const Eigen::Vector3d& lift_off_position,
                                                                 const Eigen::Vector3d& target, double horizontal_speed,
                                                                 const Eigen::Vector3d& gravity) {
  requireFinite(lift_off_position, "lift-off position");
  requireFinite(target, "target");
  verticalGravity(gravity, "liftOffVelocityForHorizontalSpeed");
  if (!(horizontal_speed > 0.0) || !std::isfinite(horizontal_speed)) {
    throw std::invalid_argument(fmt::format(
        "liftOffVelocityForHorizontalSpeed: horizontal speed {:g} m/s must be positive and finite", horizontal_speed));
  }
  const double h = (target - lift_off_position).head<2>().norm();
  if (h < 1e-12) return std::nullopt;
  return liftOffVelocityForFlightTime(lift_off_position, target, h / horizontal_speed, gravity);
}

// ---------------------------------------------------------------------------
// The hyperbola of lift-off velocities

LiftOffHyperbola::LiftOffHyperbola(const Eigen::Vector3d& lift_off_position, const Eigen::Vector3d& target,
                                   const Eigen::Vector3d& gravity)
    : lift_off_(lift_off_position), target_(target), gravity_(gravity) {
  requireFinite(lift_off_position, "lift-off position");
  requireFinite(target, "target");
  g_ = verticalGravity(gravity, "LiftOffHyperbola");
  const Eigen::Vector3d delta = target - lift_off_position;
  h_ = delta.head<2>().norm();
  dz_ = delta.z();
  if (h_ < 1e-9) {
    throw std::invalid_argument(fmt::format(
        "LiftOffHyperbola: target is {:g} m horizontally from the lift-off point; a vertical jump has no hyperbola "
        "(use liftOffVelocityForFlightTime)",
        h_));
  }
  u_ = Eigen::Vector3d(delta.x() / h_, delta.y() / h_, 0.0);
  min_elevation_ = std::atan2(dz_, h_);
}

double LiftOffHyperbola::verticalSpeed(double horizontal_speed) const {
  if (!(horizontal_speed > 0.0) || !std::isfinite(horizontal_speed)) {
    throw std::invalid_argument(
        fmt::format("LiftOffHyperbola: horizontal speed {:g} m/s must be positive and finite", horizontal_speed));
  }
  return dz_ * horizontal_speed / h_ + g_ * h_ / (2.0 * horizontal_speed);
}

LiftOffVelocity LiftOffHyperbola::atHorizontalSpeed(double horizontal_speed) const {
  const double vz = verticalSpeed(horizontal_speed);
  const Eigen::Vector3d v = horizontal_speed * u_ + Eigen::Vector3d(0.0, 0.0, vz);
  return makeSolution(v, h_ / horizontal_speed, gravity_);
}

LiftOffVelocity LiftOffHyperbola::atFlightTime(double flight_time) const {
  if (!(flight_time > 0.0) || !std::isfinite(flight_time)) {
    throw std::invalid_argument(fmt::format("LiftOffHyperbola: flight time {:g} s must be positive and finite", flight_time));
  }
  return atHorizontalSpeed(h_ / flight_time);
}

std::optional<LiftOffVelocity> LiftOffHyperbola::atElevation(double elevation) const {
  return atElevation(elevation, std::tan(elevation));
}

std::optional<LiftOffVelocity> LiftOffHyperbola::atElevation(double elevation, double tan_elevation) const {
  if (!std::isfinite(elevation) || elevation <= min_elevation_ || elevation >= kPi / 2.0) return std::nullopt;
  const double excess = tan_elevation - dz_ / h_;
  if (!(excess > 0.0)) return std::nullopt;
  const double s = std::sqrt(g_ * h_ / (2.0 * excess));
  if (!(s > 0.0) || !std::isfinite(s)) return std::nullopt;
  return atHorizontalSpeed(s);
}

LiftOffVelocity LiftOffHyperbola::leastSpeed() const {
  // tan(theta*) = (dz + R) / h with R = |(h, dz)|, so tan(theta*) - dz/h = R/h and
  // s^2 = g h^2 / (2 R).
  const double r = std::hypot(h_, dz_);
  return atHorizontalSpeed(h_ * std::sqrt(g_ / (2.0 * r)));
}

Eigen::Vector2d landingStopOffset(const Eigen::Vector3d& v, double friction, double frequency) {
  if (!(friction >= 0.0) || !(frequency > 0.0)) {
    throw std::invalid_argument("landingStopOffset: friction must be >= 0 and frequency > 0");
  }
  const Eigen::Vector2d horizontal = v.head<2>();
  const double speed = horizontal.norm();
  if (!(speed > 0.0)) return Eigen::Vector2d::Zero();
  const double left = std::max(0.0, speed - friction * std::abs(v.z()));
  return horizontal / speed * left / frequency;
}

double landingExtension(double leg_length, double knee_lever, double knee_effort, double mass, double gravity,
                        int legs) {
  if (!(leg_length > 0.0) || !(knee_lever > 0.0) || !(knee_effort > 0.0) || !(mass > 0.0) || !(gravity > 0.0) ||
      legs <= 0) {
    throw std::invalid_argument("landingExtension: every length, the effort, the mass and gravity must be > 0");
  }
  const double deceleration = legs * knee_effort / (mass * knee_lever) - gravity;
  if (!(deceleration > 0.0)) return leg_length * kMaxLandingExtension;  // the knees cannot hold the weight
  return leg_length * std::clamp(kLandingFallHeight * gravity / deceleration - kStanceStroke, 0.0, kMaxLandingExtension);
}

}  // namespace pronk::jump
