#include "abi/jump_params.h"

#include <string>

#include <fmt/format.h>

#include "abi/abi_boundary.h"
#include "method/action_mapping.h"

namespace pronk::guided_jump {
namespace {

constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);

constexpr const char* kMotorDoc =
    "joint motors: dc (torque falls linearly with speed to none at the URDF velocity limit, the paper's DC motor) "
    "or effort (the URDF effort limit at any speed)";
constexpr const char* kFeedforwardDoc =
    "thrust feed-forward: gravity (m g, the paper's), dynamic (m (a_ref + g)) or dynamic_angular (dynamic and the "
    "orientation plan's rate of angular momentum)";

// The stance controller's (control/hold_controller.h), both factories.
const pronk_param_decl kHoldParamDecls[] = {
    // Defaults from the platform (ABI 1.5); the Go1's for a host before 1.5.
    {kDeclSize, "kp", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "100", "N m/rad",
     "joint stiffness towards the stance (default: the platform's <joints kp>)", "kp"},
    {kDeclSize, "kd", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "2", "N m s/rad",
     "joint damping (default: the platform's <joints kd>)", "kd"},
    {kDeclSize, "stance", PRONK_PARAM_VECTOR, 0, -3.2, 3.2, 3, "0 0.75 -1.5", "rad",
     "joint positions held by every leg: hip, thigh, calf (default: the platform's <initial stance>)", "stance"},
    {kDeclSize, "gravity_compensation", PRONK_PARAM_INT, 0, 0.0, 1.0, 0, "1", "",
     "1: feet in contact carry the weight through J^T f; 0: PD only"},
    {kDeclSize, "motor", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "effort", "", kMotorDoc},
};

// The phase machine's (control/jump_phases.h), both factories.
// The planned acceleration in the feed-forward: the PD alone lags a hard thrust
// (measured on the Go1's 0.7 m jump: 0.2 m/s short at lift-off, 11 cm off
// instead of 3; docs/method.md).
const pronk_param_decl kFeedforward = {kDeclSize, "feedforward", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "dynamic", "",
                                       kFeedforwardDoc};
const pronk_param_decl kStartDelay = {kDeclSize, "start_delay", PRONK_PARAM_REAL, 0, 0.0, 60.0, 0, "0.2", "s",
                                      "standing time before the thrust"};
const pronk_param_decl kFlightKpDivision = {kDeclSize, "flight_kp_division", PRONK_PARAM_REAL, 0, 1.0, 100.0, 0, "3",
                                            "", "Kp is divided by this from lift-off to touchdown"};
const pronk_param_decl kMomentumGain = {
    kDeclSize, "momentum_gain", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "10", "1/s",
    "thrust: the trunk turns against the touchdown roll and pitch error the whole-body angular momentum predicts, at "
    "this rate per rad/s (0: the paper's kinematic thrust)"};
const pronk_param_decl kMomentumMomentGain = {
    kDeclSize, "momentum_moment_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "50", "1/s",
    "thrust: a moment about the vertical of this gain times the whole-body angular momentum error (planned I w "
    "minus L) joins the feed-forward wrench (0: the paper's)"};
const pronk_param_decl kMomentumMomentFriction = {
    kDeclSize, "momentum_moment_friction", PRONK_PARAM_REAL, 0, 0.0, 2.0, 0, "0.6", "",
    "thrust: that moment only as far as the feet's feed-forward forces stay within this friction coefficient "
    "(0: all of it)"};
const pronk_param_decl kStanceFeet = {
    kDeclSize, "stance_feet", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "anchored", "",
    "thrust: each stance foot's IK target is where it stood when the thrust began (anchored: a foot the thrust "
    "unloads presses back down) or where it is now (measured, the paper's)"};
// The landing's body wrench (control/jump_phases.h, LandingSettings), both factories.
const pronk_param_decl kLandingParamDecls[] = {
    {kDeclSize, "landing_frequency", PRONK_PARAM_REAL, 0, 0.1, 100.0, 0, "5", "rad/s",
     "landing: natural frequency of the CoM's critically damped stop (also where the planner expects it to stop)"},
    {kDeclSize, "landing_friction", PRONK_PARAM_REAL, 0, 0.0, 2.0, 0, "0.6", "",
     "landing: the share of the normal force the CoM's stop may ask sideways"},
    {kDeclSize, "landing_tilt_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "4", "N m/rad/kg",
     "landing: trunk levelling stiffness per kg of the robot's mass"},
    {kDeclSize, "landing_tilt_damping", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "0.4", "N m s/rad/kg",
     "landing: trunk levelling damping per kg of the robot's mass"},
    {kDeclSize, "landing_yaw_damping", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "1.5", "N m s/rad/kg",
     "landing: damping of the trunk's turn about the vertical per kg of the robot's mass"},
    {kDeclSize, "landing_yaw_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "10", "N m/rad/kg",
     "landing: stiffness per kg of the robot's mass that turns the trunk to the plan's touchdown heading (0: off)"},
    {kDeclSize, "landing_extension", PRONK_PARAM_REAL, 0, -1.0, 0.3, 0, "-1", "m",
     "landing: the descent's landing pose reaches this far below the stance feet, for the stroke saturated knees "
     "need to stop a fall (-1: derived from the robot's knee effort, mass and legs; 0: the stance pose)"},
    {kDeclSize, "landing_vertical_frequency", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "10", "rad/s",
     "landing: natural frequency of the CoM's critically damped vertical stop, which the legs' reference follows "
     "down (0: landing_frequency)"},
    {kDeclSize, "landing_pose_levelling", PRONK_PARAM_REAL, 0, -5.0, 5.0, 0, "1.5", "",
     "descent: the landing pose's feet turn against the trunk's tilt by this multiple of it (1: as under a level "
     "trunk; above 1 further, as the trunk turns against the legs' swing; 0: the pose in the trunk's frame)"},
};


}  // namespace

