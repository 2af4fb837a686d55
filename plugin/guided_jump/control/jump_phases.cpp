#include "control/jump_phases.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "abi/abi_boundary.h"
#include "method/force_distribution.h"
#include "method/action_mapping.h"
#include "method/ballistics.h"

namespace pronk::guided_jump {

const char* jumpPhaseName(JumpPhase phase) {
  switch (phase) {
    case JumpPhase::kHold: return "hold";
    case JumpPhase::kStand: return "stand";
    case JumpPhase::kThrust: return "thrust";
    case JumpPhase::kExplosive: return "explosive";
    case JumpPhase::kFlight: return "flight";
    case JumpPhase::kDescend: return "descend";
    case JumpPhase::kLanding: return "landing";
  }
  return "unknown";
}

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

namespace {

Eigen::Matrix3d rotationOf(const pronk_robot_state& s) {
  return Eigen::Quaterniond(s.base_quaternion[0], s.base_quaternion[1], s.base_quaternion[2], s.base_quaternion[3])
      .normalized()
      .toRotationMatrix();
}

Eigen::Vector3d vec(const double* p) { return {p[0], p[1], p[2]}; }

}  // namespace

JumpController::JumpController(const pronk_host_api* host, const JumpSettings& settings)
    : host_(host), settings_(settings), hold_(host, settings.hold) {
  n_ = hold_.jointCount();
  feet_ = hold_.footCount();
  if (!host->foot_position_base) throw InvalidArgument("the host API lacks foot_position_base");
  if (!(settings.flight_kp_division >= 1.0) || !std::isfinite(settings.flight_kp_division)) {
    throw InvalidArgument("flight_kp_division must be >= 1");
  }
  if (!(settings.start_delay >= 0.0) || !std::isfinite(settings.start_delay)) {
    throw InvalidArgument("start_delay must be >= 0");
  }
  if (!settings.action.empty()) {
    if (settings.action.size() != static_cast<size_t>(jump::kActionSize)) {
      throw InvalidArgument("parameter 'action' needs " + std::to_string(jump::kActionSize) +
                            " numbers (T_th r_p theta_p r_v theta_v k d roll pitch yaw roll_rate pitch_rate "
                            "yaw_rate) or none, got " +
                            std::to_string(settings.action.size()));
    }
    jump::ActionVector v{};
    std::copy(settings.action.begin(), settings.action.end(), v.begin());
    action_ = jump::fromVector(v);
    if (!(action_.thrust_duration_s > 0)) throw InvalidArgument("action: the thrust duration must be > 0");
    if (!(action_.liftoff_speed_mps > 0)) throw InvalidArgument("action: the lift-off speed must be > 0");
    if (!(action_.speed_ratio >= 1.0)) throw InvalidArgument("action: k must be >= 1");
    if (!(action_.explosive_distance_m >= 0.0)) throw InvalidArgument("action: d must be >= 0");
    // Built once here so that the method's own checks refuse a bad action at create().
    try {
      jump::ThrustPlan check(action_, 0.0, Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d::Zero());
      jump::OrientationTrajectory o(Eigen::Vector3d::Zero(), action_, check.duration());
    } catch (const std::invalid_argument& e) {
      throw InvalidArgument(std::string("action: ") + e.what());
    }
    has_action_ = true;
  }
  motors_ = motorLimitsFromHost(host, n_);
  mass_ = host->total_mass(host->host);
  double g[3] = {0, 0, 0};
  host->gravity(host->host, g);
  gravity_ = Eigen::Vector3d(g[0], g[1], g[2]);
  q_ref_ = Eigen::VectorXd::Zero(n_);
  qd_ref_ = Eigen::VectorXd::Zero(n_);
  blend_from_ = Eigen::VectorXd::Zero(n_);
  commanded_ = Eigen::VectorXd::Zero(n_);
  jacobian_.resize(3, 6 + n_);
  if (!std::isfinite(settings.azimuth)) throw InvalidArgument("the jump azimuth is not finite");
  if (settings_.landing.extension < 0.0) settings_.landing.extension = derivedLandingExtension();
}

double JumpController::derivedLandingExtension() const {
  if (!settings_.legs || feet_ != jump::kLegCount || !(gravity_.norm() > 0.0) || !(mass_ > 0.0)) return 0.0;
  const Eigen::Vector3d stance(settings_.hold.stance[0], settings_.hold.stance[1], settings_.hold.stance[2]);
  double length = 0.0, lever = 0.0, effort = std::numeric_limits<double>::infinity();
  for (int f = 0; f < feet_; ++f) {
    const jump::LegGeometry& leg = (*settings_.legs)[f];
    length += (leg.thigh_length + leg.calf_length) / feet_;
    lever += std::abs(jump::footPosition(leg, stance).x() - jump::kneePosition(leg, stance).x()) / feet_;
    effort = std::min(effort, motors_[3 * f + 2].effort);
  }
  if (!(lever > 0.0) || !std::isfinite(effort)) return 0.0;  // knees that hold any load need no extension
  return jump::landingExtension(length, lever, effort, mass_, gravity_.norm(), feet_);
}

void JumpController::enter(JumpPhase phase, double time, const std::string& detail) {
  phase_ = phase;
  phase_start_ = time;
  if (host_->emit_event) {
    const std::string name = std::string("phase:") + jumpPhaseName(phase);
    host_->emit_event(host_->host, time, name.c_str(), detail.c_str());
  }
}

void JumpController::reset(const pronk_robot_state& state) {
  hold_.reset(state);  // checks the state, emits "hold"
  reset_time_ = state.time;
  phase_start_ = state.time;
  all_down_seen_ = false;
  touchdown_com_.reset();
  plan_.reset();
  orientation_.reset();
  phase_ = has_action_ ? JumpPhase::kStand : JumpPhase::kHold;
}

StartFrame takeOffFrame(const pronk_host_api* host, const pronk_robot_state& s) {
  StartFrame S;
  S.heading = Eigen::AngleAxisd(rpyFromRotation(rotationOf(s)).z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  double ground = 0;
  int counted = 0;
  for (int pass = 0; pass < 2 && counted == 0; ++pass) {  // feet in contact; all feet when none is
    for (int f = 0; f < s.foot_count; ++f) {
      if (pass == 0 && !s.foot_in_contact[f]) continue;
      const double r = host->foot_radius ? host->foot_radius(host->host, f) : 0.0;
      ground += s.foot_position[3 * f + 2] - (std::isfinite(r) ? r : 0.0);
      ++counted;
    }
  }
  S.origin = Eigen::Vector3d(s.com_position[0], s.com_position[1], counted ? ground / counted : 0.0);
  return S;
}

void JumpController::startThrust(const pronk_robot_state& s) {
  const Eigen::Matrix3d R = rotationOf(s);
  const StartFrame S = takeOffFrame(host_, s);
  heading_ = S.heading;
  origin_ = S.origin;
  const double ground = origin_.z();
  standing_height_ = s.com_position[2] - ground;
  const Eigen::Vector3d com_start_S(0, 0, s.com_position[2] - ground);
  plan_ = std::make_unique<jump::ThrustPlan>(action_, settings_.azimuth, com_start_S, Eigen::Vector3d::Zero());
  const Eigen::Vector3d rpy0 = rpyFromRotation(heading_.transpose() * R);
  orientation_ = std::make_unique<jump::OrientationTrajectory>(rpy0, action_, plan_->duration());
  thrust_start_ = s.time;
  last_thrust_time_ = s.time;
  momentum_tilt_.setZero();
  {
    const jump::PointState& lo = plan_->liftOff();
    const jump::BallisticFlight flight({lo.position, lo.velocity}, heading_.transpose() * gravity_);
    planned_flight_time_ = std::max(0.05, flight.landingTime(standing_height_ + settings_.landing_height).value_or(0.0));
    planned_touchdown_yaw_ = std::atan2(heading_(1, 0), heading_(0, 0)) + orientation_->liftOffRpy().z() +
                             orientation_->liftOffRpyRate().z() * planned_flight_time_;
  }
  for (int j = 0; j < n_; ++j) q_ref_(j) = s.q[j];
  thrust_feet_.resize(3, feet_);
  for (int f = 0; f < feet_; ++f) thrust_feet_.col(f) = vec(s.foot_position + 3 * f);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int f = 0; f < feet_; ++f) centroid += thrust_feet_.col(f) / feet_;  // the sum as before, bit for bit
  stance_offset_ = R.transpose() * (vec(s.base_position) - centroid);
  Eigen::VectorXd stance(n_);
  for (int j = 0; j < n_; ++j) stance(j) = settings_.hold.stance[j % 3];
  stance_feet_.resize(3, feet_);
  for (int f = 0; f < feet_; ++f) {
    double p[3];
    if (host_->foot_position_base(host_->host, f, stance.data(), p) != PRONK_OK) {
      throw std::runtime_error("the host has no forward kinematics for foot " + std::to_string(f));
    }
    stance_feet_.col(f) = vec(p);
  }
  char detail[200];
  const jump::PointState& lo = plan_->liftOff();
  std::snprintf(detail, sizeof detail,
                "T_th %.3f s, T_e %.3f s, lift-off CoM (%.3f, %.3f, %.3f) m, velocity (%.3f, %.3f, %.3f) m/s (start frame)",
                plan_->bezierDuration(), plan_->explosiveDuration(), lo.position.x(), lo.position.y(), lo.position.z(),
                lo.velocity.x(), lo.velocity.y(), lo.velocity.z());
  enter(JumpPhase::kThrust, s.time, detail);
}

std::optional<CentroidalMomentum> centroidalMomentum(const pronk_host_api* host) {
  if (host->struct_size < offsetof(pronk_host_api, centroidal_momentum) + sizeof(host->centroidal_momentum) ||
      !host->centroidal_momentum) {
    return std::nullopt;
  }
  CentroidalMomentum m;
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> I;
  if (host->centroidal_momentum(host->host, m.angular.data(), I.data()) != PRONK_OK) return std::nullopt;
  m.inertia = I;
  if (!m.angular.allFinite() || !m.inertia.allFinite()) return std::nullopt;
  return m;
}

std::optional<Eigen::Vector3d> averageRate(const CentroidalMomentum& m) {
  const Eigen::Vector3d w = m.inertia.ldlt().solve(m.angular);
  return w.allFinite() ? std::optional<Eigen::Vector3d>(w) : std::nullopt;
}

std::optional<Eigen::Vector3d> wholeBodyRate(const pronk_host_api* host) {
  const std::optional<CentroidalMomentum> m = centroidalMomentum(host);
  return m ? averageRate(*m) : std::nullopt;
}

Eigen::Matrix3d JumpController::legJacobian(int foot, const Eigen::VectorXd& q) {
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> J;
  if (host_->leg_jacobian_base(host_->host, foot, q.data(), J.data()) != PRONK_OK) {
    throw std::runtime_error("the host has no leg Jacobian for foot " + std::to_string(foot));
  }
  return J;
}

Eigen::Vector3d JumpController::legIk(int foot, const Eigen::Vector3d& target) {
  if (settings_.legs && foot < jump::kLegCount) {
    const jump::LegIkResult exact = jump::solveLegIk((*settings_.legs)[foot], target);
    if (exact.ok() && exact.within_limits) return exact.q;
  }
  Eigen::VectorXd q = q_ref_;
  for (int iteration = 0; iteration < 6; ++iteration) {
    double p[3];
    if (host_->foot_position_base(host_->host, foot, q.data(), p) != PRONK_OK) {
      throw std::runtime_error("the host has no forward kinematics for foot " + std::to_string(foot));
    }
    const Eigen::Vector3d e = target - vec(p);
    if (e.norm() < 1e-6) break;
    const Eigen::Matrix3d J = legJacobian(foot, q);
    // Damped least squares: stays bounded near the stretched-leg singularity.
    constexpr double lambda = 5e-3;
    const Eigen::Vector3d dq =
        (J.transpose() * J + lambda * lambda * Eigen::Matrix3d::Identity()).lu().solve(J.transpose() * e);
    q.segment<3>(3 * foot) += dq.cwiseMax(-0.2).cwiseMin(0.2);
  }
  return q.segment<3>(3 * foot);
}

Eigen::Vector3d JumpController::stanceFoot(const pronk_robot_state& s, int f) const {
  return settings_.anchored_stance_feet ? Eigen::Vector3d(thrust_feet_.col(f)) : vec(s.foot_position + 3 * f);
}

void JumpController::thrustTorques(const pronk_robot_state& s, double t, double* torque) {
  const bool running = t <= plan_->duration();
  const double tc = std::min(t, plan_->duration());
  const Eigen::Vector3d c_ref = origin_ + heading_ * plan_->position(tc);
  const Eigen::Vector3d v_ref = running ? Eigen::Vector3d(heading_ * plan_->velocity(tc)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d a_ref = running ? Eigen::Vector3d(heading_ * plan_->acceleration(tc)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w_plan =
      running ? Eigen::Vector3d(heading_ * orientation_->angularVelocityWorld(tc)) : Eigen::Vector3d::Zero();
  const bool angular_feedforward = settings_.feedforward == Feedforward::kDynamicAngular && running;
  const bool moment_feedback = settings_.momentum_moment_gain > 0 && running;
  const std::optional<CentroidalMomentum> momentum =
      settings_.momentum_gain > 0 || angular_feedforward || moment_feedback ? centroidalMomentum(host_)
                                                                           : std::nullopt;
  Eigen::Vector3d w_ref = w_plan;
  // Whole-body momentum: the legs swinging under the trunk carry angular momentum
  // the trunk's attitude does not show; the trunk turns against it so that the
  // whole body's rate I^-1 L follows the plan's rate (the flight keeps L).
  if (settings_.momentum_gain > 0 && momentum) {
    if (const std::optional<Eigen::Vector3d> body = averageRate(*momentum)) {
      Eigen::Vector3d extra = settings_.momentum_gain * ((w_ref - *body) - momentum_tilt_ / planned_flight_time_);
      extra.z() = 0.0;  // the vertical goes to the feet (momentum_moment_gain)
      momentum_tilt_ += (s.time - last_thrust_time_) * extra;
      w_ref += extra;
    }
  }
  last_thrust_time_ = s.time;
  Eigen::Matrix3d R_des = heading_ * orientation_->rotation(tc);
  if (momentum_tilt_.norm() > 0) R_des = Eigen::AngleAxisd(momentum_tilt_.norm(), momentum_tilt_.normalized()) * R_des;
  const Eigen::Vector3d trunk_des = vec(s.base_position) + (c_ref - vec(s.com_position));

  for (int f = 0; f < feet_; ++f) {
    const Eigen::Vector3d foot = stanceFoot(s, f);
    const Eigen::Vector3d target = R_des.transpose() * (foot - trunk_des);
    q_ref_.segment<3>(3 * f) = legIk(f, target);
  }
  for (int f = 0; f < feet_; ++f) {
    const Eigen::Vector3d foot = stanceFoot(s, f);
    const Eigen::Vector3d v_rel = R_des.transpose() * (-(v_ref + w_ref.cross(foot - trunk_des)));
    const Eigen::Matrix3d J = legJacobian(f, q_ref_);
    constexpr double lambda = 1e-2;
    qd_ref_.segment<3>(3 * f) =
        (J.transpose() * J + lambda * lambda * Eigen::Matrix3d::Identity()).lu().solve(J.transpose() * v_rel);
  }
  // Dynamic feed-forward: the planned CoM acceleration; dynamic_angular adds the
  // orientation plan's rate of angular momentum d(I w)/dt = I alpha + w x I w, with
  // I the whole body's locked-joint inertia now (none from a host before ABI 1.2).
  Eigen::Vector3d acc = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  if (settings_.feedforward != Feedforward::kGravity && running) acc = a_ref;
  if (angular_feedforward && momentum) {
    const Eigen::Vector3d alpha_plan = heading_ * orientation_->angularAccelerationWorld(tc);
    moment = momentum->inertia * alpha_plan + w_plan.cross(momentum->inertia * w_plan);
  }
  // The whole body turns about the vertical only by the ground's friction: the
  // momentum error there is asked of the feet as a moment, not of the trunk's twist.
  if (moment_feedback && momentum) {
    Eigen::Vector3d twist(0, 0, settings_.momentum_moment_gain * (momentum->inertia * w_plan - momentum->angular).z());
    if (settings_.momentum_moment_friction > 0) twist *= twistShareWithinFriction(s, acc, moment, twist);
    moment += twist;
  }
  jointTorques(s, settings_.hold.kp, q_ref_, qd_ref_,
               settings_.hold.gravity_compensation && running, acc, moment, torque);
}

Eigen::Vector2d JumpController::landingStop(const LandingSettings& landing, const Eigen::Vector3d& v) {
  return jump::landingStopOffset(v, landing.friction, landing.frequency);
}

double JumpController::verticalStopFrequency() const {
  return settings_.landing.vertical_frequency > 0 ? settings_.landing.vertical_frequency : settings_.landing.frequency;
}

double JumpController::verticalStopSink(double t) const {
  const double wz = verticalStopFrequency();
  return (touchdown_sink_ + (touchdown_sink_rate_ + wz * touchdown_sink_) * t) * std::exp(-wz * t);
}

void JumpController::landingReference(const pronk_robot_state& s) {
  // A level trunk at the stance height over the feet: the trunk frame at the
  // current yaw, placed over the feet's centroid as it was at the thrust start.
  // Feet in contact stay where they are (IK); feet in the air take the stance.
  const Eigen::Matrix3d R = rotationOf(s);
  const Eigen::Matrix3d R_des = Eigen::AngleAxisd(std::atan2(R(1, 0), R(0, 0)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double ground = 0;
  int down = 0;
  for (int f = 0; f < feet_; ++f) {
    centroid += vec(s.foot_position + 3 * f) / feet_;
    if (s.foot_in_contact[f]) {
      ground += s.foot_position[3 * f + 2];
      ++down;
    }
  }
  Eigen::Vector3d trunk_des = centroid + R_des * stance_offset_;
  if (down > 0) trunk_des.z() = ground / down + stance_offset_.z();
  if (down > 0 && touchdown_com_) trunk_des.z() += verticalStopSink(s.time - phase_start_);
  for (int f = 0; f < feet_; ++f) {
    if (s.foot_in_contact[f]) {
      const Eigen::Vector3d target = R_des.transpose() * (vec(s.foot_position + 3 * f) - trunk_des);
      q_ref_.segment<3>(3 * f) = legIk(f, target);
    } else {
      // Reach for the ground: the stance foot under a level trunk, from the
      // trunk as it is (a pitched trunk would hold a stance-joint foot in the air),
      // and down to the level of the feet that are down (a trunk that sits pitched
      // would otherwise keep one foot hanging above the ground for good).
      Eigen::Vector3d reach = R_des * stance_feet_.col(f);
      if (down > 0) reach.z() = std::min(reach.z(), ground / down - kGroundReach - s.base_position[2]);
      q_ref_.segment<3>(3 * f) = legIk(f, R.transpose() * reach);
    }
  }
  qd_ref_.setZero();
}

std::vector<int> JumpController::wrenchFeet(const pronk_robot_state& s, bool every_foot, Eigen::Matrix3Xd* points) const {
  std::vector<int> feet;
  for (int f = 0; f < feet_; ++f) {
    if (every_foot || s.foot_in_contact[f]) feet.push_back(f);
  }
  points->resize(3, static_cast<Eigen::Index>(feet.size()));
  for (size_t i = 0; i < feet.size(); ++i) points->col(static_cast<Eigen::Index>(i)) = vec(s.foot_position + 3 * feet[i]);
  return feet;
}

double JumpController::twistShareWithinFriction(const pronk_robot_state& s, const Eigen::Vector3d& com_acceleration,
                                                const Eigen::Vector3d& moment, const Eigen::Vector3d& twist) const {
  Eigen::Matrix3Xd points;
  if (wrenchFeet(s, false, &points).empty()) return 1.0;
  return jump::momentShareWithinFriction(points, vec(s.com_position), mass_ * (com_acceleration - gravity_), moment,
                                         twist, settings_.momentum_moment_friction);
}

void JumpController::applyBodyWrench(const pronk_robot_state& s, const Eigen::Vector3d& force,
                                     const Eigen::Vector3d& moment, Eigen::Ref<Eigen::VectorXd> tau, bool every_foot) {
  Eigen::Matrix3Xd points;
  const std::vector<int> contact = wrenchFeet(s, every_foot, &points);
  if (contact.empty()) return;
  const Eigen::Matrix3Xd forces = jump::distributeWrench(points, vec(s.com_position), force, moment);
  for (size_t i = 0; i < contact.size(); ++i) {
    if (host_->foot_jacobian_world(host_->host, contact[i], jacobian_.data()) != PRONK_OK) {
      throw std::runtime_error("the host has no Jacobian for foot " + std::to_string(contact[i]));
    }
    tau -= jacobian_.rightCols(n_).transpose() * forces.col(static_cast<Eigen::Index>(i));
  }
}

void JumpController::saturate(const pronk_robot_state& s, Eigen::Ref<Eigen::VectorXd> tau) {
  commanded_ = tau;
  for (int j = 0; j < n_; ++j) {
    if (!std::isfinite(tau(j))) throw std::runtime_error("torque of joint " + std::to_string(j) + " is not finite");
    tau(j) = jump::saturateTorque(settings_.hold.motor, motors_[j], tau(j), s.qd[j]);
  }
}

void JumpController::landingTorques(const pronk_robot_state& s, double kp, double* torque) {
  Eigen::Map<const Eigen::VectorXd> q(s.q, n_), qd(s.qd, n_);
  Eigen::Map<Eigen::VectorXd> tau(torque, n_);
  tau = kp * (q_ref_ - q) + settings_.hold.kd * (qd_ref_ - qd);
  double ground = 0;
  int down = 0;
  for (int f = 0; f < feet_; ++f) {
    if (!s.foot_in_contact[f]) continue;
    const double r = host_->foot_radius ? host_->foot_radius(host_->host, f) : 0.0;
    ground += s.foot_position[3 * f + 2] - (std::isfinite(r) ? r : 0.0);
    ++down;
  }
  if (down > 0 && settings_.hold.gravity_compensation) {
    // The body wrench that stops the CoM where it touched down, at the standing
    // height, with a level trunk: critically damped, friction-limited.
    const Eigen::Vector3d c = vec(s.com_position), v = vec(s.com_velocity);
    Eigen::Vector3d goal = *touchdown_com_;
    goal.z() = ground / down + standing_height_;
    const double wn = settings_.landing.frequency;
    Eigen::Vector3d a_des = wn * wn * (goal - c) - 2.0 * wn * v;
    const double wz = verticalStopFrequency();
    a_des.z() = wz * wz * (goal.z() - c.z()) - 2.0 * wz * v.z();
    Eigen::Vector3d force = mass_ * (a_des - gravity_);
    force.z() = std::max(force.z(), 0.0);
    const double horizontal = force.head<2>().norm(), cap = settings_.landing.friction * force.z();
    if (horizontal > cap) force.head<2>() *= cap / horizontal;
    const Eigen::Vector3d rpy = rpyFromRotation(rotationOf(s));
    const Eigen::Matrix3d yaw = Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const double tilt = settings_.landing.tilt;
    const Eigen::Vector3d w = vec(s.base_angular_velocity);
    const Eigen::Vector3d damping(settings_.landing.tilt_damping * w.x(), settings_.landing.tilt_damping * w.y(),
                                  settings_.landing.yaw_damping * w.z());
    // The heading: towards the plan's touchdown heading, so that a trunk that
    // touched down past it (or short of it) turns back (or on) on its feet.
    const double heading_error = std::remainder(planned_touchdown_yaw_ - rpy.z(), 2.0 * M_PI);
    const Eigen::Vector3d moment =
        mass_ * (yaw * Eigen::Vector3d(-tilt * rpy.x(), -tilt * rpy.y(), settings_.landing.yaw_gain * heading_error) -
                 damping);
    // A foot that touches with no load flickers in and out of contact; left out
    // of the wrench, it stays unloaded, and the robot balances on the other
    // side's feet until it tips over them (docs/results.md).
    applyBodyWrench(s, force, moment, tau, all_down_seen_);
  }
  saturate(s, tau);
}

void JumpController::jointTorques(const pronk_robot_state& s, double kp, const Eigen::VectorXd& q_ref,
                                  const Eigen::VectorXd& qd_ref, bool gravity, const Eigen::Vector3d& com_acceleration,
                                  const Eigen::Vector3d& moment, double* torque) {
  Eigen::Map<const Eigen::VectorXd> q(s.q, n_), qd(s.qd, n_);
  Eigen::Map<Eigen::VectorXd> tau(torque, n_);
  tau = kp * (q_ref - q) + settings_.hold.kd * (qd_ref - qd);
  if (gravity) applyBodyWrench(s, mass_ * (com_acceleration - gravity_), moment, tau);
  saturate(s, tau);
}

void JumpController::compute(const pronk_robot_state& s, double* torque) {
  if (!torque) throw InvalidArgument("no torque buffer");
  if (phase_ == JumpPhase::kHold) {
    hold_.compute(s, torque);
    commanded_ = Eigen::Map<const Eigen::VectorXd>(torque, n_);
    return;
  }
  if (s.joint_count != n_ || s.foot_count != feet_ || !s.q || !s.qd || !s.foot_position || !s.foot_in_contact) {
    hold_.compute(s, torque);  // throws with the details
    return;
  }
  bool any_contact = false, all_contact = true;
  for (int f = 0; f < feet_; ++f) {
    any_contact = any_contact || s.foot_in_contact[f];
    all_contact = all_contact && s.foot_in_contact[f];
  }
  if (phase_ == JumpPhase::kLanding) {
    // The weight goes back on the legs once every foot has touched down: carried by
    // the first foot alone it would push the robot off again.
    if (all_contact) all_down_seen_ = true;
    // The stiffness comes back over kLandingRamp after touchdown: full Kp at the
    // impact would throw the robot back up.
    const double a = smoothstep((s.time - phase_start_) / kLandingRamp);
    const double kp_low = settings_.hold.kp / settings_.flight_kp_division;
    landingReference(s);
    if (!touchdown_com_) {  // no flight before (an abandoned jump): plain stance
      int down = 0;
      for (int f = 0; f < feet_; ++f) down += s.foot_in_contact[f] ? 1 : 0;
      jointTorques(s, kp_low + a * (settings_.hold.kp - kp_low), q_ref_, qd_ref_,
                   settings_.hold.gravity_compensation && all_down_seen_ && (down >= 3 || down == feet_),
                   Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), torque);
      return;
    }
    landingTorques(s, kp_low + a * (settings_.hold.kp - kp_low), torque);
    return;
  }

  if (phase_ == JumpPhase::kStand) {
    if (s.time - reset_time_ < settings_.start_delay - 1e-9) {
      hold_.compute(s, torque);
      commanded_ = Eigen::Map<const Eigen::VectorXd>(torque, n_);
      return;
    }
    startThrust(s);
  }
  if (phase_ == JumpPhase::kThrust || phase_ == JumpPhase::kExplosive) {
    const double t = s.time - thrust_start_;
    if (!any_contact) {
      for (int j = 0; j < n_; ++j) blend_from_(j) = s.q[j];
      char detail[360];
      const Eigen::Vector3d v = heading_.transpose() * vec(s.com_velocity);
      int n = std::snprintf(detail, sizeof detail,
                            "%.3f s into the thrust (plan %.3f s); CoM velocity (%.3f, %.3f, %.3f) m/s (start frame)", t,
                            plan_->duration(), v.x(), v.y(), v.z());
      const std::optional<Eigen::Vector3d> w = wholeBodyRate(host_);
      if (w && n > 0 && n < static_cast<int>(sizeof detail)) {
        const Eigen::Vector3d w_S = heading_.transpose() * *w;
        n += std::snprintf(detail + n, sizeof detail - n, "; whole-body rate (%.2f, %.2f, %.2f) rad/s", w_S.x(),
                           w_S.y(), w_S.z());
      }
      if (momentum_tilt_.norm() > 0 && n > 0 && n < static_cast<int>(sizeof detail)) {
        const Eigen::Vector3d tilt_S = heading_.transpose() * momentum_tilt_;
        std::snprintf(detail + n, sizeof detail - n, "; momentum turn (%.2f, %.2f, %.2f) rad", tilt_S.x(), tilt_S.y(),
                      tilt_S.z());
      }
      enter(JumpPhase::kFlight, s.time, detail);
    } else if (t > plan_->duration() + kLiftOffWait) {
      enter(JumpPhase::kLanding, s.time, "no lift-off: the jump is abandoned");
      phase_start_ -= kLandingRamp;  // nothing to absorb: full gains at once
      all_down_seen_ = true;
      compute(s, torque);
      return;
    } else {
      if (phase_ == JumpPhase::kThrust && t > plan_->bezierDuration() && plan_->explosiveDuration() > 0) {
        enter(JumpPhase::kExplosive, s.time);
      }
      thrustTorques(s, t, torque);
      return;
    }
  }
  const double kp_flight = settings_.hold.kp / settings_.flight_kp_division;
  if (phase_ == JumpPhase::kFlight || phase_ == JumpPhase::kDescend) {
    // A foot that brushes the ground while the CoM still rises (a toe that
    // scuffs just after lift-off) is not a touchdown: taken for one, the landing's
    // stop would pull the robot back to where it left and steer the whole flight
    // (docs/results.md, "Session 28").
    if (any_contact && s.com_velocity[2] <= 0.0) {
      // The CoM comes to rest landingStop() beyond the touchdown point: with that
      // goal the critically damped stop is a pure exponential, with no overshoot.
      touchdown_com_ = vec(s.com_position);
      touchdown_com_->head<2>() += landingStop(settings_.landing, vec(s.com_velocity));
      touchdown_sink_ = s.com_position[2] - (origin_.z() + settings_.landing_height + standing_height_);
      touchdown_sink_rate_ = s.com_velocity[2];
      enter(JumpPhase::kLanding, s.time);
      all_down_seen_ = false;
      compute(s, torque);
      return;
    }
    // The legs stay tucked until the extension, kBlendTime long, ends kExtensionLead
    // before the predicted touchdown on the landing surface (the reference extends
    // at the apex; docs/results.md has the measured comparison).
    // The CoM touches down landing.extension higher than it stands.
    const double landing_com_z = origin_.z() + settings_.landing_height + standing_height_ + settings_.landing.extension;
    const auto timeToTouchdown = [&] {  // 0 once the CoM is below its touchdown height
      if (!(gravity_.z() < 0.0)) return std::numeric_limits<double>::infinity();
      const jump::BallisticFlight fall({vec(s.com_position), vec(s.com_velocity)}, gravity_);
      return fall.landingTime(landing_com_z).value_or(0.0);
    };
    if (phase_ == JumpPhase::kFlight && s.com_velocity[2] < 0.0 && timeToTouchdown() <= kBlendTime + kExtensionLead) {
      const double a = smoothstep((s.time - phase_start_) / kBlendTime);
      for (int j = 0; j < n_; ++j) blend_from_(j) = blend_from_(j) + a * (settings_.tuck[j % 3] - blend_from_(j));
      char detail[80];
      std::snprintf(detail, sizeof detail, "landing pose %.3f m below the stance feet", settings_.landing.extension);
      enter(JumpPhase::kDescend, s.time, detail);
    }
    const double a = smoothstep((s.time - phase_start_) / kBlendTime);
    Eigen::VectorXd goal(n_);
    if (phase_ == JumpPhase::kFlight) {
      for (int j = 0; j < n_; ++j) goal(j) = settings_.tuck[j % 3];
    } else {
      // The landing pose: the stance feet as they would be under a level trunk, so
      // that a pitched or rolled trunk still lands on all four feet together.
      // Levelling swings the legs against the trunk's tilt (R = level tilt); in the
      // air the legs carry most of the roll inertia, so the trunk turns further
      // against that swing than the legs do. A levelling above 1 swings them
      // further, so that they come nearer the pose they aim for.
      // The feet land where the landing will stop the CoM (landingStop), with the
      // vertical speed the CoM will have when it is back at the standing height.
      const Eigen::Matrix3d R = rotationOf(s);
      const Eigen::Matrix3d level = Eigen::AngleAxisd(std::atan2(R(1, 0), R(0, 0)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::AngleAxisd tilt(level.transpose() * R);
      const Eigen::Matrix3d counter =
          Eigen::AngleAxisd(-settings_.landing.pose_levelling * tilt.angle(), tilt.axis()).toRotationMatrix();
      const double drop = std::max(0.0, s.com_position[2] - landing_com_z);
      Eigen::Vector3d v_touchdown = vec(s.com_velocity);
      v_touchdown.z() = -std::sqrt(v_touchdown.z() * v_touchdown.z() - 2.0 * gravity_.z() * drop);
      Eigen::Vector3d ahead = Eigen::Vector3d::Zero();
      ahead.head<2>() = landingStop(settings_.landing, v_touchdown);
      ahead.z() = -settings_.landing.extension;
      for (int f = 0; f < feet_; ++f) goal.segment<3>(3 * f) = legIk(f, counter * (stance_feet_.col(f) + level.transpose() * ahead));
    }
    q_ref_ = blend_from_ + a * (goal - blend_from_);
    qd_ref_.setZero();
    jointTorques(s, kp_flight, q_ref_, qd_ref_, false, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), torque);
  }
}

}  // namespace pronk::guided_jump
