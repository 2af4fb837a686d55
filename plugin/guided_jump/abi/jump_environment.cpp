// Environment `jump`: one episode is one jump to a target, driven by one action
// (the paper's 13 jump parameters).
//   observation (6): the target x, y, z (m), yaw, roll, pitch (rad), relative to
//                    the start, in the robot's initial heading frame;
//   action (13):     the policy's raw outputs, clipped to +-raw_limit and mapped
//                    affinely onto the action ranges (method/action_mapping.h);
//   act():           the safety filter (method/safety_filter.h) runs before
//                    anything moves: a flight whose apex stays below the target,
//                    a thrust path that loses a foot's reach, or one the motors
//                    cannot push, is rejected (PRONK_REJECTED, with why);
//   step():          the guided_jump phase machine (control/jump_controller.h);
//   finish():        the paper's reward with every term reported as a metric
//                    (method/reward.h), plus the plan's predictions;
//   prior_action():  the analytic ballistic planner (method/planner.h) as raw
//                    outputs: `pronk run --policy ballistic`; PRONK_REJECTED
//                    (ABI 1.4) with the plan's best try when it finds no
//                    feasible jump.
// The frame of the reward and the plan is the controller's start frame S (origin
// on the ground below the CoM at the thrust start, x along the heading then).
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "abi/abi_boundary.h"
#include "abi/factories.h"
#include "abi/host_leg_geometry.h"
#include "abi/jump_params.h"
#include "control/param_reader.h"
#include "control/jump_controller.h"
#include "control/robot_state.h"
#include "method/action_mapping.h"
#include "method/ballistics.h"
#include "method/orientation_trajectory.h"
#include "method/planner.h"
#include "method/reward.h"
#include "method/safety_filter.h"