const std::vector<pronk_param_decl>& controllerParamDecls() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d(std::begin(kHoldParamDecls), std::end(kHoldParamDecls));
    // The action is a vector of any size so that its default can be empty ("no
    // action: hold the stance"); create() accepts 0 or 13 numbers.
    d.push_back({kDeclSize, "action", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
                 "empty: hold the stance; or the 13 physical jump parameters T_th r_p theta_p r_v theta_v "
                 "k d roll pitch yaw roll_rate pitch_rate yaw_rate (s, m, rad, m/s, rad, 1, m, rad, rad/s)"});
    d.push_back(kStartDelay);
    d.push_back(kFeedforward);
    d.push_back(kFlightKpDivision);
    d.push_back({kDeclSize, "landing_height", PRONK_PARAM_REAL, 0, -5.0, 5.0, 0, "0", "m",
                 "the landing surface's height above the take-off surface (when the legs extend)"});
    d.push_back(kMomentumGain);
    d.push_back(kMomentumMomentGain);
    d.push_back(kMomentumMomentFriction);
    d.push_back(kStanceFeet);
    d.insert(d.end(), std::begin(kLandingParamDecls), std::end(kLandingParamDecls));
    return d;
  }();
  return decls;
}

const std::vector<pronk_param_decl>& environmentParamDecls() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d(std::begin(kHoldParamDecls), std::end(kHoldParamDecls));
    const std::vector<pronk_param_decl> own = {
        {kDeclSize, "duration", PRONK_PARAM_REAL, 0, 0.01, 60.0, 0, "1.5", "s", "episode length, from reset"},
        kStartDelay,
        kFeedforward,
        kFlightKpDivision,
        kMomentumGain,
        kMomentumMomentGain,
        kMomentumMomentFriction,
        kStanceFeet,
        // Empty: derived from the robot (action_mapping.h, scaledActionRanges).
        {kDeclSize, "action_min", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
         "lower ends of the 13 action ranges (T_th r_p theta_p r_v theta_v k d roll pitch yaw and rates; "
         "s, m, rad, m/s, rad, 1, m, rad, rad/s); empty: the paper's Go1 table with r_p and d scaled by the "
         "robot's leg length (thigh + calf) over the Go1's 0.426 m"},
        {kDeclSize, "action_max", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
         "upper ends of the 13 action ranges; empty: derived as action_min"},
        {kDeclSize, "raw_limit", PRONK_PARAM_REAL, 0, 0.01, 100.0, 0, "5", "",
         "raw policy outputs are clipped to +-this before the affine map"},
        {kDeclSize, "friction_coefficient", PRONK_PARAM_REAL, 0, 0.0, 10.0, 0, "0.8", "",
         "mu of the reward's friction-cone term"},
        {kDeclSize, "workspace_z", PRONK_PARAM_VECTOR, 0, -10.0, 10.0, 0, "", "m",
         "trunk height band (2 numbers) of the reward's workspace term; empty: the paper's Go1 band 0.15 0.40 "
         "scaled by the robot's leg length over the Go1's 0.426 m (the paper's Aliengo: 0.20 0.60)"},
        {kDeclSize, "error_scale", PRONK_PARAM_REAL, 0, 0.001, 10.0, 0, "0.1", "m",
         "sigma_e of the landing reward exp(-e / sigma_e)"},
        {kDeclSize, "workspace_check", PRONK_PARAM_INT, 0, 0.0, 1.0, 0, "1", "",
         "safety filter and planner: 1 keeps every stance foot reachable on the thrust path"},
        {kDeclSize, "knee_clearance", PRONK_PARAM_REAL, 0, -1.0, 1.0, 0, "0.01", "m",
         "safety filter and planner (with workspace_check): every knee stays this far above its stance foot's "
         "centre on the thrust path (-1: off)"},
        {kDeclSize, "max_speed_shortfall", PRONK_PARAM_REAL, 0, 0.0, 10.0, 0, "0.1", "m/s",
         "safety filter and planner: the lift-off speed the motors are predicted to miss by at most (the "
         "torque check, under the 'motor' model)"},
        {kDeclSize, "sideways_roll_rate_gain", PRONK_PARAM_REAL, 0, -10.0, 10.0, 0, "1.5", "1/m",
         "planner: lift-off roll rate (rad/s) per m/s of lift-off velocity across the trunk, clamped into the "
         "roll rate range (0: none)"},
    };
    d.insert(d.end(), own.begin(), own.end());
    d.insert(d.end(), std::begin(kLandingParamDecls), std::end(kLandingParamDecls));
    return d;
  }();
  return decls;
}

