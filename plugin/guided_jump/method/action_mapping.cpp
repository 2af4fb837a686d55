#include "method/action_mapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct ParameterInfo {
  const char* name;
  const char* unit;
};

constexpr std::array<ParameterInfo, kActionSize> kInfo = {{
    {"thrust_duration", "s"},
    {"liftoff_radius", "m"},
    {"liftoff_elevation", "rad"},
    {"liftoff_speed", "m/s"},
    {"velocity_elevation", "rad"},
    {"speed_ratio", "1"},
    {"explosive_distance", "m"},
    {"liftoff_roll", "rad"},
    {"liftoff_pitch", "rad"},
    {"liftoff_yaw", "rad"},
    {"liftoff_roll_rate", "rad/s"},
    {"liftoff_pitch_rate", "rad/s"},
    {"liftoff_yaw_rate", "rad/s"},
}};

[[noreturn]] void rangeError(int i, const ParameterRange& r, const std::string& why) {
  std::ostringstream msg;
  msg << "action range '" << kInfo[i].name << "' [" << r.min << ", " << r.max << "] " << kInfo[i].unit << ": "
      << why;
  throw std::invalid_argument(msg.str());
}

}  // namespace

const char* actionParameterName(ActionParameter p) { return kInfo.at(actionIndex(p)).name; }
const char* actionParameterUnit(ActionParameter p) { return kInfo.at(actionIndex(p)).unit; }

ActionRanges::ActionRanges() {
  using P = ActionParameter;
  (*this)[P::kThrustDuration] = {0.4, 1.0};
  (*this)[P::kLiftOffRadius] = {0.2, 0.4};
  (*this)[P::kLiftOffElevation] = {kPi / 4, kPi / 2};
  (*this)[P::kLiftOffSpeed] = {0.5, 5.0};
  (*this)[P::kVelocityElevation] = {kPi / 6, kPi / 2};
  (*this)[P::kSpeedRatio] = {1.0, 3.0};
  (*this)[P::kExplosiveDistance] = {0.0, 0.3};
  (*this)[P::kLiftOffRoll] = {-kPi / 6, kPi / 6};
  (*this)[P::kLiftOffPitch] = {-kPi / 6, kPi / 6};
  (*this)[P::kLiftOffYaw] = {-kPi / 4, kPi / 4};
  (*this)[P::kLiftOffRollRate] = {-1.0, 1.0};
  (*this)[P::kLiftOffPitchRate] = {-1.0, 1.0};
  (*this)[P::kLiftOffYawRate] = {-4.0, 4.0};
}

void ActionRanges::check() const {
  if (!(std::isfinite(raw_limit) && raw_limit > 0.0)) {
    std::ostringstream msg;
    msg << "action raw_limit must be finite and > 0, got " << raw_limit;
    throw std::invalid_argument(msg.str());
  }
  for (int i = 0; i < kActionSize; ++i) {
    const ParameterRange& r = bounds[i];
    if (!std::isfinite(r.min) || !std::isfinite(r.max)) rangeError(i, r, "bounds must be finite");
    if (r.min > r.max) rangeError(i, r, "min > max");
  }
  // The physical domain of each parameter's lower bound.
  const struct {
    ActionParameter p;
    bool strict;  // min > 0 rather than min >= 0
  } lower_bounds[] = {
      {ActionParameter::kThrustDuration, true},  {ActionParameter::kLiftOffRadius, false},
      {ActionParameter::kLiftOffSpeed, true},    {ActionParameter::kSpeedRatio, false},
      {ActionParameter::kExplosiveDistance, false},
  };
  for (const auto& b : lower_bounds) {
    const ParameterRange& r = (*this)[b.p];
    const bool outside = b.strict ? r.min <= 0.0 : r.min < 0.0;
    if (outside) rangeError(actionIndex(b.p), r, b.strict ? "min must be > 0" : "min must be >= 0");
  }
}

ActionRanges go1ActionRanges() { return ActionRanges(); }

double lengthScaleToGo1(double leg_length) {
  if (!(std::isfinite(leg_length) && leg_length > 0.0)) {
    throw std::invalid_argument("leg length must be finite and > 0, got " + std::to_string(leg_length));
  }
  return std::abs(leg_length - kGo1LegLength) < 1e-6 ? 1.0 : leg_length / kGo1LegLength;
}

