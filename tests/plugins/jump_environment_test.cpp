// The `jump` environment through the plugin ABI: the observation is the task,
// the action is checked, step() holds the stance (the jump itself is not there
// yet), and finish() gives the paper's landing reward exp(-e / 0.1).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "fake_robot.h"
#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

using test::FakeRobot;
using ::testing::HasSubstr;

class JumpEnvironment : public ::testing::Test {
 protected:
  void SetUp() override {
    const PluginLibrary& lib = registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
    const pronk_factory* f = registry_.find(PRONK_FACTORY_ENVIRONMENT, "jump");
    ASSERT_NE(f, nullptr);
    env_ = std::make_unique<EnvironmentInstance>(*f, lib.path(), robot_.api(),
                                                 resolveParams(*f, {{"duration", "0.5", {}}}, {}));
  }
  static std::vector<double> midAction() { return std::vector<double>(13, 0.0); }

  PluginRegistry registry_;
  FakeRobot robot_;
  std::unique_ptr<EnvironmentInstance> env_;
};

TEST_F(JumpEnvironment, ObservationIsTheTask) {
  const std::vector<double> task = {0.6, -0.2, 0.1, 0.5, 0.05, -0.1};
  EXPECT_EQ(env_->reset(task, 7, robot_.state()), task);
  ASSERT_FALSE(robot_.events.empty());
  EXPECT_EQ(robot_.events.back().name, "hold");
}

TEST_F(JumpEnvironment, TaskMustHaveSixFiniteNumbers) {
  try {
    env_->reset({0.6, 0, 0}, 0, robot_.state());
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("6 numbers"));
  }
}

TEST_F(JumpEnvironment, ActionMustBeThirteenFiniteNumbers) {
  env_->reset({0.6, 0, 0, 0, 0, 0}, 0, robot_.state());
  EXPECT_THROW(env_->act(std::vector<double>(12, 0.0)), Error);
  std::vector<double> action = midAction();
  action[4] = std::numeric_limits<double>::quiet_NaN();
  try {
    env_->act(action);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("action number 4 is not finite"));
  }
  EXPECT_NO_THROW(env_->act(midAction()));
}

TEST_F(JumpEnvironment, StepNeedsAnActionHoldsTheStanceAndEndsAtTheDuration) {
  env_->reset({0.6, 0, 0, 0, 0, 0}, 0, robot_.state());
  std::vector<double> tau(robot_.jointCount());
  try {
    env_->step(robot_.state(), tau.data());
    FAIL() << "stepped without an action";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("step() before act()"));
  }
  env_->act(midAction());
  robot_.time = 0.1;
  EXPECT_FALSE(env_->step(robot_.state(), tau.data()));
  // The hold controller's gravity compensation: the legs push down.
  double sum = 0;
  for (double t : tau) sum += std::abs(t);
  EXPECT_GT(sum, 0);
  robot_.time = 0.5;
  EXPECT_TRUE(env_->step(robot_.state(), tau.data()));
}

TEST_F(JumpEnvironment, RewardIsTheLandingTermOfTheHorizontalError) {
  robot_.com = Eigen::Vector3d(1.0, 2.0, 0.3);
  env_->reset({0.6, 0.0, 0.2, 0, 0, 0}, 0, robot_.state());
  env_->act(midAction());
  robot_.com = Eigen::Vector3d(1.5, 2.1, 0.9);  // moved 0.5 forward, 0.1 left; height does not count
  const double e = std::hypot(0.5 - 0.6, 0.1 - 0.0);
  EXPECT_NEAR(env_->finish(robot_.state()), std::exp(-e / 0.1), 1e-12);
}

TEST_F(JumpEnvironment, TargetIsInTheStartHeadingFrame) {
  robot_.base_quaternion = {std::cos(M_PI / 4), 0, 0, std::sin(M_PI / 4)};  // facing +y
  env_->reset({0.5, 0.0, 0, 0, 0, 0}, 0, robot_.state());
  env_->act(midAction());
  robot_.com += Eigen::Vector3d(0, 0.5, 0);  // 0.5 m straight ahead
  EXPECT_NEAR(env_->finish(robot_.state()), 1.0, 1e-12);
}

}  // namespace
}  // namespace pronk
