#include "method/reward.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace pronk::jump {
namespace {

constexpr int kJoints = 12;
constexpr int kFeet = 4;
constexpr double kTight = 1e-12;

Eigen::Quaterniond yaw(double angle) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())); }
Eigen::Quaterniond roll(double angle) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())); }

// A Go1 jump that breaks no constraint and lands exactly on its target
// (0.5, 0.1, 0) with yaw 0.3: every cost is zero.
JumpRecord feasibleRecord() {
  JumpRecord r;
  r.tick_s = 0.005;
  r.joint_limits.position_min.resize(kJoints);
  r.joint_limits.position_max.resize(kJoints);
  r.joint_limits.velocity_max.resize(kJoints);
  Eigen::VectorXd stance(kJoints);
  for (int leg = 0; leg < 4; ++leg) {
    r.joint_limits.position_min.segment<3>(3 * leg) << -0.863, -0.686, -2.818;
    r.joint_limits.position_max.segment<3>(3 * leg) << 0.863, 4.501, -0.888;
    r.joint_limits.velocity_max.segment<3>(3 * leg) << 30.1, 30.1, 20.06;
    stance.segment<3>(3 * leg) << 0.0, 0.75, -1.5;
  }
  r.start_base_position = Eigen::Vector3d(0.0134, 0.0, 0.31);
  for (int k = 0; k < 100; ++k) {
    TickSample s;
    s.time = k * r.tick_s;
    s.q = stance;
    s.qd = Eigen::VectorXd::Constant(kJoints, 2.0);
    s.tau_commanded = Eigen::VectorXd::Constant(kJoints, 5.0);
    s.tau_applied = s.tau_commanded;
    s.foot_force.assign(kFeet, Eigen::Vector3d(3.0, -2.0, 32.0));
    s.foot_in_contact.assign(kFeet, true);
    s.base_position = r.start_base_position + Eigen::Vector3d(0.001 * k, 0.0, -0.001 * k);
    r.ticks.push_back(s);
  }
  r.plan.lift_off_com_position = Eigen::Vector3d(0.1, 0.02, 0.38);
  r.plan.lift_off_com_velocity = Eigen::Vector3d(1.2, 0.24, 1.9);
  r.plan.lift_off_orientation = yaw(0.1);
  r.plan.lift_off_angular_velocity = Eigen::Vector3d(0.0, 0.0, 1.5);
  BodyState lift_off;
  lift_off.time = 0.5;
  lift_off.com_position = r.plan.lift_off_com_position;
  lift_off.com_velocity = r.plan.lift_off_com_velocity;
  lift_off.orientation = r.plan.lift_off_orientation;
  lift_off.angular_velocity = r.plan.lift_off_angular_velocity;
  r.lift_off = lift_off;

  r.target.displacement = Eigen::Vector3d(0.5, 0.1, 0.0);
  r.target.orientation = yaw(0.3);
  r.final_state.time = 1.5;
  r.final_state.base_position = r.start_base_position + Eigen::Vector3d(0.5, 0.1, 0.0);
  r.final_state.orientation = yaw(0.3);
  BodyState touchdown = r.final_state;
  touchdown.time = 0.9;
  touchdown.angular_velocity.setZero();
  r.touchdown = touchdown;
  for (int f = 0; f < kFeet; ++f) {
    r.final_foot_positions.push_back(r.final_state.base_position + Eigen::Vector3d(f < 2 ? 0.19 : -0.19, 0.0, 0.0));
    r.final_foot_positions.back().z() = 0.02;  // foot radius: the feet stand on z = 0
  }
  r.raw_action = Eigen::VectorXd::Zero(13);
  return r;
}

double cost(const RewardBreakdown& b, const std::string& name) { return b.asMap().at(name); }

