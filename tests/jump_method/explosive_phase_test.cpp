// Explosive (UARM) extension after the Bezier and the combined ThrustPlan: a true
// uniformly accelerated profile from |v| to k|v| over the distance d, joined to
// the Bezier in position and velocity, with T_e = 2 d / ((1 + k) |v|).
#include "method/explosive_phase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).lpNorm<Eigen::Infinity>(), tol)
      << "actual (" << actual.transpose() << ") expected (" << expected.transpose() << ")";
}

const Eigen::Vector3d kComStart(-0.013, 0.0, 0.308);
// The lift-off velocity is deliberately not parallel to the lift-off position
// vector, where the reference code's norm-difference "distance" differs from d.
const PointState kBezierLiftOff{{0.15, 0.05, 0.33}, {1.2, 0.4, 1.5}};

ThrustPlan makePlan(double k, double d, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  PointState lo = kBezierLiftOff;
  lo.position += offset;
  return ThrustPlan(kComStart + offset, lo, 0.6, k, d);
}

TEST(ExplosivePhase, DurationIsTwoDOverTheMeanSpeed) {
  const double v0 = kBezierLiftOff.velocity.norm();
  for (double k : {0.5, 1.0, 1.7, 3.0}) {
    for (double d : {0.01, 0.15, 0.3}) {
      const ExplosivePhase e(kBezierLiftOff, k, d);
      SCOPED_TRACE(testing::Message() << "k " << k << " d " << d);
      EXPECT_NEAR(e.duration(), 2.0 * d / ((1.0 + k) * v0), 1e-15);
      EXPECT_NEAR(e.accelerationAlongPath(), (k * v0 - v0) / e.duration(), 1e-9);
      EXPECT_DOUBLE_EQ(e.startSpeed(), v0);
    }
  }
}

TEST(ExplosivePhase, EndsAtDistanceDAlongTheLiftOffVelocityWithSpeedKTimesV) {
  const double k = 2.2, d = 0.18;
  const ExplosivePhase e(kBezierLiftOff, k, d);
  const Eigen::Vector3d u = kBezierLiftOff.velocity.normalized();
  expectNear(e.direction(), u, 1e-15);
  // End state from the closed-form motion, not from the stored end state.
  const double tau = e.duration() * (1.0 - 1e-12);
  EXPECT_NEAR((e.position(tau) - kBezierLiftOff.position).norm(), d, 1e-12);
  expectNear(e.velocity(tau), k * kBezierLiftOff.velocity, 1e-10);
  // And the stored end state.
  expectNear(e.endState().position, kBezierLiftOff.position + d * u, 1e-15);
  expectNear(e.endState().velocity, k * kBezierLiftOff.velocity, 1e-15);
}

TEST(ExplosivePhase, PositionIsHalfATSquaredAndSpeedIsLinearInTime) {
  const double k = 3.0, d = 0.2;
  const ExplosivePhase e(kBezierLiftOff, k, d);
  const double v0 = e.startSpeed(), a = e.accelerationAlongPath();
  const Eigen::Vector3d u = e.direction();
  for (double frac : {0.1, 0.25, 0.5, 0.8, 0.95}) {
    const double tau = frac * e.duration();
    SCOPED_TRACE(frac);
    expectNear(e.position(tau), kBezierLiftOff.position + (v0 * tau + 0.5 * a * tau * tau) * u, 1e-14);
    expectNear(e.velocity(tau), (v0 + a * tau) * u, 1e-13);
    expectNear(e.acceleration(tau), a * u, 1e-12);
  }
  // Not the reference code's constant-velocity lerp: halfway in time, a UARM
  // from v0 to 3 v0 has covered (1 + (k - 1) / 4) / (1 + k) d = 0.375 d, not d / 2.
  EXPECT_NEAR((e.position(0.5 * e.duration()) - kBezierLiftOff.position).norm(), 0.375 * d, 1e-14);
}

TEST(ThrustPlan, PositionAndVelocityAreContinuousAtTheEndOfTheBezier) {
  const ThrustPlan plan = makePlan(2.5, 0.2);
  const double tb = plan.bezierDuration();
  EXPECT_DOUBLE_EQ(tb, 0.6);
  expectNear(plan.position(tb), kBezierLiftOff.position, 1e-12);
  expectNear(plan.velocity(tb), kBezierLiftOff.velocity, 1e-12);
  const double eps = 1e-9;
  expectNear(plan.position(tb + eps), plan.position(tb - eps), 1e-8);
  expectNear(plan.velocity(tb + eps), plan.velocity(tb - eps), 1e-6);
  // The acceleration jumps there: the Bezier's end value on the left, a u on the right.
  expectNear(plan.acceleration(tb), plan.bezier().acceleration(tb), 0.0);
  expectNear(plan.acceleration(tb + eps), plan.explosive().accelerationAlongPath() * plan.explosive().direction(), 0.0);
}

