// Holding the stance: joint PD towards the stance plus gravity compensation.
//   tau = kp (q_stance - q) - kd qd  -  sum over feet in contact of J_i^T f_i
// where f = G^+ (-m g, 0) are the ground forces that carry the weight with no
// moment about the CoM (method/force_distribution.h) and J_i is the joint part (columns
// 6..) of foot i's world Jacobian: a leg pushes the ground with -f_i, which takes
// tau = -J_i^T f_i. Each torque is then clamped to what the joint's motor can
// deliver at its speed (method/motor_model.h).
// This is the controller the jump's thrust, flight and landing phases build on.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/param_reader.h"
#include "method/motor_model.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

struct HoldSettings {
  double kp = 100;                          // N m/rad
  double kd = 2;                            // N m s/rad
  std::array<double, 3> stance{0, 0.75, -1.5};  // rad per leg: hip, thigh, calf
  jump::MotorModel motor = jump::MotorModel::kEffortBox;

  // kp, kd, stance (the platform's by default, ABI 1.5), motor.
  static const std::vector<pronk_param_decl>& parameters();
  // Throws InvalidArgument naming the parameter for a value it does not know.
  static HoldSettings read(const ParamReader& read);
};

// "dc" or "effort"; throws InvalidArgument naming the parameter for any other name.
jump::MotorModel motorModelFromName(const std::string& name);

// Each joint's effort and velocity limits from the host (infinity where the
// model gives none).
std::vector<jump::MotorLimits> motorLimitsFromHost(const pronk_host_api* host, int joint_count);

class HoldController {
 public:
  // Checks the robot through `host`: at least one leg, every leg exactly three
  // joints (leg_jacobian_base answers), joint_count = 3 x foot_count. Throws
  // std::runtime_error saying what does not fit. `host` must outlive the controller.
  HoldController(const pronk_host_api* host, const HoldSettings& settings);

  // Emits the "hold" event.
  void reset(const pronk_robot_state& state);
  // Writes joint_count torques.
  void compute(const pronk_robot_state& state, double* torque);

  int jointCount() const { return joint_count_; }
  int footCount() const { return foot_count_; }

 private:
  void checkState(const pronk_robot_state& state) const;

  const pronk_host_api* host_;
  HoldSettings settings_;
  int joint_count_ = 0;
  int foot_count_ = 0;
  double mass_ = 0;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::vector<jump::MotorLimits> motors_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian_;  // 3 x (6 + n) buffer
};

}  // namespace pronk::guided_jump
