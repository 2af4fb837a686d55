// The guided_jump controller through the plugin ABI, on a fake robot with
// hand-written kinematics: stance PD, gravity compensation by the grasp-matrix
// pseudo-inverse mapped through J^T, effort clamping.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>

#include "fake_robot.h"
#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

using test::FakeRobot;
using ::testing::HasSubstr;

constexpr double kG = 9.81;

class GuidedJumpController : public ::testing::Test {
 protected:
  void SetUp() override {
    const PluginLibrary& lib = registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
    path_ = lib.path();
    factory_ = registry_.find(PRONK_FACTORY_CONTROLLER, "guided_jump");
    ASSERT_NE(factory_, nullptr);
  }

  std::unique_ptr<ControllerInstance> make(const std::vector<ParamSetting>& settings) {
    return std::make_unique<ControllerInstance>(*factory_, path_, robot_.api(),
                                                resolveParams(*factory_, settings, {"test.xml", 1}));
  }

  // Gravity compensation only: no PD.
  std::unique_ptr<ControllerInstance> makeGravityOnly() { return make({{"kp", "0", {}}, {"kd", "0", {}}}); }

  Eigen::VectorXd torques(ControllerInstance& c) {
    Eigen::VectorXd tau = Eigen::VectorXd::Constant(robot_.jointCount(), 1e9);
    c.compute(robot_.state(), tau.data());
    return tau;
  }

  // The ground force on each foot, recovered from its leg's torques: tau_i = -A_i^T f_i.
  Eigen::Matrix3Xd forcesFrom(const Eigen::VectorXd& tau) {
    Eigen::Matrix3Xd f(3, FakeRobot::kFeet);
    for (int i = 0; i < FakeRobot::kFeet; ++i) {
      f.col(i) = -FakeRobot::legJacobian(i).transpose().lu().solve(tau.segment<3>(3 * i));
    }
    return f;
  }

  // Minimum-norm forces for the weight, written independently of the plugin:
  // f = G^T (G G^T)^-1 w for the feet in contact (G full row rank here).
  Eigen::Matrix3Xd expectedForces() {
    std::vector<int> feet;
    for (int i = 0; i < FakeRobot::kFeet; ++i) {
      if (robot_.contact()[i]) feet.push_back(i);
    }
    Eigen::MatrixXd G(6, 3 * feet.size());
    for (size_t k = 0; k < feet.size(); ++k) {
      const Eigen::Vector3d r = robot_.feet().col(feet[k]) - robot_.com;
      Eigen::Matrix3d skew;
      skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
      G.block<3, 3>(0, 3 * k).setIdentity();
      G.block<3, 3>(3, 3 * k) = skew;
    }
    Eigen::Matrix<double, 6, 1> w;
    w << 0, 0, 12.0 * kG, 0, 0, 0;
    const Eigen::VectorXd f = G.transpose() * (G * G.transpose()).ldlt().solve(w);
    Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, FakeRobot::kFeet);
    for (size_t k = 0; k < feet.size(); ++k) out.col(feet[k]) = f.segment<3>(3 * k);
    return out;
  }

  // Net force and moment about the CoM of the foot forces.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> wrench(const Eigen::Matrix3Xd& f) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
    for (int i = 0; i < FakeRobot::kFeet; ++i) {
      force += f.col(i);
      moment += (robot_.feet().col(i) - robot_.com).cross(f.col(i));
    }
    return {force, moment};
  }

  PluginRegistry registry_;
  std::string path_;
  const pronk_factory* factory_ = nullptr;
  FakeRobot robot_;
};

TEST_F(GuidedJumpController, WeightSplitsEquallyWithTheCoMCentred) {
  auto c = makeGravityOnly();
  const Eigen::Matrix3Xd f = forcesFrom(torques(*c));
  for (int i = 0; i < FakeRobot::kFeet; ++i) {
    EXPECT_NEAR(f(0, i), 0, 1e-9);
    EXPECT_NEAR(f(1, i), 0, 1e-9);
    EXPECT_NEAR(f(2, i), 12.0 * kG / 4, 1e-9) << "foot " << i;
  }
}

TEST_F(GuidedJumpController, FrontFeetCarryMoreWithTheCoMForwardAndTheWrenchBalances) {
  robot_.com = Eigen::Vector3d(0.08, 0.0, 0.3);
  auto c = makeGravityOnly();
  const Eigen::Matrix3Xd f = forcesFrom(torques(*c));
  // Feet 0 and 1 are the front ones (x = +0.2).
  EXPECT_GT(f(2, 0), f(2, 2) + 1.0);
  EXPECT_GT(f(2, 1), f(2, 3) + 1.0);
  const auto [force, moment] = wrench(f);
  EXPECT_NEAR(force.x(), 0, 1e-9);
  EXPECT_NEAR(force.y(), 0, 1e-9);
  EXPECT_NEAR(force.z(), 12.0 * kG, 1e-9);
  EXPECT_NEAR(moment.norm(), 0, 1e-9);
  EXPECT_LT((f - expectedForces()).norm(), 1e-9);
}