TEST(ThrustPlan, VelocityAndAccelerationAreDerivativesOnBothSegments) {
  const ThrustPlan plan = makePlan(1.8, 0.25);
  const double h = 1e-7;
  const double tb = plan.bezierDuration(), end = plan.duration();
  for (double t : {0.05, 0.3, 0.55, tb + 0.2 * (end - tb), tb + 0.5 * (end - tb), tb + 0.9 * (end - tb)}) {
    SCOPED_TRACE(t);
    expectNear(plan.velocity(t), (plan.position(t + h) - plan.position(t - h)) / (2 * h), 1e-6);
    expectNear(plan.acceleration(t), (plan.velocity(t + h) - plan.velocity(t - h)) / (2 * h), 1e-5);
  }
}

TEST(ThrustPlan, CoversBezierThenExplosiveAndReportsTheActualLiftOff) {
  const double k = 2.0, d = 0.15;
  const ThrustPlan plan = makePlan(k, d);
  const double te = 2 * d / ((1 + k) * kBezierLiftOff.velocity.norm());
  EXPECT_NEAR(plan.explosiveDuration(), te, 1e-15);
  EXPECT_NEAR(plan.duration(), 0.6 + te, 1e-15);
  expectNear(plan.position(0.0), kComStart, 1e-15);
  expectNear(plan.velocity(0.0), Eigen::Vector3d::Zero(), 1e-15);
  expectNear(plan.position(plan.duration()), plan.liftOff().position, 1e-15);
  expectNear(plan.velocity(plan.duration()), plan.liftOff().velocity, 1e-15);
  expectNear(plan.liftOff().position, kBezierLiftOff.position + d * kBezierLiftOff.velocity.normalized(), 1e-15);
  expectNear(plan.liftOff().velocity, k * kBezierLiftOff.velocity, 1e-15);
  expectNear(plan.bezierLiftOff().position, kBezierLiftOff.position, 0.0);
  // Past the end the plan holds its end state.
  expectNear(plan.position(plan.duration() + 0.1), plan.liftOff().position, 0.0);
  expectNear(plan.velocity(plan.duration() + 0.1), plan.liftOff().velocity, 0.0);
}

TEST(ThrustPlan, FromAnActionEqualsTheCartesianConstruction) {
  JumpAction a;
  a.thrust_duration_s = 0.55;
  a.liftoff_radius_m = 0.33;
  a.liftoff_elevation_rad = 1.1;
  a.liftoff_speed_mps = 2.4;
  a.velocity_elevation_rad = 0.8;
  a.speed_ratio = 1.6;
  a.explosive_distance_m = 0.1;
  const double az = -kPi / 3;
  const Eigen::Vector3d origin(0.0, 0.0, 0.0);
  const ThrustPlan from_action(a, az, kComStart, origin);
  const ThrustPlan cartesian(kComStart, bezierLiftOffState(a, az, origin), 0.55, 1.6, 0.1);
  for (double t = 0.0; t <= from_action.duration(); t += 0.01) {
    expectNear(from_action.position(t), cartesian.position(t), 0.0);
    expectNear(from_action.velocity(t), cartesian.velocity(t), 0.0);
  }
  EXPECT_EQ(from_action.explosiveDuration(), cartesian.explosiveDuration());
}

TEST(ThrustPlan, ZeroDistanceMeansNoExtensionAndIsTheLimitOfSmallD) {
  const ThrustPlan plan = makePlan(2.5, 0.0);
  EXPECT_EQ(plan.explosiveDuration(), 0.0);
  EXPECT_EQ(plan.duration(), plan.bezierDuration());
  expectNear(plan.liftOff().position, kBezierLiftOff.position, 0.0);
  expectNear(plan.liftOff().velocity, kBezierLiftOff.velocity, 0.0);
  expectNear(plan.position(plan.duration() + 0.05), kBezierLiftOff.position, 1e-12);
  expectNear(plan.velocity(plan.duration() + 0.05), kBezierLiftOff.velocity, 1e-12);
  expectNear(plan.acceleration(plan.duration() + 0.05), plan.bezier().acceleration(plan.bezierDuration()), 0.0);

  // Continuity in d: a tiny d gives a tiny T_e and an end position within d.
  const ThrustPlan tiny = makePlan(2.5, 1e-9);
  EXPECT_GT(tiny.explosiveDuration(), 0.0);
  EXPECT_LT(tiny.explosiveDuration(), 1e-9);
  expectNear(tiny.liftOff().position, kBezierLiftOff.position, 1e-9);
  for (double t : {0.1, 0.4, 0.6}) expectNear(tiny.position(t), plan.position(t), 0.0);
}

