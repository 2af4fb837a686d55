#include "control/leg_drive.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/LU>

#include "control/invalid_argument.h"
#include "control/robot_state.h"
#include "method/force_distribution.h"

namespace pronk::guided_jump {

LegDrive::LegDrive(const pronk_host_api* host, const HoldSettings& hold, int joint_count, int foot_count,
                   std::optional<LegModels> legs)
    : host_(host), hold_(hold), legs_(std::move(legs)), n_(joint_count), feet_(foot_count) {
  if (!host->foot_position_base) throw InvalidArgument("the host API lacks foot_position_base");
  motors_ = motorLimitsFromHost(host, n_);
  mass_ = host->total_mass(host->host);
  double g[3] = {0, 0, 0};
  host->gravity(host->host, g);
  gravity_ = Eigen::Vector3d(g[0], g[1], g[2]);
  q_ref_ = Eigen::VectorXd::Zero(n_);
  qd_ref_ = Eigen::VectorXd::Zero(n_);
  commanded_ = Eigen::VectorXd::Zero(n_);
  jacobian_.resize(3, 6 + n_);
}

Eigen::Matrix3d LegDrive::legJacobian(int foot, const Eigen::VectorXd& q) {
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> J;
  if (host_->leg_jacobian_base(host_->host, foot, q.data(), J.data()) != PRONK_OK) {
    throw std::runtime_error("the host has no leg Jacobian for foot " + std::to_string(foot));
  }
  return J;
}

Eigen::Vector3d LegDrive::legIk(int foot, const Eigen::Vector3d& target) {
  if (legs_ && foot < jump::kLegCount) {
    const jump::LegIkResult exact = jump::solveLegIk((*legs_)[foot], target);
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

Eigen::Matrix3Xd LegDrive::feetAt(const Eigen::VectorXd& q) const {
  Eigen::Matrix3Xd feet(3, feet_);
  for (int f = 0; f < feet_; ++f) {
    double p[3];
    if (host_->foot_position_base(host_->host, f, q.data(), p) != PRONK_OK) {
      throw std::runtime_error("the host has no forward kinematics for foot " + std::to_string(f));
    }
    feet.col(f) = vec(p);
  }
  return feet;
}

std::vector<int> LegDrive::wrenchFeet(const pronk_robot_state& s, bool every_foot, Eigen::Matrix3Xd* points) const {
  std::vector<int> feet;
  for (int f = 0; f < feet_; ++f) {
    if (every_foot || s.foot_in_contact[f]) feet.push_back(f);
  }
  points->resize(3, static_cast<Eigen::Index>(feet.size()));
  for (size_t i = 0; i < feet.size(); ++i) points->col(static_cast<Eigen::Index>(i)) = vec(s.foot_position + 3 * feet[i]);
  return feet;
}

void LegDrive::applyBodyWrench(const pronk_robot_state& s, const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                               Eigen::Ref<Eigen::VectorXd> tau, bool every_foot) {
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

void LegDrive::saturate(const pronk_robot_state& s, Eigen::Ref<Eigen::VectorXd> tau) {
  commanded_ = tau;
  for (int j = 0; j < n_; ++j) {
    if (!std::isfinite(tau(j))) throw std::runtime_error("torque of joint " + std::to_string(j) + " is not finite");
    tau(j) = jump::saturateTorque(hold_.motor, motors_[j], tau(j), s.qd[j]);
  }
}

void LegDrive::jointTorques(const pronk_robot_state& s, double kp, bool gravity, const Eigen::Vector3d& com_acceleration,
                            const Eigen::Vector3d& moment, double* torque) {
  Eigen::Map<const Eigen::VectorXd> q(s.q, n_), qd(s.qd, n_);
  Eigen::Map<Eigen::VectorXd> tau(torque, n_);
  tau = kp * (q_ref_ - q) + hold_.kd * (qd_ref_ - qd);
  if (gravity) applyBodyWrench(s, mass_ * (com_acceleration - gravity_), moment, tau);
  saturate(s, tau);
}

}  // namespace pronk::guided_jump
