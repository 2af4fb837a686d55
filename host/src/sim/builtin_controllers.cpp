// The host's own controllers: holding a stance, and a scripted joint-space
// jump used to exercise and benchmark contact, flight and landing.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>

#include "pronk/controller.h"

namespace pronk {
namespace {

// Per-joint PD gains from the scenario (defaults plus overrides by name).
struct Gains {
  Eigen::VectorXd kp, kd;
};

Gains gainsOf(const World& world) {
  const JointSettings& js = world.platform().joints;
  Gains g{Eigen::VectorXd::Constant(world.jointCount(), js.kp), Eigen::VectorXd::Constant(world.jointCount(), js.kd)};
  for (int i = 0; i < world.jointCount(); ++i) {
    for (const auto& o : js.overrides) {
      if (o.joint != world.jointNames()[i]) continue;
      if (o.kp) g.kp(i) = *o.kp;
      if (o.kd) g.kd(i) = *o.kd;
    }
  }
  return g;
}

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

class StandController : public Controller {
 public:
  StandController(const World& world, Trace* trace)
      : world_(world), trace_(trace), gains_(gainsOf(world)), q_ref_(world.initialJointPositions()) {}

  void reset(const RobotState& state) override {
    if (trace_) trace_->addEvent(state.time, "phase:stand");
  }

  Eigen::VectorXd compute(const RobotState& s) override {
    Eigen::VectorXd tau = gains_.kp.cwiseProduct(q_ref_ - s.q) - gains_.kd.cwiseProduct(s.qd);
    return tau + gravityCompensation(world_, s);
  }

 private:
  const World& world_;
  Trace* trace_;
  Gains gains_;
  Eigen::VectorXd q_ref_;
};

// Stand, crouch, push, tuck in flight, extend after the apex, land. Every leg
// gets the same (hip, thigh, calf) targets; legs with other joint counts are
// held at their initial configuration.
class ScriptedJumpController : public Controller {
 public:
  enum class Phase { Stand, Crouch, Push, Flight, Descend, Landing };

  ScriptedJumpController(const World& world, Trace* trace)
      : world_(world), trace_(trace), gains_(gainsOf(world)), q_stand_(world.initialJointPositions()) {
    q_crouch_ = legPose({0, 1.05, -2.1});
    q_push_ = legPose({0, 0.75, -1.5});
    q_tuck_ = legPose({0, 0.9, -1.8});
  }

  void reset(const RobotState& state) override {
    phase_ = Phase::Stand;
    phase_start_ = state.time;
    event(state.time, "phase:stand");
  }

  Eigen::VectorXd compute(const RobotState& s) override {
    const double t = s.time;
    bool any_contact = false;
    for (uint8_t c : s.foot_in_contact) any_contact = any_contact || c;
    switch (phase_) {
      case Phase::Stand:
        if (t >= kStandEnd) enter(Phase::Crouch, t, "phase:crouch");
        break;
      case Phase::Crouch:
        if (t >= kCrouchEnd) enter(Phase::Push, t, "phase:push");
        break;
      case Phase::Push:
        if (!any_contact) enter(Phase::Flight, t, "phase:flight");
        else if (t >= kPushTimeout) enter(Phase::Landing, t, "phase:landing");
        break;
      case Phase::Flight:
        if (s.com_velocity.z() < 0) enter(Phase::Descend, t, "phase:descend");
        if (any_contact) enter(Phase::Landing, t, "phase:landing");
        break;
      case Phase::Descend:
        if (any_contact) enter(Phase::Landing, t, "phase:landing");
        break;
      case Phase::Landing:
        break;
    }

    Eigen::VectorXd q_ref = q_stand_;
    double kp_scale = 1;
    bool compensate = true;
    switch (phase_) {
      case Phase::Stand:
        break;
      case Phase::Crouch:
        q_ref = blend(q_stand_, q_crouch_, (t - kStandEnd) / (kCrouchEnd - kStandEnd));
        break;
      case Phase::Push:
        q_ref = blend(q_crouch_, q_push_, (t - kCrouchEnd) / kPushRamp);
        kp_scale = 1;
        break;
      case Phase::Flight:
        q_ref = blend(q_push_, q_tuck_, (t - phase_start_) / 0.08);
        kp_scale = 1.0 / 3;
        compensate = false;
        break;
      case Phase::Descend:
        q_ref = blend(q_tuck_, q_stand_, (t - phase_start_) / 0.08);
        kp_scale = 1.0 / 3;
        compensate = false;
        break;
      case Phase::Landing:
        break;
    }
    // Trunk roll and pitch (ZYX Euler) and their rates, from the base orientation.
    const Eigen::Quaterniond quat(s.base_quaternion(0), s.base_quaternion(1), s.base_quaternion(2), s.base_quaternion(3));
    const Eigen::Matrix3d R = quat.toRotationMatrix();
    const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));  // > 0: nose down
    const double roll = std::atan2(R(2, 1), R(2, 2));
    const Eigen::Vector3d omega_body = R.transpose() * s.base_angular_velocity;
    Eigen::VectorXd tau = kp_scale * gains_.kp.cwiseProduct(q_ref - s.q) - gains_.kd.cwiseProduct(s.qd);
    if (compensate) {
      tau += gravityCompensation(world_, s);
      // Posture: hip and thigh torques react on the trunk; share a roll and
      // pitch correction over the legs on the ground.
      const double legs = static_cast<double>(world_.legJoints().size());
      for (const auto& leg : world_.legJoints()) {
        if (leg.size() != 3) continue;
        tau(leg[0]) += (kAttitudeKp * roll + kAttitudeKd * omega_body.x()) / legs;
        tau(leg[1]) += (kAttitudeKp * pitch + kAttitudeKd * omega_body.y()) / legs;
      }
    }
    return tau;
  }

