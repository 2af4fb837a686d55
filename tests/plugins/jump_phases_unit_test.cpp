// Each phase of the jump controller (plugin/guided_jump/control/) on its own
// inputs, on the fake robot of fake_robot.h: no plugin loading, no Simbody.
// With Kp = Kd = 0 a phase's torques are the body wrench alone,
// tau = -sum_i J_i^T f_i, and the fake robot's constant leg Jacobians give the
// feet's forces back: f_i = -(J_i^T)^-1 tau_i.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "control/flight_phase.h"
#include "control/jump_plan.h"
#include "control/landing_phase.h"
#include "control/leg_drive.h"
#include "control/robot_state.h"
#include "control/terrain_clearance.h"
#include "control/thrust_phase.h"
#include "fake_robot.h"
#include "method/ballistics.h"
#include "method/leg_ik.h"

namespace pronk::guided_jump {
namespace {

using test::FakeRobot;

constexpr double kG = 9.81;

class JumpPhaseUnit : public ::testing::Test {
 protected:
  void SetUp() override {
    api_ = robot_.api();
    api_.foot_position_base = FakeRobot::linearFootPositionBase;
    // The wrench alone: no PD.
    hold_.kp = 0.0;
    hold_.kd = 0.0;
  }

  LegDrive drive(std::optional<LegModels> legs = std::nullopt) {
    return LegDrive(&api_, hold_, robot_.jointCount(), FakeRobot::kFeet, legs);
  }

  // The feet's ground forces (world) behind torques that are the wrench alone.
  static Eigen::Matrix<double, 3, FakeRobot::kFeet> feetForces(const Eigen::VectorXd& tau) {
    Eigen::Matrix<double, 3, FakeRobot::kFeet> f;
    for (int i = 0; i < FakeRobot::kFeet; ++i) {
      f.col(i) = -FakeRobot::legJacobian(i).transpose().lu().solve(tau.segment<3>(3 * i));
    }
    return f;
  }

  // The moment of the feet's forces about the CoM.
  Eigen::Vector3d momentAboutCom(const Eigen::Matrix<double, 3, FakeRobot::kFeet>& f) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (int i = 0; i < FakeRobot::kFeet; ++i) m += (robot_.feet().col(i) - robot_.com).cross(f.col(i));
    return m;
  }

  // A plan for a straight-up jump started from the fake robot's stance.
  JumpPlan plan(const LegDrive& d, double landing_height = 0.0) {
    jump::JumpAction a;
    a.thrust_duration_s = 0.45;
    a.liftoff_radius_m = 0.38;
    a.liftoff_elevation_rad = 1.5708;
    a.liftoff_speed_mps = 1.6;
    a.velocity_elevation_rad = 1.5708;
    a.speed_ratio = 1.0;
    a.explosive_distance_m = 0.0;
    return makeJumpPlan(d, robot_.state(), a, 0.0, landing_height);
  }

  FakeRobot robot_;
  pronk_host_api api_{};
  HoldSettings hold_;
};

TEST_F(JumpPhaseUnit, TheJumpPlanStartsOnTheGroundBelowTheCom) {
  LegDrive d = drive();
  const JumpPlan p = plan(d, 0.1);
  // The feet stand at z = 0 with 2 cm radius: the take-off surface is 2 cm below them.
  EXPECT_NEAR(p.origin.z(), -0.02, 1e-12);
  EXPECT_NEAR(p.standing_height, 0.32, 1e-12);
  EXPECT_NEAR(p.landingComHeight(), -0.02 + 0.1 + 0.32, 1e-12);
  // Straight up at 1.6 m/s, down onto a surface 0.1 m up: the CoM at 0.1 + 0.32 m.
  const jump::PointState& lo = p.thrust->liftOff();
  const jump::BallisticFlight flight({lo.position, lo.velocity}, Eigen::Vector3d(0, 0, -kG));
  ASSERT_TRUE(flight.landingTime(0.42).has_value());
  EXPECT_GT(*flight.landingTime(0.42), 0.1);
  EXPECT_NEAR(p.flight_time, *flight.landingTime(0.42), 1e-12);
}

TEST_F(JumpPhaseUnit, TheThrustsDynamicFeedForwardAsksTheFeetForTheMassTimesThePlannedAcceleration) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  ThrustSettings s;
  s.momentum_gain = 0.0;  // the host has no momentum (ABI 1.2): both feedbacks are off either way
  s.momentum_moment_gain = 0.0;
  ThrustPhase thrust(d, s);
  thrust.begin(robot_.state());
  const double t = 0.2;
  Eigen::VectorXd tau(robot_.jointCount());
  thrust.compute(robot_.state(), p, t, tau.data());
  const Eigen::Vector3d a_ref = p.thrust->acceleration(t);
  const Eigen::Vector3d total = feetForces(d.commandedTorque()).rowwise().sum();
  EXPECT_TRUE(total.isApprox(12.0 * (a_ref - Eigen::Vector3d(0, 0, -kG)), 1e-9)) << total.transpose();
  EXPECT_NEAR(momentAboutCom(feetForces(d.commandedTorque())).norm(), 0.0, 1e-9);