TEST(Reward, FeasibleJumpOnTargetHasNoPenalty) {
  const RewardBreakdown b = computeReward(feasibleRecord());
  for (const RewardTerm* t : b.terms()) EXPECT_EQ(t->cost(), 0.0) << t->name << " value " << t->value;
  EXPECT_EQ(b.terms().size(), 14u);
  EXPECT_TRUE(b.lifted_off);
  EXPECT_TRUE(b.touched_down);
  EXPECT_EQ(b.thrust_ticks, 100);
  EXPECT_NEAR(b.landing_error, 0.0, kTight);
  EXPECT_NEAR(b.jump_distance, std::sqrt(0.26), kTight);
  EXPECT_EQ(b.penalty_gate, 1.0);
  EXPECT_NEAR(b.reward, std::exp(std::sqrt(0.26) / 1.5), kTight);
}

TEST(Reward, WeightsAreTheReferenceCodes) {
  const RewardWeights w;
  EXPECT_EQ(w.joint_position_limits, 1e-3);
  EXPECT_EQ(w.joint_velocity_limits, 1e-3);
  EXPECT_EQ(w.torque_saturation, 1e-3);
  EXPECT_EQ(w.friction_cone, 1e-4);
  EXPECT_EQ(w.unilaterality, 1e-4);
  EXPECT_EQ(w.workspace, 5.0);
  EXPECT_EQ(w.target_orientation, 3.5);
  EXPECT_EQ(w.lift_off_position, 2.0);
  EXPECT_EQ(w.lift_off_orientation, 1.0);
  EXPECT_EQ(w.lift_off_linear_velocity, 0.2);
  EXPECT_EQ(w.lift_off_angular_velocity, 0.2);
  EXPECT_EQ(w.touchdown_bounce, 3.0);
  EXPECT_EQ(w.touchdown_angular_velocity, 0.1);
  EXPECT_EQ(w.action_limit, 5.0);
  const RewardSettings s = go1RewardSettings();
  EXPECT_EQ(s.friction_coefficient, 0.8);
  EXPECT_EQ(s.error_scale, 0.1);
  EXPECT_EQ(s.distance_scale, 1.5);
  EXPECT_EQ(s.penalty_scale, 5.0);
  EXPECT_EQ(aliengoRewardSettings().workspace_z_min, 0.20);
  EXPECT_EQ(aliengoRewardSettings().workspace_z_max, 0.60);
  EXPECT_EQ(aliengoRewardSettings().foot_radius, 0.0265);
  EXPECT_EQ(go1RewardSettings().foot_radius, 0.02);
}

TEST(Reward, ActivationIsTheDistanceOutsideTheInterval) {
  EXPECT_EQ(reward_terms::activation(0.5, 0.0, 1.0), 0.0);
  EXPECT_NEAR(reward_terms::activation(1.3, 0.0, 1.0), 0.3, kTight);
  EXPECT_NEAR(reward_terms::activation(-0.2, 0.0, 1.0), 0.2, kTight);
}

TEST(Reward, JointPositionBeyondTheSoftLimit) {
  JumpRecord r = feasibleRecord();
  // Go1 calf soft upper limit: -1.853 + 0.9 * 0.965 = -0.9845 rad; 0.05 rad beyond it on one tick.
  r.ticks[10].q[2] = -0.9345;
  // Within the hard limit but beyond the soft one on the thigh of another leg: 0.02 rad below -0.4267.
  const double thigh_soft_min = 1.9075 - 0.9 * 2.5935;
  r.ticks[20].q[4] = thigh_soft_min - 0.02;
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.joint_position_limits.value, 0.07, 1e-9);
  EXPECT_NEAR(cost(b, "joint_position_limits"), 0.07 * 1e-3, 1e-12);
  EXPECT_NEAR(b.running_cost, 0.07 * 1e-3, 1e-12);
}

