// How the host classifies a jump's end state from its trace alone.
#include "pronk/landing.h"
#include "pronk/report.h"

#include <gtest/gtest.h>

#include <optional>

#include <Eigen/Geometry>

namespace pronk {
namespace {

TraceSample sample(double time, const Eigen::Vector3d& position, const Eigen::Quaterniond& q,
                   std::vector<uint8_t> contacts) {
  TraceSample s;
  s.time = time;
  s.base_position = position;
  s.base_quaternion = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  s.foot_in_contact = std::move(contacts);
  return s;
}

Trace jump(const Eigen::Vector3d& end_position, const Eigen::Quaterniond& end_q, std::vector<uint8_t> end_contacts) {
  Trace t;
  t.samples.push_back(sample(0, Eigen::Vector3d(1, 2, 0.3), Eigen::Quaterniond::Identity(), {1, 1, 1, 1}));
  t.samples.push_back(sample(1.5, end_position, end_q, std::move(end_contacts)));
  return t;
}

TargetSpec forward(double x, double yaw = 0) {
  TargetSpec t;
  t.x = x;
  t.yaw = yaw;
  return t;
}

Eigen::Quaterniond tilted(double angle_deg) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_deg * M_PI / 180, Eigen::Vector3d::UnitY()));
}

TEST(JumpLanding, AStandingLandingIsMeasuredInTheStartFrame) {
  const Eigen::Quaterniond yawed(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  const Landing l = landingOf(jump(Eigen::Vector3d(1.38, 2.01, 0.3), yawed, {1, 1, 1, 1}), forward(0.4, 0.45));
  EXPECT_TRUE(l.standing);
  EXPECT_TRUE(l.end_failure.empty());
  EXPECT_NEAR(l.displacement.x(), 0.38, 1e-12);
  EXPECT_NEAR(l.error_xy, std::hypot(0.02, 0.01), 1e-12);
  EXPECT_NEAR(l.error_yaw, 0.05, 1e-12);
  EXPECT_NEAR(l.tilt, 0, 1e-12);
}

TEST(JumpLanding, ATargetWithAHeightCountsTheFeetsHeightAsThePaperDoes) {
  // The feet stand 0.15 m higher at the end (the one in the air is not counted);
  // the target is 0.2 m up: the error is 3-D, 0.05 m short in z, 0.02 / 0.01 in xy.
  Trace t = jump(Eigen::Vector3d(1.38, 2.01, 0.45), Eigen::Quaterniond::Identity(), {1, 1, 1, 0});
  t.samples.front().foot_position.assign(4, Eigen::Vector3d(0, 0, 0.02));
  t.samples.back().foot_position.assign(4, Eigen::Vector3d(0, 0, 0.17));
  t.samples.back().foot_position[3].z() = 0.4;
  TargetSpec up = forward(0.4);
  up.z = 0.2;
  const Landing l = landingOf(t, up);
  EXPECT_NEAR(l.height, 0.15, 1e-12);
  EXPECT_NEAR(l.error_xy, std::hypot(0.02, 0.01), 1e-12);
  EXPECT_NEAR(l.error, std::sqrt(0.02 * 0.02 + 0.01 * 0.01 + 0.05 * 0.05), 1e-12);
  // Without a height the error is the horizontal one, whatever the feet did.
  EXPECT_EQ(landingOf(t, forward(0.4)).error, l.error_xy);
}

TEST(JumpLanding, AFootInTheAirOrAModerateTiltIsALandingThatIsNotStanding) {
  const Landing three_feet = landingOf(jump(Eigen::Vector3d(1.4, 2, 0.3), tilted(10), {1, 1, 0, 1}), forward(0.4));
  EXPECT_FALSE(three_feet.standing);
  EXPECT_TRUE(three_feet.end_failure.empty());
  const Landing leaning = landingOf(jump(Eigen::Vector3d(1.4, 2, 0.3), tilted(45), {1, 1, 1, 1}), forward(0.4));
  EXPECT_FALSE(leaning.standing);
  EXPECT_TRUE(leaning.end_failure.empty());
}

TEST(JumpLanding, ATurnedOverRobotFailsEvenWithItsFeetDown) {
  const Landing l = landingOf(jump(Eigen::Vector3d(1.4, 2, 0.3), tilted(120), {1, 1, 1, 1}), forward(0.4));
  EXPECT_FALSE(l.standing);
  EXPECT_EQ(l.end_failure.rfind("tipped_over: ", 0), 0u) << l.end_failure;
  EXPECT_NE(l.end_failure.find("120 deg"), std::string::npos) << l.end_failure;
}

TEST(JumpLanding, ARobotStillInTheAirAtTheEndFails) {
  const Landing l = landingOf(jump(Eigen::Vector3d(1.4, 2, 0.6), tilted(5), {0, 0, 0, 0}), forward(0.4));
  EXPECT_FALSE(l.standing);
  EXPECT_EQ(l.end_failure.rfind("airborne: ", 0), 0u) << l.end_failure;
}

TEST(JumpLanding, ATraceTooShortHasNoLanding) {
  Trace t;
  t.samples.push_back(sample(0, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {1, 1, 1, 1}));
  const Landing l = landingOf(t, forward(0.4));
  EXPECT_FALSE(l.standing);
  EXPECT_TRUE(std::isnan(l.error_xy));
}

// judgeJump: a landing more than the paper's 0.2 m off is a miss, also for a
// target that sets no tolerance; a tolerance replaces the radius.
TEST(JumpJudge, ALandingBeyondTwentyCentimetresIsAMissWithoutATolerance) {
  auto judged = [](double landed_x, std::optional<double> tolerance) {
    EpisodeRecord r;
    r.episode.target = forward(0.4);
    r.episode.target.tolerance_xy = tolerance;
    r.result.episode.trace = jump(Eigen::Vector3d(1 + landed_x, 2, 0.3), Eigen::Quaterniond::Identity(), {1, 1, 1, 1});
    return judgeJump(r);
  };
  EXPECT_EQ(judged(0.55, std::nullopt).status, "ok");  // 15 cm off
  const JumpOutcome far = judged(0.65, std::nullopt);  // 25 cm off
  EXPECT_EQ(far.status, "missed");
  EXPECT_NE(far.reason.find("error 25.0 cm beyond 20 cm"), std::string::npos) << far.reason;
  EXPECT_EQ(judged(0.65, 0.3).status, "ok");
  EXPECT_EQ(judged(0.55, 0.1).status, "missed");
}

}  // namespace
}  // namespace pronk
