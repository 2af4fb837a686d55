// The `jump` environment through the plugin ABI on a fake robot: the
// observation is the task, the action is checked, prior_action is the ballistic
// planner, the safety filter rejects what cannot work before anything runs, and
// finish() reports the reward with every term as a metric. (Whole jumps on the
// simulated Go1 are scenario tests: tests/cli/guided_jump_cli_test.cpp.)
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
                                                 resolveParams(*f, {{"duration", "0.5", {}}, {"start_delay", "1.0", {}}}, {}));
  }
  static std::vector<double> midAction() { return std::vector<double>(13, 0.0); }

  PluginRegistry registry_;
  FakeRobot robot_;
  std::unique_ptr<EnvironmentInstance> env_;
};

TEST_F(JumpEnvironment, ObservationIsTheTask) {
  const std::vector<double> task = {0.6, -0.2, 0.1, 0.5, 0.05, -0.1};
  EXPECT_EQ(env_->reset(task, 7, robot_.state()), task);
}

TEST_F(JumpEnvironment, TaskMustHaveSixFiniteNumbers) {
  try {
    env_->reset({0.6, 0, 0}, 0, robot_.state());
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("6 numbers"));
  }
}

TEST_F(JumpEnvironment, ActionMustBeThirteenNumbersWithoutNaN) {
  env_->reset({0.6, 0, 0, 0, 0, 0}, 0, robot_.state());
  EXPECT_THROW(env_->act(std::vector<double>(12, 0.0)), Error);
  std::vector<double> action = midAction();
  action[4] = std::numeric_limits<double>::quiet_NaN();
  try {
    env_->act(action);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("action number 4 is NaN"));
  }
}

TEST_F(JumpEnvironment, PriorActionIsAFeasiblePlanTheFilterAccepts) {
  ASSERT_TRUE(env_->hasPriorAction());
  const std::vector<double> obs = env_->reset({0.4, 0, 0, 0, 0, 0}, 0, robot_.state());
  const std::vector<double> action = env_->priorAction(obs);
  ASSERT_EQ(action.size(), 13u);
  for (double a : action) EXPECT_LE(std::abs(a), 5.0 + 1e-9);  // inside the raw range: no action-limit penalty
  EXPECT_EQ(env_->act(action), std::nullopt);
  // The plan's predicted CoM landing is the target, less the landing's stopping distance.
  ASSERT_TRUE(robot_.metrics.count("predicted_landing_x"));
  EXPECT_GT(robot_.metrics["predicted_landing_x"], 0.1);
  EXPECT_LT(robot_.metrics["predicted_landing_x"], 0.4 + 1e-9);
  EXPECT_NEAR(robot_.metrics["predicted_landing_y"], 0.0, 1e-9);
  // Carried on by that stop, the CoM comes to rest at the target: the video's ball.
  EXPECT_NEAR(robot_.metrics["predicted_rest_x"], 0.4, 0.01);
  EXPECT_NEAR(robot_.metrics["predicted_rest_y"], 0.0, 1e-9);
}

TEST_F(JumpEnvironment, SafetyFilterRejectsAnImpossibleUpJumpBeforeItRuns) {
  // 1 m up: no action in the ranges gets the CoM that high. The planner's best
  // try is refused for the planner's reason; any other action, by the filter.
  const std::vector<double> obs = env_->reset({0.3, 0, 1.0, 0, 0, 0}, 0, robot_.state());
  std::vector<double> best = env_->priorAction(obs);
  const std::optional<std::string> why = env_->act(best);
  ASSERT_TRUE(why.has_value());
  EXPECT_THAT(*why, HasSubstr("action_range: "));
  EXPECT_THAT(*why, HasSubstr("exceeds k_max x the Bezier speed cap"));
  env_->reset({0.3, 0, 1.0, 0, 0, 0}, 0, robot_.state());
  best[0] += 1e-6;
  const std::optional<std::string> filtered = env_->act(best);
  ASSERT_TRUE(filtered.has_value());
  EXPECT_THAT(*filtered, HasSubstr("apex_below_target"));
  // The slowest lift-off (every raw output at its lower end) cannot reach 0.4 m up either.
  env_->reset({0.3, 0, 0.4, 0, 0, 0}, 0, robot_.state());
  const std::optional<std::string> slow = env_->act(std::vector<double>(13, -5.0));
  ASSERT_TRUE(slow.has_value());
  EXPECT_THAT(*slow, HasSubstr("apex"));
  // Nothing runs after a rejection.
  std::vector<double> tau(robot_.jointCount());
  EXPECT_THROW(env_->step(robot_.state(), tau.data()), Error);
}