// A continuous joint (the vendor Aliengo's thighs have no position limits) adds
// nothing and keeps the reward finite; a joint with one bound counts beyond it.
TEST(Reward, AJointWithoutPositionLimitsAddsNothing) {
  JointLimits limits;
  limits.position_min = Eigen::Vector3d(-1.0, -INFINITY, -INFINITY);
  limits.position_max = Eigen::Vector3d(1.0, INFINITY, 0.5);
  limits.velocity_max = Eigen::Vector3d::Constant(30);
  EXPECT_EQ(reward_terms::jointPositionExcess(Eigen::Vector3d(0, 100.0, 0.2), limits, 0.9), 0.0);
  EXPECT_NEAR(reward_terms::jointPositionExcess(Eigen::Vector3d(0, -100.0, 0.7), limits, 0.9), 0.2, kTight);
  JumpRecord r = feasibleRecord();
  r.joint_limits.position_min[4] = -INFINITY;
  r.joint_limits.position_max[4] = INFINITY;
  const RewardBreakdown b = computeReward(r);
  EXPECT_TRUE(std::isfinite(b.reward));
  EXPECT_EQ(b.joint_position_limits.value, 0.0);
}

TEST(Reward, RunningTermsCountPerReferenceStepOfTime) {
  // At 1 kHz, five ticks with the same violation weigh as one 5 ms reference step.
  JumpRecord r = feasibleRecord();
  r.tick_s = 0.001;
  for (TickSample& s : r.ticks) s.time *= 0.2;
  for (int k = 0; k < 5; ++k) r.ticks[k].q[2] = -0.9345;
  EXPECT_NEAR(computeReward(r).joint_position_limits.value, 0.05, 1e-9);
}

TEST(Reward, JointVelocityBeyondTheLimitIsCappedPerJoint) {
  JumpRecord r = feasibleRecord();
  r.ticks[3].qd[1] = -30.4;  // 0.3 rad/s beyond 30.1
  r.ticks[4].qd[2] = 25.0;   // 4.94 beyond 20.06, counted as 1.0
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.joint_velocity_limits.value, 1.3, 1e-9);
  EXPECT_NEAR(b.joint_velocity_limits.cost(), 1.3e-3, 1e-12);
}

TEST(Reward, TorqueSaturationIsTheClippedAmount) {
  JumpRecord r = feasibleRecord();
  r.ticks[7].tau_commanded[1] = 30.0;
  r.ticks[7].tau_applied[1] = 23.7;
  r.ticks[8].tau_commanded[2] = -40.0;
  r.ticks[8].tau_applied[2] = -35.5;
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.torque_saturation.value, 6.3 + 4.5, 1e-9);
  EXPECT_NEAR(b.torque_saturation.cost(), 10.8e-3, 1e-12);
}

TEST(Reward, FrictionConeViolation) {
  JumpRecord r = feasibleRecord();
  r.ticks[5].foot_force[0] = Eigen::Vector3d(6.0, 8.0, 10.0);  // |f_xy| 10 > 0.8 * 10: 2 N outside
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.friction_cone.value, 2.0, 1e-12);
  EXPECT_NEAR(b.friction_cone.cost(), 2e-4, 1e-15);
  // A foot not meant to be in contact is not judged.
  r.ticks[5].foot_in_contact[0] = false;
  EXPECT_EQ(computeReward(r).friction_cone.value, 0.0);
}

TEST(Reward, PullingFootViolatesUnilaterality) {
  JumpRecord r = feasibleRecord();
  r.ticks[9].foot_force[3] = Eigen::Vector3d(0.0, 0.0, -5.0);
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.unilaterality.value, 5.0, kTight);
  EXPECT_NEAR(b.unilaterality.cost(), 5e-4, 1e-15);
  // A pulling foot is also outside the friction cone (0 > 0.8 * -5): 4 N.
  EXPECT_NEAR(b.friction_cone.value, 4.0, kTight);
}

