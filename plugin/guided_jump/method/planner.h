// Analytic ballistic jump planner (the CLI's `--policy ballistic`): from a
// target alone it produces the 13 physical action parameters by physics, with
// no learning and no simulation. The rule and its equations:
// docs/method-planner.md.
//
// Frame: the start frame S of thrust_trajectory.h (z up, x the initial
// heading). The polar origin of the action is the take-off surface point
// directly below the start CoM. Units SI, angles rad.
//
// Outline (all exact, closed form except a short fixed-point loop that only
// picks the rule's parameters, never the ballistic solution itself):
//   1. target CoM c_tg = (c0_x + x, c0_y + y, surface + z + standing height);
//   2. actual lift-off CoM c_e in the jump plane, at a chosen height above the
//      take-off surface and a chosen distance ahead of the start CoM;
//   3. lift-off velocity v_e on the ballistic hyperbola from c_e to c_tg: the
//      least-speed member (for a down target, at the least-speed elevation of a
//      jump to the take-off height), its elevation clamped into the theta_v range, then
//      raised (if needed) until the apex clears the lift-off point by
//      min_apex_rise;
//   4. Bezier speed r_v = clamp(|v_e|, r_v min, max_bezier_speed), k = |v_e| / r_v,
//      d = max(d min, (|v_e|^2 - r_v^2) / (2 max_explosive_acceleration));
//   5. Bezier lift-off c_b = c_e - d v_e / |v_e|, so ThrustPlan's explosive phase
//      (which ends d along v with speed k |v_b|) lifts off exactly at (c_e, v_e);
//      r_p, theta_p are c_b's polar coordinates;
//   6. yaw split: lift-off yaw psi_lo and yaw rate psi_dot with
//      psi_lo + psi_dot * T_flight = target yaw;
//   7. when leg geometry is given, the whole thrust path must keep all four
//      stance feet reachable and in support, within the motors' torque (the
//      safety filter's path checks, safety_filter.h); a fixed candidate list of
//      lift-off heights, offsets, thrust durations and yaw splits is searched
//      in order, and the first feasible candidate wins;
//   8. when the motors' torque (thrustExceedsTorque) refuses every candidate, the
//      search repeats with each of gentler_thrusts: lower lift-offs, longer
//      thrusts, a lower explosive acceleration; when the leg workspace refuses
//      every candidate, it repeats with harder_explosive_accelerations.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "method/action_mapping.h"
#include "method/ballistics.h"
#include "method/edge_clearance.h"
#include "method/explosive_phase.h"
#include "method/leg_ik.h"
#include "method/motor_model.h"
#include "method/safety_filter.h"
#include "method/thrust_trajectory.h"

namespace pronk::jump {

// A jump target relative to the start: the landing surface point's displacement
// from the take-off surface point below the start CoM (x forward, y left, z up,
// m), and the yaw change (rad).
struct JumpTarget {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
};

struct PlannerConfig {
  ActionRanges ranges = go1ActionRanges();
  Eigen::Vector3d gravity = standardGravity();  // must be along -z
  // Start CoM in S. The polar origin is (c0_x, c0_y, c0_z - standing height).
  // Default: the Go1 whole-body CoM height of the planner prototype.
  Eigen::Vector3d start_com{0.0, 0.0, 0.3081};
  // Standing CoM height above the feet (take-off and landing posture). NaN:
  // start_com.z (the start CoM stands on the surface z = 0).
  double standing_com_height = std::numeric_limits<double>::quiet_NaN();

