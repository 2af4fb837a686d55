// The flight, from lift-off (every foot off the ground): a 0.1 s smoothstep to a
// tucked pose at Kp / 3 (the paper's), no gravity compensation; then the
// descent, once the predicted fall to the landing surface is down to
// kBlendTime + kExtensionLead: a 0.1 s smoothstep to the landing pose, which
// ends kExtensionLead before touchdown. The landing pose is the stance's feet
// placed where the landing will stop the CoM, turned against the trunk's tilt
// (so that a trunk that rotated in the air still lands on all four feet) and
// reaching landing_extension below the stance. In both, the legs stay clear of
// the terrain they fly over (TerrainClearance).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "control/jump_plan.h"
#include "control/landing_phase.h"
#include "control/leg_drive.h"
#include "control/param_reader.h"
#include "control/terrain_clearance.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

struct FlightSettings {
  double kp_division = 3.0;  // Kp in flight and descent = kp / this (the paper's 3)
  // The landing pose's feet turn against the trunk's tilt by this multiple of it
  // (1: the feet as under a level trunk; 0: the trunk's frame). In the air the
  // legs carry most of the roll inertia, and the trunk turns against their swing.
  double pose_levelling = 1.5;
  // m the landing pose reaches below the stance feet: a leg that touches down
  // longer has more stroke to stop the fall in before a thigh comes down to the
  // ground (0: the stance pose). Below 0: derived from the robot
  // (jump::landingExtension; 0 without an analytic leg model).
  double extension = -1.0;
  std::array<double, 3> tuck{0.0, 1.38, -2.4};  // rad per leg: flight pose (hip, thigh, calf)

  // landing_extension, landing_pose_levelling.
  static const std::vector<pronk_param_decl>& parameters();
  static FlightSettings read(const ParamReader& read);
};

class FlightPhase {
 public:
  static constexpr double kBlendTime = 0.1;       // s, tuck and extension smoothsteps
  static constexpr double kExtensionLead = 0.06;  // s: the landing extension ends this long before touchdown

  // Resolves a derived extension from the drive's robot.
  FlightPhase(LegDrive& drive, const FlightSettings& settings, const LandingPhase& landing);

  // The derived landing_extension (jump::landingExtension) of a robot with these
  // legs at the stance joints, its weakest knee's effort (N m), its mass (kg)
  // and gravity (m/s^2): 0 where the knees hold any load.
  static double derivedExtension(const LegModels& legs, const std::array<double, 3>& stance, double knee_effort,
                                 double mass, double gravity);

  double kp() const { return drive_.hold().kp / settings_.kp_division; }
  double extension() const { return settings_.extension; }

  // At lift-off: the tuck starts from the joints as they are.
  void liftOff(const pronk_robot_state& s);
  // Whether the descent is due, `elapsed` seconds into the flight.
  bool descentDue(const pronk_robot_state& s, const JumpPlan& plan) const;
  // At the descent's start, `elapsed` seconds into the flight: it starts from the
  // tuck's blend as it was.
  void descend(double elapsed);
  // The tick's torques, `elapsed` seconds into the flight or the descent.
  void compute(const pronk_robot_state& s, const JumpPlan& plan, bool descending, double elapsed, double* torque);

 private:
  LegDrive& drive_;
  FlightSettings settings_;
  const LandingPhase& landing_;
  TerrainClearance clearance_;
  Eigen::VectorXd blend_from_;
};

}  // namespace pronk::guided_jump