namespace pronk::guided_jump {
namespace {

constexpr int32_t kObservationSize = 6;
constexpr int32_t kActionSize = jump::kActionSize;
constexpr double kRestSpeed = 0.05;  // m/s: the CoM is at rest below this

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
  bool workspace_check = true;
  double max_speed_shortfall = 0.1;
  double knee_clearance = 0.01;
  double sideways_roll_rate_gain = 0.0;
  // As set (13 numbers each), or empty: derived from the robot's leg length once
  // the host is known (deriveFromRobot).
  std::vector<double> action_min, action_max;
  bool derive_workspace_z = false;
};

// The paper's Go1 workspace band of the trunk height (m), scaled like the ranges.
constexpr double kGo1WorkspaceZ[2] = {0.15, 0.40};

// The action ranges and the workspace band from the robot: lengths scaled by
// its leg length over the Go1's (no leg model: the Go1's own numbers).
void deriveFromRobot(EnvironmentSettings* s, const std::optional<std::array<jump::LegGeometry, jump::kLegCount>>& legs) {
  double scale = 1.0;
  if (legs) {
    double length = 0.0;
    for (const jump::LegGeometry& leg : *legs) length += (leg.thigh_length + leg.calf_length) / jump::kLegCount;
    scale = jump::lengthScaleToGo1(length);
  }
  const jump::ActionRanges derived = jump::scaledActionRanges(scale);
  for (int i = 0; i < kActionSize; ++i) {
    s->ranges.bounds[i] = {s->action_min.empty() ? derived.bounds[i].min : s->action_min[i],
                           s->action_max.empty() ? derived.bounds[i].max : s->action_max[i]};
  }
  try {
    s->ranges.check();
  } catch (const std::invalid_argument& e) {
    throw InvalidArgument(std::string("parameters 'action_min' / 'action_max': ") + e.what());
  }
  if (s->derive_workspace_z) {
    s->reward.workspace_z_min = scale * kGo1WorkspaceZ[0];
    s->reward.workspace_z_max = scale * kGo1WorkspaceZ[1];
  }
}

EnvironmentSettings readSettings(const ParamReader& read) {
  EnvironmentSettings s;
  JumpSettings::read(read, &s.jump);
  s.duration = read.real("duration");
  // Filled in and checked once the robot is known (deriveFromRobot).
  s.action_min = read.vector("action_min");
  s.action_max = read.vector("action_max");
  for (const auto& [name, bounds] : {std::pair{"action_min", &s.action_min}, std::pair{"action_max", &s.action_max}}) {
    if (!bounds->empty() && bounds->size() != kActionSize) {
      throw InvalidArgument(std::string("parameter '") + name + "' has " + std::to_string(bounds->size()) +
                            " numbers; it takes 13, or none for the robot's own");
    }
  }
  s.ranges.raw_limit = read.real("raw_limit");
  s.reward.friction_coefficient = read.real("friction_coefficient");
  const std::vector<double> band = read.vector("workspace_z");
  if (band.size() != 0 && band.size() != 2) {
    throw InvalidArgument("parameter 'workspace_z' has " + std::to_string(band.size()) +
                          " numbers; it takes 2 (low, high), or none for the robot's own");
  }
  s.derive_workspace_z = band.empty();
  if (!s.derive_workspace_z) {
    s.reward.workspace_z_min = band[0];
    s.reward.workspace_z_max = band[1];
  }
  s.reward.error_scale = read.real("error_scale");
  s.reward.raw_action_limit = s.ranges.raw_limit;
  s.workspace_check = read.integer("workspace_check") != 0;
  s.max_speed_shortfall = read.real("max_speed_shortfall");
  s.knee_clearance = read.real("knee_clearance");
  s.sideways_roll_rate_gain = read.real("sideways_roll_rate_gain");
  return s;
}

Eigen::Quaterniond quaternionOf(const pronk_robot_state& s) {
  return Eigen::Quaterniond(s.base_quaternion[0], s.base_quaternion[1], s.base_quaternion[2], s.base_quaternion[3])
      .normalized();
}


Eigen::Matrix3d rotationZYX(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

class JumpEnvironment {
 public:
  JumpEnvironment(const pronk_host_api* host, const EnvironmentSettings& settings)
      : host_(host), settings_(settings) {
    HoldController check(host, settings.jump.hold);  // throws for a robot the controller cannot drive
    n_ = check.jointCount();
    feet_ = check.footCount();
    std::string why;
    legs_ = legGeometryFromHost(host, &why);
    if (!legs_ && settings.workspace_check && host->log) {
      host->log(host->host, 1, ("jump: no analytic leg model (" + why + "); the planner and the safety filter do "
                                "not check the leg workspace")
                                   .c_str());
    }
    if (!legs_ && (settings.action_min.empty() || settings.action_max.empty() || settings.derive_workspace_z) &&
        host->log) {
      host->log(host->host, 1, "jump: no leg length to scale the action ranges and the workspace band by; they are "
                               "the Go1's (set action_min, action_max and workspace_z)");
    }
    deriveFromRobot(&settings_, legs_);
    double g[3] = {0, 0, 0};
    host->gravity(host->host, g);
    gravity_ = vec(g);
    mass_ = host->total_mass(host->host);
    // Joints come as (hip, thigh, calf) per leg: the weakest leg's limits per kind,
    // as the controller saturates them (a limit the model lacks: none).
    const std::vector<jump::MotorLimits> motors = motorLimitsFromHost(host, n_);
    for (int j = 0; j < n_; ++j) {
      jump::MotorLimits& kind = joint_motors_[j % 3];
      kind.effort = std::min(kind.effort, motors[j].effort);
      kind.velocity = std::min(kind.velocity, motors[j].velocity);
    }
    limits_.position_min.resize(n_);
    limits_.position_max.resize(n_);
    limits_.velocity_max.resize(n_);
    for (int j = 0; j < n_; ++j) {
      double lo = 0, hi = 0, v = 0;
      host->joint_limits(host->host, j, &lo, &hi, &v, nullptr);
      limits_.position_min(j) = lo;
      limits_.position_max(j) = hi;
      limits_.velocity_max(j) = std::isfinite(v) && v > 0 ? v : 1e9;
    }
    if (host->foot_radius) settings_.reward.foot_radius = host->foot_radius(host->host, 0);
  }

  void reset(const double* task, int32_t task_size, const pronk_robot_state& state, double* observation) {
    if (!task || task_size != kObservationSize) {
      throw InvalidArgument("the jump task has 6 numbers (x, y, z, yaw, roll, pitch); got " + std::to_string(task_size));
    }
    if (!observation) throw InvalidArgument("no observation buffer");
    for (int i = 0; i < kObservationSize; ++i) {
      if (!std::isfinite(task[i])) throw InvalidArgument("task number " + std::to_string(i) + " is not finite");
    }
    if (state.joint_count != n_ || state.foot_count != feet_) throw InvalidArgument("the state does not fit the robot");
    for (int i = 0; i < kObservationSize; ++i) task_[i] = observation[i] = task[i];
    reset_time_ = state.time;
    start_ = takeOffFrame(host_, state);
    const Eigen::Matrix3d R = quaternionOf(state).toRotationMatrix();
    standing_height_ = state.com_position[2] - start_.origin.z();
    com_to_trunk_ = R.transpose() * (vec(state.base_position) - vec(state.com_position));
    for (int f = 0; f < feet_ && f < jump::kLegCount; ++f) start_feet_[f] = start_.point(state.foot_position + 3 * f);
    controller_.reset();
    action_.reset();
    record_ = jump::JumpRecord{};
    started_ = false;
    previous_phase_ = JumpPhase::kStand;
    rest_time_.reset();
    has_task_ = true;
  }

  // The planner's action for an observation; *infeasible gets its reason when
  // it found no feasible plan (the action is then its best try).
  std::vector<double> priorAction(const double* observation, std::string* infeasible) {
    if (!has_task_) throw InvalidArgument("prior_action() before reset(): the planner needs the start pose");
    jump::PlannerConfig config;
    config.ranges = settings_.ranges;
    config.gravity = gravity_;
    config.start_com = Eigen::Vector3d(0, 0, standing_height_);
    config.standing_com_height = standing_height_;
    config.sideways_roll_rate_gain = settings_.sideways_roll_rate_gain;
    if (std::optional<jump::LegWorkspace> ws = workspace()) config.workspace = *ws;
    jump::JumpTarget target;
    target.displacement = Eigen::Vector3d(observation[0], observation[1], observation[2]);
    target.yaw_rad = observation[3];
    // Aimed short by where the controller's landing will stop the CoM.
    const LandingSettings& landing = settings_.jump.landing;
    const jump::PlannedJump plan = jump::planPriorJump(
        target, config, [&landing](const Eigen::Vector3d& v) { return LandingPhase::landingStop(landing, v); });
    if (!plan.feasible && host_->log) {
      host_->log(host_->host, 1, ("jump: the ballistic planner found no feasible jump: " + plan.reason).c_str());
    }
    if (!plan.feasible && infeasible) *infeasible = "no feasible jump: " + plan.reason;
    const jump::ActionVector raw = jump::unmapAction(plan.action, settings_.ranges);
    return std::vector<double>(raw.begin(), raw.end());
  }

  void act(const double* raw_action) {
    if (!has_task_) throw InvalidArgument("act() before reset()");
    jump::ActionVector raw{};
    for (int i = 0; i < kActionSize; ++i) {
      if (std::isnan(raw_action[i])) throw InvalidArgument("action number " + std::to_string(i) + " is NaN");
      raw[i] = raw_action[i];
    }
    const jump::MappedAction mapped = jump::mapAction(raw, settings_.ranges);
    action_ = mapped.action;
    record_.raw_action = Eigen::Map<const Eigen::VectorXd>(raw.data(), kActionSize);
    const Eigen::Vector3d target(task_[0], task_[1], task_[2]);
    const double azimuth = jump::jumpPlaneAzimuth(target);

    // The plan as the controller will make it (from the reset pose), and its flight.
    const Eigen::Vector3d com_start(0, 0, standing_height_);
    const jump::ThrustPlan plan(mapped.action, azimuth, com_start, Eigen::Vector3d::Zero());
    const jump::PointState lift_off = plan.liftOff();
    const jump::BallisticFlight flight({lift_off.position, lift_off.velocity}, gravity_);
    const double t_lift_off = settings_.jump.start_delay + plan.duration();
    const Eigen::Vector3d target_com(target.x(), target.y(), target.z() + standing_height_);
    metric("planned_lift_off_time", t_lift_off);
    metric("planned_lift_off_x", lift_off.position.x());
    metric("planned_lift_off_y", lift_off.position.y());
    metric("planned_lift_off_z", lift_off.position.z());
    metric("planned_lift_off_vx", lift_off.velocity.x());
    metric("planned_lift_off_vy", lift_off.velocity.y());
    metric("planned_lift_off_vz", lift_off.velocity.z());
    metric("planned_apex_time", t_lift_off + flight.apexTime());
    metric("planned_apex_height", flight.apexHeight() - standing_height_);
    const std::optional<double> t_fall = flight.landingTime(target_com.z());
    metric("planned_touchdown_time", t_fall ? t_lift_off + *t_fall : NAN);
    metric("planned_flight_time", t_fall ? *t_fall : NAN);
    const std::optional<Eigen::Vector3d> landing = flight.landingPoint(target_com.z());
    metric("predicted_landing_x", landing ? landing->x() : NAN);
    metric("predicted_landing_y", landing ? landing->y() : NAN);
    metric("predicted_landing_z", landing ? landing->z() - standing_height_ : NAN);
    metric("action_excess", mapped.totalRawExcess());
    const jump::ActionVector physical = jump::toVector(mapped.action);
    for (int i = 0; i < kActionSize; ++i) {
      metric(std::string("action_") + jump::actionParameterName(static_cast<jump::ActionParameter>(i)), physical[i]);
    }

    // The safety filter: nothing runs that cannot work.
    jump::SafetyCheck ballistic;
    ballistic.gravity = gravity_;
    const std::optional<jump::LegWorkspace> ws = workspace();
    const jump::SafetyFilterResult safety = jump::safetyFilter(mapped.action, plan, target_com, ballistic, ws);
    if (safety.speed_shortfall) metric("predicted_speed_shortfall", *safety.speed_shortfall);
    if (ws) metric("planned_knee_clearance", jump::thrustKneeClearance(plan, mapped.action, *ws));
    if (!safety.verdict) {
      throw Rejected(std::string(jump::safetyIssueName(safety.verdict.issue)) + ": " + safety.verdict.reason);
    }

    JumpSettings js = settings_.jump;
    js.action.assign(physical.begin(), physical.end());
    js.azimuth = azimuth;
    js.landing_height = target.z();
    js.legs = legs_;
    controller_ = std::make_unique<JumpController>(host_, js);
  }

  bool step(const pronk_robot_state& state, double* torque) {
    if (!controller_) throw InvalidArgument("step() before act(): the episode has no action");
    if (!torque) throw InvalidArgument("no torque buffer");
    if (!started_) {
      controller_->reset(state);
      started_ = true;
    }
    controller_->compute(state, torque);
    const JumpPhase phase = controller_->phase();
    if (phase != previous_phase_) onPhaseChange(phase, state);
    previous_phase_ = phase;
    if (phase == JumpPhase::kThrust || phase == JumpPhase::kExplosive) recordTick(state, torque);
    if (record_.touchdown && !rest_time_) {
      if (vec(state.com_velocity).norm() < kRestSpeed) {
        rest_time_ = state.time - reset_time_;
      }
    } else if (rest_time_ && vec(state.com_velocity).norm() >= kRestSpeed) {
      rest_time_.reset();  // moving again: not at rest yet
    }
    return state.time - reset_time_ >= settings_.duration - 1e-9;
  }

  double finish(const pronk_robot_state& state) {
    if (!has_task_) throw InvalidArgument("finish() before reset()");
    const StartFrame S = frame();
    record_.tick_s = kControlPeriod;
    record_.joint_limits = limits_;
    record_.final_state = bodyState(state, S);
    record_.final_foot_positions.clear();
    for (int f = 0; f < feet_; ++f) record_.final_foot_positions.push_back(S.point(state.foot_position + 3 * f));
    record_.target.displacement = Eigen::Vector3d(task_[0], task_[1], task_[2]);
    record_.target.orientation = Eigen::Quaterniond(rotationZYX(task_[4], task_[5], task_[3]));
    if (controller_ && controller_->plan()) {
      const jump::PointState& lo = controller_->plan()->liftOff();
      record_.plan.lift_off_com_position = lo.position;
      record_.plan.lift_off_com_velocity = lo.velocity;
    }
    if (action_) {
      const jump::JumpAction& a = *action_;
      record_.plan.lift_off_orientation =
          Eigen::Quaterniond(rotationZYX(a.liftoff_rpy_rad.x(), a.liftoff_rpy_rad.y(), a.liftoff_rpy_rad.z()));
      record_.plan.lift_off_angular_velocity = jump::worldAngularVelocity(a.liftoff_rpy_rad, a.liftoff_rpy_rate_radps);
    }
    if (record_.raw_action.size() == 0) record_.raw_action = Eigen::VectorXd::Zero(kActionSize);
    const jump::RewardBreakdown r = jump::computeReward(record_, settings_.reward);
    for (const jump::RewardTerm* term : r.terms()) metric(term->name, term->cost());
    metric("running_cost", r.running_cost);
    metric("terminal_cost", r.terminal_cost);
    metric("cost_gate", r.penalty_gate);  // exp(-C^2 / 5); not a cost term
    metric("landing_reward", r.landing_reward);
    metric("reward_error_xy", r.landing_error_xy);
    metric("reward_error_z", r.landing_error_z);
    if (record_.lift_off) metric("lift_off_time", record_.lift_off->time);
    if (record_.apex) metric("apex_time", record_.apex->time);
    if (record_.touchdown) {
      metric("touchdown_time", record_.touchdown->time);
      // The trunk's attitude as the feet touch down (ZYX Euler, start frame): what the
      // flight's angular momentum did to it.
      const Eigen::Vector3d rpy = rpyFromRotation(record_.touchdown->orientation.toRotationMatrix());
      metric("touchdown_roll", rpy.x());
      metric("touchdown_pitch", rpy.y());
    }
    if (record_.lift_off) {
      const Eigen::Vector3d dv = record_.lift_off->com_velocity - record_.plan.lift_off_com_velocity;
      const Eigen::Vector3d dp = record_.lift_off->com_position - record_.plan.lift_off_com_position;
      metric("lift_off_velocity_error", dv.norm());
      metric("lift_off_position_error", dp.norm());
    }
    metric("rest_time", rest_time_ ? *rest_time_ : NAN);
    has_task_ = false;
    return r.reward;
  }

 private:
  void metric(const std::string& name, double value) {
    if (host_->struct_size >= offsetof(pronk_host_api, report_metric) + sizeof(host_->report_metric) &&
        host_->report_metric) {
      host_->report_metric(host_->host, name.c_str(), value);
    }
  }

  // The controller's S once the thrust has begun, the reset's before.
  StartFrame frame() const {
    if (controller_ && controller_->plan()) return {controller_->startOrigin(), controller_->startHeading()};
    return start_;
  }

  std::optional<jump::LegWorkspace> workspace() const {
    if (!legs_ || !settings_.workspace_check || feet_ != jump::kLegCount) return std::nullopt;
    jump::LegWorkspace ws;
    ws.legs = *legs_;
    ws.feet = start_feet_;
    ws.com_to_trunk = com_to_trunk_;
    ws.mass = mass_;
    ws.joint_motors = joint_motors_;
    ws.motor = settings_.jump.hold.motor;
    ws.max_speed_shortfall = settings_.max_speed_shortfall;
    ws.knee_clearance = settings_.knee_clearance;
    return ws;
  }

  jump::BodyState bodyState(const pronk_robot_state& s, const StartFrame& S) const {
    jump::BodyState b;
    b.time = s.time - reset_time_;
    b.base_position = S.point(s.base_position);
    b.orientation = Eigen::Quaterniond(S.heading.transpose() * quaternionOf(s).toRotationMatrix());
    b.com_position = S.point(s.com_position);
    b.com_velocity = S.direction(s.com_velocity);
    b.angular_velocity = S.direction(s.base_angular_velocity);
    return b;
  }

  void onPhaseChange(JumpPhase phase, const pronk_robot_state& s) {
    const StartFrame S = frame();
    if (phase == JumpPhase::kThrust) record_.start_base_position = S.point(s.base_position);
    if (phase == JumpPhase::kFlight) {
      record_.lift_off = bodyState(s, S);
      if (const std::optional<Eigen::Vector3d> w = wholeBodyRate(host_)) {
        const Eigen::Vector3d w_S = S.heading.transpose() * *w;
        metric("lift_off_body_rate_x", w_S.x());
        metric("lift_off_body_rate_y", w_S.y());
        metric("lift_off_body_rate_z", w_S.z());
      }
    }
    if (phase == JumpPhase::kDescend) record_.apex = bodyState(s, S);
    if (phase == JumpPhase::kLanding && record_.lift_off) record_.touchdown = bodyState(s, S);
  }

  void recordTick(const pronk_robot_state& s, const double* torque) {
    const StartFrame S = frame();
    jump::TickSample t;
    t.time = s.time - reset_time_;
    t.q = Eigen::Map<const Eigen::VectorXd>(s.q, n_);
    t.qd = Eigen::Map<const Eigen::VectorXd>(s.qd, n_);
    t.tau_commanded = controller_->commandedTorque();
    t.tau_applied = Eigen::Map<const Eigen::VectorXd>(torque, n_);
    for (int f = 0; f < feet_; ++f) {
      t.foot_force.push_back(s.foot_force ? S.direction(s.foot_force + 3 * f) : Eigen::Vector3d::Zero());
      t.foot_in_contact.push_back(s.foot_in_contact[f] != 0);
    }
    t.base_position = S.point(s.base_position);
    record_.ticks.push_back(std::move(t));
  }

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
};

JumpEnvironment* self(void* instance) { return static_cast<JumpEnvironment*>(instance); }

void need(const void* instance, const void* pointer) {
  if (!instance || !pointer) throw InvalidArgument("called without an instance or a required pointer");
}

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const std::vector<pronk_param_decl>& decls = environmentParamDecls();
    const ParamReader read(params, param_count, decls.data(), static_cast<int32_t>(decls.size()));
    *instance = new JumpEnvironment(host, readSettings(read));
  });
}

