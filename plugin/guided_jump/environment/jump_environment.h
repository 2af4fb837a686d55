// Environment `jump`: one episode is one jump to a target, driven by one action
// (the paper's 13 jump parameters).
//   observation (6): the target x, y, z (m), yaw, roll, pitch (rad), relative to
//                    the start, in the robot's initial heading frame;
//   action (13):     the policy's raw outputs, clipped to +-5 (the paper's) and mapped
//                    affinely onto the action ranges (method/action_mapping.h);
//   act():           the safety filter (method/safety_filter.h) runs before
//                    anything moves: a flight whose apex stays below the target,
//                    a thrust path that loses a foot's reach, or one the motors
//                    cannot push, is rejected (PRONK_REJECTED, with why);
//   step():          the guided_jump phase machine (control/jump_controller.h),
//                    until `duration`; a robot in the air then runs on until
//                    0.3 s after a foot is down (the landing's gains back);
//   finish():        the paper's reward with every term reported as a metric
//                    (method/reward.h), plus the plan's predictions;
//   prior_action():  the analytic ballistic planner (method/planner.h) as raw
//                    outputs: `pronk run --policy ballistic`; PRONK_REJECTED
//                    (ABI 1.4) with the plan's best try when it finds no
//                    feasible jump.
// The frame of the reward and the plan is the controller's start frame S (origin
// on the ground below the CoM at the thrust start, x along the heading then).
// The C callbacks are abi/jump_environment.cpp's.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/jump_controller.h"
#include "control/leg_drive.h"
#include "control/param_reader.h"
#include "control/robot_state.h"
#include "method/action_mapping.h"
#include "method/reward.h"
#include "method/planner.h"
#include "method/safety_filter.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

constexpr int32_t kObservationSize = 6;

// The action was refused before the episode ran: PRONK_REJECTED.
class Rejected : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct EnvironmentSettings {
  JumpSettings jump;
  double duration = 1.5;
  jump::ActionRanges ranges;
  jump::RewardSettings reward;
  double knee_clearance = 0.01;
  double sideways_roll_rate_gain = 0.0;
  // As set (13 numbers each), or empty: derived from the robot's leg length once
  // the host is known (deriveFromRobot).
  std::vector<double> action_min, action_max;
  bool derive_workspace_z = false;
  // The robot's leg length over the Go1's (deriveFromRobot): the planner's
  // constants are Froude-scaled by it (PlannerConfig::scaledToRobot).
  double length_scale = 1.0;

  // The environment's own parameters (the phases' are JumpSettings::parameters()):
  // duration, the action ranges, the reward's, the safety filter's and the planner's.
  static const std::vector<pronk_param_decl>& parameters();
  // The phases' and its own (throws InvalidArgument naming the parameter).
  static EnvironmentSettings read(const ParamReader& read);
};

class JumpEnvironment {
 public:
  // Checks the robot (HoldController's checks). `legs`: the analytic leg model
  // measured on the host's kinematics (abi/host_leg_geometry.h); none, with the
  // reason in `no_legs`: the planner and the safety filter skip the leg checks,
  // and the ranges and the band keep the Go1's numbers (both logged).
  JumpEnvironment(const pronk_host_api* host, const EnvironmentSettings& settings, std::optional<LegModels> legs,
                  const std::string& no_legs);

  void reset(const double* task, int32_t task_size, const pronk_robot_state& state, double* observation);

  // The planner's action for an observation; *infeasible gets its reason when
  // it found no feasible plan (the action is then its best try).
  std::vector<double> priorAction(const double* observation, std::string* infeasible);

  void act(const double* raw_action);

  bool step(const pronk_robot_state& state, double* torque);

  double finish(const pronk_robot_state& state);

 private:
  void metric(const std::string& name, double value);

  // The controller's S once the thrust has begun, the reset's before.
  StartFrame frame() const;

  std::optional<jump::LegWorkspace> workspace() const;

  // The terrain's edges under the line from the start towards `towards` (start
  // frame, horizontal) and 0.3 m beyond it, from the host's terrain (ABI 1.6;
  // none from an older host), with the hips and the tucked legs about the CoM
  // and the trunk's turn `turn` (rad) over the flight: what the planner clears
  // and the safety filter checks.
  jump::TerrainEdges terrainEdges(const Eigen::Vector2d& towards, double turn) const;

  // Where the controller's landing stops the CoM beyond its touchdown point.
  jump::LandingStop landingStop() const;

  jump::BodyState bodyState(const pronk_robot_state& s, const StartFrame& S) const;

  void onPhaseChange(JumpPhase phase, const pronk_robot_state& s);

  void recordTick(const pronk_robot_state& s, const double* torque);

  const pronk_host_api* host_;
  EnvironmentSettings settings_;
  int n_ = 0, feet_ = 0;
  std::optional<std::array<jump::LegGeometry, jump::kLegCount>> legs_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  jump::JointLimits limits_;

  std::array<double, kObservationSize> task_{};
  bool has_task_ = false;
  double reset_time_ = 0;
  StartFrame start_;
  double standing_height_ = 0;
  Eigen::Vector3d com_to_trunk_ = Eigen::Vector3d::Zero();
  double mass_ = 0;                            // kg, the whole robot
  std::array<jump::MotorLimits, 3> joint_motors_{};  // hip, thigh, calf (none until the constructor's)
  std::array<Eigen::Vector3d, jump::kLegCount> start_feet_{};

  std::optional<jump::JumpAction> action_;  // the mapped action of this episode
  std::unique_ptr<JumpController> controller_;
  bool started_ = false;
  JumpPhase previous_phase_ = JumpPhase::kStand;
  jump::JumpRecord record_;
  std::optional<double> rest_time_;
  std::optional<bool> overrun_;  // at `duration`: whether the robot was in the air, and runs on
  bool feet_down_ = true;          // a foot was in contact at the last tick
  double touched_ = 0.0;           // s after reset: the last time a foot came down
  // The planner's best try and why it is infeasible, from this episode's
  // prior_action(): act() given that very action refuses it for the planner's
  // reason (the edge it cannot clear, the foot it loses) rather than for the
  // safety filter's finding on a clamped try.
  struct PriorRefusal {
    std::vector<double> raw_action;
    std::string reason;
    bool terrain = false;  // the plan was refused for an edge on the way
  };
  std::optional<PriorRefusal> prior_refusal_;
};

}  // namespace pronk::guided_jump