TEST(Reward, TrunkOutsideTheWorkspaceBox) {
  JumpRecord r = feasibleRecord();
  r.ticks[0].base_position = r.start_base_position + Eigen::Vector3d(0.2, 0.0, 0.0);    // 0.05 beyond 0.15 in x
  r.ticks[1].base_position = r.start_base_position + Eigen::Vector3d(0.0, -0.17, 0.0);  // 0.02 in y
  r.ticks[2].base_position = Eigen::Vector3d(0.0134, 0.0, 0.12);                        // 0.03 below 0.15
  r.ticks[3].base_position = Eigen::Vector3d(0.0134, 0.0, 0.44);                        // 0.04 above 0.40
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.workspace.value, 0.14, 1e-12);
  EXPECT_NEAR(b.workspace.cost(), 0.7, 1e-11);
  // Aliengo's window is [0.20, 0.60]: 0.44 is fine there, 0.12 is 0.08 low.
  EXPECT_NEAR(computeReward(r, aliengoRewardSettings()).workspace.value, 0.05 + 0.02 + 0.08, 1e-12);
}

TEST(Reward, RunningTermsStopAtLiftOff) {
  JumpRecord r = feasibleRecord();
  r.lift_off->time = 0.2475;  // ticks 0..49 are thrust
  for (std::size_t k = 50; k < r.ticks.size(); ++k) {
    r.ticks[k].q[2] = 0.0;  // far outside the limits, but in flight
    r.ticks[k].foot_force[0] = Eigen::Vector3d(0, 0, -100);
  }
  const RewardBreakdown b = computeReward(r);
  EXPECT_EQ(b.thrust_ticks, 50);
  EXPECT_EQ(b.running_cost, 0.0);
  // Without a lift-off event every tick counts.
  r.lift_off.reset();
  EXPECT_GT(computeReward(r).running_cost, 0.0);
}

TEST(Reward, TargetOrientationError) {
  JumpRecord r = feasibleRecord();
  r.final_state.orientation = yaw(0.3) * roll(0.2);  // 0.2 rad away from the target
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.target_orientation.value, 0.2, 1e-12);
  EXPECT_NEAR(b.target_orientation.cost(), 0.7, 1e-11);
  // The shortest rotation: a yaw error of 2 pi - 0.1 is 0.1.
  r.final_state.orientation = yaw(0.3 + 2 * M_PI - 0.1);
  EXPECT_NEAR(computeReward(r).target_orientation.value, 0.1, 1e-9);
}

TEST(Reward, LiftOffErrorsAgainstThePlan) {
  JumpRecord r = feasibleRecord();
  r.lift_off->com_position += Eigen::Vector3d(0.03, 0.0, -0.04);       // 0.05 m
  r.lift_off->orientation = r.plan.lift_off_orientation * roll(0.15);  // 0.15 rad
  r.lift_off->com_velocity += Eigen::Vector3d(-0.3, 0.4, 0.0);         // 0.5 m/s
  r.lift_off->angular_velocity += Eigen::Vector3d(0.0, 2.0, 0.0);      // 2 rad/s
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.lift_off_position.value, 0.05, kTight);
  EXPECT_NEAR(b.lift_off_orientation.value, 0.15, 1e-12);
  EXPECT_NEAR(b.lift_off_linear_velocity.value, 0.5, kTight);
  EXPECT_NEAR(b.lift_off_angular_velocity.value, 2.0, kTight);
  EXPECT_NEAR(b.terminal_cost, 2 * 0.05 + 1 * 0.15 + 0.2 * 0.5 + 0.2 * 2.0, 1e-11);
}

TEST(Reward, MissingLiftOffComparesThePlanWithTheFinalState) {
  JumpRecord r = feasibleRecord();
  r.lift_off.reset();
  r.final_state.com_position = r.plan.lift_off_com_position + Eigen::Vector3d(0, 0, -0.1);
  r.final_state.com_velocity = r.plan.lift_off_com_velocity;
  r.final_state.angular_velocity = r.plan.lift_off_angular_velocity;
  r.final_state.orientation = r.plan.lift_off_orientation;
  r.target.orientation = r.plan.lift_off_orientation;
  const RewardBreakdown b = computeReward(r);
  EXPECT_FALSE(b.lifted_off);
  EXPECT_NEAR(b.lift_off_position.value, 0.1, kTight);
  EXPECT_EQ(b.lift_off_linear_velocity.value, 0.0);
}