pronk_status reset(void* instance, const double* task, int32_t task_size, uint64_t, const pronk_robot_state* state,
                   double* observation, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    self(instance)->reset(task, task_size, *state, observation);
  });
}

pronk_status act(void* instance, const double* action, char* error, size_t error_size) {
  std::string rejection;
  const pronk_status status = guarded(error, error_size, [&] {
    need(instance, action);
    try {
      self(instance)->act(action);
    } catch (const Rejected& e) {
      rejection = e.what();
    }
  });
  if (status != PRONK_OK || rejection.empty()) return status;
  writeError(error, error_size, rejection.c_str());
  return PRONK_REJECTED;
}

pronk_status step(void* instance, const pronk_robot_state* state, double* torque, int32_t* done, char* error,
                  size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    if (!done) throw InvalidArgument("no done flag");
    *done = self(instance)->step(*state, torque) ? 1 : 0;
  });
}

pronk_status finish(void* instance, const pronk_robot_state* state, double* reward, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    if (!reward) throw InvalidArgument("no reward pointer");
    *reward = self(instance)->finish(*state);
  });
}

pronk_status priorAction(void* instance, const double* observation, double* action, char* error, size_t error_size) {
  std::string infeasible;
  const pronk_status status = guarded(error, error_size, [&] {
    need(instance, observation);
    if (!action) throw InvalidArgument("no action buffer");
    const std::vector<double> a = self(instance)->priorAction(observation, &infeasible);
    std::copy(a.begin(), a.end(), action);
  });
  // A host before 1.4 takes any status but PRONK_OK for an error.
  if (status != PRONK_OK || infeasible.empty() || negotiatedAbiMinor() < 4) return status;
  writeError(error, error_size, infeasible.c_str());
  return PRONK_REJECTED;
}

