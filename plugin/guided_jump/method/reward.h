// Reward: the paper's physically informative reward ("A Physically Informative
// Reward Function") with the terms, weights and constants of the reference code
// (reference-implementation.md section 5; table and deviations in
// docs/method-ballistics-ik-reward.md).
//
//   R    = R_lt * exp(-(C_run + C_term)^2 / penalty_scale)
//   R_lt = exp(-e / sigma_e) * exp(D / sigma_d)
//   e    = |xy_target - xy_landed| + (|dz_target - z_landed| if it exceeds z_dead_band, else 0)
//   D    = |(dx, dy, dz)|, the commanded displacement
//
// C_run sums the feasibility penalties over the control ticks up to lift-off,
// C_term the terminal penalties; every term is a non-negative cost
// weight * value (the reference code writes the same terms with negative
// weights; only |C| enters R).
//
// Frame: the start frame S of thrust_trajectory.h (z up, origin on the take-off
// surface below the start CoM, x along the initial heading). Units SI, angles rad.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pronk::jump {

// Joint limits in the order of TickSample::q (e.g. 12 joints).
struct JointLimits {
  Eigen::VectorXd position_min;  // rad, hard (URDF) limits; the soft ones are derived
  Eigen::VectorXd position_max;  // rad
  Eigen::VectorXd velocity_max;  // rad/s, > 0
};

// One control tick during the thrust (up to lift-off).
struct TickSample {
  double time = 0.0;              // s since the start of the jump
  Eigen::VectorXd q;              // joint positions, rad
  Eigen::VectorXd qd;             // joint velocities, rad/s
  Eigen::VectorXd tau_commanded;  // N m, what the controller asked for (before saturation)
  Eigen::VectorXd tau_applied;    // N m, what the actuators delivered (after saturation)
  // Per foot: the force the ground exerts on the foot (N, frame S; z > 0 pushes
  // the robot up), measured or estimated from the joint torques, and whether
  // the foot is meant to be in contact. The friction and unilateral terms only
  // look at feet with foot_in_contact set.
  std::vector<Eigen::Vector3d> foot_force;
  std::vector<bool> foot_in_contact;
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();  // trunk origin, S
};

// The robot at one instant (an event, or the end of the episode).
struct BodyState {
  double time = 0.0;                                                // s
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();          // trunk origin, S
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // trunk -> S
  Eigen::Vector3d com_position = Eigen::Vector3d::Zero();           // whole-body CoM, S
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();           // m/s, S
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();       // trunk, S axes, rad/s
};

struct LandingTarget {
  // (dx, dy): trunk displacement in S; dz: height of the landing surface above
  // the take-off surface.
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // trunk -> S at landing
};

// The planned lift-off state: the end of the explosive phase (c_lo_e, its
// velocity), the lift-off orientation and angular velocity. The angular
// velocity is a true angular velocity in S (convert the action's Euler rates
// with worldAngularVelocity of orientation_trajectory.h), not Euler rates.
struct JumpPlan {
  Eigen::Vector3d lift_off_com_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d lift_off_com_velocity = Eigen::Vector3d::Zero();
  Eigen::Quaterniond lift_off_orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d lift_off_angular_velocity = Eigen::Vector3d::Zero();
};

// Everything the reward needs from one jump.
struct JumpRecord {
  double tick_s = 0.001;  // control period of the ticks, s
  JointLimits joint_limits;
  std::vector<TickSample> ticks;  // thrust ticks; those after lift_off->time are ignored
  Eigen::Vector3d start_base_position = Eigen::Vector3d::Zero();  // trunk origin at the start, S
  // Events; std::nullopt when not detected. Without a lift-off the lift-off
  // errors compare the plan with final_state (where the robot stayed) and every
  // tick counts; without a touchdown the two touchdown terms take the
  // missing_touchdown_* values of the settings.
  std::optional<BodyState> lift_off;
  std::optional<BodyState> apex;  // recorded for reports; no term uses it
  std::optional<BodyState> touchdown;
  BodyState final_state;                              // at the end of the episode
  std::vector<Eigen::Vector3d> final_foot_positions;  // foot centres at the end, S
  LandingTarget target;
  JumpPlan plan;
  Eigen::VectorXd raw_action;  // the policy's raw (unclipped) outputs
};

// Weights (cost = weight * value), from the reference code's jump_env_cfg.py
// (reference-implementation.md 5.1, 5.3).
struct RewardWeights {
  // running, per 5 ms of thrust
  double joint_position_limits = 1e-3;
  double joint_velocity_limits = 1e-3;
  double torque_saturation = 1e-3;
  double friction_cone = 1e-4;
  double unilaterality = 1e-4;
  double workspace = 5.0;
  // terminal
  double target_orientation = 3.5;
  double lift_off_position = 2.0;
  double lift_off_orientation = 1.0;
  double lift_off_linear_velocity = 0.2;
  double lift_off_angular_velocity = 0.2;
  double touchdown_bounce = 3.0;
  double touchdown_angular_velocity = 0.1;
  double action_limit = 5.0;
};

struct RewardSettings {
  RewardWeights weights;
  double soft_limit_factor = 0.9;         // soft position limits: middle +- factor * half range
  double velocity_excess_cap = 1.0;       // rad/s: per joint and tick, the velocity excess counts at most this
  double friction_coefficient = 0.8;      // mu of the friction-cone term
  double workspace_half_width = 0.15;     // m: |x|, |y| of the trunk from its start position
  double workspace_z_min = 0.15;          // m: trunk height above the take-off surface
  double workspace_z_max = 0.40;          // m
  double raw_action_limit = 5.0;          // raw outputs beyond +-this are penalised
  double error_scale = 0.1;               // sigma_e, m
  double distance_scale = 1.5;            // sigma_d, m
  double z_dead_band = 0.1;               // m: height errors up to this count as 0
  double foot_radius = 0.02;              // m: landing surface = mean foot-centre z - this
  double penalty_scale = 5.0;             // R_lt * exp(-C^2 / penalty_scale)
  double missing_touchdown_bounce = 2.0;  // m, bounce value without a touchdown
  double missing_touchdown_angular_velocity = 10.0;  // rad/s, without a touchdown
  double reference_tick_s = 0.005;                   // the reference's step: running terms count per this much time

