// The legs as the jump's phases drive them: the joints' PD reference, leg IK
// and Jacobians, a body wrench spread over the feet through J^T, the motors'
// limits. One per jump controller; each phase writes the reference and asks
// for torques:
//   tau = Kp (q_ref - q) + Kd (qd_ref - qd) - sum over feet of J_i^T f_i, clamped
// with f = G^+ (m (a - g), M) the minimum-norm ground forces that put the force
// m (a - g) and the moment M about the CoM on the body (method/force_distribution.h).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "control/hold_controller.h"
#include "method/leg_ik.h"
#include "method/motor_model.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

using LegModels = std::array<jump::LegGeometry, jump::kLegCount>;

class LegDrive {
 public:
  // joint_count = 3 feet (HoldController has checked the robot). `legs`: the
  // analytic leg model (abi/host_leg_geometry.h); none: Newton steps on the
  // host's kinematics alone. Throws InvalidArgument without foot_position_base.
  LegDrive(const pronk_host_api* host, const HoldSettings& hold, int joint_count, int foot_count,
           std::optional<LegModels> legs);

  const pronk_host_api* host() const { return host_; }
  const HoldSettings& hold() const { return hold_; }
  const std::optional<LegModels>& legs() const { return legs_; }
  int jointCount() const { return n_; }
  int footCount() const { return feet_; }
  double mass() const { return mass_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }
  const std::vector<jump::MotorLimits>& motors() const { return motors_; }

  // The joints' PD reference (positions, velocities).
  Eigen::VectorXd& q_ref() { return q_ref_; }
  Eigen::VectorXd& qd_ref() { return qd_ref_; }

  // The leg's joint angles for a foot position in the trunk frame: the planner's
  // exact IK (jump::solveLegIk) on the analytic leg model when there is one and
  // its answer lies within the joint limits; otherwise (no analytic model, out
  // of reach or out of the limits) at most 6 damped Newton steps of at most
  // 0.2 rad on the host's leg kinematics from the reference, stopping at a 1 um
  // residual.
  Eigen::Vector3d legIk(int foot, const Eigen::Vector3d& foot_in_trunk);
  Eigen::Matrix3d legJacobian(int foot, const Eigen::VectorXd& q);
  // Every foot at the given joints, trunk frame (3 x feet).
  Eigen::Matrix3Xd feetAt(const Eigen::VectorXd& q) const;

  // tau = kp (q_ref - q) + kd (qd_ref - qd), plus with `gravity` the body wrench
  // (m (com_acceleration - g), moment) over the feet in contact; clamped.
  void jointTorques(const pronk_robot_state& s, double kp, bool gravity, const Eigen::Vector3d& com_acceleration,
                    const Eigen::Vector3d& moment, double* torque);
  // tau -= sum over the feet in contact (every_foot: all feet) of J_i^T f_i.
  void applyBodyWrench(const pronk_robot_state& s, const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                       Eigen::Ref<Eigen::VectorXd> tau, bool every_foot = false);
  // The feet a body wrench is spread over (those in contact; every_foot: all)
  // and, in *points, where they are (world).
  std::vector<int> wrenchFeet(const pronk_robot_state& s, bool every_foot, Eigen::Matrix3Xd* points) const;
  // Keeps tau as commandedTorque(), then clamps it to what each motor delivers
  // at its speed (throws if not finite).
  void saturate(const pronk_robot_state& s, Eigen::Ref<Eigen::VectorXd> tau);
  // The last tick's torques before the motors clamp them (what was asked for).
  const Eigen::VectorXd& commandedTorque() const { return commanded_; }
  void setCommandedTorque(const double* torque) { commanded_ = Eigen::Map<const Eigen::VectorXd>(torque, n_); }

 private:
  const pronk_host_api* host_;
  HoldSettings hold_;
  std::optional<LegModels> legs_;
  int n_ = 0;
  int feet_ = 0;
  double mass_ = 0;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::vector<jump::MotorLimits> motors_;
  Eigen::VectorXd q_ref_, qd_ref_, commanded_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian_;
};

}  // namespace pronk::guided_jump
