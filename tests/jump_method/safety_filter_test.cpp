// The safety filter (method/safety_filter.h): the paper's ballistic feasibility
// check on a lift-off state, and the whole filter on an action, in its order.
#include "method/safety_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "method/planner.h"
#include "edge_reference.h"

namespace pronk::jump {
namespace {

// Lift-off CoM of the ballistic tests (ballistics_test.cpp).
const Eigen::Vector3d kLiftOff(0.1, 0.02, 0.36);

TEST(SafetyCheck, AcceptsAPlanThatLandsOnTheTarget) {
  const Eigen::Vector3d target(0.8, 0.1, 0.31);
  const LiftOffVelocity v = LiftOffHyperbola(kLiftOff, target).atFlightTime(0.4);
  SafetyCheck check;
  check.max_landing_miss = 0.01;
  check.workspace = [](const Eigen::Vector3d&) { return true; };
  const SafetyVerdict verdict = check(FlightState{kLiftOff, v.velocity}, target);
  EXPECT_TRUE(verdict.safe()) << verdict.reason;
  EXPECT_TRUE(static_cast<bool>(verdict));
  EXPECT_TRUE(verdict.reason.empty());
  EXPECT_STREQ(safetyIssueName(verdict.issue), "none");
}

TEST(SafetyCheck, RejectsAFlightThatStrikesAnEdgeOnTheWay) {
  // Onto a 0.4 m box 1 m ahead: a flat 0.3 s flight passes its edge at 0.5 m too
  // low for the tucked legs (0.17 m below the CoM), a 0.6 s one high enough.
  const Eigen::Vector3d target(1.0, 0.0, 0.4 + 0.31);
  SafetyCheck check;
  check.terrain.edges = {{0.5, 0.4, true}};
  const TerrainEdges::Edge& edge = check.terrain.edges[0];
  auto lowest = [&](const LiftOffVelocity& v) {  // the body's least clearance over the edge (edge_reference.h)
    return edge.top + reference::leastClearanceOver(check.terrain, edge, FlightState{kLiftOff, v.velocity}, target.z(),
                                                  Eigen::Vector3d::Zero(), Eigen::Vector2d::UnitX(), standardGravity());
  };
  const LiftOffVelocity flat = LiftOffHyperbola(kLiftOff, target).atFlightTime(0.3);
  const LiftOffVelocity high = LiftOffHyperbola(kLiftOff, target).atFlightTime(0.6);
  ASSERT_LT(lowest(flat), edge.top + check.terrain.clearance_m);
  ASSERT_GT(lowest(high), edge.top + check.terrain.clearance_m + 1e-3);
  const SafetyVerdict low = check(FlightState{kLiftOff, flat.velocity}, target);
  EXPECT_EQ(low.issue, SafetyIssue::kTerrainEdge);
  EXPECT_STREQ(safetyIssueName(low.issue), "terrain_edge");
  EXPECT_NE(low.reason.find("the edge 0.5 m along the jump (top 0.4 m)"), std::string::npos) << low.reason;
  EXPECT_TRUE(check(FlightState{kLiftOff, high.velocity}, target).safe());
  // Without edges the low flight is fine.
  check.terrain.edges.clear();
  EXPECT_TRUE(check(FlightState{kLiftOff, flat.velocity}, target).safe());
}

TEST(SafetyCheck, RejectsAnApexBelowTheTarget) {
  // v_z = 1 m/s from 0.36 m: apex 0.411 m, target on a 0.3 m platform at 0.61 m.
  const FlightState lo{kLiftOff, Eigen::Vector3d(1.0, 0.0, 1.0)};
  const SafetyVerdict verdict = SafetyCheck{}(lo, Eigen::Vector3d(0.5, 0.0, 0.61));
  EXPECT_FALSE(verdict.safe());
  EXPECT_EQ(verdict.issue, SafetyIssue::kApexBelowTarget);
  EXPECT_NE(verdict.reason.find("apex"), std::string::npos) << verdict.reason;
  EXPECT_NE(verdict.reason.find("0.61"), std::string::npos) << verdict.reason;

  // Above the target, but not by the clearance the caller asks for.
  SafetyCheck strict;
  strict.apex_clearance = 0.1;
  EXPECT_TRUE(SafetyCheck{}(lo, Eigen::Vector3d(0.1, 0, 0.36)).safe());
  EXPECT_EQ(strict(lo, Eigen::Vector3d(0.1, 0, 0.36)).issue, SafetyIssue::kApexBelowTarget);
}

TEST(SafetyCheck, RejectsAnUnreachableTarget) {
  // Jumping backward while the target is ahead.
  const FlightState lo{kLiftOff, Eigen::Vector3d(-1.0, 0.0, 2.0)};
  SafetyCheck check;
  check.max_landing_miss = 0.2;
  const SafetyVerdict verdict = check(lo, Eigen::Vector3d(0.6, 0.0, 0.31));
  EXPECT_EQ(verdict.issue, SafetyIssue::kTargetUnreachable);
  EXPECT_STREQ(safetyIssueName(verdict.issue), "target_unreachable");
  EXPECT_NE(verdict.reason.find("from the target"), std::string::npos) << verdict.reason;

  // A negative clearance lets the apex check pass, but the CoM never gets down to the target height.
  SafetyCheck lax;
  lax.apex_clearance = -1.0;
  EXPECT_EQ(lax(FlightState{kLiftOff, Eigen::Vector3d(1, 0, 0.5)}, Eigen::Vector3d(0.3, 0, 0.8)).issue,
            SafetyIssue::kTargetUnreachable);
}

TEST(SafetyCheck, RejectsALiftOffOutsideTheWorkspace) {
  const Eigen::Vector3d target(0.5, 0.0, 0.31);
  const LiftOffVelocity v = LiftOffHyperbola(kLiftOff, target).leastSpeed();
  SafetyCheck check;
  Eigen::Vector3d seen = Eigen::Vector3d::Constant(NAN);
  check.workspace = [&seen](const Eigen::Vector3d& p) {
    seen = p;
    return p.z() < 0.3;  // lift-off at 0.36 m is too high for these legs
  };
  const SafetyVerdict verdict = check(FlightState{kLiftOff, v.velocity}, target);
  EXPECT_EQ(verdict.issue, SafetyIssue::kOutsideWorkspace);
  EXPECT_EQ(seen, kLiftOff);
  EXPECT_NE(verdict.reason.find("workspace"), std::string::npos);
}

TEST(SafetyCheck, RejectsNonFiniteStates) {
  const SafetyVerdict verdict = SafetyCheck{}(FlightState{kLiftOff, Eigen::Vector3d(NAN, 0, 1)}, kLiftOff);
  EXPECT_EQ(verdict.issue, SafetyIssue::kNotFinite);
  EXPECT_FALSE(verdict.reason.empty());
}

// The whole filter on the Go1's planned 0.4 m forward jump, with the planner's
// workspace (feet on z = 0 under the standing robot, as in planner_test.cpp).
class SafetyFilterOnAPlan : public ::testing::Test {
 protected:
  void SetUp() override {
    cfg_.start_com = {0.0, 0.0, 0.3081};
    cfg_.workspace = standingWorkspace(go1Legs(), Eigen::Vector3d(0.0, 0.75, -1.5), cfg_.start_com,
                                       Eigen::Vector3d(0.0134, 0.0, 0.0036));
    cfg_.workspace->mass = 12.7;  // the Go1's, with its motors' effort limits
    cfg_.workspace->joint_motors = {MotorLimits{23.7}, MotorLimits{23.7}, MotorLimits{35.55}};
    plan_ = planJump({{0.4, 0.0, 0.0}, 0.0}, cfg_);
    ASSERT_TRUE(plan_.feasible) << plan_.reason;
    ballistic_.gravity = cfg_.gravity;
  }
  ThrustPlan thrust() const { return ThrustPlan(plan_.action, plan_.azimuth_rad, cfg_.start_com, cfg_.polarOrigin()); }
  SafetyFilterResult filter(const std::optional<LegWorkspace>& ws) const {
    return safetyFilter(plan_.action, thrust(), plan_.target_com, ballistic_, ws);
  }

