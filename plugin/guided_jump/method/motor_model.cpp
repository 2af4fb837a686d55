#include "method/motor_model.h"

#include <algorithm>
#include <cmath>

namespace pronk::jump {

TorqueRange availableTorque(MotorModel model, const MotorLimits& limits, double speed) {
  const double effort = limits.effort;
  // Without a finite effort there is no torque to scale: unlimited.
  if (model == MotorModel::kEffortBox || !std::isfinite(limits.velocity) || !std::isfinite(effort)) {
    return {-effort, effort};
  }
  const double ratio = speed / limits.velocity;
  return {std::clamp(effort * (-1.0 - ratio), -effort, 0.0), std::clamp(effort * (1.0 - ratio), 0.0, effort)};
}

double saturateTorque(MotorModel model, const MotorLimits& limits, double torque, double speed) {
  const TorqueRange range = availableTorque(model, limits, speed);
  return std::clamp(torque, range.lower, range.upper);
}

}  // namespace pronk::jump