void destroy(void* instance) { delete self(instance); }

// ABI 1.3: every metric this environment reports, declared, so that the host's
// table, results files and video take them from here (docs/results-format.md).
struct MetricTable {
  std::vector<std::string> names;  // owns the generated names (action_*, cost terms)
  std::vector<pronk_metric_decl> decls;
};

const MetricTable& metricTable() {
  static const MetricTable table = [] {
    MetricTable t;
    struct Plain {
      const char* name;
      uint32_t kind;
      const char* unit;
      const char* description;
      const char* column;
      const char* pairs_with;
    };
    const Plain plain[] = {
        {"planned_lift_off_time", PRONK_METRIC_TIME, "s", "the plan's lift-off", "lift-off s", "lift_off"},
        {"planned_apex_time", PRONK_METRIC_TIME, "s", "the plan's apex", "apex s", "apex_time"},
        // Beside the controller's touchdown, not the host's first contact: a toe that
        // brushes the ground just after lift-off is a contact but not the landing.
        {"planned_touchdown_time", PRONK_METRIC_TIME, "s", "the plan's touchdown on the target's surface",
         "touchdown s", "touchdown_time"},
        {"predicted_landing_x", PRONK_METRIC_VALUE, "m", "the plan's CoM landing point, start frame", "pred. x m",
         nullptr},
        {"predicted_landing_y", PRONK_METRIC_VALUE, "m", "the plan's CoM landing point, start frame", "pred. y m",
         nullptr},
        {"predicted_landing_z", PRONK_METRIC_VALUE, "m", "the plan's landing height above the take-off surface",
         nullptr, nullptr},
        {"planned_lift_off_x", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_y", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_z", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_vx", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_lift_off_vy", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_lift_off_vz", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_flight_time", PRONK_METRIC_VALUE, "s", "the plan's flight from lift-off to the target's surface",
         nullptr, nullptr},
        {"planned_apex_height", PRONK_METRIC_VALUE, "m", "the plan's CoM apex above standing", nullptr, nullptr},
        {"action_excess", PRONK_METRIC_VALUE, "1", "raw action beyond +-raw_limit, summed", nullptr, nullptr},
        {"predicted_speed_shortfall", PRONK_METRIC_VALUE, "m/s",
         "the safety filter's torque check: lift-off speed the motors are predicted to miss", nullptr, nullptr},
        {"running_cost", PRONK_METRIC_VALUE, "1", "the reward's running (thrust) costs, summed", nullptr, nullptr},
        {"terminal_cost", PRONK_METRIC_VALUE, "1", "the reward's lift-off and touchdown costs, summed", nullptr,
         nullptr},
        {"cost_gate", PRONK_METRIC_VALUE, "1", "exp(-C^2 / 5), the gate the costs put on the landing reward", nullptr,
         nullptr},
        {"landing_reward", PRONK_METRIC_VALUE, "1", "R_lt, the landing-target reward before the gate", nullptr,
         nullptr},
        {"reward_error_xy", PRONK_METRIC_VALUE, "m", "the reward's horizontal landing error", nullptr, nullptr},
        {"reward_error_z", PRONK_METRIC_VALUE, "m", "the reward's vertical landing error", nullptr, nullptr},
        {"lift_off_time", PRONK_METRIC_TIME, "s", "the controller's flight phase began", nullptr, nullptr},
        {"apex_time", PRONK_METRIC_TIME, "s", "the CoM's vertical velocity turned negative", nullptr, nullptr},
        {"touchdown_time", PRONK_METRIC_TIME, "s", "the controller's landing phase began", nullptr, nullptr},
        {"touchdown_roll", PRONK_METRIC_VALUE, "rad", "trunk roll at touchdown (ZYX, start frame)", nullptr, nullptr},
        {"touchdown_pitch", PRONK_METRIC_VALUE, "rad", "trunk pitch at touchdown (ZYX, start frame)", nullptr,
         nullptr},
        {"lift_off_velocity_error", PRONK_METRIC_VALUE, "m/s", "|CoM velocity at lift-off - the plan's|", nullptr,
         nullptr},
        {"lift_off_position_error", PRONK_METRIC_VALUE, "m", "|CoM at lift-off - the plan's|", nullptr, nullptr},
        {"lift_off_body_rate_x", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"lift_off_body_rate_y", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"lift_off_body_rate_z", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"rest_time", PRONK_METRIC_TIME, "s", "after touchdown, the CoM's speed stays below 0.05 m/s from here",
         nullptr, nullptr},
    };
    // Generated names first, so that their storage does not move afterwards.
    const jump::RewardBreakdown breakdown;
    for (const jump::RewardTerm* term : breakdown.terms()) t.names.push_back(term->name);
    for (int i = 0; i < kActionSize; ++i) {
      t.names.push_back(std::string("action_") + jump::actionParameterName(static_cast<jump::ActionParameter>(i)));
    }
    for (const Plain& m : plain) {
      t.decls.push_back({sizeof(pronk_metric_decl), m.name, m.kind, m.unit, m.description, m.column, m.pairs_with});
    }
    const size_t terms = breakdown.terms().size();
    for (size_t k = 0; k < terms; ++k) {
      t.decls.push_back({sizeof(pronk_metric_decl), t.names[k].c_str(), PRONK_METRIC_PENALTY, "1",
                         "a cost term of the paper's reward (weight x value)", nullptr, nullptr});
    }
    for (int i = 0; i < kActionSize; ++i) {
      const auto p = static_cast<jump::ActionParameter>(i);
      t.decls.push_back({sizeof(pronk_metric_decl), t.names[terms + i].c_str(), PRONK_METRIC_VALUE,
                         jump::actionParameterUnit(p), "the mapped action parameter", nullptr, nullptr});
    }
    return t;
  }();
  return table;
}

