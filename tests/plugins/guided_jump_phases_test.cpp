// The guided_jump controller's jump phases through the plugin ABI, on the fake
// robot of fake_robot.h: parameters, the phase events in order, the stand and
// landing phases being the stance controller, the flight phase's reduced
// stiffness without gravity compensation. (The jump itself, with Simbody, is in
// tests/cli/guided_jump_cli_test.cpp.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "fake_robot.h"
#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

using test::FakeRobot;
using ::testing::HasSubstr;

// T_th r_p theta_p r_v theta_v k d roll pitch yaw and rates: straight up.
const char* const kVerticalAction = "0.45 0.38 1.5708 1.6 1.5708 1 0 0 0 0 0 0 0";

class GuidedJumpPhases : public ::testing::Test {
 protected:
  void SetUp() override {
    const PluginLibrary& lib = registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
    path_ = lib.path();
    factory_ = registry_.find(PRONK_FACTORY_CONTROLLER, "guided_jump");
    ASSERT_NE(factory_, nullptr);
    api_ = robot_.api();
    api_.foot_position_base = FakeRobot::linearFootPositionBase;
  }

  std::unique_ptr<ControllerInstance> make(const std::vector<ParamSetting>& settings) {
    return std::make_unique<ControllerInstance>(*factory_, path_, api_,
                                                resolveParams(*factory_, settings, {"test.xml", 1}));
  }