  // Throws std::invalid_argument naming the setting when one is out of its domain.
  void check() const;
};

RewardSettings go1RewardSettings();      // == RewardSettings()
RewardSettings aliengoRewardSettings();  // workspace z in [0.20, 0.60] m, foot radius 0.0265 m

// One named term: its raw value (summed over ticks for the running terms, in
// the term's unit) and its weight; cost = weight * value >= 0.
struct RewardTerm {
  std::string name;
  double value = 0.0;
  double weight = 0.0;
  double cost() const { return weight * value; }
};

struct RewardBreakdown {
  // Running terms (values summed over the thrust ticks, each tick scaled by tick_s / reference_tick_s).
  RewardTerm joint_position_limits{"joint_position_limits"};  // rad beyond the soft limits
  RewardTerm joint_velocity_limits{"joint_velocity_limits"};  // rad/s beyond the limits, capped per joint and tick
  RewardTerm torque_saturation{"torque_saturation"};          // N m clipped by saturation
  RewardTerm friction_cone{"friction_cone"};                  // N outside the cone
  RewardTerm unilaterality{"unilaterality"};                  // N of pull
  RewardTerm workspace{"workspace"};                          // m outside the trunk box
  // Terminal terms.
  RewardTerm target_orientation{"target_orientation"};                  // rad, final vs target
  RewardTerm lift_off_position{"lift_off_position"};                    // m, CoM vs plan
  RewardTerm lift_off_orientation{"lift_off_orientation"};              // rad
  RewardTerm lift_off_linear_velocity{"lift_off_linear_velocity"};      // m/s, CoM vs plan
  RewardTerm lift_off_angular_velocity{"lift_off_angular_velocity"};    // rad/s
  RewardTerm touchdown_bounce{"touchdown_bounce"};                      // m, touchdown xy -> final xy
  RewardTerm touchdown_angular_velocity{"touchdown_angular_velocity"};  // rad/s at touchdown
  RewardTerm action_limit{"action_limit"};                              // raw units beyond the limit

  // Landing target reward.
  double landing_error_xy = 0.0;  // m
  double landing_error_z = 0.0;   // m, after the dead band
  double landing_error = 0.0;     // e = xy + z, m
  double jump_distance = 0.0;     // D, m
  double landing_reward = 0.0;    // R_lt

  double running_cost = 0.0;   // C_run
  double terminal_cost = 0.0;  // C_term
  double total_cost = 0.0;     // C_run + C_term
  double penalty_gate = 0.0;   // exp(-total_cost^2 / penalty_scale)
  double reward = 0.0;         // R = landing_reward * penalty_gate

  bool lifted_off = false;
  bool touched_down = false;
  int thrust_ticks = 0;  // ticks that entered the running terms

  // All fourteen terms, running ones first.
  std::vector<const RewardTerm*> terms() const;
  // name -> cost, plus "landing_reward", "penalty_gate", "reward", "running_cost", "terminal_cost".
  std::map<std::string, double> asMap() const;
};

// Throws std::invalid_argument (naming the tick and the field) when the sizes
// in the record disagree, tick_s <= 0, or the settings are invalid.
RewardBreakdown computeReward(const JumpRecord& record, const RewardSettings& settings = go1RewardSettings());

// The single terms, for tests and per-tick logging. All return values >= 0.
namespace reward_terms {

// The paper's linear activation A(x, lo, hi) = |min(x - lo, 0) + max(x - hi, 0)|.
double activation(double x, double lo, double hi);

// sum_j A(q_j, soft_min_j, soft_max_j), soft limits = middle +- factor * half range.
double jointPositionExcess(const Eigen::VectorXd& q, const JointLimits& limits, double soft_limit_factor);
// sum_j min(max(|qd_j| - qd_max_j, 0), cap).
double jointVelocityExcess(const Eigen::VectorXd& qd, const JointLimits& limits, double cap);
// sum_j |tau_commanded_j - tau_applied_j|.
double torqueSaturation(const Eigen::VectorXd& tau_commanded, const Eigen::VectorXd& tau_applied);
// sum over feet in contact of max(|f_xy| - mu f_z, 0).
double frictionConeExcess(const std::vector<Eigen::Vector3d>& forces, const std::vector<bool>& in_contact, double mu);
// sum over feet in contact of max(-f_z, 0).
double pullingForce(const std::vector<Eigen::Vector3d>& forces, const std::vector<bool>& in_contact);
// A(x - x0, -w, w) + A(y - y0, -w, w) + A(z, z_min, z_max), trunk in S.
double workspaceExcess(const Eigen::Vector3d& base_position, const Eigen::Vector3d& start_base_position,
                       const RewardSettings& settings);
// The angle of the rotation between two orientations, in [0, pi].
double rotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);
// sum_i max(|a_i| - limit, 0).
double actionExcess(const Eigen::VectorXd& raw_action, double limit);
// exp(-error / sigma_e) * exp(distance / sigma_d).
double landingTargetReward(double error, double distance, const RewardSettings& settings);

}  // namespace reward_terms

}  // namespace pronk::jump