// ABI 1.4: the planner's verdict comes with its action; retask() starts the
// episode again with another task (an aim correction's), nothing moved.
TEST_F(JumpEnvironment, PriorActionSaysWhenItHasNoFeasiblePlanAndRetaskChangesTheTask) {
  const std::vector<double> obs = env_->reset({0.4, 0, 0, 0, 0, 0}, 0, robot_.state());
  const EnvironmentInstance::PriorAction feasible = env_->prior(obs);
  EXPECT_EQ(feasible.infeasible, std::nullopt);
  EXPECT_EQ(feasible.action, env_->priorAction(obs));
  const EnvironmentInstance::PriorAction far = env_->prior({3.0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(far.infeasible.has_value());
  EXPECT_THAT(*far.infeasible, HasSubstr("no feasible jump"));
  ASSERT_EQ(far.action.size(), 13u);  // its best try, which act() refuses
  const std::vector<double> aimed = env_->retask({0.45, 0.02, 0, 0.05, 0, 0});
  EXPECT_EQ(aimed, (std::vector<double>{0.45, 0.02, 0, 0.05, 0, 0}));
  EXPECT_EQ(env_->act(env_->priorAction(aimed)), std::nullopt);
  EXPECT_NEAR(robot_.metrics["predicted_landing_y"], 0.02 * robot_.metrics["predicted_landing_x"] / 0.45, 1e-3)
      << "the jump plane is the new task's";
  EXPECT_THROW(env_->retask(obs), Error) << "no retask once the action is taken";
}

TEST_F(JumpEnvironment, StepNeedsAnActionAndEndsAtTheDuration) {
  const std::vector<double> obs = env_->reset({0.4, 0, 0, 0, 0, 0}, 0, robot_.state());
  std::vector<double> tau(robot_.jointCount());
  try {
    env_->step(robot_.state(), tau.data());
    FAIL() << "stepped without an action";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("step() before act()"));
  }
  ASSERT_EQ(env_->act(env_->priorAction(obs)), std::nullopt);
  robot_.time = 0.1;
  EXPECT_FALSE(env_->step(robot_.state(), tau.data()));
  double sum = 0;  // standing before the thrust (start_delay 1 s): the legs carry the weight
  for (double t : tau) sum += std::abs(t);
  EXPECT_GT(sum, 0);
  // Not in the air at the duration: the episode ends there. (A jump in the air
  // runs on: JumpRuns.AFlightInTheAirAtTheDurationIsNotCutOff, on the whole robot.)
  robot_.time = 0.5;
  EXPECT_TRUE(env_->step(robot_.state(), tau.data()));
}

TEST_F(JumpEnvironment, FinishReportsTheRewardAndEveryTerm) {
  const std::vector<double> obs = env_->reset({0.4, 0, 0, 0, 0, 0}, 0, robot_.state());
  ASSERT_EQ(env_->act(env_->priorAction(obs)), std::nullopt);
  std::vector<double> tau(robot_.jointCount());
  robot_.time = 0.1;
  env_->step(robot_.state(), tau.data());
  const double reward = env_->finish(robot_.state());
  EXPECT_GE(reward, 0.0);
  EXPECT_LE(reward, 1.0);
  for (const char* term : {"joint_position_limits", "friction_cone", "workspace", "lift_off_position",
                           "touchdown_bounce", "action_limit", "landing_reward", "cost_gate", "reward_error_xy"}) {
    EXPECT_TRUE(robot_.metrics.count(term)) << term;
  }
  // Every metric it reported is declared (ABI 1.3), the cost terms as penalties:
  // the host's report files them by these declarations alone.
  const EnvironmentSchema schema = environmentSchema(env_->factory());
  for (const auto& [name, value] : robot_.metrics) {
    const MetricSpec* spec = schema.find(name);
    ASSERT_NE(spec, nullptr) << name << " is reported but not declared";
  }
  for (const char* term : {"joint_position_limits", "friction_cone", "action_limit"}) {
    ASSERT_NE(schema.find(term), nullptr) << term;
    EXPECT_EQ(schema.find(term)->kind, MetricSpec::Kind::Penalty) << term;
  }
  EXPECT_EQ(schema.find("landing_reward")->kind, MetricSpec::Kind::Value);
  EXPECT_EQ(schema.find("planned_lift_off_time")->kind, MetricSpec::Kind::Time);
  EXPECT_EQ(schema.task_names, (std::vector<std::string>{"x", "y", "z", "yaw", "roll", "pitch"}));
  ASSERT_EQ(schema.markers.size(), 2u);
  EXPECT_EQ(schema.markers[0].kind, MarkerSpec::Kind::Arc);
  // The robot never moved: the landing error is the whole target distance, and
  // the reward is the landing term times the penalty gate.
  EXPECT_NEAR(robot_.metrics["reward_error_xy"], 0.4, 1e-6);
  EXPECT_NEAR(reward, robot_.metrics["landing_reward"] * robot_.metrics["cost_gate"], 1e-12);
}

}  // namespace
}  // namespace pronk
