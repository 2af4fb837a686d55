// Hindsight relabelling's pieces (host/src/training/hindsight.h): which jumps
// count as examples of the task they achieved, and the pair buffer (the newest
// pairs kept, and back from a checkpoint).
#include <gtest/gtest.h>

#include "hindsight.h"
#include "pronk/error.h"

namespace pronk {
namespace {

TrainingSpec flatRegion() {
  TrainingSpec t;
  t.x = {-0.6, 1.2};
  t.y = {-0.6, 0.6};
  t.z = {0, 0};
  t.yaw = {-1.5, 1.5};
  return t;
}

JumpOutcome standingAt(double x, double y, double z, double yaw) {
  JumpOutcome o;
  o.ran = true;
  o.status = "missed";  // relative to its target; hindsight does not care
  o.landing.displacement = Eigen::Vector3d(x, y, z);
  o.landing.yaw = yaw;
  o.landing.standing = true;
  return o;
}

TEST(Hindsight, AJumpThatEndedStandingAchievedWhereItLanded) {
  TargetSpec target;
  target.x = 0.5;
  target.yaw = 0.3;
  const auto task = hindsight::achievedTask(standingAt(0.42, 0.05, 0.01, 0.25), target, flatRegion());
  ASSERT_TRUE(task.has_value());
  EXPECT_EQ(*task, (std::vector<double>{0.42, 0.05, 0.0, 0.25, 0.0, 0.0}));  // z, roll, pitch: the target's
}

TEST(Hindsight, FailedFallenOffLevelAndFarJumpsTeachNothing) {
  TargetSpec target;
  target.x = 0.5;
  const TrainingSpec region = flatRegion();
  JumpOutcome failed = standingAt(0.4, 0, 0, 0);
  failed.status = "failed";
  EXPECT_FALSE(hindsight::achievedTask(failed, target, region));
  JumpOutcome rejected = standingAt(0.4, 0, 0, 0);
  rejected.status = "rejected";
  rejected.ran = false;
  EXPECT_FALSE(hindsight::achievedTask(rejected, target, region));
  JumpOutcome lying = standingAt(0.4, 0, 0, 0);
  lying.landing.standing = false;
  EXPECT_FALSE(hindsight::achievedTask(lying, target, region));
  EXPECT_FALSE(hindsight::achievedTask(standingAt(0.4, 0, -0.08, 0), target, region)) << "below the target's level";
  // The region widened by a quarter of each range: x up to 1.2 + 0.45.
  EXPECT_TRUE(hindsight::achievedTask(standingAt(1.6, 0, 0, 0), target, region));
  EXPECT_FALSE(hindsight::achievedTask(standingAt(1.7, 0, 0, 0), target, region));
}

TEST(Hindsight, TheBufferKeepsTheNewestPairsAndComesBackFromItsJson) {
  hindsight::Buffer buffer(3);
  for (int i = 0; i < 5; ++i) buffer.add({double(i), 0, 0, 0, 0, 0}, Eigen::VectorXd::Constant(2, 10.0 * i));
  ASSERT_EQ(buffer.size(), 3);
  EXPECT_EQ(buffer.observations()(0, 0), 2.0);  // the two oldest are gone
  EXPECT_EQ(buffer.actions()(1, 2), 40.0);
  hindsight::Buffer back(3);
  back.fromJson(buffer.toJson(), 6, 2);
  EXPECT_EQ(back.observations(), buffer.observations());
  EXPECT_EQ(back.actions(), buffer.actions());
  hindsight::Buffer wrong(3);
  EXPECT_THROW(wrong.fromJson(buffer.toJson(), 6, 3), Error);
  EXPECT_THROW(wrong.fromJson(nlohmann::json::array(), 6, 2), Error);
}

}  // namespace
}  // namespace pronk