  // The paper's gravity feed-forward: the weight alone.
  s.feedforward = Feedforward::kGravity;
  ThrustPhase paper(d, s);
  paper.begin(robot_.state());
  paper.compute(robot_.state(), p, t, tau.data());
  EXPECT_TRUE(feetForces(d.commandedTorque()).rowwise().sum().isApprox(Eigen::Vector3d(0, 0, 12.0 * kG), 1e-9));
}

TEST_F(JumpPhaseUnit, PastThePlansEndTheFeetStillDownCarryNoWeight) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  ThrustPhase thrust(d, ThrustSettings{});
  thrust.begin(robot_.state());
  Eigen::VectorXd tau(robot_.jointCount());
  thrust.compute(robot_.state(), p, p.thrust->duration() + 0.01, tau.data());
  // Kp = Kd = 0 and no wrench: nothing at all.
  EXPECT_NEAR(d.commandedTorque().norm(), 0.0, 1e-12);
  // The reference holds the plan's end point, at rest.
  EXPECT_NEAR(d.qd_ref().norm(), 0.0, 1e-12);
}

TEST_F(JumpPhaseUnit, TheFlightTucksAtAThirdOfTheStiffnessWithoutCarryingTheWeight) {
  hold_.kp = 90.0;
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  LandingPhase landing(d, LandingSettings{});
  FlightSettings s;
  FlightPhase flight(d, s, landing);
  flight.liftOff(robot_.state());  // q = 0
  Eigen::VectorXd tau(robot_.jointCount());
  flight.compute(robot_.state(), p, false, FlightPhase::kBlendTime, tau.data());
  for (int j = 0; j < robot_.jointCount(); ++j) {
    EXPECT_NEAR(d.q_ref()(j), s.tuck[j % 3], 1e-12);
    EXPECT_NEAR(tau(j), 30.0 * s.tuck[j % 3], 1e-9) << j;  // 90 / 3, no J^T f
  }
  // Halfway through the blend, the smoothstep's half.
  flight.compute(robot_.state(), p, false, 0.5 * FlightPhase::kBlendTime, tau.data());
  EXPECT_NEAR(d.q_ref()(1), 0.5 * s.tuck[1], 1e-12);
}

TEST_F(JumpPhaseUnit, TheDescentStartsTheBlendAndTheLeadBeforeThePredictedTouchdown) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  LandingPhase landing(d, LandingSettings{});
  FlightSettings s;
  s.extension = 0.0;
  FlightPhase flight(d, s, landing);
  // Falling at 1 m/s: the CoM reaches its landing height h below after t with
  // h = t + g t^2 / 2. Just over and just under the blend plus the lead (0.16 s).
  const double lead = FlightPhase::kBlendTime + FlightPhase::kExtensionLead;
  pronk_robot_state s0 = robot_.state();
  s0.com_velocity[2] = -1.0;
  for (const double t : {lead + 0.005, lead - 0.005}) {
    s0.com_position[2] = p.landingComHeight() + t + 0.5 * kG * t * t;
    EXPECT_EQ(flight.descentDue(s0, p), t < lead) << t;
  }
  s0.com_velocity[2] = 0.5;  // still rising
  EXPECT_FALSE(flight.descentDue(s0, p));
}

