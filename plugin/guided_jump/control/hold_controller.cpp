#include "control/hold_controller.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "control/invalid_argument.h"
#include "method/force_distribution.h"

namespace pronk::guided_jump {

namespace {
constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
}  // namespace

const std::vector<pronk_param_decl>& HoldSettings::parameters() {
  // Defaults from the platform (ABI 1.5); the Go1's for a host before 1.5.
  static const std::vector<pronk_param_decl> decls = {
      {kDeclSize, "kp", PRONK_PARAM_REAL, 0, 0.0, 1000.0, 0, "100", "N m/rad",
       "joint stiffness towards the stance (default: the platform's <joints kp>)", "kp"},
      {kDeclSize, "kd", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "2", "N m s/rad",
       "joint damping (default: the platform's <joints kd>)", "kd"},
      {kDeclSize, "stance", PRONK_PARAM_VECTOR, 0, -3.2, 3.2, 3, "0 0.75 -1.5", "rad",
       "joint positions held by every leg: hip, thigh, calf (default: the platform's <initial stance>)", "stance"},
      {kDeclSize, "motor", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "effort", "",
       "joint motors: effort (the URDF effort limit at any speed) or dc (torque falls linearly with speed to none "
       "at the URDF velocity limit, the paper's DC motor)"},
  };
  return decls;
}

HoldSettings HoldSettings::read(const ParamReader& read) {
  HoldSettings s;
  s.kp = read.real("kp");
  s.kd = read.real("kd");
  const std::vector<double> stance = read.vector("stance");
  s.stance = {stance[0], stance[1], stance[2]};
  s.motor = motorModelFromName(read.string("motor"));
  return s;
}

jump::MotorModel motorModelFromName(const std::string& name) {
  if (name == "dc") return jump::MotorModel::kDcMotor;
  if (name == "effort") return jump::MotorModel::kEffortBox;
  throw InvalidArgument("parameter 'motor': '" + name + "' is neither dc nor effort");
}

std::vector<jump::MotorLimits> motorLimitsFromHost(const pronk_host_api* host, int joint_count) {
  std::vector<jump::MotorLimits> motors(static_cast<size_t>(joint_count));
  for (int j = 0; j < joint_count; ++j) {
    double velocity = 0, effort = 0;
    if (host->joint_limits(host->host, j, nullptr, nullptr, &velocity, &effort) != PRONK_OK) {
      throw std::runtime_error("the host has no limits for joint " + std::to_string(j));
    }
    const double inf = std::numeric_limits<double>::infinity();
    motors[j].effort = std::isfinite(effort) && effort > 0 ? effort : inf;
    motors[j].velocity = std::isfinite(velocity) && velocity > 0 ? velocity : inf;
  }
  return motors;
}

namespace {

// The host API functions this controller calls were all in ABI 1.0.
constexpr size_t kHostApiSize_1_0 = offsetof(pronk_host_api, log) + sizeof(pronk_host_api::log);
constexpr size_t kStateSize_1_0 = offsetof(pronk_robot_state, foot_in_contact) + sizeof(pronk_robot_state::foot_in_contact);

}  // namespace

HoldController::HoldController(const pronk_host_api* host, const HoldSettings& settings)
    : host_(host), settings_(settings) {
  if (!host || host->struct_size < kHostApiSize_1_0) {
    throw InvalidArgument("the host API is missing or older than ABI 1.0");
  }
  if (!host->joint_count || !host->foot_count || !host->joint_limits || !host->total_mass || !host->gravity ||
      !host->foot_jacobian_world || !host->leg_jacobian_base) {
    throw InvalidArgument("the host API lacks a kinematics function this controller needs");
  }
  joint_count_ = host->joint_count(host->host);
  foot_count_ = host->foot_count(host->host);
  if (foot_count_ < 1) throw std::runtime_error("the robot has no feet");
  if (joint_count_ != 3 * foot_count_) {
    throw std::runtime_error("guided_jump needs exactly 3 joints per leg; the robot has " + std::to_string(joint_count_) +
                             " joints for " + std::to_string(foot_count_) + " feet");
  }
  const std::vector<double> q(static_cast<size_t>(joint_count_), 0.0);
  double leg_jacobian[9];
  for (int foot = 0; foot < foot_count_; ++foot) {
    if (host->leg_jacobian_base(host->host, foot, q.data(), leg_jacobian) != PRONK_OK) {
      throw std::runtime_error("guided_jump needs exactly 3 joints per leg; the host has no 3-joint leg Jacobian for foot " +
                               std::to_string(foot));
    }
  }
  motors_ = motorLimitsFromHost(host, joint_count_);
  mass_ = host->total_mass(host->host);
  double g[3] = {0, 0, 0};
  host->gravity(host->host, g);
  gravity_ = Eigen::Vector3d(g[0], g[1], g[2]);
  if (!std::isfinite(mass_) || mass_ <= 0 || !gravity_.allFinite()) {
    throw std::runtime_error("the host reports a mass or gravity that is not usable");
  }
  jacobian_.resize(3, 6 + joint_count_);
}

void HoldController::checkState(const pronk_robot_state& s) const {
  if (s.struct_size < kStateSize_1_0) throw InvalidArgument("the robot state is older than ABI 1.0");
  if (s.joint_count != joint_count_ || s.foot_count != foot_count_) {
    throw InvalidArgument("the state has " + std::to_string(s.joint_count) + " joints and " +
                          std::to_string(s.foot_count) + " feet; the robot has " + std::to_string(joint_count_) +
                          " and " + std::to_string(foot_count_));
  }
  if (!s.q || !s.qd || !s.foot_position || !s.foot_in_contact) throw InvalidArgument("the state lacks an array");
}

void HoldController::reset(const pronk_robot_state& state) {
  checkState(state);
  if (host_->emit_event) {
    host_->emit_event(host_->host, state.time, "hold", "stance PD + gravity compensation");
  }
}

void HoldController::compute(const pronk_robot_state& s, double* torque) {
  checkState(s);
  if (!torque) throw InvalidArgument("no torque buffer");
  const int n = joint_count_;
  Eigen::Map<const Eigen::VectorXd> q(s.q, n), qd(s.qd, n);
  Eigen::Map<Eigen::VectorXd> tau(torque, n);
  for (int j = 0; j < n; ++j) tau(j) = settings_.kp * (settings_.stance[j % 3] - q(j)) - settings_.kd * qd(j);

  std::vector<int> contact;
  for (int f = 0; f < foot_count_; ++f) {
    if (s.foot_in_contact[f]) contact.push_back(f);
  }
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(contact.size()));
  for (size_t i = 0; i < contact.size(); ++i) {
    points.col(static_cast<Eigen::Index>(i)) = Eigen::Map<const Eigen::Vector3d>(s.foot_position + 3 * contact[i]);
  }
  const Eigen::Vector3d com(s.com_position[0], s.com_position[1], s.com_position[2]);
  const Eigen::Matrix3Xd forces = jump::distributeWeight(points, com, mass_, gravity_);
  for (size_t i = 0; i < contact.size(); ++i) {
    if (host_->foot_jacobian_world(host_->host, contact[i], jacobian_.data()) != PRONK_OK) {
      throw std::runtime_error("the host has no Jacobian for foot " + std::to_string(contact[i]));
    }
    tau -= jacobian_.rightCols(n).transpose() * forces.col(static_cast<Eigen::Index>(i));
  }

  for (int j = 0; j < n; ++j) {
    if (!std::isfinite(tau(j))) throw std::runtime_error("torque of joint " + std::to_string(j) + " is not finite");
    tau(j) = jump::saturateTorque(settings_.motor, motors_[j], tau(j), qd(j));
  }
}

}  // namespace pronk::guided_jump