TEST(Reward, TouchdownBounceAndAngularVelocity) {
  JumpRecord r = feasibleRecord();
  r.touchdown->base_position = r.final_state.base_position + Eigen::Vector3d(-0.06, 0.08, 0.05);  // 0.1 m in xy
  r.touchdown->angular_velocity = Eigen::Vector3d(1.0, 2.0, 2.0);                                 // 3 rad/s
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.touchdown_bounce.value, 0.1, kTight);
  EXPECT_NEAR(b.touchdown_bounce.cost(), 0.3, 1e-12);
  EXPECT_NEAR(b.touchdown_angular_velocity.value, 3.0, kTight);
  EXPECT_NEAR(b.touchdown_angular_velocity.cost(), 0.3, 1e-12);
}

TEST(Reward, NoTouchdownTakesTheDefaultsAndKillsTheReward) {
  JumpRecord r = feasibleRecord();
  r.touchdown.reset();
  const RewardBreakdown b = computeReward(r);
  EXPECT_FALSE(b.touched_down);
  EXPECT_EQ(b.touchdown_bounce.value, 2.0);
  EXPECT_EQ(b.touchdown_angular_velocity.value, 10.0);
  EXPECT_NEAR(b.total_cost, 3 * 2.0 + 0.1 * 10.0, kTight);
  EXPECT_NEAR(b.penalty_gate, std::exp(-49.0 / 5.0), 1e-15);
  EXPECT_LT(b.reward, 1e-4);
}

TEST(Reward, ActionLimitIsTheOutOfRangeAmount) {
  JumpRecord r = feasibleRecord();
  r.raw_action[0] = 6.0;     // 1 beyond +5
  r.raw_action[4] = -7.5;    // 2.5 beyond -5
  r.raw_action[12] = 4.999;  // inside
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.action_limit.value, 3.5, kTight);
  EXPECT_NEAR(b.action_limit.cost(), 17.5, 1e-12);
}

TEST(Reward, LandingRewardFormula) {
  JumpRecord r = feasibleRecord();
  r.final_state.base_position += Eigen::Vector3d(0.03, -0.04, 0.0);  // 0.05 m off in xy
  const RewardBreakdown b = computeReward(r);
  EXPECT_NEAR(b.landing_error_xy, 0.05, kTight);
  EXPECT_EQ(b.landing_error_z, 0.0);
  EXPECT_NEAR(b.landing_reward, std::exp(-0.05 / 0.1) * std::exp(std::sqrt(0.26) / 1.5), 1e-12);
  EXPECT_NEAR(reward_terms::landingTargetReward(0.2, 1.0, go1RewardSettings()), std::exp(-2.0 + 1.0 / 1.5), 1e-15);
}

TEST(Reward, HeightErrorHasADeadBand) {
  JumpRecord r = feasibleRecord();
  r.target.displacement = Eigen::Vector3d(0.5, 0.1, 0.2);  // a 0.2 m platform
  const double distance = std::sqrt(0.25 + 0.01 + 0.04);
  auto land_at = [&](double surface) {
    JumpRecord copy = r;
    for (Eigen::Vector3d& f : copy.final_foot_positions) f.z() = surface + 0.02;
    return computeReward(copy);
  };
  const RewardBreakdown inside = land_at(0.2 - 0.09);  // 0.09 m low: inside the band, no error
  EXPECT_EQ(inside.landing_error_z, 0.0);
  EXPECT_NEAR(inside.landing_reward, std::exp(distance / 1.5), 1e-12);
  const RewardBreakdown high = land_at(0.2 + 0.095);
  EXPECT_EQ(high.landing_error_z, 0.0);
  const RewardBreakdown outside = land_at(0.2 - 0.11);  // 0.11 m low: all of it counts
  EXPECT_NEAR(outside.landing_error_z, 0.11, 1e-12);
  EXPECT_NEAR(outside.landing_error, 0.11, 1e-12);
  EXPECT_NEAR(outside.landing_reward, std::exp(-0.11 / 0.1) * std::exp(distance / 1.5), 1e-12);
  // The landing height is the mean foot-centre height less the foot radius.
  JumpRecord tilted = r;
  tilted.final_foot_positions[0].z() = 0.22 + 0.3;
  tilted.final_foot_positions[1].z() = 0.22 + 0.3;
  tilted.final_foot_positions[2].z() = 0.22 - 0.3;
  tilted.final_foot_positions[3].z() = 0.22 - 0.3;
  EXPECT_EQ(computeReward(tilted).landing_error_z, 0.0);
}

