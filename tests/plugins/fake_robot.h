// A fake pronk_host_api for plugin tests: a four-legged robot with hand-written
// kinematics (feet where the test puts them, constant Jacobians chosen per leg),
// no Simbody. Records the events and log lines a plugin sends.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <limits>
#include <string>
#include <map>
#include <vector>

#include "pronk/plugin_abi.h"

namespace pronk::test {

class FakeRobot {
 public:
  static constexpr int kFeet = 4;

  explicit FakeRobot(int joints_per_leg = 3) : joints_per_leg_(joints_per_leg) {
    // Feet at the corners of a 0.4 m x 0.24 m rectangle on the ground, CoM 0.3 m above its centre.
    foot_position_ << 0.2, 0.2, -0.2, -0.2,  //
        0.12, -0.12, 0.12, -0.12,            //
        0, 0, 0, 0;
    effort_.assign(jointCount(), 1000.0);
    velocity_.assign(jointCount(), std::numeric_limits<double>::infinity());
    q_.assign(jointCount(), 0.0);
    qd_.assign(jointCount(), 0.0);
    contact_.fill(1);
    api_.struct_size = sizeof(pronk_host_api);
    api_.host = this;
    api_.joint_count = [](void* h) { return self(h).jointCount(); };
    api_.foot_count = [](void*) { return static_cast<int32_t>(kFeet); };
    api_.joint_name = [](void*, int32_t) -> const char* { return "joint"; };
    api_.joint_limits = [](void* h, int32_t j, double* lo, double* hi, double* vel, double* eff) {
      if (j < 0 || j >= self(h).jointCount()) return PRONK_ERROR_INVALID_ARGUMENT;
      const double inf = std::numeric_limits<double>::infinity();
      if (lo) *lo = -inf;
      if (hi) *hi = inf;
      if (vel) *vel = self(h).velocity_[j];
      if (eff) *eff = self(h).effort_[j];
      return PRONK_OK;
    };
    api_.total_mass = [](void* h) { return self(h).mass_; };
    api_.gravity = [](void*, double g[3]) {
      g[0] = 0;
      g[1] = 0;
      g[2] = -9.81;
    };
    api_.foot_radius = [](void*, int32_t) { return 0.02; };
    api_.foot_position_world = [](void* h, int32_t f, double p[3]) {
      if (f < 0 || f >= kFeet) return PRONK_ERROR_INVALID_ARGUMENT;
      for (int i = 0; i < 3; ++i) p[i] = self(h).foot_position_(i, f);
      return PRONK_OK;
    };
    api_.foot_jacobian_world = [](void* h, int32_t f, double* jacobian) {
      if (f < 0 || f >= kFeet) return PRONK_ERROR_INVALID_ARGUMENT;
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobian, 3,
                                                                                       6 + self(h).jointCount()) =
          self(h).footJacobianWorld(f);
      return PRONK_OK;
    };
    api_.foot_position_base = [](void*, int32_t, const double*, double p[3]) {
      p[0] = p[1] = p[2] = 0;
      return PRONK_ERROR_UNSUPPORTED;
    };
    api_.leg_jacobian_base = [](void* h, int32_t f, const double*, double* jacobian) {
      if (f < 0 || f >= kFeet) return PRONK_ERROR_INVALID_ARGUMENT;
      if (self(h).joints_per_leg_ != 3 || !self(h).three_joint_legs_) return PRONK_ERROR_UNSUPPORTED;
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> out(jacobian);
      out = legJacobian(f);
      return PRONK_OK;
    };
    api_.emit_event = [](void* h, double t, const char* name, const char* detail) {
      self(h).events.push_back({t, name ? name : "", detail ? detail : ""});
    };
    api_.log = [](void* h, int32_t, const char* message) { self(h).log_lines.push_back(message ? message : ""); };
    api_.report_metric = [](void* h, const char* name, double value) { self(h).metrics[name ? name : ""] = value; };
  }

  int32_t jointCount() const { return kFeet * joints_per_leg_; }

