// The safety filter: what refuses an action before anything moves. The paper's
// "physical feasibility check" (its section of that name, eq:apex: the apex
// c_lo,z + v_lo,z^2 / (2 g) must reach the target height) on the planned
// lift-off state, then pronk's checks of the thrust path against the legs:
// every stance foot stays reachable, and the motors deliver the planned lift-off
// speed. The environment runs them in that order on every action (safetyFilter);
// the planner runs the path checks, plus a support check, on every candidate.
// Frame: the start frame S of thrust_trajectory.h. Units SI, angles rad.
// The equations: docs/method-ballistics-ik-reward.md (the ballistic check) and
// docs/method-planner.md, step 9 (the path checks).
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "method/action_mapping.h"
#include "method/ballistics.h"
#include "method/edge_clearance.h"
#include "method/explosive_phase.h"
#include "method/leg_ik.h"
#include "method/motor_model.h"

namespace pronk::jump {

// Why an action was rejected.
enum class SafetyIssue {
  kNone,               // safe
  kNotFinite,          // a position, velocity or the target is NaN or infinite
  kApexBelowTarget,    // the apex does not reach target height + apex_clearance
  kTargetUnreachable,  // the CoM never comes down to the target height, or lands too far from the target
  kOutsideWorkspace,   // the caller's workspace predicate rejects the lift-off position
  kLegWorkspace,       // a stance foot leaves the leg workspace, or a knee comes down to the ground, on the
                       // thrust path (thrustLeavesWorkspace)
  kTorqueLimit,        // the motors would miss the lift-off speed by too much (thrustExceedsTorque)
  kTerrainEdge,        // the flight passes an edge of the terrain too low (edge_clearance.h)
};
// "none", "not_finite", "apex_below_target", ..., "leg_workspace", "torque_limit", "terrain_edge"
const char* safetyIssueName(SafetyIssue issue);

struct SafetyVerdict {
  SafetyIssue issue = SafetyIssue::kNone;
  std::string reason;  // empty when safe; otherwise one sentence with the numbers
  bool safe() const { return issue == SafetyIssue::kNone; }
  explicit operator bool() const { return safe(); }
};

// The paper's "physical feasibility check": reject a planned lift-off state
// before the jump runs. `target` is where the plan wants the CoM at touchdown
// (its z is the touchdown CoM height). Checks, in this order (the first failure wins):
//   1. every input is finite;
//   2. apex height >= target.z + apex_clearance (the paper's test is clearance 0);
//   3. the CoM comes down through target.z (descending root exists) and, when
//      max_landing_miss is finite, lands within max_landing_miss (horizontal
//      distance, m) of the target;
//   4. workspace(lift-off position) is true, when a predicate is given;
//   5. the flight passes every edge of `terrain` high enough (edgePass from
//      terrain_origin, the polar origin), when it has edges.
struct SafetyCheck {
  Eigen::Vector3d gravity = standardGravity();
  double apex_clearance = 0.0;                                        // m
  double max_landing_miss = std::numeric_limits<double>::infinity();  // m
  // Caller-supplied: true when the lift-off CoM position is inside the leg
  // workspace (e.g. all feet reachable by IK, see leg_ik.h). Empty: not checked.
  std::function<bool(const Eigen::Vector3d& lift_off_position)> workspace;
  TerrainEdges terrain;                                    // empty: flat
  Eigen::Vector3d terrain_origin = Eigen::Vector3d::Zero();  // the polar origin the edges are measured from