TEST(Reward, TotalIsLandingRewardGatedBySquaredCost) {
  JumpRecord r = feasibleRecord();
  r.ticks[10].q[2] = -0.9345;                                      // 0.05 rad -> 5e-5
  r.ticks[11].base_position = Eigen::Vector3d(0.0134, 0.0, 0.10);  // 0.05 m -> 0.25
  r.final_state.orientation = yaw(0.3) * roll(0.1);                // 0.1 rad -> 0.35
  r.lift_off->com_velocity += Eigen::Vector3d(0.0, 0.0, 0.25);     // 0.25 m/s -> 0.05
  r.raw_action[3] = 5.1;                                           // 0.1 -> 0.5
  r.final_state.base_position += Eigen::Vector3d(0.02, 0.0, 0.0);  // e = 0.02; touchdown 0.02 away -> 0.06
  const RewardBreakdown b = computeReward(r);
  const double running = 0.05 * 1e-3 + 0.05 * 5.0;
  const double terminal = 0.1 * 3.5 + 0.25 * 0.2 + 0.1 * 5.0 + 0.02 * 3.0;
  EXPECT_NEAR(b.running_cost, running, 1e-9);
  EXPECT_NEAR(b.terminal_cost, terminal, 1e-9);
  EXPECT_NEAR(b.total_cost, running + terminal, 1e-9);
  double sum = 0.0;
  for (const RewardTerm* t : b.terms()) sum += t->cost();
  EXPECT_NEAR(sum, b.total_cost, 1e-12);
  const double landing = std::exp(-0.02 / 0.1) * std::exp(std::sqrt(0.26) / 1.5);
  EXPECT_NEAR(b.landing_reward, landing, 1e-12);
  EXPECT_NEAR(b.penalty_gate, std::exp(-(running + terminal) * (running + terminal) / 5.0), 1e-9);
  EXPECT_NEAR(b.reward, landing * b.penalty_gate, 1e-12);
  EXPECT_NEAR(cost(b, "reward"), b.reward, 0.0);
}

TEST(Reward, BreakdownNamesEveryTerm) {
  const std::map<std::string, double> m = computeReward(feasibleRecord()).asMap();
  for (const char* name :
       {"joint_position_limits", "joint_velocity_limits", "torque_saturation", "friction_cone", "unilaterality",
        "workspace", "target_orientation", "lift_off_position", "lift_off_orientation", "lift_off_linear_velocity",
        "lift_off_angular_velocity", "touchdown_bounce", "touchdown_angular_velocity", "action_limit", "landing_reward",
        "penalty_gate", "reward", "running_cost", "terminal_cost"}) {
    EXPECT_EQ(m.count(name), 1u) << name;
  }
}

TEST(Reward, InconsistentRecordsAreRejected) {
  JumpRecord r = feasibleRecord();
  r.ticks[4].qd.resize(11);
  try {
    computeReward(r);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tick 4: qd"), std::string::npos) << e.what();
  }
  r = feasibleRecord();
  r.ticks[2].foot_in_contact.pop_back();
  EXPECT_THROW(computeReward(r), std::invalid_argument);
  r = feasibleRecord();
  r.tick_s = 0.0;
  EXPECT_THROW(computeReward(r), std::invalid_argument);
  r = feasibleRecord();
  r.final_foot_positions.clear();
  EXPECT_THROW(computeReward(r), std::invalid_argument);
  RewardSettings bad;
  bad.error_scale = 0.0;
  EXPECT_THROW(computeReward(feasibleRecord(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace pronk::jump
