#include "control/landing_phase.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "control/robot_state.h"
#include "method/ballistics.h"

namespace pronk::guided_jump {

namespace {
constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
}  // namespace

const std::vector<pronk_param_decl>& LandingSettings::parameters() {
  static const std::vector<pronk_param_decl> decls = {
      {kDeclSize, "landing_frequency", PRONK_PARAM_REAL, 0, 0.1, 100.0, 0, "5", "rad/s",
       "landing: natural frequency of the CoM's critically damped stop (also where the planner expects it to stop)"},
      {kDeclSize, "landing_friction", PRONK_PARAM_REAL, 0, 0.0, 2.0, 0, "0.45", "",
       "landing: the share of the normal force the CoM's stop may ask sideways"},
      {kDeclSize, "landing_tilt_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "4", "N m/rad/kg",
       "landing: trunk levelling stiffness per kg of the robot's mass"},
      {kDeclSize, "landing_tilt_damping", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "0.4", "N m s/rad/kg",
       "landing: trunk levelling damping per kg of the robot's mass"},
      {kDeclSize, "landing_yaw_damping", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "1.5", "N m s/rad/kg",
       "landing: damping of the trunk's turn about the vertical per kg of the robot's mass"},
      {kDeclSize, "landing_yaw_gain", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "10", "N m/rad/kg",
       "landing: stiffness per kg of the robot's mass that turns the trunk to the plan's touchdown heading (0: off)"},
      {kDeclSize, "landing_vertical_frequency", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "10", "rad/s",
       "landing: natural frequency of the CoM's critically damped vertical stop, which the legs' reference follows "
       "down (0: landing_frequency)"},
  };
  return decls;
}

LandingSettings LandingSettings::read(const ParamReader& read) {
  LandingSettings s;
  s.frequency = read.real("landing_frequency");
  s.friction = read.real("landing_friction");
  s.tilt = read.real("landing_tilt_gain");
  s.tilt_damping = read.real("landing_tilt_damping");
  s.yaw_damping = read.real("landing_yaw_damping");
  s.yaw_gain = read.real("landing_yaw_gain");
  s.vertical_frequency = read.real("landing_vertical_frequency");
  return s;
}

Eigen::Vector2d LandingPhase::landingStop(const LandingSettings& landing, const Eigen::Vector3d& v) {
  return jump::landingStopOffset(v, landing.friction, landing.frequency);
}

void LandingPhase::reset() {
  all_down_seen_ = false;
  touchdown_com_.reset();
}

void LandingPhase::touchDown(const pronk_robot_state& s, const JumpPlan& plan) {
  touchdown_com_ = vec(s.com_position);
  touchdown_com_->head<2>() += landingStop(settings_, vec(s.com_velocity));
  touchdown_sink_ = s.com_position[2] - plan.landingComHeight();
  touchdown_sink_rate_ = s.com_velocity[2];
  all_down_seen_ = false;
}

double LandingPhase::verticalStopFrequency() const {
  return settings_.vertical_frequency > 0 ? settings_.vertical_frequency : settings_.frequency;
}

double LandingPhase::verticalStopSink(double t) const {
  const double wz = verticalStopFrequency();
  return (touchdown_sink_ + (touchdown_sink_rate_ + wz * touchdown_sink_) * t) * std::exp(-wz * t);
}

void LandingPhase::reference(const pronk_robot_state& s, const JumpPlan& plan, double elapsed) {
  // A level trunk at the stance height over the feet: the trunk frame at the
  // current yaw, placed over the feet's centroid as it was at the thrust start.
  // Feet in contact stay where they are (IK); feet in the air take the stance.
  const Eigen::Matrix3d R = rotationOf(s);
  const Eigen::Matrix3d R_des = headingOf(R);
  const int feet = drive_.footCount();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double ground = 0;
  int down = 0;
  for (int f = 0; f < feet; ++f) {
    centroid += vec(s.foot_position + 3 * f) / feet;
    if (s.foot_in_contact[f]) {
      ground += s.foot_position[3 * f + 2];
      ++down;
    }
  }
  Eigen::Vector3d trunk_des = centroid + R_des * plan.stance_offset;
  if (down > 0) trunk_des.z() = ground / down + plan.stance_offset.z();
  if (down > 0 && touchdown_com_) trunk_des.z() += verticalStopSink(elapsed);
  Eigen::VectorXd& q_ref = drive_.q_ref();
  for (int f = 0; f < feet; ++f) {
    if (s.foot_in_contact[f]) {
      const Eigen::Vector3d target = R_des.transpose() * (vec(s.foot_position + 3 * f) - trunk_des);
      q_ref.segment<3>(3 * f) = drive_.legIk(f, target);
    } else {
      // Reach for the ground: the stance foot under a level trunk, from the
      // trunk as it is (a pitched trunk would hold a stance-joint foot in the air),
      // and down to the level of the feet that are down (a trunk that sits pitched
      // would otherwise keep one foot hanging above the ground for good).
      Eigen::Vector3d reach = R_des * plan.stance_feet.col(f);
      if (down > 0) reach.z() = std::min(reach.z(), ground / down - kGroundReach - s.base_position[2]);
      q_ref.segment<3>(3 * f) = drive_.legIk(f, R.transpose() * reach);
    }
  }
  drive_.qd_ref().setZero();
}

void LandingPhase::wrenchTorques(const pronk_robot_state& s, const JumpPlan& plan, double kp, double* torque) {
  const int n = drive_.jointCount(), feet = drive_.footCount();
  Eigen::Map<const Eigen::VectorXd> q(s.q, n), qd(s.qd, n);
  Eigen::Map<Eigen::VectorXd> tau(torque, n);
  tau = kp * (drive_.q_ref() - q) + drive_.hold().kd * (drive_.qd_ref() - qd);
  double ground = 0;
  int down = 0;
  const pronk_host_api* host = drive_.host();
  for (int f = 0; f < feet; ++f) {
    if (!s.foot_in_contact[f]) continue;
    const double r = host->foot_radius ? host->foot_radius(host->host, f) : 0.0;
    ground += s.foot_position[3 * f + 2] - (std::isfinite(r) ? r : 0.0);
    ++down;
  }
  if (down > 0) {
    // The body wrench that stops the CoM where the landing model says, at the
    // standing height, with a level trunk: critically damped, friction-limited.
    const Eigen::Vector3d c = vec(s.com_position), v = vec(s.com_velocity);
    Eigen::Vector3d goal = *touchdown_com_;
    goal.z() = ground / down + plan.standing_height;
    const double wn = settings_.frequency;
    Eigen::Vector3d a_des = wn * wn * (goal - c) - 2.0 * wn * v;
    const double wz = verticalStopFrequency();
    a_des.z() = wz * wz * (goal.z() - c.z()) - 2.0 * wz * v.z();
    const double mass = drive_.mass();
    Eigen::Vector3d force = mass * (a_des - drive_.gravity());
    force.z() = std::max(force.z(), 0.0);
    const double horizontal = force.head<2>().norm(), cap = settings_.friction * force.z();
    if (horizontal > cap) force.head<2>() *= cap / horizontal;
    const Eigen::Vector3d rpy = rpyFromRotation(rotationOf(s));
    const Eigen::Matrix3d yaw = Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const double tilt = settings_.tilt;
    const Eigen::Vector3d w = vec(s.base_angular_velocity);
    const Eigen::Vector3d damping(settings_.tilt_damping * w.x(), settings_.tilt_damping * w.y(),
                                  settings_.yaw_damping * w.z());
    // The heading: towards the plan's touchdown heading, so that a trunk that
    // touched down past it (or short of it) turns back (or on) on its feet.
    const double heading_error = std::remainder(plan.touchdown_yaw - rpy.z(), 2.0 * M_PI);
    const Eigen::Vector3d moment =
        mass * (yaw * Eigen::Vector3d(-tilt * rpy.x(), -tilt * rpy.y(), settings_.yaw_gain * heading_error) - damping);
    // A foot that touches with no load flickers in and out of contact; left out
    // of the wrench, it stays unloaded, and the robot balances on the other
    // side's feet until it tips over them (docs/method.md).
    drive_.applyBodyWrench(s, force, moment, tau, all_down_seen_);
  }
  drive_.saturate(s, tau);
}

void LandingPhase::compute(const pronk_robot_state& s, const JumpPlan& plan, double elapsed, double kp_flight,
                           double* torque) {
  const int feet = drive_.footCount();
  bool all_contact = true;
  for (int f = 0; f < feet; ++f) all_contact = all_contact && s.foot_in_contact[f];
  // The weight goes back on the legs once every foot has touched down: carried by
  // the first foot alone it would push the robot off again.
  if (all_contact) all_down_seen_ = true;
  // The stiffness comes back over kLandingRamp after touchdown: full Kp at the
  // impact would throw the robot back up.
  const double a = smoothstep(elapsed / kLandingRamp);
  const double kp = kp_flight + a * (drive_.hold().kp - kp_flight);
  reference(s, plan, elapsed);
  clearance_.apply(s, plan);
  if (!touchdown_com_) {  // no flight before (an abandoned jump): plain stance
    int down = 0;
    for (int f = 0; f < feet; ++f) down += s.foot_in_contact[f] ? 1 : 0;
    drive_.jointTorques(s, kp, all_down_seen_ && (down >= 3 || down == feet),
                        Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), torque);
    return;
  }
  wrenchTorques(s, plan, kp, torque);
}

}  // namespace pronk::guided_jump