TEST_F(GuidedJumpController, TorquesAreMinusJacobianTransposeTimesForces) {
  robot_.com = Eigen::Vector3d(-0.05, 0.03, 0.28);
  auto c = makeGravityOnly();
  const Eigen::VectorXd tau = torques(*c);
  const Eigen::Matrix3Xd f = expectedForces();
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(robot_.jointCount());
  for (int i = 0; i < FakeRobot::kFeet; ++i) {
    expected -= robot_.footJacobianWorld(i).rightCols(robot_.jointCount()).transpose() * f.col(i);
  }
  EXPECT_LT((tau - expected).norm(), 1e-9) << tau.transpose() << "\n" << expected.transpose();
}

TEST_F(GuidedJumpController, FootOutOfContactGetsNoShare) {
  robot_.contact()[3] = 0;
  robot_.com = Eigen::Vector3d(0.05, 0.03, 0.3);  // inside the triangle of feet 0, 1, 2
  auto c = makeGravityOnly();
  const Eigen::VectorXd tau = torques(*c);
  EXPECT_EQ(tau.segment<3>(9), Eigen::Vector3d::Zero());
  const Eigen::Matrix3Xd f = forcesFrom(tau);
  const auto [force, moment] = wrench(f);
  EXPECT_NEAR(force.z(), 12.0 * kG, 1e-9);
  EXPECT_NEAR(moment.norm(), 0, 1e-9);
  EXPECT_LT((f - expectedForces()).norm(), 1e-9);
}

TEST_F(GuidedJumpController, NoFootInContactMeansPdOnly) {
  robot_.contact().fill(0);
  auto c = makeGravityOnly();
  EXPECT_EQ(torques(*c), Eigen::VectorXd::Zero(robot_.jointCount()));
}

TEST_F(GuidedJumpController, PdTermAtAnOffsetPose) {
  const double stance[3] = {0.1, 0.8, -1.6};
  for (int j = 0; j < robot_.jointCount(); ++j) {
    robot_.q()[j] = stance[j % 3] + 0.01 * (j + 1) * (j % 2 ? 1 : -1);
    robot_.qd()[j] = 0.2 - 0.03 * j;
  }
  robot_.contact().fill(0);  // no foot carries weight: the PD alone
  auto c = make({{"kp", "50", {}}, {"kd", "3", {}}, {"stance", "0.1 0.8 -1.6", {}}});
  const Eigen::VectorXd tau = torques(*c);
  for (int j = 0; j < robot_.jointCount(); ++j) {
    EXPECT_NEAR(tau(j), 50 * (stance[j % 3] - robot_.q()[j]) - 3 * robot_.qd()[j], 1e-12) << "joint " << j;
  }
}

TEST_F(GuidedJumpController, PdAndGravityCompensationAdd) {
  robot_.q()[4] = 0.6;  // thigh of leg 1, 0.15 rad from the default stance
  auto both = make({});
  auto gravity_only = makeGravityOnly();
  const Eigen::VectorXd sum = torques(*both), gravity = torques(*gravity_only);
  robot_.contact().fill(0);  // in the air: the PD alone
  const Eigen::VectorXd pd_only = torques(*both);
  EXPECT_LT((sum - pd_only - gravity).norm(), 1e-9);
}

TEST_F(GuidedJumpController, TorquesAreClampedToEffortLimits) {
  for (int j = 0; j < robot_.jointCount(); ++j) robot_.effort()[j] = 5.0 + j;
  for (int j = 0; j < robot_.jointCount(); ++j) robot_.q()[j] = (j % 2 ? 1.0 : -1.0) + (j % 3 == 1 ? 0.75 : 0);
  robot_.q()[2] = -1.5 + 0.01;  // a small error: stays inside its limit
  robot_.contact().fill(0);  // the PD alone
  auto c = make({});
  const Eigen::VectorXd tau = torques(*c);
  for (int j = 0; j < robot_.jointCount(); ++j) {
    if (j == 2) {
      EXPECT_NEAR(tau(j), -1.0, 1e-12);
    } else {
      EXPECT_DOUBLE_EQ(std::abs(tau(j)), 5.0 + j) << "joint " << j;
    }
  }
}

TEST_F(GuidedJumpController, ResetEmitsHold) {
  auto c = make({});
  robot_.time = 0.25;
  c->reset(robot_.state());
  ASSERT_EQ(robot_.events.size(), 1u);
  EXPECT_EQ(robot_.events[0].name, "hold");
  EXPECT_DOUBLE_EQ(robot_.events[0].time, 0.25);
}

TEST_F(GuidedJumpController, CreateFailsUnlessEveryLegHasThreeJoints) {
  FakeRobot two_joint_legs(2);
  try {
    ControllerInstance c(*factory_, path_, two_joint_legs.api(), resolveParams(*factory_, {}, {}));
    FAIL() << "created";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("controller 'guided_jump'"));
    EXPECT_THAT(e.what(), HasSubstr(path_));
    EXPECT_THAT(e.what(), HasSubstr("exactly 3 joints per leg; the robot has 8 joints for 4 feet"));
  }
  robot_.setThreeJointLegs(false);  // 12 joints, but the host has no 3-joint leg Jacobian
  try {
    make({});
    FAIL() << "created";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("no 3-joint leg Jacobian for foot 0"));
  }
}

TEST_F(GuidedJumpController, StateOfTheWrongRobotIsRejected) {
  auto c = make({});
  FakeRobot other(2);
  Eigen::VectorXd tau(12);
  try {
    c->compute(other.state(), tau.data());
    FAIL() << "computed";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("the state has 8 joints"));
  }
}

}  // namespace
}  // namespace pronk