ActionRanges scaledActionRanges(double scale) {
  ActionRanges r;
  for (ActionParameter p : {ActionParameter::kLiftOffRadius, ActionParameter::kExplosiveDistance}) {
    r[p].min *= scale;
    r[p].max *= scale;
  }
  return r;
}

ActionRanges aliengoActionRanges() {
  ActionRanges r;
  r[ActionParameter::kLiftOffRadius] = {0.2, 0.6};
  return r;
}

ActionVector toVector(const JumpAction& a) {
  return {a.thrust_duration_s,       a.liftoff_radius_m,          a.liftoff_elevation_rad,
          a.liftoff_speed_mps,       a.velocity_elevation_rad,    a.speed_ratio,
          a.explosive_distance_m,    a.liftoff_rpy_rad.x(),       a.liftoff_rpy_rad.y(),
          a.liftoff_rpy_rad.z(),     a.liftoff_rpy_rate_radps.x(), a.liftoff_rpy_rate_radps.y(),
          a.liftoff_rpy_rate_radps.z()};
}

JumpAction fromVector(const ActionVector& v) {
  using P = ActionParameter;
  JumpAction a;
  a.thrust_duration_s = v[actionIndex(P::kThrustDuration)];
  a.liftoff_radius_m = v[actionIndex(P::kLiftOffRadius)];
  a.liftoff_elevation_rad = v[actionIndex(P::kLiftOffElevation)];
  a.liftoff_speed_mps = v[actionIndex(P::kLiftOffSpeed)];
  a.velocity_elevation_rad = v[actionIndex(P::kVelocityElevation)];
  a.speed_ratio = v[actionIndex(P::kSpeedRatio)];
  a.explosive_distance_m = v[actionIndex(P::kExplosiveDistance)];
  a.liftoff_rpy_rad = {v[actionIndex(P::kLiftOffRoll)], v[actionIndex(P::kLiftOffPitch)],
                       v[actionIndex(P::kLiftOffYaw)]};
  a.liftoff_rpy_rate_radps = {v[actionIndex(P::kLiftOffRollRate)], v[actionIndex(P::kLiftOffPitchRate)],
                              v[actionIndex(P::kLiftOffYawRate)]};
  return a;
}

double MappedAction::totalRawExcess() const {
  double sum = 0.0;
  for (double e : raw_excess) sum += e;
  return sum;
}

MappedAction mapAction(const ActionVector& raw, const ActionRanges& ranges) {
  const double L = ranges.raw_limit;
  MappedAction out;
  ActionVector physical{};
  for (int i = 0; i < kActionSize; ++i) {
    const double a = raw[i];
    if (std::isnan(a)) {
      std::ostringstream msg;
      msg << "raw action '" << kInfo[i].name << "' (index " << i << ") is NaN";
      throw std::invalid_argument(msg.str());
    }
    const double clipped = std::clamp(a, -L, L);
    out.raw_excess[i] = std::max(std::abs(a) - L, 0.0);
    const ParameterRange& r = ranges.bounds[i];
    physical[i] = r.min + (clipped + L) * (r.max - r.min) / (2.0 * L);
  }
  out.action = fromVector(physical);
  return out;
}

ActionVector unmapAction(const JumpAction& action, const ActionRanges& ranges) {
  const double L = ranges.raw_limit;
  const ActionVector physical = toVector(action);
  ActionVector raw{};
  for (int i = 0; i < kActionSize; ++i) {
    const ParameterRange& r = ranges.bounds[i];
    const double width = r.max - r.min;
    raw[i] = width > 0.0 ? -L + 2.0 * L * (physical[i] - r.min) / width : 0.0;
  }
  return raw;
}

double jumpPlaneAzimuth(const Eigen::Vector3d& target_displacement) {
  const double dx = target_displacement.x();
  const double dy = target_displacement.y();
  if (!std::isfinite(dx) || !std::isfinite(dy)) {
    std::ostringstream msg;
    msg << "jump target displacement must be finite, got (" << dx << ", " << dy << ")";
    throw std::invalid_argument(msg.str());
  }
  if (std::hypot(dx, dy) < kPureTwistDistance) return 0.0;
  const double az = std::atan2(dy, dx);
  return az <= -kPi ? kPi : az;  // atan2(-0.0, x < 0) == -pi: the same direction as +pi
}

}  // namespace pronk::jump