TEST_F(JumpPhaseUnit, TheLandingExtensionIsDerivedFromTheKneesMassAndLegs) {
  // No analytic leg model: none.
  {
    LegDrive d = drive();
    LandingPhase landing(d, LandingSettings{});
    EXPECT_EQ(FlightPhase(d, FlightSettings{}, landing).extension(), 0.0);
  }
  // The Go1's legs and knees (35.55 N m) at 13.1 kg: none; at 26.2 kg the
  // stroke its knees need beyond the stance pose's.
  hold_.stance = {0.0, 0.75, -1.5};
  for (int j = 0; j < robot_.jointCount(); ++j) robot_.effort()[j] = j % 3 == 2 ? 35.55 : 23.7;
  const LegModels legs = jump::go1Legs();
  const Eigen::Vector3d q(0.0, 0.75, -1.5);
  const double lever = std::abs(jump::footPosition(legs[0], q).x() - jump::kneePosition(legs[0], q).x());
  const double length = legs[0].thigh_length + legs[0].calf_length;
  for (const double mass : {13.1, 26.2}) {
    robot_.setMass(mass);
    LegDrive d = drive(legs);
    LandingPhase landing(d, LandingSettings{});
    const double extension = FlightPhase(d, FlightSettings{}, landing).extension();
    EXPECT_NEAR(extension, jump::landingExtension(length, lever, 35.55, mass, kG, 4), 1e-12) << mass;
    if (mass < 20) {
      EXPECT_EQ(extension, 0.0);
    } else {
      EXPECT_GT(extension, 0.05);
    }
  }
  // A set extension is kept.
  FlightSettings set;
  set.extension = 0.07;
  LegDrive d = drive(legs);
  LandingPhase landing(d, LandingSettings{});
  EXPECT_EQ(FlightPhase(d, set, landing).extension(), 0.07);
}

TEST_F(JumpPhaseUnit, AtRestAtItsGoalTheLandingCarriesTheWeightOnEveryFoot) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  LandingPhase landing(d, LandingSettings{});
  landing.reset();
  pronk_robot_state s = robot_.state();
  s.com_position[2] = p.landingComHeight();  // at the standing height, at rest: the goal
  landing.touchDown(s, p);
  Eigen::VectorXd tau(robot_.jointCount());
  landing.compute(s, p, 1.0, 0.0, tau.data());
  const auto f = feetForces(d.commandedTorque());
  const Eigen::Vector3d total = f.rowwise().sum();
  // The goal is the feet's level plus the standing height: the feet stand at
  // 0, the ground below their 2 cm radius; no acceleration asked.
  EXPECT_NEAR(total.z(), 12.0 * kG, 1e-6);
  EXPECT_NEAR(total.head<2>().norm(), 0.0, 1e-6);
  for (int i = 0; i < FakeRobot::kFeet; ++i) EXPECT_GT(f(2, i), 0.0) << i;
}

TEST_F(JumpPhaseUnit, TheLandingsStopAsksNoMoreSidewaysThanItsFrictionShare) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);
  LandingSettings settings;
  LandingPhase landing(d, settings);
  landing.reset();
  pronk_robot_state s = robot_.state();
  s.com_position[2] = p.landingComHeight();
  s.com_velocity[0] = 2.0;  // sliding forward fast: the stop wants far more than friction allows
  landing.touchDown(s, p);
  Eigen::VectorXd tau(robot_.jointCount());
  landing.compute(s, p, 1.0, 0.0, tau.data());
  const Eigen::Vector3d total = feetForces(d.commandedTorque()).rowwise().sum();
  EXPECT_LT(total.x(), 0.0);  // braking
  EXPECT_NEAR(total.head<2>().norm(), settings.friction * total.z(), 1e-6);
  // Where the stop brings it: the landing model's offset.
  const Eigen::Vector2d stop = LandingPhase::landingStop(settings, Eigen::Vector3d(2.0, 0.0, 0.0));
  EXPECT_TRUE(stop.isApprox(jump::landingStopOffset(Eigen::Vector3d(2.0, 0.0, 0.0), 0.6, 5.0)));
  EXPECT_NEAR(stop.x(), 2.0 / 5.0, 1e-12);
}