  // Rule parameters (defaults in docs/method-planner.md).
  // Actual lift-off CoM height above standing, m: candidates tried in order.
  std::vector<double> lift_off_rise_m{0.08, 0.06, 0.04, 0.02, 0.0, -0.02, -0.04};
  // Nominal horizontal lift-off offset ahead of the start CoM, m (the
  // prototype's 0.08), capped at half the horizontal target distance; raised to
  // d cos(theta_v) so that the Bezier lift-off never lies behind the polar origin.
  std::vector<double> lift_off_ahead_m{0.08, 0.04, 0.0};
  // Before those offsets, try the still start: the lift-off offset T_th/3 v_b
  // (+ d cos(theta_v)) that puts the Bezier's P2 above P0, so the CoM starts with
  // no horizontal acceleration and no countermovement. A countermovement's
  // initial acceleration 2 v_b / T_th moves the centre of pressure by
  // h a / g: out of the support polygon for lateral and diagonal jumps.
  bool still_start_first = true;
  // Thrust durations tried (clamped into the T_th range).
  std::vector<double> thrust_duration_s{0.45, 0.4};
  // Fractions of the target yaw done during the thrust (the rest in flight).
  std::vector<double> yaw_at_lift_off_fraction{0.5, 0.25, 0.0};
  double max_bezier_speed_mps = 1.25;       // the prototype's saturation threshold (~1.3 m/s)
  double max_explosive_acceleration = 20.0;  // m/s^2 along the UARM line
  double min_apex_rise_m = 0.03;             // apex above the lift-off CoM
  // Sideways jumps lift off steeper: the elevation is raised from the rule's
  // towards this one by lambda^2, lambda = sin^2 of the jump direction off the
  // trunk's mid-turn heading (half the target yaw). A sideways push over planted
  // feet swings the legs across the jump and the whole body leaves the ground
  // rolling; a steeper lift-off velocity lies closer to the legs' axes and
  // swings them less (docs/method-planner.md, step 3). NaN: off.
  double sideways_elevation_rad = 1.35;
  // Roll compensation: a push with a component across the trunk (at its
  // lift-off heading) leaves the ground with the trunk rolling away from the
  // jump, and it lands rolled (docs/method-planner.md, step 6). The lift-off
  // roll rate (rad/s) leans into it in proportion to that component v_side
  // (m/s): roll rate = sideways_roll_rate_gain v_side, clamped into its range.
  // 0: off.
  double sideways_roll_rate_gain = 0.0;  // the jump environment's default: 1.5
  // Vertical (in-place) jumps: apex this far above max(lift-off, target) CoM height.
  double in_place_apex_rise_m = 0.10;

  // When every candidate needs more torque than the motors have (PlanLimit::kTorque),
  // the search runs again with each of these gentler thrusts in turn, and the first
  // feasible plan wins. A DC motor's torque falls with joint speed, and near full
  // extension a calf turns fastest for a given lift-off speed: a lower lift-off
  // posture, a longer thrust and a lower explosive acceleration trade the
  // extended push for torque at lower joint speeds (docs/method-planner.md, step 9).
  struct GentlerThrust {
    std::vector<double> lift_off_rise_m;
    std::vector<double> thrust_duration_s;
    double max_bezier_speed_mps = 1.25;
    double max_explosive_acceleration = 20.0;
  };
  std::vector<GentlerThrust> gentler_thrusts{
      {{0.0, -0.02, -0.04, -0.06, -0.08}, {0.45, 0.6, 0.8}, 1.25, 20.0},
      {{0.02, 0.0, -0.02, -0.04, -0.06, -0.08}, {0.45, 0.6, 0.8}, 1.75, 12.0},
      {{0.02, 0.0, -0.02, -0.04, -0.06}, {0.45, 0.6, 0.8}, 1.75, 8.0},
  };

  // When every candidate loses a stance foot (PlanLimit::kLegWorkspace), the
  // search runs again with each of these explosive accelerations (m/s^2) in
  // turn, and the first feasible plan wins: a stronger explosive phase is
  // shorter, so the thrust path stays within the legs' reach (docs/method-planner.md,
  // step 12). The torque check still refuses what the motors cannot push.
  std::vector<double> harder_explosive_accelerations{25.0, 30.0, 35.0};

  // The terrain's edges under the jump line (empty: flat). Where the flight
  // would pass one too low, the velocity elevation is raised until it clears
  // (edge_clearance.h), no faster than the thrust can lift off; a jump that
  // cannot is refused (PlanLimit::kTerrain) naming the edge and the shortfall.
  TerrainEdges terrain;

  std::optional<LegWorkspace> workspace;  // empty: legs and support not checked
  // With a workspace: the least share of the mean vertical foot force any
  // stance foot may get on the thrust path (thrustLeavesSupport).
  double min_support_share = 0.2;

  // The rule's constants for a robot `scale` times the Go1's leg length, the
  // robot they were set for, by Froude similarity (the same motion at the same
  // gravity): lengths times scale, durations and speeds times sqrt(scale),
  // rates per metre over scale; accelerations stay. scale 1 changes nothing.
  PlannerConfig scaledToRobot(double scale) const;