TEST(ThrustPlan, SpeedRatioOneIsConstantVelocityAndTheLimitOfNearbyK) {
  const double d = 0.2;
  const ThrustPlan plan = makePlan(1.0, d);
  const double v0 = kBezierLiftOff.velocity.norm();
  EXPECT_NEAR(plan.explosiveDuration(), d / v0, 1e-15);  // not a clamp such as 1e-4 s
  EXPECT_EQ(plan.explosive().accelerationAlongPath(), 0.0);
  const double tb = plan.bezierDuration();
  for (double frac : {0.0, 0.3, 0.7, 1.0}) {
    const double t = tb + frac * plan.explosiveDuration();
    SCOPED_TRACE(frac);
    expectNear(plan.velocity(t), kBezierLiftOff.velocity, 1e-14);
    expectNear(plan.position(t), kBezierLiftOff.position + frac * plan.explosiveDuration() * kBezierLiftOff.velocity,
               1e-14);
  }
  // k -> 1 is continuous: k = 1 + 1e-9 differs by O(1e-9).
  const ThrustPlan near = makePlan(1.0 + 1e-9, d);
  EXPECT_NEAR(near.explosiveDuration(), plan.explosiveDuration(), 1e-9);
  for (double frac : {0.3, 0.7}) {
    const double t = tb + frac * plan.explosiveDuration();
    expectNear(near.position(t), plan.position(t), 1e-9);
    expectNear(near.velocity(t), plan.velocity(t), 1e-8);
  }
}

TEST(ThrustPlan, ExplosiveTimingDoesNotDependOnWhereTheFrameOriginIs) {
  // The reference code takes the path length as |c_exp| - |c_lo| (norms of
  // position vectors), so T_e changed with the frame origin. Here it is d.
  const ThrustPlan here = makePlan(2.0, 0.15);
  const Eigen::Vector3d offset(3.0, -2.0, 0.5);
  const ThrustPlan moved = makePlan(2.0, 0.15, offset);
  EXPECT_NEAR(moved.explosiveDuration(), here.explosiveDuration(), 1e-15);
  for (double t = 0.0; t <= here.duration(); t += 0.013) {
    expectNear(moved.position(t) - offset, here.position(t), 1e-12);
    expectNear(moved.velocity(t), here.velocity(t), 1e-12);
  }
  // In the reference's env frame (origin 0.5 m below the take-off surface) the
  // norm-difference length of this extension is well short of d = 0.15 m.
  const Eigen::Vector3d below(0.0, 0.0, 0.5);
  const Eigen::Vector3d c_lo = kBezierLiftOff.position + below;
  const Eigen::Vector3d c_exp = c_lo + 0.15 * kBezierLiftOff.velocity.normalized();
  EXPECT_LT(c_exp.norm() - c_lo.norm(), 0.14);
}

TEST(ThrustPlan, SpeedRatioBelowOneDecelerates) {
  const ThrustPlan plan = makePlan(0.5, 0.1);
  EXPECT_LT(plan.explosive().accelerationAlongPath(), 0.0);
  expectNear(plan.liftOff().velocity, 0.5 * kBezierLiftOff.velocity, 1e-15);
  const double tau = plan.explosiveDuration() * (1 - 1e-12);
  EXPECT_NEAR((plan.explosive().position(tau) - kBezierLiftOff.position).norm(), 0.1, 1e-12);
}

TEST(ExplosivePhase, RejectsInvalidParameters) {
  EXPECT_THROW(ExplosivePhase(kBezierLiftOff, -0.1, 0.1), std::invalid_argument);
  EXPECT_THROW(ExplosivePhase(kBezierLiftOff, 2.0, -0.01), std::invalid_argument);
  EXPECT_THROW(ExplosivePhase(kBezierLiftOff, std::nan(""), 0.1), std::invalid_argument);
  const PointState at_rest{{0.1, 0.0, 0.3}, Eigen::Vector3d::Zero()};
  EXPECT_THROW(ExplosivePhase(at_rest, 2.0, 0.1), std::invalid_argument);
  const ExplosivePhase none(at_rest, 2.0, 0.0);  // no extension needs no direction
  EXPECT_EQ(none.duration(), 0.0);
  expectNear(none.endState().position, at_rest.position, 0.0);
}

}  // namespace
}  // namespace pronk::jump