TEST_F(JumpPhaseUnit, TheLandingTurnsTheTrunkToThePlannedHeading) {
  LegDrive d = drive();
  const JumpPlan p = plan(d);  // straight up: the planned heading is the start's, 0
  ASSERT_NEAR(p.touchdown_yaw, 0.0, 1e-12);
  LandingSettings settings;
  LandingPhase landing(d, settings);
  landing.reset();
  pronk_robot_state s = robot_.state();
  s.com_position[2] = p.landingComHeight();
  // The trunk turned 0.1 rad past it.
  s.base_quaternion[0] = std::cos(0.05);
  s.base_quaternion[3] = std::sin(0.05);
  landing.touchDown(s, p);
  Eigen::VectorXd tau(robot_.jointCount());
  landing.compute(s, p, 1.0, 0.0, tau.data());
  const Eigen::Vector3d moment = momentAboutCom(feetForces(d.commandedTorque()));
  EXPECT_NEAR(moment.z(), 12.0 * settings.yaw_gain * -0.1, 1e-6);
  EXPECT_NEAR(moment.head<2>().norm(), 0.0, 1e-6);
}

// Boxes across the x axis on a ground plane at z = -0.02 (the fake robot's
// feet are spheres of 0.02 m centred at z = 0), answered as the host's
// terrain_top answers (the highest top over the point).
struct TestBox {
  double x0, x1, top;
};
std::vector<TestBox> g_boxes;
double g_ground = -0.02;
pronk_status testTerrainTop(void*, double x, double y, double* height, int32_t* surface) {
  (void)y;
  double best = g_ground;
  int32_t which = -1;
  for (size_t i = 0; i < g_boxes.size(); ++i) {
    if (x >= g_boxes[i].x0 && x <= g_boxes[i].x1 && g_boxes[i].top > best) {
      best = g_boxes[i].top;
      which = static_cast<int32_t>(i);
    }
  }
  if (height) *height = best;
  if (surface) *surface = which;
  return PRONK_OK;
}

class TerrainClearanceUnit : public JumpPhaseUnit {
 protected:
  void SetUp() override {
    JumpPhaseUnit::SetUp();
    api_.terrain_top = testTerrainTop;
    g_boxes.clear();
    g_ground = -0.02;
    robot_.contact().fill(0);  // in the air
  }
  // The Go1's legs at the stance under a level trunk 0.3 m up: the feet just
  // above the ground, the rear ones at x = -0.19, the front ones at +0.19.
  static Eigen::VectorXd stance() {
    Eigen::VectorXd q(12);
    for (int f = 0; f < 4; ++f) q.segment<3>(3 * f) = Eigen::Vector3d(0, 0.75, -1.5);
    return q;
  }
  // The lowest clearance of foot f's knee, mid-calf and foot sphere over the top h.
  double lowest(LegDrive& d, int f, double h) const {
    const jump::LegGeometry& leg = (*d.legs())[f];
    const Eigen::Vector3d q = d.q_ref().segment<3>(3 * f);
    const Eigen::Vector3d base(0, 0, 0.3), knee = base + jump::kneePosition(leg, q),
                          foot = base + jump::footPosition(leg, q);
    return std::min({knee.z() - h, 0.5 * (knee.z() + foot.z()) - h, foot.z() - 0.02 - h});
  }
};

TEST_F(TerrainClearanceUnit, TheHostsTerrainIsReadWhenItOffersIt) {
  g_boxes = {{-1.0, 0.0, 0.25}};
  const std::optional<TerrainTop> top = terrainTop(&api_, -0.5, 0.0);
  ASSERT_TRUE(top);
  EXPECT_DOUBLE_EQ(top->height, 0.25);
  EXPECT_EQ(top->surface, 0);
  api_.struct_size = offsetof(pronk_host_api, terrain_top);  // a host before ABI 1.6
  EXPECT_FALSE(terrainTop(&api_, -0.5, 0.0));
}

TEST_F(TerrainClearanceUnit, OverFlatGroundNothingChanges) {
  LegDrive d = drive(jump::go1Legs());
  const JumpPlan p = plan(d);
  d.q_ref() = stance();
  robot_.com = Eigen::Vector3d(0, 0, 0.3);
  TerrainClearance clearance(d);
  EXPECT_EQ(clearance.apply(robot_.state(), p), 0.0);
  EXPECT_EQ(d.q_ref(), stance());
}