 private:
  static constexpr double kAttitudeKp = 400, kAttitudeKd = 30;  // N m/rad, N m s/rad
  static constexpr double kStandEnd = 0.2, kCrouchEnd = 0.45, kPushRamp = 0.15, kPushTimeout = 0.75;

  Eigen::VectorXd legPose(const std::array<double, 3>& leg_q) const {
    Eigen::VectorXd q = q_stand_;
    for (const auto& leg : world_.legJoints()) {
      if (leg.size() != 3) continue;
      for (int k = 0; k < 3; ++k) q(leg[k]) = leg_q[k];
    }
    return q;
  }
  static Eigen::VectorXd blend(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double s) {
    return a + smoothstep(s) * (b - a);
  }
  void enter(Phase p, double t, const char* name) {
    phase_ = p;
    phase_start_ = t;
    event(t, name);
  }
  void event(double t, const char* name) {
    if (trace_) trace_->addEvent(t, name);
  }

  const World& world_;
  Trace* trace_;
  Gains gains_;
  Eigen::VectorXd q_stand_, q_crouch_, q_push_, q_tuck_;
  Phase phase_ = Phase::Stand;
  double phase_start_ = 0;
};

}  // namespace

const std::vector<std::string>& builtinControllerNames() {
  static const std::vector<std::string> names{"stand", "scripted_jump"};
  return names;
}

Eigen::VectorXd gravityCompensation(const World& world, const RobotState& s) {
  std::vector<int> feet;
  for (int f = 0; f < world.footCount(); ++f)
    if (s.foot_in_contact[f]) feet.push_back(f);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(world.jointCount());
  if (feet.empty()) return tau;
  // Grasp matrix: foot forces -> net force and moment about the CoM.
  const int n = static_cast<int>(feet.size());
  Eigen::MatrixXd grasp = Eigen::MatrixXd::Zero(6, 3 * n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d r = s.foot_position[feet[k]] - s.com_position;
    grasp.block<3, 3>(0, 3 * k).setIdentity();
    grasp.block<3, 3>(3, 3 * k) << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  }
  Eigen::VectorXd wrench = Eigen::VectorXd::Zero(6);
  wrench.head<3>() = -world.totalMass() * world.gravity();
  const Eigen::VectorXd forces = grasp.completeOrthogonalDecomposition().solve(wrench);
  std::vector<Eigen::Vector3d> per_foot;
  for (int k = 0; k < n; ++k) per_foot.push_back(forces.segment<3>(3 * k));
  // The legs push the ground with -f so that the ground pushes the robot with f.
  tau = -world.footForcesToJointTorques(feet, per_foot);
  return tau;
}

std::unique_ptr<Controller> makeStandController(const World& world, Trace* trace) {
  return std::make_unique<StandController>(world, trace);
}

std::unique_ptr<Controller> makeScriptedJumpController(const World& world, Trace* trace) {
  return std::make_unique<ScriptedJumpController>(world, trace);
}

std::unique_ptr<Controller> makeBuiltinController(const std::string& name, const World& world, Trace* trace) {
  if (name == "stand") return makeStandController(world, trace);
  if (name == "scripted_jump") return makeScriptedJumpController(world, trace);
  throw Error("unknown built-in controller '" + name + "'");
}

}  // namespace pronk