  // The message create() refuses `settings` with ("no error" when it does not).
  std::string createError(const std::vector<ParamSetting>& settings) {
    try {
      make(settings);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  }

  Eigen::VectorXd torques(ControllerInstance& c, const pronk_robot_state& s) {
    Eigen::VectorXd tau = Eigen::VectorXd::Constant(robot_.jointCount(), 1e9);
    c.compute(s, tau.data());
    return tau;
  }

  std::vector<std::string> eventNames() const {
    std::vector<std::string> names;
    for (const auto& e : robot_.events) names.push_back(e.name);
    return names;
  }

  PluginRegistry registry_;
  std::string path_;
  const pronk_factory* factory_ = nullptr;
  FakeRobot robot_;
  pronk_host_api api_{};
};

TEST_F(GuidedJumpPhases, JumpParametersHaveDefaults) {
  const ResolvedParams p = resolveParams(*factory_, {}, {"test.xml", 1});
  EXPECT_EQ(*p.find("action"), "");
  EXPECT_EQ(*p.find("start_delay"), "0.2");
  EXPECT_EQ(*p.find("feedforward"), "dynamic");
  EXPECT_EQ(*p.find("momentum_gain"), "10");
  EXPECT_EQ(*p.find("landing_vertical_frequency"), "10");
  EXPECT_EQ(*p.find("motor"), "effort");
  EXPECT_EQ(*p.find("landing_extension"), "-1");
}

TEST_F(GuidedJumpPhases, ActionOfTheWrongSizeIsRefused) {
  EXPECT_THAT(createError({{"action", "0.45 0.38 1.5708", {}}}), HasSubstr("'action' needs 13 numbers"));
}

TEST_F(GuidedJumpPhases, UnknownFeedforwardIsRefused) {
  EXPECT_THAT(createError({{"feedforward", "magic", {}}}), HasSubstr("'magic' is none of gravity, dynamic, dynamic_angular"));
}

TEST_F(GuidedJumpPhases, UnknownMotorModelIsRefused) {
  EXPECT_THAT(createError({{"motor", "servo", {}}}), HasSubstr("parameter 'motor': 'servo' is neither dc nor effort"));
}

TEST_F(GuidedJumpPhases, DcMotorTorqueFallsWithJointSpeed) {
  // 10 N m motors with a 20 rad/s no-load speed (joint 2: 10 rad/s); the stance
  // PD pushes every joint below its stance hard in + (far more than 10 N m).
  // A DC motor pushes along its motion with 10 (1 - w / w_max) at most, and with
  // its full effort against it; the effort box gives 10 N m at any speed.
  robot_.effort().assign(robot_.effort().size(), 10.0);
  robot_.velocityLimit().assign(robot_.velocityLimit().size(), 20.0);
  robot_.velocityLimit()[2] = 10.0;
  robot_.q() = {0.0, 0.0, -3.0, 0.0, 0.75, -3.0, 0, 0.75, -1.5, 0, 0.75, -1.5};
  robot_.qd()[1] = 10.0;   // along the push at half the no-load speed
  robot_.qd()[2] = -20.0;  // against the push, twice the no-load speed
  robot_.qd()[5] = 25.0;   // along the push, beyond the no-load speed
  robot_.contact().fill(0);  // the PD alone
  auto dc = make({{"motor", "dc", {}}});
  auto box = make({{"motor", "effort", {}}});
  dc->reset(robot_.state());
  box->reset(robot_.state());
  const Eigen::VectorXd t_dc = torques(*dc, robot_.state()), t_box = torques(*box, robot_.state());
  for (int j : {1, 2, 5}) EXPECT_NEAR(t_box(j), 10.0, 1e-12) << j;
  EXPECT_NEAR(t_dc(1), 5.0, 1e-12);
  EXPECT_NEAR(t_dc(2), 10.0, 1e-12);
  EXPECT_NEAR(t_dc(5), 0.0, 1e-12);
}

TEST_F(GuidedJumpPhases, WithoutAnActionItOnlyHolds) {
  auto c = make({});
  c->reset(robot_.state());
  for (double t : {0.0, 0.3, 1.0}) {
    robot_.time = t;
    torques(*c, robot_.state());
  }
  EXPECT_EQ(eventNames(), std::vector<std::string>{"hold"});
}

TEST_F(GuidedJumpPhases, PhasesFollowTheContacts) {
  auto jump = make({{"action", kVerticalAction, {}}});
  auto hold = make({});
  robot_.q() = {0.1, 0.7, -1.4, -0.1, 0.8, -1.5, 0.0, 0.9, -1.6, 0.05, 0.75, -1.5};
  jump->reset(robot_.state());
  hold->reset(robot_.state());

  // Standing until start_delay: the stance controller's torques, no phase yet.
  robot_.time = 0.1;
  const Eigen::VectorXd stand = torques(*jump, robot_.state());
  EXPECT_TRUE(stand.isApprox(torques(*hold, robot_.state()), 1e-12));
  EXPECT_EQ(eventNames(), (std::vector<std::string>{"hold", "hold"}));

  robot_.events.clear();
  robot_.time = 0.2;
  const Eigen::VectorXd thrust = torques(*jump, robot_.state());
  EXPECT_TRUE(thrust.allFinite());
  ASSERT_EQ(eventNames(), std::vector<std::string>{"phase:thrust"});
  EXPECT_DOUBLE_EQ(robot_.events[0].time, 0.2);
  robot_.time = 0.4;
  EXPECT_TRUE(torques(*jump, robot_.state()).allFinite());

  // All feet off: flight, with the reference starting at the measured joints.
  robot_.contact().fill(0);
  robot_.time = 0.6;
  const Eigen::VectorXd flight0 = torques(*jump, robot_.state());
  EXPECT_EQ(eventNames(), (std::vector<std::string>{"phase:thrust", "phase:flight"}));
  EXPECT_LT(flight0.norm(), 1e-9);  // q_ref = q, qd = 0, no gravity compensation
  // After the 0.1 s blend: Kp / 3 towards the tuck (0, 1.38, -2.4).
  robot_.time = 0.75;
  const Eigen::VectorXd tucked = torques(*jump, robot_.state());
  const double tuck[3] = {0.0, 1.38, -2.4};
  for (int j = 0; j < robot_.jointCount(); ++j) EXPECT_NEAR(tucked(j), 100.0 / 3.0 * (tuck[j % 3] - robot_.q()[j]), 1e-9);

  // CoM falling: descend towards the stance (here the trunk is level, so the stance joints).
  pronk_robot_state falling = robot_.state();
  falling.com_velocity[2] = -0.1;
  robot_.time = 0.8;
  falling.time = 0.8;
  torques(*jump, falling);
  EXPECT_EQ(eventNames().back(), "phase:descend");
  falling.time = 0.95;
  const Eigen::VectorXd extended = torques(*jump, falling);
  const double stance[3] = {0.0, 0.75, -1.5};
  for (int j = 0; j < robot_.jointCount(); ++j) {
    EXPECT_NEAR(extended(j), 100.0 / 3.0 * (stance[j % 3] - robot_.q()[j]), 1e-4);  // IK to the level stance
  }

  // One foot down: landing. The legs in the air reach for the stance feet under a
  // level trunk (here: the stance joints, by IK) at Kp / 3 (the stiffness ramps
  // back from touchdown on); only the foot in contact carries the landing wrench.
  robot_.contact()[2] = 1;
  robot_.time = 1.0;
  const Eigen::VectorXd landing = torques(*jump, robot_.state());
  EXPECT_TRUE(landing.allFinite());
  for (int j : {0, 1, 2, 3, 4, 5, 9, 10, 11}) {
    EXPECT_NEAR(landing(j), 100.0 / 3.0 * (stance[j % 3] - robot_.q()[j]), 1e-3) << j;
  }
  // All feet down and the ramp over: full Kp with gravity compensation, finite.
  robot_.contact().fill(1);
  robot_.time = 1.5;
  EXPECT_TRUE(torques(*jump, robot_.state()).allFinite());
  EXPECT_EQ(eventNames(),
            (std::vector<std::string>{"phase:thrust", "phase:flight", "phase:descend", "phase:landing"}));
}

TEST_F(GuidedJumpPhases, NoLiftOffAbandonsTheJump) {
  auto jump = make({{"action", kVerticalAction, {}}, {"start_delay", "0", {}}});
  jump->reset(robot_.state());
  for (int k = 0; k <= 700; ++k) {
    robot_.time = 0.001 * k;
    torques(*jump, robot_.state());
  }
  ASSERT_EQ(eventNames().back(), "phase:landing");
  EXPECT_THAT(robot_.events.back().detail, HasSubstr("no lift-off"));
  EXPECT_NEAR(robot_.events.back().time, 0.45 + 0.15, 2e-3);
}

// The dynamic_angular feed-forward puts the orientation plan's rate of angular
// momentum I alpha + w x I w on the stance feet (besides m (a - g)): its share of
// the torques vanishes without a planned rotation and scales with the inertia the
// host reports. The plain dynamic one has no such share.
double g_inertia_scale = 0.0;

TEST_F(GuidedJumpPhases, DynamicFeedforwardCarriesThePlannedRateOfAngularMomentum) {
  robot_.q() = {0.1, 0.7, -1.4, -0.1, 0.8, -1.5, 0.0, 0.9, -1.6, 0.05, 0.75, -1.5};
  // A jump turning 0.3 rad during the thrust and lifting off at 1 rad/s of yaw.
  const char* const turning = "0.45 0.38 1.5708 1.6 1.5708 1 0 0 0 0.3 0 0 1.0";
  auto thrustTorques = [&](const char* action, double inertia_scale, const char* feedforward = "dynamic_angular") {
    g_inertia_scale = inertia_scale;
    api_.centroidal_momentum = [](void*, double L[3], double I[9]) {
      const double inertia[9] = {0.05, 0.0, 0.0, 0.0, 0.2, 0.01, 0.0, 0.01, 0.25};
      for (int i = 0; i < 3; ++i) L[i] = 0.0;
      for (int i = 0; i < 9; ++i) I[i] = g_inertia_scale * inertia[i];
      return PRONK_OK;
    };
    // Without the momentum feedback, whose ground moment scales with the inertia too.
    auto jump = make({{"action", action, {}},
                      {"feedforward", feedforward, {}},
                      {"start_delay", "0", {}},
                      {"momentum_gain", "0", {}},
                      {"momentum_moment_gain", "0", {}}});
    robot_.time = 0.0;
    jump->reset(robot_.state());
    torques(*jump, robot_.state());  // the thrust starts
    robot_.time = 0.1;               // the yaw Bezier accelerates here
    return torques(*jump, robot_.state());
  };
  const Eigen::VectorXd none = thrustTorques(turning, 0.0);
  const Eigen::VectorXd once = thrustTorques(turning, 1.0) - none;
  const Eigen::VectorXd twice = thrustTorques(turning, 2.0) - none;
  EXPECT_GT(once.norm(), 1e-3);
  EXPECT_TRUE(twice.isApprox(2.0 * once, 1e-9));
  EXPECT_LT((thrustTorques(kVerticalAction, 1.0) - thrustTorques(kVerticalAction, 0.0)).norm(), 1e-12);
  EXPECT_LT((thrustTorques(turning, 1.0, "dynamic") - thrustTorques(turning, 0.0, "dynamic")).norm(), 1e-12);
}

}  // namespace
}  // namespace pronk