TEST_F(TerrainClearanceUnit, TheRearLegsStayAboveTheBoxBeingLeft) {
  LegDrive d = drive(jump::go1Legs());
  const JumpPlan p = plan(d, -0.3);  // a down jump, 0.3 m
  // The robot has just left the box's edge at x = 0: its rear feet are still
  // over the box's top, its front feet over the ground 0.3 m below.
  g_ground = -0.32;
  g_boxes = {{-1.0, 0.0, -0.02}};
  d.q_ref() = stance();
  TerrainClearance clearance(d);
  const double raised = clearance.apply(robot_.state(), p);
  EXPECT_GT(raised, TerrainClearance::kClearance - 1e-3);
  for (const int rear : {2, 3}) EXPECT_GE(lowest(d, rear, -0.02), TerrainClearance::kClearance - 1e-3) << rear;
  EXPECT_EQ(d.q_ref().head<6>(), stance().head<6>());
}

TEST_F(TerrainClearanceUnit, ATrailingKneeIsSwungAheadOffTheBoxBeingLeft) {
  // Tucked (the flight's 0, 1.37, -2.37), the Go1's rear knees reach 0.40 m
  // behind the trunk, 4 cm below it; the trunk flies on at 1.2 m/s. The box
  // being left ends at x = -0.35, its top 2 cm under the knees: raising the
  // foot would fold the knee further back, so the foot swings ahead instead.
  LegDrive d = drive(jump::go1Legs());
  const JumpPlan p = plan(d, -0.3);
  g_ground = -0.32;
  g_boxes = {{-1.5, -0.35, 0.24}};
  Eigen::VectorXd tuck(12);
  for (int f = 0; f < 4; ++f) tuck.segment<3>(3 * f) = Eigen::Vector3d(0, 1.37, -2.37);
  d.q_ref() = tuck;
  pronk_robot_state s = robot_.state();
  s.com_velocity[0] = 1.2;
  TerrainClearance clearance(d);
  EXPECT_GT(clearance.apply(s, p), 0.0);
  const Eigen::Vector3d base(0, 0, 0.3);
  for (const int rear : {2, 3}) {
    const jump::LegGeometry& leg = (*d.legs())[rear];
    const Eigen::Vector3d q = d.q_ref().segment<3>(3 * rear), q0 = tuck.segment<3>(3 * rear);
    EXPECT_GT(jump::footPosition(leg, q).x(), jump::footPosition(leg, q0).x() + 0.02) << rear;
    // Every point of the thigh and calf over the box is 3 cm above its top.
    const Eigen::Vector3d hip = base + leg.hipPosition(), knee = base + jump::kneePosition(leg, q),
                          foot = base + jump::footPosition(leg, q);
    for (double a = 0.0; a <= 1.0; a += 0.05) {
      for (const Eigen::Vector3d& point : {Eigen::Vector3d(hip + a * (knee - hip)), Eigen::Vector3d(knee + a * (foot - knee))}) {
        if (point.x() <= -0.35) {
          EXPECT_GE(point.z() - 0.24, TerrainClearance::kClearance - 2e-3) << rear << " " << a;
        }
      }
    }
  }
  EXPECT_EQ(d.q_ref().head<6>(), tuck.head<6>());  // the front legs, over the ground, stay
}

TEST_F(TerrainClearanceUnit, TheFrontLegsRiseBeforeTheEdgeAhead) {
  LegDrive d = drive(jump::go1Legs());
  const JumpPlan p = plan(d, 0.1);  // an up jump onto the box ahead
  g_boxes = {{0.3, 1.5, 0.1}};
  d.q_ref() = stance();
  TerrainClearance clearance(d);
  // Standing still, the box's edge is 0.11 m ahead of the front feet: nothing to do.
  EXPECT_EQ(clearance.apply(robot_.state(), p), 0.0);
  // Moving at 2 m/s, the front feet reach it within the look-ahead: they rise.
  pronk_robot_state s = robot_.state();
  s.com_velocity[0] = 2.0;
  EXPECT_GT(clearance.apply(s, p), 0.1);
  for (const int front : {0, 1}) EXPECT_GE(lowest(d, front, 0.1), TerrainClearance::kClearance - 1e-3) << front;
  EXPECT_EQ(d.q_ref().tail<6>(), stance().tail<6>());
  // A foot on the ground is not moved.
  d.q_ref() = stance();
  robot_.contact().fill(1);
  pronk_robot_state down = robot_.state();
  down.com_velocity[0] = 2.0;
  EXPECT_EQ(clearance.apply(down, p), 0.0);
}

}  // namespace
}  // namespace pronk::guided_jump
