#include "environment/jump_environment.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "control/invalid_argument.h"
#include "method/ballistics.h"
#include "method/orientation_trajectory.h"
#include "method/planner.h"

namespace pronk::guided_jump {
namespace {

constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
constexpr int32_t kActionSize = jump::kActionSize;
constexpr double kRestSpeed = 0.05;  // m/s: the CoM is at rest below this
constexpr double kMaxOverrun = 2.0;  // s past `duration` that a robot in the air may run on
constexpr double kHipRadiusPerLeg = 0.108;  // the hip motor's radius per m of leg (thigh + calf)

// The paper's Go1 workspace band of the trunk height (m), scaled like the ranges.
constexpr double kGo1WorkspaceZ[2] = {0.15, 0.40};

// The action ranges, the workspace band and the planner's length scale from the
// robot: its leg length over the Go1's (no leg model: the Go1's own numbers).
void deriveFromRobot(EnvironmentSettings* s, const std::optional<std::array<jump::LegGeometry, jump::kLegCount>>& legs) {
  double scale = 1.0;
  if (legs) {
    scale = jump::lengthScaleToGo1(jump::meanLegLength(*legs));
  }
  s->length_scale = scale;
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

}  // namespace

EnvironmentSettings EnvironmentSettings::read(const ParamReader& read) {
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
  s.reward.raw_action_limit = s.ranges.raw_limit;
  s.knee_clearance = read.real("knee_clearance");
  s.sideways_roll_rate_gain = read.real("sideways_roll_rate_gain");
  return s;
}

namespace {

Eigen::Matrix3d rotationZYX(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

const std::vector<pronk_param_decl>& EnvironmentSettings::parameters() {
static const std::vector<pronk_param_decl> decls = {
      {kDeclSize, "duration", PRONK_PARAM_REAL, 0, 0.01, 60.0, 0, "1.5", "s",
       "episode length, from reset; a robot in the air then runs on until 0.3 s after a foot is down"},
      // Empty: derived from the robot (action_mapping.h, scaledActionRanges).
      {kDeclSize, "action_min", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
       "lower ends of the 13 action ranges (T_th r_p theta_p r_v theta_v k d roll pitch yaw and rates; "
       "s, m, rad, m/s, rad, 1, m, rad, rad/s); empty: the paper's Go1 table with r_p and d scaled by the "
       "robot's leg length (thigh + calf) over the Go1's 0.426 m"},
      {kDeclSize, "action_max", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
       "upper ends of the 13 action ranges; empty: derived as action_min"},
      {kDeclSize, "workspace_z", PRONK_PARAM_VECTOR, 0, -10.0, 10.0, 0, "", "m",
       "trunk height band (2 numbers) of the reward's workspace term; empty: the paper's Go1 band 0.15 0.40 "
       "scaled by the robot's leg length over the Go1's 0.426 m (the paper's Aliengo: 0.20 0.60)"},
      {kDeclSize, "knee_clearance", PRONK_PARAM_REAL, 0, -1.0, 1.0, 0, "0.01", "m",
       "safety filter and planner (with a leg model): every knee stays this far above its stance foot's "
       "centre on the thrust path (-1: off)"},
      {kDeclSize, "sideways_roll_rate_gain", PRONK_PARAM_REAL, 0, -10.0, 10.0, 0, "1.5", "1/m",
       "planner: lift-off roll rate (rad/s) per m/s of lift-off velocity across the trunk of a Go1-sized "
       "robot (Froude-scaled to the robot's legs), clamped into the roll rate range (0: none)"},
  };
  return decls;
}

JumpEnvironment::JumpEnvironment(const pronk_host_api* host, const EnvironmentSettings& settings,
                                 std::optional<LegModels> legs, const std::string& no_legs)
    : host_(host), settings_(settings), legs_(std::move(legs)) {
  HoldController check(host, settings.jump.hold);  // throws for a robot the controller cannot drive
  n_ = check.jointCount();
  feet_ = check.footCount();
  if (!legs_ && host->log) {
    host->log(host->host, 1, ("jump: no analytic leg model (" + no_legs + "); the planner and the safety filter do "
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
  // The landing extension the flight phase would derive, resolved once: the
  // edge model and the controller take the same number.
  FlightSettings& flight = settings_.jump.flight;
  if (flight.extension < 0.0) {
    flight.extension = legs_ && feet_ == jump::kLegCount
                           ? FlightPhase::derivedExtension(*legs_, settings_.jump.hold.stance,
                                                           joint_motors_[2].effort, mass_, gravity_.norm())
                           : 0.0;
  }
}

jump::LandingStop JumpEnvironment::landingStop() const {
  const LandingSettings landing = settings_.jump.landing;
  return [landing](const Eigen::Vector3d& v) { return LandingPhase::landingStop(landing, v); };
}

void JumpEnvironment::reset(const double* task, int32_t task_size, const pronk_robot_state& state, double* observation) {
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
  const Eigen::Matrix3d R = rotationOf(state);
  standing_height_ = state.com_position[2] - start_.origin.z();
  com_to_trunk_ = R.transpose() * (vec(state.base_position) - vec(state.com_position));
  for (int f = 0; f < feet_ && f < jump::kLegCount; ++f) start_feet_[f] = start_.point(state.foot_position + 3 * f);
  controller_.reset();
  action_.reset();
  record_ = jump::JumpRecord{};
  prior_refusal_.reset();
  overrun_.reset();
  feet_down_ = true;
  touched_ = 0.0;
  started_ = false;
  previous_phase_ = JumpPhase::kStand;
  rest_time_.reset();
  has_task_ = true;
}

jump::TerrainEdges JumpEnvironment::terrainEdges(const Eigen::Vector2d& towards, double turn) const {
  jump::TerrainEdges terrain;
  constexpr double kStep = 0.01;         // m between samples of the surface
  constexpr double kBeyond = 0.3;        // m sampled past the target
  constexpr double kEdgeHeight = 0.01;   // m: a smaller change of height is no edge
  const double distance = towards.norm();
  if (!(distance > 0.0)) return terrain;
  const Eigen::Vector2d u = towards / distance;
  std::optional<double> before;
  for (double s = 0.0; s <= distance + kBeyond; s += kStep) {
    const Eigen::Vector3d world = start_.origin + start_.heading * Eigen::Vector3d(s * u.x(), s * u.y(), 0.0);
    const std::optional<TerrainTop> top = terrainTop(host_, world.x(), world.y());
    if (!top) return {};  // an older host, or nothing under the line: no edges known
    const double height = top->height - start_.origin.z();
    if (before && std::abs(height - *before) > kEdgeHeight) {
      terrain.edges.push_back({s - 0.5 * kStep, std::max(height, *before), height > *before});
    }
    before = height;
  }
  terrain.turn_rad = turn;
  terrain.tuck_time_s = FlightPhase::kBlendTime;
  terrain.descent_s = FlightPhase::kBlendTime + FlightPhase::kExtensionLead;
  terrain.descent_blend_s = FlightPhase::kBlendTime;
  terrain.landing_stop = landingStop();
  if (terrain.edges.empty() || !legs_) return terrain;
  // The hips, and the knees and feet at the flight's tuck and in the landing
  // pose, about the CoM. The hips are the motors, balls of about a ninth of a
  // leg in radius (the Go1's 0.046 m on its 0.426 m leg); the knees and feet the
  // foot's.
  const std::array<double, 3>& tuck = settings_.jump.flight.tuck;
  const Eigen::Vector3d q_tuck(tuck[0], tuck[1], tuck[2]);
  const std::array<double, 3>& stance = settings_.jump.hold.stance;
  const Eigen::Vector3d q_stance(stance[0], stance[1], stance[2]);
  const double extension = settings_.jump.flight.extension;  // resolved by the constructor
  terrain.landing_extension_m = extension;
  const double leg_radius = settings_.reward.foot_radius;
  const double hip_radius = kHipRadiusPerLeg * jump::meanLegLength(*legs_);
  terrain.body.clear();
  for (const jump::LegGeometry& leg : *legs_) {
    const Eigen::Vector3d hip = leg.hipPosition() + com_to_trunk_;
    const Eigen::Vector3d foot = jump::footPosition(leg, q_stance) - Eigen::Vector3d(0.0, 0.0, extension);
    const jump::LegIkResult ik = jump::solveLegIk(leg, foot);
    const Eigen::Vector3d knee = jump::kneePosition(leg, ik.ok() ? ik.q : q_stance);
    terrain.body.push_back({hip, hip, hip_radius});
    terrain.body.push_back({jump::kneePosition(leg, q_tuck) + com_to_trunk_, knee + com_to_trunk_, leg_radius});
    terrain.body.push_back(
        {jump::footPosition(leg, q_tuck) + com_to_trunk_, foot + com_to_trunk_, leg_radius, true, true});
  }
  return terrain;
}

std::vector<double> JumpEnvironment::priorAction(const double* observation, std::string* infeasible) {
  if (!has_task_) throw InvalidArgument("prior_action() before reset(): the planner needs the start pose");
  prior_refusal_.reset();  // only the last answer's best try is the planner's
  jump::PlannerConfig config;
  config.ranges = settings_.ranges;
  config.gravity = gravity_;
  config.start_com = Eigen::Vector3d(0, 0, standing_height_);
  config.standing_com_height = standing_height_;
  config.sideways_roll_rate_gain = settings_.sideways_roll_rate_gain;
  // The rule's constants were set for the Go1: Froude-scaled to this robot.
  config = config.scaledToRobot(settings_.length_scale);
  if (std::optional<jump::LegWorkspace> ws = workspace()) config.workspace = *ws;
  jump::JumpTarget target;
  target.displacement = Eigen::Vector3d(observation[0], observation[1], observation[2]);
  target.yaw_rad = observation[3];
  config.terrain = terrainEdges(target.displacement.head<2>(), target.yaw_rad);
  // Aimed short by where the controller's landing will stop the CoM.
  const jump::PlannedJump plan = jump::planPriorJump(target, config, landingStop());
  if (!plan.feasible && infeasible) *infeasible = "no feasible jump: " + plan.reason;
  const jump::ActionVector raw = jump::unmapAction(plan.action, settings_.ranges);
  std::vector<double> action(raw.begin(), raw.end());
  if (!plan.feasible) {
    prior_refusal_ = PriorRefusal{action, std::string(jump::planLimitName(plan.limit)) + ": " + plan.reason,
                                  plan.limit == jump::PlanLimit::kTerrain};
  }
  return action;
}

void JumpEnvironment::act(const double* raw_action) {
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
  const Eigen::Vector2d stop = landing && t_fall ? landingStop()(flight.velocity(*t_fall)) : Eigen::Vector2d(NAN, NAN);
  metric("predicted_rest_x", landing ? landing->x() + stop.x() : NAN);
  metric("predicted_rest_y", landing ? landing->y() + stop.y() : NAN);
  metric("action_excess", mapped.totalRawExcess());
  const jump::ActionVector physical = jump::toVector(mapped.action);
  for (int i = 0; i < kActionSize; ++i) {
    metric(std::string("action_") + jump::actionParameterName(static_cast<jump::ActionParameter>(i)), physical[i]);
  }

  // The safety filter: nothing runs that cannot work.
  jump::SafetyCheck ballistic;
  ballistic.gravity = gravity_;
  // The edges on the way: refused where the flight's model strikes one (the
  // planner keeps its clearance margin; the filter refuses only a strike).
  ballistic.terrain = terrainEdges(target.head<2>(), task_[3]);
  ballistic.terrain.clearance_m = 0.0;
  const std::optional<jump::LegWorkspace> ws = workspace();
  const jump::SafetyFilterResult safety = jump::safetyFilter(mapped.action, plan, target_com, ballistic, ws);
  if (safety.speed_shortfall) metric("predicted_speed_shortfall", *safety.speed_shortfall);
  if (ws) metric("planned_knee_clearance", jump::thrustKneeClearance(plan, mapped.action, *ws));
  // The planner's best try for a target it found no plan for is refused for the
  // planner's reason where the filter refuses it too, and always where the
  // planner could not clear an edge by its margin: a try it predicts passes an
  // edge closer than that is not flown into the edge.
  const bool planners_try = prior_refusal_ && std::equal(prior_refusal_->raw_action.begin(),
                                                         prior_refusal_->raw_action.end(), raw.begin());
  // Said once, for the try the episode takes: a policy may ask the planner for
  // other targets first (an aim it then falls back from).
  if (planners_try && host_->log) {
    host_->log(host_->host, 1, ("jump: the ballistic planner found no feasible jump: " + prior_refusal_->reason).c_str());
  }
  if (planners_try && prior_refusal_->terrain) throw Rejected(prior_refusal_->reason);
  if (!safety.verdict) {
    if (planners_try) throw Rejected(prior_refusal_->reason);
    throw Rejected(std::string(jump::safetyIssueName(safety.verdict.issue)) + ": " + safety.verdict.reason);
  }

  JumpSettings js = settings_.jump;
  js.action.assign(physical.begin(), physical.end());
  js.azimuth = azimuth;
  js.landing_height = target.z();
  js.legs = legs_;
  controller_ = std::make_unique<JumpController>(host_, js);
}

bool JumpEnvironment::step(const pronk_robot_state& state, double* torque) {
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
  const double t = state.time - reset_time_;
  bool down = false;
  for (int f = 0; f < feet_; ++f) down = down || state.foot_in_contact[f] != 0;
  if (down && !feet_down_) touched_ = t;
  feet_down_ = down;
  if (t < settings_.duration - 1e-9) return false;
  // A robot in the air at `duration` (a far drop, a high arc over an edge, a
  // bounce) is not cut off there: it runs on until its landing has its gains
  // back, kLandingRamp after a foot is down again.
  if (!overrun_) overrun_ = !down;
  if (!*overrun_ || t >= settings_.duration + kMaxOverrun - 1e-9) return true;
  return down && t >= touched_ + LandingPhase::kLandingRamp - 1e-9;
}

double JumpEnvironment::finish(const pronk_robot_state& state) {
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

void JumpEnvironment::metric(const std::string& name, double value) {
  if (host_->struct_size >= offsetof(pronk_host_api, report_metric) + sizeof(host_->report_metric) &&
      host_->report_metric) {
    host_->report_metric(host_->host, name.c_str(), value);
  }
}

StartFrame JumpEnvironment::frame() const {
  if (controller_ && controller_->plan()) return {controller_->startOrigin(), controller_->startHeading()};
  return start_;
}

std::optional<jump::LegWorkspace> JumpEnvironment::workspace() const {
  if (!legs_ || feet_ != jump::kLegCount) return std::nullopt;
  jump::LegWorkspace ws;
  ws.legs = *legs_;
  ws.feet = start_feet_;
  ws.com_to_trunk = com_to_trunk_;
  ws.mass = mass_;
  ws.joint_motors = joint_motors_;
  ws.motor = settings_.jump.hold.motor;
  ws.knee_clearance = settings_.knee_clearance;
  return ws;
}

jump::BodyState JumpEnvironment::bodyState(const pronk_robot_state& s, const StartFrame& S) const {
  jump::BodyState b;
  b.time = s.time - reset_time_;
  b.base_position = S.point(s.base_position);
  b.orientation = Eigen::Quaterniond(S.heading.transpose() * rotationOf(s));
  b.com_position = S.point(s.com_position);
  b.com_velocity = S.direction(s.com_velocity);
  b.angular_velocity = S.direction(s.base_angular_velocity);
  return b;
}

void JumpEnvironment::onPhaseChange(JumpPhase phase, const pronk_robot_state& s) {
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

void JumpEnvironment::recordTick(const pronk_robot_state& s, const double* torque) {
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

}  // namespace pronk::guided_jump
