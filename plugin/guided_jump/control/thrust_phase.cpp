#include "control/thrust_phase.h"

#include <algorithm>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "control/invalid_argument.h"
#include "control/robot_state.h"
#include "method/force_distribution.h"

namespace pronk::guided_jump {

namespace {
constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
}  // namespace

const std::vector<pronk_param_decl>& ThrustSettings::parameters() {
  static const std::vector<pronk_param_decl> decls = {
      {kDeclSize, "feedforward", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "dynamic", "",
       "thrust feed-forward: dynamic (m (a_ref + g): the PD alone lags a hard thrust), gravity (m g, the paper's) "
       "or dynamic_angular (dynamic and the orientation plan's rate of angular momentum)"},
      {kDeclSize, "momentum_gain", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "10", "1/s",
       "thrust: the trunk turns against the touchdown roll and pitch error the whole-body angular momentum "
       "predicts, at this rate per rad/s (0: the paper's kinematic thrust)"},
      {kDeclSize, "momentum_moment_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "50", "1/s",
       "thrust: a moment about the vertical of this gain times the whole-body angular momentum error (planned I w "
       "minus L) joins the feed-forward wrench (0: the paper's)"},
      {kDeclSize, "momentum_moment_friction", PRONK_PARAM_REAL, 0, 0.0, 2.0, 0, "0.6", "",
       "thrust: that moment only as far as the feet's feed-forward forces stay within this friction coefficient "
       "(0: all of it)"},
      {kDeclSize, "stance_feet", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "anchored", "",
       "thrust: each stance foot's IK target is where it stood when the thrust began (anchored: a foot the thrust "
       "unloads presses back down) or where it is now (measured, the paper's)"},
  };
  return decls;
}

ThrustSettings ThrustSettings::read(const ParamReader& read) {
  ThrustSettings s;
  s.feedforward = feedforwardFromName(read.string("feedforward"));
  s.momentum_gain = read.real("momentum_gain");
  s.momentum_moment_gain = read.real("momentum_moment_gain");
  s.momentum_moment_friction = read.real("momentum_moment_friction");
  const std::string feet = read.string("stance_feet");
  if (feet != "anchored" && feet != "measured") {
    throw InvalidArgument("parameter 'stance_feet': '" + feet + "' is neither anchored nor measured");
  }
  s.anchored_stance_feet = feet == "anchored";
  return s;
}

Feedforward feedforwardFromName(const std::string& name) {
  if (name == "gravity") return Feedforward::kGravity;
  if (name == "dynamic") return Feedforward::kDynamic;
  if (name == "dynamic_angular") return Feedforward::kDynamicAngular;
  throw InvalidArgument("parameter 'feedforward': '" + name + "' is none of gravity, dynamic, dynamic_angular");
}

void ThrustPhase::begin(const pronk_robot_state& s) {
  last_time_ = s.time;
  momentum_tilt_.setZero();
}

Eigen::Vector3d ThrustPhase::stanceFoot(const pronk_robot_state& s, const JumpPlan& plan, int f) const {
  return settings_.anchored_stance_feet ? Eigen::Vector3d(plan.start_feet.col(f)) : vec(s.foot_position + 3 * f);
}

double ThrustPhase::twistShareWithinFriction(const pronk_robot_state& s, const Eigen::Vector3d& com_acceleration,
                                             const Eigen::Vector3d& moment, const Eigen::Vector3d& twist) const {
  Eigen::Matrix3Xd points;
  if (drive_.wrenchFeet(s, false, &points).empty()) return 1.0;
  return jump::momentShareWithinFriction(points, vec(s.com_position),
                                         drive_.mass() * (com_acceleration - drive_.gravity()), moment, twist,
                                         settings_.momentum_moment_friction);
}

void ThrustPhase::compute(const pronk_robot_state& s, const JumpPlan& plan, double t, double* torque) {
  const jump::ThrustPlan& thrust = *plan.thrust;
  const Eigen::Matrix3d& heading = plan.heading;
  const bool running = t <= thrust.duration();
  const double tc = std::min(t, thrust.duration());
  const Eigen::Vector3d c_ref = plan.origin + heading * thrust.position(tc);
  const Eigen::Vector3d v_ref = running ? Eigen::Vector3d(heading * thrust.velocity(tc)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d a_ref = running ? Eigen::Vector3d(heading * thrust.acceleration(tc)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w_plan =
      running ? Eigen::Vector3d(heading * plan.orientation->angularVelocityWorld(tc)) : Eigen::Vector3d::Zero();
  const bool angular_feedforward = settings_.feedforward == Feedforward::kDynamicAngular && running;
  const bool moment_feedback = settings_.momentum_moment_gain > 0 && running;
  const std::optional<CentroidalMomentum> momentum =
      settings_.momentum_gain > 0 || angular_feedforward || moment_feedback ? centroidalMomentum(drive_.host())
                                                                           : std::nullopt;
  Eigen::Vector3d w_ref = w_plan;
  // Whole-body momentum: the legs swinging under the trunk carry angular momentum
  // the trunk's attitude does not show; the trunk turns against it so that the
  // whole body's rate I^-1 L follows the plan's rate (the flight keeps L).
  if (settings_.momentum_gain > 0 && momentum) {
    if (const std::optional<Eigen::Vector3d> body = averageRate(*momentum)) {
      Eigen::Vector3d extra = settings_.momentum_gain * ((w_ref - *body) - momentum_tilt_ / plan.flight_time);
      extra.z() = 0.0;  // the vertical goes to the feet (momentum_moment_gain)
      momentum_tilt_ += (s.time - last_time_) * extra;
      w_ref += extra;
    }
  }
  last_time_ = s.time;
  Eigen::Matrix3d R_des = heading * plan.orientation->rotation(tc);
  if (momentum_tilt_.norm() > 0) R_des = Eigen::AngleAxisd(momentum_tilt_.norm(), momentum_tilt_.normalized()) * R_des;
  const Eigen::Vector3d trunk_des = vec(s.base_position) + (c_ref - vec(s.com_position));

  Eigen::VectorXd& q_ref = drive_.q_ref();
  Eigen::VectorXd& qd_ref = drive_.qd_ref();
  const int feet = drive_.footCount();
  for (int f = 0; f < feet; ++f) {
    const Eigen::Vector3d foot = stanceFoot(s, plan, f);
    const Eigen::Vector3d target = R_des.transpose() * (foot - trunk_des);
    q_ref.segment<3>(3 * f) = drive_.legIk(f, target);
  }
  for (int f = 0; f < feet; ++f) {
    const Eigen::Vector3d foot = stanceFoot(s, plan, f);
    const Eigen::Vector3d v_rel = R_des.transpose() * (-(v_ref + w_ref.cross(foot - trunk_des)));
    const Eigen::Matrix3d J = drive_.legJacobian(f, q_ref);
    constexpr double lambda = 1e-2;
    qd_ref.segment<3>(3 * f) =
        (J.transpose() * J + lambda * lambda * Eigen::Matrix3d::Identity()).lu().solve(J.transpose() * v_rel);
  }
  // Dynamic feed-forward: the planned CoM acceleration; dynamic_angular adds the
  // orientation plan's rate of angular momentum d(I w)/dt = I alpha + w x I w, with
  // I the whole body's locked-joint inertia now (none from a host before ABI 1.2).
  Eigen::Vector3d acc = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  if (settings_.feedforward != Feedforward::kGravity && running) acc = a_ref;
  if (angular_feedforward && momentum) {
    const Eigen::Vector3d alpha_plan = heading * plan.orientation->angularAccelerationWorld(tc);
    moment = momentum->inertia * alpha_plan + w_plan.cross(momentum->inertia * w_plan);
  }
  // The whole body turns about the vertical only by the ground's friction: the
  // momentum error there is asked of the feet as a moment, not of the trunk's twist.
  if (moment_feedback && momentum) {
    Eigen::Vector3d twist(0, 0, settings_.momentum_moment_gain * (momentum->inertia * w_plan - momentum->angular).z());
    if (settings_.momentum_moment_friction > 0) twist *= twistShareWithinFriction(s, acc, moment, twist);
    moment += twist;
  }
  drive_.jointTorques(s, drive_.hold().kp, running, acc, moment, torque);
}

}  // namespace pronk::guided_jump