  SafetyVerdict operator()(const FlightState& lift_off, const Eigen::Vector3d& target) const;
};

// Stance feet the legs must keep reaching during the thrust.
struct LegWorkspace {
  std::array<LegGeometry, kLegCount> legs{};
  std::array<Eigen::Vector3d, kLegCount> feet{};  // stance feet in S, fixed during the thrust
  Eigen::Vector3d com_to_trunk = Eigen::Vector3d::Zero();  // trunk centre - CoM, trunk frame, assumed constant
  int path_samples = 60;  // samples of the thrust path (plus both ends) checked
  bool require_within_limits = true;
  // Every knee (the calf joint) stays at least this high above its stance
  // foot's centre on the thrust path, m. A deep crouch that twists the trunk
  // over planted feet folds a thigh down to the ground (measured on the Go1:
  // the thrusts whose thighs touched had knees at or below their feet's centres).
  // -inf: not checked.
  double knee_clearance = -std::numeric_limits<double>::infinity();
  // For the torque prediction (thrustExceedsTorque): the whole robot's mass (0:
  // torques not checked), the motor limits of each leg's hip, thigh and calf
  // (default: none), and the motor model that turns them into the torque
  // available at a joint speed (method/motor_model.h).
  double mass = 0.0;
  std::array<MotorLimits, 3> joint_motors{};
  MotorModel motor = MotorModel::kEffortBox;
  // The planned lift-off speed the motors may fall short of, m/s: where a joint
  // needs more torque than its motor delivers, the ground force shrinks by that
  // ratio, and the lost acceleration is integrated over the thrust.
  double max_speed_shortfall = 0.1;
};

// The workspace of a robot standing at rest with every leg at joint angles
// `stance_q` (hip, thigh, calf) and the trunk centre at start_com + com_to_trunk
// (trunk yaw 0): the feet are the forward kinematics of that pose.
LegWorkspace standingWorkspace(const std::array<LegGeometry, kLegCount>& legs, const Eigen::Vector3d& stance_q,
                               const Eigen::Vector3d& start_com, const Eigen::Vector3d& com_to_trunk);

// Where a thrust leaves the leg workspace: samples the thrust path of `action`
// (ThrustPlan at `azimuth` from com_start about polar_origin, with the action's
// orientation Bezier from a level start) and returns, for the first sample at
// which a stance foot of `workspace` is out of reach or a knee is lower than
// workspace.knee_clearance above its foot (the lift-off end is checked first,
// then the path from its start), a sentence saying when and where;
// std::nullopt when every foot stays reachable and every knee clear.
std::optional<std::string> thrustLeavesWorkspace(const JumpAction& action, double azimuth,
                                                 const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                                 const LegWorkspace& workspace);

// Where a thrust would need a stance foot to pull: samples the thrust path of
// `action` and, at each sample, shares the vertical force m (a_z + g) of the
// planned CoM acceleration over the stance feet `feet` (in S, on one level) by
// the minimum-norm solution that puts the centre of pressure at the zero-moment
// point c_xy - c_z' a_xy / (a_z + g) (c_z' the CoM height above the feet). The
// controller distributes its feed-forward the same way. Returns a sentence saying
// when a foot's share drops below `min_share` of the mean share (the first such
// sample), std::nullopt when none does. A countermovement's initial
// acceleration 2 v_b / T_th moves the zero-moment point h a / g away: for a
// diagonal jump out of the diamond spanned by the feet, so that a foot would have
// to pull, lifts instead, and the robot tips about the other diagonal.
std::optional<std::string> thrustLeavesSupport(const JumpAction& action, double azimuth,
                                               const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                               const std::array<Eigen::Vector3d, kLegCount>& feet,
                                               const Eigen::Vector3d& gravity, double min_share, int path_samples);

// Where a thrust would need more joint torque than the motors have: at each
// sample of the thrust path the force m (a - g) of the planned CoM acceleration
// is shared over the stance feet by the minimum-norm distribution with no moment
// about the CoM (the controller's feed-forward, force_distribution.h), and each
// leg's torques -J(q)^T f follow from the leg's IK at that trunk pose. Its joint
// speeds J(q)^-1 x' follow from the planned CoM velocity and trunk angular
// velocity (x the stance foot in the trunk frame). Where a joint needs more than
// its motor delivers at that speed (workspace.motor), the whole ground force is
// taken to shrink by the ratio; the acceleration so lost, integrated over the
// thrust, is the lift-off speed the motors fall short by. Returns a sentence
// with that shortfall and the tightest joint (when, how much) when it exceeds
// workspace.max_speed_shortfall, std::nullopt otherwise or when workspace.mass
// is 0. The legs' own inertia is not in the prediction.
std::optional<std::string> thrustExceedsTorque(const JumpAction& action, double azimuth,
                                               const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                               const LegWorkspace& workspace, const Eigen::Vector3d& gravity);

// The least height of a knee above its stance foot's centre on the thrust path
// (world z, m), from each leg's IK at the planned trunk pose; +inf when a foot is
// out of reach (workspaceProblem's finding).
double thrustKneeClearance(const ThrustPlan& thrust, const JumpAction& action, const LegWorkspace& workspace);

// The lift-off speed shortfall thrustExceedsTorque compares with
// workspace.max_speed_shortfall, m/s (NaN when workspace.mass is 0).
double thrustSpeedShortfall(const JumpAction& action, double azimuth, const Eigen::Vector3d& com_start,
                            const Eigen::Vector3d& polar_origin, const LegWorkspace& workspace,
                            const Eigen::Vector3d& gravity);

// The whole filter, first failure wins: `ballistic` on the thrust's lift-off
// state against target_com (the CoM at touchdown), then, with a workspace, the
// leg workspace on the thrust path (kLegWorkspace) and the motors' torque
// (kTorqueLimit, under ballistic.gravity). `thrust` is the ThrustPlan of
// `action` (the controller's, from the start pose).
struct SafetyFilterResult {
  SafetyVerdict verdict;
  // The lift-off speed the motors are predicted to miss by, m/s
  // (thrustSpeedShortfall): set once the torque check ran; NaN when the
  // workspace has no mass.
  std::optional<double> speed_shortfall;
};
SafetyFilterResult safetyFilter(const JumpAction& action, const ThrustPlan& thrust, const Eigen::Vector3d& target_com,
                                const SafetyCheck& ballistic, const std::optional<LegWorkspace>& workspace);

// The path checks on a ThrustPlan already built, for a search over many
// candidates (the planner). With `explain` false a finding comes back as an empty
// sentence: a search that already holds a reason of that kind only needs the
// verdict, and formatting the reasons of rejected candidates was an eighth of
// planning time.
std::array<LegReachCheck, kLegCount> reachChecks(const LegWorkspace& workspace);
std::optional<std::string> workspaceProblem(const ThrustPlan& thrust, const JumpAction& action,
                                            const LegWorkspace& workspace,
                                            const std::array<LegReachCheck, kLegCount>& reach, bool explain);
std::optional<std::string> supportProblem(const ThrustPlan& thrust, const std::array<Eigen::Vector3d, kLegCount>& feet,
                                          const Eigen::Vector3d& gravity, double min_share, int path_samples,
                                          bool explain);
// The torque check's finding: the predicted lift-off speed shortfall and the
// tightest joint on the way.
struct TorqueVerdict {
  double shortfall = 0.0;  // m/s of planned lift-off speed the motors do not deliver
  double scale = 1.0, t = 0.0, need = 0.0, have = 0.0, speed = 0.0;  // the tightest joint
  int leg = 0, joint = 0;
};
TorqueVerdict torqueVerdict(const ThrustPlan& thrust, const JumpAction& action, const LegWorkspace& workspace,
                            const Eigen::Vector3d& gravity);
// The sentence thrustExceedsTorque returns for a verdict.
std::string torqueProblem(const TorqueVerdict& verdict, const LegWorkspace& workspace, double thrust_duration);

}  // namespace pronk::jump