  double standingHeight() const;            // standing_com_height or start_com.z
  Eigen::Vector3d polarOrigin() const;      // start_com - standingHeight() e_z
  // Throws std::invalid_argument naming the field on a bad value.
  void check() const;
};

// What stopped a target.
enum class PlanLimit {
  kNone,
  kActionRange,    // a parameter would leave its range (see limiting_parameter)
  kExplosive,      // the explosive acceleration cap would need d beyond its range
  kLegWorkspace,   // every candidate loses a foot somewhere on the thrust path
  kSupport,        // every candidate in reach would need a foot to pull
  kTorque,         // every candidate in reach and support needs more torque than the motors have
  kTerrain,        // the flight cannot clear an edge of the terrain (PlannerConfig::terrain)
};
// "none", "action_range", "explosive", "leg_workspace", "support", "torque", "terrain"
const char* planLimitName(PlanLimit limit);

struct PlannedJump {
  JumpAction action;  // always within the ranges (clamped when infeasible)
  double azimuth_rad = 0.0;
  Eigen::Vector3d target_com = Eigen::Vector3d::Zero();

  PointState bezier_lift_off;  // (c_b, v_b) of ThrustPlan
  PointState lift_off;         // actual (c_e, v_e) = ThrustPlan::liftOff()
  double lift_off_time = 0.0;  // T_th + T_e since the thrust starts, s
  double explosive_acceleration = 0.0;  // m/s^2

  // Ballistic prediction from `lift_off` (NaN when it never comes down to the target height).
  double flight_time = 0.0;          // lift-off to touchdown, s
  double touchdown_time = 0.0;       // since the thrust starts, s
  Eigen::Vector3d landing_point = Eigen::Vector3d::Zero();  // CoM at touchdown height
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();
  double apex_time = 0.0;            // since lift-off, s
  double touchdown_yaw = 0.0;        // psi_lo + psi_dot * flight_time

  // The lift-off speed the motors are predicted to miss by (thrustExceedsTorque),
  // m/s; NaN when the torques were not checked (no workspace, or its mass 0).
  double speed_shortfall = std::numeric_limits<double>::quiet_NaN();

  bool feasible = false;
  PlanLimit limit = PlanLimit::kNone;
  std::optional<ActionParameter> limiting_parameter;
  std::string reason;  // empty when feasible
};

// Plans the jump. Never throws for an unreachable target (feasible = false with
// a reason); throws std::invalid_argument for a non-finite target or a bad config.
PlannedJump planJump(const JumpTarget& target, const PlannerConfig& config = PlannerConfig());

// The jump environment's prior (`pronk run --policy ballistic`): planJump with
// the yaw split chosen first, aimed short of the target by the landing stop.
//   1. The yaw split: half the turn on the ground first, then a quarter, then
//      three quarters, the first fraction with a feasible plan; all of it in
//      flight when none has one (config.yaw_at_lift_off_fraction is replaced).
//      planJump searches its other rule parameters before its yaw splits, so the
//      split is chosen out here. Yaw turned in the thrust costs nothing in flight,
//      while a fast yaw spin in the air couples into roll through the swinging
//      legs (measured: a 45 deg turn all in the thrust sat the robot down, all in
//      flight tumbled it).
//   2. The landing stops the CoM landing_stop(v_touchdown) beyond its touchdown
//      point: the touchdown is aimed that much short of the target, four
//      fixed-point rounds from the plan's ballistic touchdown velocity; a round
//      with no feasible plan ends them (the last feasible plan stands).
PlannedJump planPriorJump(const JumpTarget& target, PlannerConfig config, const LandingStop& landing_stop);

// Correction for a measured lift-off tracking error (the planner prototype's
// target-correction scheme): assume the next jump's achieved lift-off state is
// the planned one plus `lift_off_error` (achieved - planned, position and
// velocity), and move the commanded horizontal target until that achieved
// state lands (at the target CoM height) on the real target. Each iteration
// re-plans with planJump and shifts the command by the remaining miss.
struct ReplannedJump {
  PlannedJump plan;              // the plan for `commanded` (its target_com is the commanded one)
  JumpTarget commanded;          // the shifted target handed to planJump
  Eigen::Vector3d target_com = Eigen::Vector3d::Zero();         // the real target CoM
  Eigen::Vector3d predicted_landing = Eigen::Vector3d::Zero();  // of plan.lift_off + error
  double miss = 0.0;             // |predicted_landing - target_com| (horizontal), m
  int iterations = 0;
  bool converged = false;        // miss <= tolerance and the last plan feasible
};
ReplannedJump replanJump(const JumpTarget& target, const PointState& lift_off_error,
                         const PlannerConfig& config = PlannerConfig(), int max_iterations = 50,
                         double tolerance = 1e-9);

}  // namespace pronk::jump
