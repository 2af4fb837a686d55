// The joint motors: the torque a motor can deliver at a given joint speed.
//
// The paper's actuator (Orbit's DCMotor, ../shared/reference/reference-implementation.md
// section 4) with its saturation torque equal to the effort limit tau_e and its
// no-load speed equal to the velocity limit w_max:
//   upper(w) = clip(tau_e (1 - w / w_max), 0, tau_e)
//   lower(w) = clip(tau_e (-1 - w / w_max), -tau_e, 0)
// A motor turning at w can push along w with less torque the faster it turns
// (none at w_max) and brake against it with its full effort. The effort box
// alone ([-tau_e, tau_e] at any speed) is kept for comparison.
#pragma once

#include <limits>

namespace pronk::jump {

enum class MotorModel { kDcMotor, kEffortBox };

struct MotorLimits {
  double effort = std::numeric_limits<double>::infinity();    // N m (tau_e)
  double velocity = std::numeric_limits<double>::infinity();  // rad/s (w_max); infinity: the effort box
};

struct TorqueRange {
  double lower = 0.0;  // N m, <= 0
  double upper = 0.0;  // N m, >= 0
};

// The torques the motor can deliver at joint speed `speed` (rad/s).
TorqueRange availableTorque(MotorModel model, const MotorLimits& limits, double speed);

// `torque` clamped into availableTorque(model, limits, speed).
double saturateTorque(MotorModel model, const MotorLimits& limits, double torque, double speed);

}  // namespace pronk::jump
