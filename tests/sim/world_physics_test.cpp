// The simulated world against closed forms: ballistic flight of the centre of
// mass, standing height from forward kinematics, mass properties, and failures
// (non-foot contact, divergence) reported instead of crashing.
#include <gtest/gtest.h>

#include <filesystem>

#include "go1_fixture.h"
#include "pronk/controller.h"
#include "pronk/episode.h"
#include "pronk/landing.h"
#include "pronk/world.h"

namespace pronk {
namespace {

using testing::quadrupedPlatform;
using testing::robotUrdf;

World makeWorld(const std::string& urdf, const SimSpec& sim = {}, const Terrain& terrain = Terrain(true, 0, {})) {
  UrdfOptions options;
  return World(loadUrdf(urdf, options), quadrupedPlatform(urdf), sim, terrain);
}

// CoM of every body at the current state, summed from the description (not Simbody's).
Eigen::Vector3d comFromDescription(const World& world) {
  const auto poses = world.bodyPoses();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t b = 0; b < poses.size(); ++b) {
    const MassProperties& m = world.robot().bodies[b].mass;
    sum += m.mass * (poses[b] * m.com_body);
  }
  return sum / world.robot().totalMass();
}

void expectBallistic(const SimSpec& sim, double tolerance) {
  World world = makeWorld(robotUrdf("go1"), sim);
  world.resetTo(Eigen::Vector3d(0, 0, 1.5), 0.3, world.initialJointPositions(), false);
  world.setBaseVelocity(Eigen::Vector3d(1.0, -0.4, 2.0), Eigen::Vector3d(0.5, 1.5, -0.8));
  const Eigen::Vector3d p0 = world.state().com_position, v0 = world.state().com_velocity;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(world.jointCount());
  for (int k = 0; k < 500; ++k) ASSERT_TRUE(world.step(zero)) << world.failure()->detail;
  const double t = world.time();
  ASSERT_NEAR(t, 0.5, 1e-12);
  const Eigen::Vector3d expected = p0 + v0 * t + 0.5 * world.gravity() * t * t;
  EXPECT_LT((world.state().com_position - expected).norm(), tolerance)
      << sim.integrator << ": " << (world.state().com_position - expected).transpose();
  EXPECT_LT((world.state().com_velocity - (v0 + world.gravity() * t)).norm(), 2 * tolerance / 0.5);
}

TEST(WorldPhysics, FreeFlightMatchesBallisticsWithDefaultSettings) {
  expectBallistic(SimSpec{}, 1e-3);
}

TEST(WorldPhysics, FreeFlightMatchesBallisticsWithAccurateIntegrator) {
  SimSpec sim;
  sim.integrator = "runge_kutta_merson";
  sim.accuracy = 1e-8;
  expectBallistic(sim, 1e-6);
}

TEST(WorldPhysics, MassPropertiesMatchTheDescription) {
  World world = makeWorld(robotUrdf("go1"));
  EXPECT_NEAR(world.totalMass(), 13.099448, 1e-9);
  EXPECT_LT((world.state().com_position - comFromDescription(world)).norm(), 1e-12);
  world.resetTo(Eigen::Vector3d(0.2, -0.1, 0.8), 1.0, Eigen::VectorXd::Constant(12, 0.3), false);
  EXPECT_LT((world.state().com_position - comFromDescription(world)).norm(), 1e-12);
}

// Rotational inertia of every body about the whole-body CoM, in the world, summed
// from the description (parallel-axis theorem), not Simbody's.
Eigen::Matrix3d lockedInertiaFromDescription(const World& world) {
  const auto poses = world.bodyPoses();
  const Eigen::Vector3d c = comFromDescription(world);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (size_t b = 0; b < poses.size(); ++b) {
    const MassProperties& m = world.robot().bodies[b].mass;
    const Eigen::Matrix3d R = poses[b].linear();
    const Eigen::Vector3d r = poses[b] * m.com_body - c;
    sum += R * m.inertia_com * R.transpose() + m.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return sum;
}

TEST(WorldPhysics, CentroidalMomentumIsTheLockedInertiaTimesTheRateAndIsKeptInFlight) {
  SimSpec accurate;  // conservation to the integrator's accuracy (the default one keeps 3e-4)
  accurate.integrator = "runge_kutta_merson";
  accurate.accuracy = 1e-8;
  World world = makeWorld(robotUrdf("go1"), accurate);
  world.resetTo(Eigen::Vector3d(0, 0, 1.5), 0.3, Eigen::VectorXd::LinSpaced(12, -0.4, 0.6), false);
  const Eigen::Vector3d w(1.2, -0.7, 2.0);
  world.setBaseVelocity(Eigen::Vector3d(0.5, 0.2, 1.0), w);
  const World::CentroidalMomentum m0 = world.centroidalMomentum();
  EXPECT_LT((m0.locked_inertia - lockedInertiaFromDescription(world)).norm(), 1e-10);
  // Joints at rest: the whole robot turns as one body at the base's rate.
  EXPECT_LT((m0.angular - m0.locked_inertia * world.state().base_angular_velocity).norm(), 1e-10);
  // In flight, with joints that move freely (the spin swings the legs), gravity
  // exerts no moment about the CoM: the momentum stays, the rate does not.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(world.jointCount());
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(world.step(zero)) << world.failure()->detail;
  const World::CentroidalMomentum m1 = world.centroidalMomentum();
  EXPECT_GT(world.state().qd.norm(), 0.1);
  EXPECT_LT((m1.angular - m0.angular).norm(), 1e-6 * m0.angular.norm()) << m1.angular.transpose();
}

TEST(WorldPhysics, AJointDrivenIntoItsLimitRestsOnTheEndStop) {
  // In free fall nothing else loads the joint: at rest the stop's spring carries
  // the motor's torque, q = upper + tau / k with k = 2000 N m/rad (docs/physics.md).
  World world = makeWorld(robotUrdf("go1"));
  world.resetTo(Eigen::Vector3d(0, 0, 3.0), 0.0, world.initialJointPositions(), false);
  const int hip = 3;  // FL hip
  const Joint& joint = world.joint(hip);
  ASSERT_TRUE(joint.has_position_limits);
  Eigen::VectorXd torque = Eigen::VectorXd::Zero(world.jointCount());
  torque(hip) = 10.0;
  for (int k = 0; k < 250; ++k) ASSERT_TRUE(world.step(torque)) << world.failure()->detail;
  EXPECT_NEAR(world.state().q(hip), joint.upper + 10.0 / 2000.0, 1e-3);
  EXPECT_NEAR(world.state().qd(hip), 0.0, 1e-2);
  torque(hip) = -10.0;
  for (int k = 0; k < 250; ++k) ASSERT_TRUE(world.step(torque)) << world.failure()->detail;
  EXPECT_NEAR(world.state().q(hip), joint.lower - 10.0 / 2000.0, 1e-3);
}

TEST(WorldPhysics, ForwardKinematicsMatchesTheLegGeometry) {
  World world = makeWorld(robotUrdf("go1"));
  // Stance (0, 0.75, -1.5): the foot is right below the thigh joint, 2 * 0.213 * cos(0.75) down.
  const Eigen::Vector3d fl = world.footPositionBase(1, world.initialJointPositions());
  EXPECT_NEAR(fl.x(), 0.1881, 1e-12);
  EXPECT_NEAR(fl.y(), 0.04675 + 0.08, 1e-12);
  EXPECT_NEAR(fl.z(), -2 * 0.213 * std::cos(0.75), 1e-12);
  // The leg Jacobian agrees with a central difference of forward kinematics.
  Eigen::VectorXd q = world.initialJointPositions();
  q.segment<3>(3) << 0.2, 0.9, -1.7;
  const Eigen::MatrixXd J = world.legJacobianBase(1, q);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd qp = q, qm = q;
    qp(3 + k) += 1e-6;
    qm(3 + k) -= 1e-6;
    const Eigen::Vector3d fd = (world.footPositionBase(1, qp) - world.footPositionBase(1, qm)) / 2e-6;
    EXPECT_LT((J.col(k) - fd).norm(), 1e-8);
  }
}

TEST(WorldPhysics, FootForcesMapToTorquesThroughTheJacobianTranspose) {
  World world = makeWorld(robotUrdf("go1"));
  world.resetTo(Eigen::Vector3d(0.1, 0.2, 0.5), 0.4, Eigen::VectorXd::LinSpaced(12, -0.3, 0.4), false);
  const std::vector<int> feet{0, 2, 3};
  const std::vector<Eigen::Vector3d> forces{{1, 2, 30}, {-3, 0.5, 25}, {0, -1, 40}};
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(12);
  for (size_t k = 0; k < feet.size(); ++k) {
    expected += world.footJacobianWorld(feet[k]).rightCols(12).transpose() * forces[k];
  }
  EXPECT_LT((world.footForcesToJointTorques(feet, forces) - expected).norm(), 1e-10);
}

// Standing height predicted by forward kinematics: feet on the ground, trunk level.
double predictedStandingHeight(const World& world) {
  const Eigen::Vector3d foot = world.footPositionBase(0, world.initialJointPositions());
  return -foot.z() + world.footRadius(0);
}

TEST(WorldPhysics, StandingRobotHoldsTheForwardKinematicsHeight) {
  World world = makeWorld(robotUrdf("go1"));
  EXPECT_NEAR(world.state().base_position.z(), 0.3317, 1e-4);  // placed touching the ground
  auto controller = makeStandController(world, nullptr);
  const Eigen::Vector3d foot0 = world.state().foot_position[0];
  const EpisodeResult r = runEpisode(world, *controller, {1.5});
  ASSERT_FALSE(r.failure) << r.failure->detail;
  const RobotState& s = world.state();
  // Sag: the contact spring (m g / 4 / k = 0.64 mm) plus whatever the PD leaves.
  EXPECT_NEAR(s.base_position.z(), predictedStandingHeight(world), 2e-3);
  EXPECT_LT(s.base_linear_velocity.norm(), 5e-3);
  // Stiction: standing feet do not creep.
  EXPECT_LT((s.foot_position[0] - foot0).head<2>().norm(), 1e-3);
  double total = 0;
  for (int f = 0; f < 4; ++f) {
    EXPECT_TRUE(s.foot_in_contact[f]);
    total += s.foot_force[f].z();
    EXPECT_NEAR(s.foot_force[f].z(), world.totalMass() * 9.81 / 4, 0.15 * world.totalMass() * 9.81 / 4);
  }
  EXPECT_NEAR(total, world.totalMass() * 9.81, 0.01 * world.totalMass() * 9.81);
}

// The paper's apex platform: a robot tossed straight up (legs held) rises
// v^2 / 2g = 0.115 m; at its apex the platform appears at the target's height
// when the soles clear it, else 5 cm under the lowest sole; a robot that misses
// it falls to the floor (the paper's: 0.5 m under the take-off surface).
TEST(WorldPhysics, TheApexPlatformAppearsUnderTheFeetAtTheTopOfTheFlight) {
  struct Case {
    double x, top, floor, height;  // platform centre x from the start, asked top, floor, the feet's height at the end
  };
  const double rise = 1.5 * 1.5 / (2 * 9.81);
  for (const Case& c : {Case{0, 0.3, -0.5, rise - 0.05}, Case{0, -0.2, -0.5, -0.2}, Case{3.0, -0.1, -0.2, -0.2}}) {
    World world = makeWorld(robotUrdf("go1"));
    auto controller = makeStandController(world, nullptr);
    const double sole0 = world.state().foot_position[0].z() - world.footRadius(0);
    world.setBaseVelocity(Eigen::Vector3d(0, 0, 1.5), Eigen::Vector3d::Zero());
    EpisodeOptions options;
    options.duration = 1.2;
    ApexPlatform apex;
    apex.x = world.state().base_position.x() + c.x;
    apex.y = world.state().base_position.y();
    apex.top = c.top;
    apex.floor = c.floor;
    options.apex_platform = apex;
    const EpisodeResult r = runEpisode(world, *controller, options);
    ASSERT_FALSE(r.failure) << r.failure->detail << " (top " << c.top << " at x " << c.x << ")";
    const TraceEvent* placed = r.trace.findEvent("apex_platform");
    ASSERT_NE(placed, nullptr);
    EXPECT_NEAR(placed->time, 1.5 / 9.81, 0.01);
    // What a video reads back: when, and the top the platform got.
    const std::optional<ApexPlatformEvent> seen = apexPlatformEvent(r.trace);
    ASSERT_TRUE(seen.has_value());
    EXPECT_EQ(seen->time, placed->time);
    const double expected_top = c.top > rise ? sole0 + rise - apex.clearance : std::max(c.top, c.floor);
    EXPECT_NEAR(seen->top, expected_top, 0.01) << "top " << c.top;
    const Landing l = landingOf(r.trace, TargetSpec{});
    EXPECT_NEAR(l.height, c.height - sole0, 0.01) << "top " << c.top << " at x " << c.x;
    EXPECT_TRUE(l.standing);
  }
}

// The terrain the apex platform makes: a square box turned to the target's
// heading with its top where asked, the ground plane moved to the floor, the
// earlier boxes kept.
TEST(WorldPhysics, TheApexTerrainIsThePlatformOverTheFloor) {
  TerrainBox start;
  start.size = {0.5, 0.5, 0.1};
  start.position = {0, 0, 0.05};
  const Terrain before(true, 0, {start});
  ApexPlatform a;
  a.x = 1.0;
  a.y = 0.5;
  a.yaw = M_PI / 4;
  a.floor = -0.5;
  a.size = 2.0;
  const Terrain after = withApexPlatform(before, a, 0.3);
  ASSERT_EQ(after.boxes().size(), 2u);
  EXPECT_DOUBLE_EQ(after.groundHeight(), -0.5);
  EXPECT_NEAR(after.topAt(1.0, 0.5)->height, 0.3, 1e-12);
  // A corner of the turned square: inside along its diagonal, outside beyond it.
  const double half_diagonal = std::sqrt(2.0);
  EXPECT_NEAR(after.topAt(1.0 + 0.99 * half_diagonal, 0.5)->height, 0.3, 1e-12);
  EXPECT_NEAR(after.topAt(1.0 + 1.01 * half_diagonal, 0.5)->height, -0.5, 1e-12);
  EXPECT_NEAR(after.topAt(0, 0)->height, 0.1, 1e-12);  // the take-off box stays
  EXPECT_TRUE(after.contains(Eigen::Vector3d(1.0, 0.5, -0.45)));  // solid down to the floor
}

TEST(WorldPhysics, AnUnreportedTrunkMassIsCarriedButNotTold) {
  // The paper's MV test: 2 kg more in the trunk, the controller keeps the nominal mass.
  const std::string urdf = robotUrdf("go1");
  PlatformSpec platform = quadrupedPlatform(urdf);
  platform.unreported_trunk_mass = 2.0;
  World heavy(loadUrdf(urdf, UrdfOptions{}), platform, SimSpec{}, Terrain(true, 0, {}));
  World nominal = makeWorld(urdf);
  EXPECT_DOUBLE_EQ(heavy.totalMass(), nominal.totalMass());
  auto controller = makeStandController(heavy, nullptr);
  const EpisodeResult r = runEpisode(heavy, *controller, {1.0});
  ASSERT_FALSE(r.failure) << r.failure->detail;
  double total = 0;
  for (int f = 0; f < 4; ++f) total += heavy.state().foot_force[f].z();
  // The ground carries the simulated 15.1 kg, not the told 13.1 kg.
  EXPECT_NEAR(total, (nominal.totalMass() + 2.0) * 9.81, 0.01 * nominal.totalMass() * 9.81);
}

// Summed horizontal path of the front-right foot over a stand: a chattering
// contact (explicit steps too long for the stiff bristle) walks it around.
double footPath(const SimSpec& sim, double seconds) {
  World world = makeWorld(robotUrdf("go1"), sim);
  auto controller = makeStandController(world, nullptr);
  double path = 0;
  Eigen::Vector3d last = world.state().foot_position[0];
  for (int k = 0; k < static_cast<int>(seconds * 1000); ++k) {
    if (!world.step(controller->compute(world.state()))) return INFINITY;
    path += (world.state().foot_position[0] - last).head<2>().norm();
    last = world.state().foot_position[0];
  }
  return path;
}

TEST(WorldPhysics, ImplicitContactStandsStillOnMillisecondStepsWhereExplicitChatters) {
  SimSpec sim;
  sim.integrator = "semi_explicit_euler";
  sim.step = 1e-3;
  const double explicit_path = footPath(sim, 0.5);
  sim.contact.implicit = true;
  const double implicit_path = footPath(sim, 0.5);
  // Measured: 37 mm of chatter in 0.5 s explicitly, 0.54 mm implicitly.
  EXPECT_GT(explicit_path, 0.02) << "implicit " << implicit_path;
  EXPECT_LT(implicit_path, 5e-3) << "explicit " << explicit_path;
  // The implicit contact holds the weight at the same spring sag: the static
  // balance does not depend on the step.
  World world = makeWorld(robotUrdf("go1"), sim);
  auto controller = makeStandController(world, nullptr);
  ASSERT_FALSE(runEpisode(world, *controller, {1.0}).failure);
  EXPECT_NEAR(world.state().base_position.z(), predictedStandingHeight(world), 2e-3);
  const auto& [tangential, normal] = world.footApparentMasses();
  ASSERT_EQ(tangential.size(), 4u);
  EXPECT_GT(tangential[0], 0.05);  // docs/physics.md: about 0.18 kg in stance
  EXPECT_LT(tangential[0], 2.0);
  // Error-controlled integrators choose their own steps: refused by name.
  SimSpec adaptive;
  adaptive.contact.implicit = true;
  EXPECT_THROW(makeWorld(robotUrdf("go1"), adaptive), InputError);
}

TEST(WorldPhysics, StandsOnATerrainBox) {
  TerrainBox box;
  box.size = {1.0, 1.0, 0.2};
  box.position = {0, 0, 0.1};
  World world = makeWorld(robotUrdf("go1"), SimSpec{}, Terrain(true, 0, {box}));
  EXPECT_NEAR(world.state().base_position.z(), 0.2 + 0.3317, 1e-4);
  auto controller = makeStandController(world, nullptr);
  const EpisodeResult r = runEpisode(world, *controller, {0.5});
  ASSERT_FALSE(r.failure) << r.failure->detail;
  EXPECT_NEAR(world.state().base_position.z(), 0.2 + predictedStandingHeight(world), 2e-3);
}

TEST(WorldPhysics, TrunkOnTheGroundIsANonFootContactFailure) {
  World world = makeWorld(robotUrdf("go1"));
  world.resetTo(Eigen::Vector3d(0, 0, 0.04), 0, world.initialJointPositions(), false);
  EXPECT_FALSE(world.step(Eigen::VectorXd::Zero(12)));
  ASSERT_TRUE(world.failure());
  EXPECT_EQ(world.failure()->reason, "non_foot_contact");
  EXPECT_NE(world.failure()->detail.find("trunk"), std::string::npos) << world.failure()->detail;
  EXPECT_FALSE(world.step(Eigen::VectorXd::Zero(12)));  // stays failed until reset
  world.reset();
  EXPECT_TRUE(world.step(Eigen::VectorXd::Zero(12)));
}

TEST(WorldPhysics, BlowUpIsReportedAsDivergence) {
  SimSpec sim;
  sim.integrator = "explicit_euler";
  sim.step = 1e-3;
  sim.contact.stiffness = 1e9;  // far beyond what a 1 ms explicit step can integrate
  World world = makeWorld(robotUrdf("go1"), sim);
  world.resetTo(Eigen::Vector3d(0, 0, 0.45), 0, world.initialJointPositions(), false);
  bool ok = true;
  for (int k = 0; k < 1000 && ok; ++k) ok = world.step(Eigen::VectorXd::Zero(12));
  ASSERT_FALSE(ok);
  EXPECT_EQ(world.failure()->reason, "diverged") << world.failure()->detail;
}

TEST(WorldPhysics, NonFiniteTorqueIsAFailureNotACrash) {
  World world = makeWorld(robotUrdf("go1"));
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(12);
  tau(4) = std::nan("");
  EXPECT_FALSE(world.step(tau));
  EXPECT_EQ(world.failure()->reason, "diverged");
  EXPECT_NE(world.failure()->detail.find("FL_thigh_joint"), std::string::npos) << world.failure()->detail;
}

TEST(WorldPhysics, JointOrderFollowsTheFeetList) {
  World world = makeWorld(robotUrdf("go1"));
  ASSERT_EQ(world.jointCount(), 12);
  EXPECT_EQ(world.jointNames()[0], "FR_hip_joint");
  EXPECT_EQ(world.jointNames()[2], "FR_calf_joint");
  EXPECT_EQ(world.jointNames()[3], "FL_hip_joint");
  EXPECT_EQ(world.jointNames()[11], "RL_calf_joint");
}

// The vendor's own URDFs (BSD-3, ../shared/thirdparty) must load, simulate and stand.
class VendorUrdf : public ::testing::TestWithParam<std::string> {};

TEST_P(VendorUrdf, LoadsSimulatesAndStands) {
  const std::string name = GetParam();
  const std::string path =
      std::string(PRONK_SHARED_DIR) + "/thirdparty/unitree/" + name + "_description/urdf/" + name + ".urdf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  UrdfOptions options;
  const RobotDescription robot = loadUrdf(path, options);
  if (name == "go1") {
    // The vendor's Go1 trunk mesh is not shipped: a warning and a primitive, not an error.
    bool trunk_warning = false;
    for (const std::string& w : robot.warnings) trunk_warning = trunk_warning || w.find("trunk") != std::string::npos;
    EXPECT_TRUE(trunk_warning);
  }
  World world(robot, quadrupedPlatform(path), SimSpec{}, Terrain(true, 0, {}));
  auto controller = makeStandController(world, nullptr);
  const EpisodeResult r = runEpisode(world, *controller, {1.0});
  ASSERT_FALSE(r.failure) << r.failure->detail;
  EXPECT_NEAR(world.state().base_position.z(), predictedStandingHeight(world), 3e-3);
}

INSTANTIATE_TEST_SUITE_P(Unitree, VendorUrdf, ::testing::Values("go1", "aliengo"));

}  // namespace
}  // namespace pronk
