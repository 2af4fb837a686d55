// Action mapping: the policy's 13 raw outputs -> the physical thrust parameters
// of the paper (section "The Action", table "Ranges of action parameters").
//
// Each raw output a_i is clipped to [-L, L] (L = raw_limit, 5 as in the paper's
// code) and mapped affinely so that -L -> min_i, 0 -> the middle, +L -> max_i:
//   p_i = min_i + (clip(a_i, -L, L) + L) * (max_i - min_i) / (2 L).
// The amount by which a_i lies outside [-L, L] (raw units) is kept for the
// action-limit penalty. The jump plane's azimuth is not learned: it comes from
// the target (jumpPlaneAzimuth).
//
// Units are SI, angles in rad. Lift-off orientation is ZYX Euler (roll about x,
// pitch about y, yaw about z: R = Rz(yaw) Ry(pitch) Rx(roll)) in the start frame
// (docs/method-trajectories.md); its rates are Euler-angle rates, not body or
// world angular velocities.
#pragma once

#include <Eigen/Core>
#include <array>

namespace pronk::jump {

constexpr int kActionSize = 13;

// Index of each parameter in the raw and physical action vectors. The order is
// the paper's action vector a = (T_th, r_p, theta_p, r_v, theta_v, k, d, roll,
// pitch, yaw, roll rate, pitch rate, yaw rate); the reference code orders them
// differently (docs/method-trajectories.md).
enum class ActionParameter : int {
  kThrustDuration = 0,   // T_th: duration of the Bezier part of the thrust, s
  kLiftOffRadius,        // r_p: distance of the Bezier lift-off CoM from the polar origin, m
  kLiftOffElevation,     // theta_p: elevation of that position above the horizontal, rad
  kLiftOffSpeed,         // r_v: Bezier lift-off CoM speed, m/s
  kVelocityElevation,    // theta_v: elevation of the Bezier lift-off velocity, rad
  kSpeedRatio,           // k: explosive final speed / Bezier lift-off speed, 1
  kExplosiveDistance,    // d: length of the explosive (UARM) extension, m
  kLiftOffRoll,          // lift-off roll, rad
  kLiftOffPitch,         // lift-off pitch, rad
  kLiftOffYaw,           // lift-off yaw, rad
  kLiftOffRollRate,      // roll rate at lift-off, rad/s
  kLiftOffPitchRate,     // pitch rate at lift-off, rad/s
  kLiftOffYawRate,       // yaw rate at lift-off, rad/s
};

constexpr int actionIndex(ActionParameter p) { return static_cast<int>(p); }

// Snake-case name ("thrust_duration", "liftoff_radius", ...), for scenario
// attributes and error messages; and the SI unit ("s", "m", "rad", "m/s", "1", "rad/s").
const char* actionParameterName(ActionParameter p);
const char* actionParameterUnit(ActionParameter p);

struct ParameterRange {
  double min = 0.0;
  double max = 0.0;
};

// Per-parameter [min, max] of the physical action. The defaults are Go1's,
// from the paper's table and the reference code's ActionsCfg (which agree except
// for theta_v, see docs/method-trajectories.md):
//   T_th [0.4, 1.0] s, r_p [0.2, 0.4] m, theta_p [pi/4, pi/2], r_v [0.5, 5] m/s,
//   theta_v [pi/6, pi/2], k [1, 3], d [0, 0.3] m, roll and pitch [-pi/6, pi/6],
//   yaw [-pi/4, pi/4], roll and pitch rate [-1, 1] rad/s, yaw rate [-4, 4] rad/s.
struct ActionRanges {
  ActionRanges();

  std::array<ParameterRange, kActionSize> bounds;
  double raw_limit = 5.0;  // raw outputs are clipped to [-raw_limit, raw_limit]

  ParameterRange& operator[](ActionParameter p) { return bounds[actionIndex(p)]; }
  const ParameterRange& operator[](ActionParameter p) const { return bounds[actionIndex(p)]; }

  // Throws std::invalid_argument naming the parameter when a bound is not
  // finite, min > max, raw_limit <= 0, or a range leaves the physical domain:
  // T_th > 0, r_p >= 0, r_v > 0, k >= 0, d >= 0.
  void check() const;
};

ActionRanges go1ActionRanges();      // == ActionRanges()
ActionRanges aliengoActionRanges();  // Go1's with r_p in [0.2, 0.6] m (reference code's Aliengo override)

// The Go1's leg length (thigh + calf, m): the robot the paper's ranges were set for.
constexpr double kGo1LegLength = 0.426;
// Length ratio of a robot to the Go1 for the defaults that are lengths: leg_length /
// kGo1LegLength, exactly 1 for a leg within a micrometre of the Go1's (so that the
// Go1 keeps the paper's numbers to the last bit). Throws std::invalid_argument for a
// leg length that is not finite and > 0.
double lengthScaleToGo1(double leg_length);
// The paper's Go1 ranges with the length-valued ones (r_p, d) multiplied by `scale`.
ActionRanges scaledActionRanges(double scale);

// The physical action, SI units.
struct JumpAction {
  double thrust_duration_s = 0.0;       // T_th
  double liftoff_radius_m = 0.0;        // r_p
  double liftoff_elevation_rad = 0.0;   // theta_p
  double liftoff_speed_mps = 0.0;       // r_v
  double velocity_elevation_rad = 0.0;  // theta_v
  double speed_ratio = 1.0;             // k
  double explosive_distance_m = 0.0;    // d
  Eigen::Vector3d liftoff_rpy_rad = Eigen::Vector3d::Zero();         // (roll, pitch, yaw)
  Eigen::Vector3d liftoff_rpy_rate_radps = Eigen::Vector3d::Zero();  // (roll, pitch, yaw) rates
};

using ActionVector = std::array<double, kActionSize>;

// JumpAction <-> its 13 numbers in ActionParameter order (physical units, no mapping).
ActionVector toVector(const JumpAction& action);
JumpAction fromVector(const ActionVector& values);

struct MappedAction {
  JumpAction action;
  // max(|raw_i| - raw_limit, 0) per parameter, in raw units: what clipping removed.
  ActionVector raw_excess{};

  double totalRawExcess() const;  // sum over the 13 parameters (the penalty's argument)
};

// Raw policy output -> physical action (clip, then the affine map above).
// Throws std::invalid_argument, naming the parameter, if a raw value is NaN.
// Infinite raw values clip to the range ends and report an infinite excess.
MappedAction mapAction(const ActionVector& raw, const ActionRanges& ranges);

// Physical action -> raw output, the exact inverse of the affine map:
//   a_i = -L + 2 L (p_i - min_i) / (max_i - min_i)   (0 when min_i == max_i).
// Not clipped: a value outside [min_i, max_i] gives |a_i| > L, which mapAction
// would clip and penalise. For warm-starting a policy from an analytic planner.
ActionVector unmapAction(const JumpAction& action, const ActionRanges& ranges);

// Below this horizontal target distance (m) the jump has no direction (a twist
// in place) and the azimuth is 0.
constexpr double kPureTwistDistance = 1e-5;

// Azimuth of the jump plane, rad in (-pi, pi]: the direction of the horizontal
// target displacement (dx, dy) in the start frame, measured from +x towards +y
// (0 forward, +pi/2 to the left, -pi/2 to the right, pi backward); 0 for a twist
// in place. dz does not matter. Throws std::invalid_argument if dx or dy is not finite.
double jumpPlaneAzimuth(const Eigen::Vector3d& target_displacement);

}  // namespace pronk::jump