  PlannerConfig cfg_;
  PlannedJump plan_;
  SafetyCheck ballistic_;
};

TEST_F(SafetyFilterOnAPlan, PassesAPlannedJumpAndReportsItsSpeedShortfall) {
  const SafetyFilterResult r = filter(cfg_.workspace);
  EXPECT_TRUE(r.verdict.safe()) << r.verdict.reason;
  ASSERT_TRUE(r.speed_shortfall.has_value());
  EXPECT_EQ(*r.speed_shortfall, plan_.speed_shortfall);
  // Without a workspace only the ballistic check runs.
  const SafetyFilterResult ballistic_only = filter(std::nullopt);
  EXPECT_TRUE(ballistic_only.verdict.safe());
  EXPECT_FALSE(ballistic_only.speed_shortfall.has_value());
}

TEST_F(SafetyFilterOnAPlan, TheBallisticCheckComesFirst) {
  // The target 0.2 m above where the plan's apex goes; the motors are too weak as well.
  LegWorkspace weak = *cfg_.workspace;
  weak.joint_motors = {MotorLimits{1.0}, MotorLimits{1.0}, MotorLimits{1.0}};
  const Eigen::Vector3d high(plan_.target_com.x(), 0.0, plan_.apex.z() + 0.2);
  const SafetyFilterResult r = safetyFilter(plan_.action, thrust(), high, ballistic_, weak);
  EXPECT_EQ(r.verdict.issue, SafetyIssue::kApexBelowTarget);
  EXPECT_FALSE(r.speed_shortfall.has_value());
}

TEST_F(SafetyFilterOnAPlan, RejectsAThrustPathThatLosesAFootBeforeCheckingTorque) {
  LegWorkspace far = *cfg_.workspace;
  far.feet[0].x() += 0.5;  // FR's stance foot out of its reach from the start
  const SafetyFilterResult r = filter(far);
  EXPECT_EQ(r.verdict.issue, SafetyIssue::kLegWorkspace);
  EXPECT_STREQ(safetyIssueName(r.verdict.issue), "leg_workspace");
  EXPECT_EQ(r.verdict.reason,
            thrustLeavesWorkspace(plan_.action, plan_.azimuth_rad, cfg_.start_com, cfg_.polarOrigin(), far).value_or(""));
  EXPECT_FALSE(r.speed_shortfall.has_value());
}

TEST_F(SafetyFilterOnAPlan, RejectsAThrustWhoseKneesComeDownBelowTheClearance) {
  // The forward jump's crouch keeps every knee well above its foot: a
  // clearance just below the path's least passes, one just above refuses it,
  // naming the knee, before the torque check.
  const double least = thrustKneeClearance(thrust(), plan_.action, *cfg_.workspace);
  // At the start the knees stand l2 cos(q1 + q2) = 0.213 cos(-0.75) above the feet;
  // the crouch only lowers them.
  EXPECT_LE(least, 0.213 * std::cos(0.75) + 1e-9);
  EXPECT_GT(least, 0.03);
  LegWorkspace ws = *cfg_.workspace;
  ws.knee_clearance = least - 0.005;
  EXPECT_TRUE(filter(ws).verdict.safe()) << filter(ws).verdict.reason;
  ws.knee_clearance = least + 0.005;
  const SafetyFilterResult r = filter(ws);
  EXPECT_EQ(r.verdict.issue, SafetyIssue::kLegWorkspace);
  EXPECT_NE(r.verdict.reason.find("a knee comes down to"), std::string::npos) << r.verdict.reason;
  EXPECT_FALSE(r.speed_shortfall.has_value());
}

TEST_F(SafetyFilterOnAPlan, RejectsMotorsThatMissTheLiftOffSpeedAndSaysWhichJoint) {
  LegWorkspace weak = *cfg_.workspace;
  weak.joint_motors = {MotorLimits{23.7 / 4}, MotorLimits{23.7 / 4}, MotorLimits{35.55 / 4}};
  const SafetyFilterResult r = filter(weak);
  EXPECT_EQ(r.verdict.issue, SafetyIssue::kTorqueLimit);
  EXPECT_STREQ(safetyIssueName(r.verdict.issue), "torque_limit");
  EXPECT_EQ(r.verdict.reason, thrustExceedsTorque(plan_.action, plan_.azimuth_rad, cfg_.start_com, cfg_.polarOrigin(),
                                                  weak, cfg_.gravity)
                                  .value_or(""));
  ASSERT_TRUE(r.speed_shortfall.has_value());
  EXPECT_GT(*r.speed_shortfall, weak.max_speed_shortfall);
  // Without the robot's mass the torques are not predicted: no shortfall to compare.
  weak.mass = 0.0;
  const SafetyFilterResult massless = filter(weak);
  EXPECT_TRUE(massless.verdict.safe());
  ASSERT_TRUE(massless.speed_shortfall.has_value());
  EXPECT_TRUE(std::isnan(*massless.speed_shortfall));
}

}  // namespace
}  // namespace pronk::jump