HoldSettings readHoldSettings(const ParamReader& read) {
  HoldSettings s;
  s.kp = read.real("kp");
  s.kd = read.real("kd");
  const std::vector<double> stance = read.vector("stance");
  s.stance = {stance[0], stance[1], stance[2]};
  s.gravity_compensation = read.integer("gravity_compensation") != 0;
  s.motor = motorModelFromName(read.string("motor"));
  return s;
}

void readCommonJumpSettings(const ParamReader& read, JumpSettings* s) {
  s->start_delay = read.real("start_delay");
  s->feedforward = feedforwardFromName(read.string("feedforward"));
  s->flight_kp_division = read.real("flight_kp_division");
  s->momentum_gain = read.real("momentum_gain");
  s->momentum_moment_gain = read.real("momentum_moment_gain");
  s->momentum_moment_friction = read.real("momentum_moment_friction");
  const std::string feet = read.string("stance_feet");
  if (feet != "anchored" && feet != "measured") {
    throw InvalidArgument("parameter 'stance_feet': '" + feet + "' is neither anchored nor measured");
  }
  s->anchored_stance_feet = feet == "anchored";
  s->landing.frequency = read.real("landing_frequency");
  s->landing.friction = read.real("landing_friction");
  s->landing.tilt = read.real("landing_tilt_gain");
  s->landing.tilt_damping = read.real("landing_tilt_damping");
  s->landing.yaw_damping = read.real("landing_yaw_damping");
  s->landing.yaw_gain = read.real("landing_yaw_gain");
  s->landing.extension = read.real("landing_extension");
  s->landing.vertical_frequency = read.real("landing_vertical_frequency");
  s->landing.pose_levelling = read.real("landing_pose_levelling");
}

jump::MotorModel motorModelFromName(const std::string& name) {
  if (name == "dc") return jump::MotorModel::kDcMotor;
  if (name == "effort") return jump::MotorModel::kEffortBox;
  throw InvalidArgument("parameter 'motor': '" + name + "' is neither dc nor effort");
}

Feedforward feedforwardFromName(const std::string& name) {
  if (name == "gravity") return Feedforward::kGravity;
  if (name == "dynamic") return Feedforward::kDynamic;
  if (name == "dynamic_angular") return Feedforward::kDynamicAngular;
  throw InvalidArgument("parameter 'feedforward': '" + name + "' is none of gravity, dynamic, dynamic_angular");
}

}  // namespace pronk::guided_jump