const char* const kTaskNames[kObservationSize] = {"x", "y", "z", "yaw", "roll", "pitch"};
// The mirror image across the start's x-z plane: y, yaw and roll change sign.
const double kTaskMirror[kObservationSize] = {1, -1, 1, -1, -1, 1};

const pronk_marker_decl kMarkers[] = {
    {sizeof(pronk_marker_decl), PRONK_MARKER_ARC, "planned flight",
     {"planned_lift_off_x", "planned_lift_off_y", "planned_lift_off_z", "planned_lift_off_vx", "planned_lift_off_vy",
      "planned_lift_off_vz", "planned_flight_time"}},
    {sizeof(pronk_marker_decl), PRONK_MARKER_POINT, "predicted landing",
     {"predicted_landing_x", "predicted_landing_y", "predicted_landing_z", nullptr, nullptr, nullptr, nullptr}},
};

const pronk_environment_ops kOps = {sizeof(pronk_environment_ops), reset, act, step, finish, destroy, priorAction};

}  // namespace

const pronk_factory* jumpEnvironmentFactory() {
  static const pronk_factory factory = {
      sizeof(pronk_factory),
      PRONK_FACTORY_ENVIRONMENT,
      "jump",
      "one jump to a target per episode: 6 target numbers in, 13 raw jump parameters, the paper's reward; "
      "safety filter before the jump; prior_action is the analytic ballistic planner",
      static_cast<int32_t>(environmentParamDecls().size()),
      environmentParamDecls().data(),
      0,
      kObservationSize,
      kActionSize,
      kControlPeriod,
      create,
      nullptr,
      &kOps,
      static_cast<int32_t>(metricTable().decls.size()),
      metricTable().decls.data(),
      kTaskNames,
      kObservationSize,
      static_cast<int32_t>(std::size(kMarkers)),
      kMarkers,
      kTaskMirror,
  };
  return &factory;
}

}  // namespace pronk::guided_jump
