// The landing, from touchdown (any foot in contact with the CoM no longer
// rising): joint PD towards a level trunk at the stance height over the feet (IK
// for the feet in contact, the stance under a level trunk for the others, kept
// clear of the terrain as in flight), Kp
// back from the flight's to the stance's over kLandingRamp, and a body wrench
// spread over the feet in contact, over all of them once every foot has touched
// down: a critically damped, friction-limited stop of the CoM where the landing
// model says it comes to rest (landingStop), a stiffer vertical stop that the
// legs' reference follows down, a levelling of the trunk and a turn to the
// plan's touchdown heading. The gains are per kg of the robot's mass.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "control/jump_plan.h"
#include "control/leg_drive.h"
#include "control/param_reader.h"
#include "control/terrain_clearance.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

struct LandingSettings {
  double frequency = 5.0;      // rad/s: natural frequency of the CoM's stop
  // rad/s of the vertical stop (0: frequency), which the legs' reference follows
  // down: with the reference at the standing height at once, the compressed legs
  // throw the robot back into the air.
  double vertical_frequency = 10.0;
  double friction = 0.45;      // the share of the normal force the stop may ask sideways
  double tilt = 4.0;           // N m / rad / kg: levelling stiffness
  double tilt_damping = 0.4;   // N m s / rad / kg: levelling damping
  double yaw_gain = 10.0;      // N m / rad / kg: towards the plan's touchdown heading
  double yaw_damping = 1.5;    // N m s / rad / kg: damping of the turn about the vertical

  // landing_frequency, landing_vertical_frequency, landing_friction,
  // landing_tilt_gain, landing_tilt_damping, landing_yaw_gain, landing_yaw_damping.
  static const std::vector<pronk_param_decl>& parameters();
  static LandingSettings read(const ParamReader& read);
};

class LandingPhase {
 public:
  static constexpr double kLandingRamp = 0.3;    // s from touchdown until Kp is fully back
  static constexpr double kGroundReach = 0.01;   // m below the feet that are down, for a foot still in the air

  // Where the landing brings the CoM to rest, from the touchdown point
  // (jump::landingStopOffset with the landing's friction share and frequency).
  // The airborne feet land that far ahead of the CoM, the landing wrench stops
  // the CoM there, and the ballistic prior aims short by it.
  static Eigen::Vector2d landingStop(const LandingSettings& landing, const Eigen::Vector3d& touchdown_velocity);

  LandingPhase(LegDrive& drive, const LandingSettings& settings)
      : drive_(drive), settings_(settings), clearance_(drive) {}
  const LandingSettings& settings() const { return settings_; }

  // Before a jump: no touchdown yet.
  void reset();
  // At touchdown after a flight: the stop's goal (the CoM comes to rest
  // landingStop() beyond the touchdown point: a pure exponential, no overshoot)
  // and the CoM's sink below its landing height.
  void touchDown(const pronk_robot_state& s, const JumpPlan& plan);
  // A jump abandoned on the ground: the stance, at full gains, the weight on every foot.
  void abandon() { all_down_seen_ = true; }
  // The tick's torques, `elapsed` seconds after touchdown; kp_flight the gain it ramps up from.
  void compute(const pronk_robot_state& s, const JumpPlan& plan, double elapsed, double kp_flight, double* torque);

 private:
  void reference(const pronk_robot_state& s, const JumpPlan& plan, double elapsed);
  void wrenchTorques(const pronk_robot_state& s, const JumpPlan& plan, double kp, double* torque);
  double verticalStopFrequency() const;
  // The CoM's planned height below its landing height t after touchdown (critically damped).
  double verticalStopSink(double t) const;

  LegDrive& drive_;
  LandingSettings settings_;
  TerrainClearance clearance_;                 // the feet still in the air, as in flight
  bool all_down_seen_ = false;                 // every foot has touched down
  std::optional<Eigen::Vector3d> touchdown_com_;  // the stop's goal: where the CoM comes to rest, its touchdown height
  double touchdown_sink_ = 0, touchdown_sink_rate_ = 0;  // CoM below its landing height, and its rate, at touchdown
};

}  // namespace pronk::guided_jump