  // A forward kinematics for api().foot_position_base that agrees with the
  // constant leg Jacobians: foot = (hip corner) + A_f q_leg (the robot has none
  // by default).
  static pronk_status linearFootPositionBase(void*, int32_t f, const double* q, double p[3]) {
    if (f < 0 || f >= kFeet) return PRONK_ERROR_INVALID_ARGUMENT;
    const Eigen::Vector3d corner((f < 2 ? 0.2 : -0.2), (f % 2 == 0 ? -0.12 : 0.12), -0.3);
    const Eigen::Vector3d v = corner + legJacobian(f) * Eigen::Map<const Eigen::Vector3d>(q + 3 * f);
    for (int i = 0; i < 3; ++i) p[i] = v(i);
    return PRONK_OK;
  }
  const pronk_host_api& api() const { return api_; }

  // The joint block of foot f's Jacobian: constant, invertible, different per leg.
  static Eigen::Matrix3d legJacobian(int f) {
    Eigen::Matrix3d a;
    a << 0.02, -0.21, -0.10,  //
        0.25, 0.01, 0.00,     //
        0.03, 0.12, 0.20;
    a.diagonal().array() += 0.015 * f;
    return a;
  }

  // 3 x (6 + n): base angular, base linear, joints (only this leg's columns non-zero).
  Eigen::MatrixXd footJacobianWorld(int f) const {
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, 6 + jointCount());
    const Eigen::Vector3d r = foot_position_.col(f) - base_;
    Eigen::Matrix3d skew;
    skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    j.block<3, 3>(0, 0) = -skew;
    j.block<3, 3>(0, 3).setIdentity();
    if (joints_per_leg_ == 3) j.block<3, 3>(0, 6 + 3 * f) = legJacobian(f);
    return j;
  }

  // The state handed to the plugin (pointers into this object).
  const pronk_robot_state& state() {
    state_ = pronk_robot_state{};
    state_.struct_size = sizeof(pronk_robot_state);
    state_.time = time;
    state_.joint_count = jointCount();
    state_.q = q_.data();
    state_.qd = qd_.data();
    for (int i = 0; i < 4; ++i) state_.base_quaternion[i] = base_quaternion[i];
    for (int i = 0; i < 3; ++i) {
      state_.base_position[i] = base_(i);
      state_.com_position[i] = com(i);
    }
    state_.foot_count = kFeet;
    state_.foot_position = foot_position_.data();  // column-major 3 x 4: foot f at 3f
    state_.foot_force = zero_forces_.data();
    state_.foot_in_contact = contact_.data();
    return state_;
  }

  std::vector<double>& q() { return q_; }
  std::vector<double>& qd() { return qd_; }
  std::array<uint8_t, kFeet>& contact() { return contact_; }
  Eigen::Matrix<double, 3, kFeet>& feet() { return foot_position_; }
  std::vector<double>& effort() { return effort_; }
  std::vector<double>& velocityLimit() { return velocity_; }
  void setMass(double m) { mass_ = m; }
  void setThreeJointLegs(bool v) { three_joint_legs_ = v; }

  struct Event {
    double time;
    std::string name, detail;
  };
  std::vector<Event> events;
  std::map<std::string, double> metrics;
  std::vector<std::string> log_lines;
  double time = 0;
  Eigen::Vector3d com{0, 0, 0.3};
  std::array<double, 4> base_quaternion{1, 0, 0, 0};

 private:
  static FakeRobot& self(void* h) { return *static_cast<FakeRobot*>(h); }

  int joints_per_leg_;
  bool three_joint_legs_ = true;
  double mass_ = 12.0;
  Eigen::Vector3d base_{0, 0, 0.3};
  Eigen::Matrix<double, 3, kFeet> foot_position_;
  std::array<double, 3 * kFeet> zero_forces_{};
  std::vector<double> effort_, velocity_, q_, qd_;
  std::array<uint8_t, kFeet> contact_{};
  pronk_host_api api_{};
  pronk_robot_state state_{};
};

}  // namespace pronk::test
