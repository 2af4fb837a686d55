// Orientation Bezier in ZYX Euler angles: boundary conditions, the conversion of
// Euler rates to angular velocity checked against the rotation matrix itself,
// and the yaw-only twist.
#include "method/orientation_trajectory.h"

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

Eigen::Matrix3d rotX(double a) {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return r;
}
Eigen::Matrix3d rotY(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return r;
}
Eigen::Matrix3d rotZ(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return r;
}

Eigen::Vector3d vee(const Eigen::Matrix3d& w) {
  const Eigen::Matrix3d s = 0.5 * (w - w.transpose());
  return {s(2, 1), s(0, 2), s(1, 0)};
}

// A twisting, pitching lift-off from a slightly tilted start.
const Eigen::Vector3d kStart(0.02, -0.05, 0.1);
const Eigen::Vector3d kLiftOff(-0.3, 0.4, 0.7);
const Eigen::Vector3d kLiftOffRate(0.6, -0.9, 3.5);
constexpr double kDuration = 0.74;

TEST(OrientationTrajectory, StartsAtRestAndEndsAtTheLiftOffAnglesAndRates) {
  const OrientationTrajectory o(kStart, kLiftOff, kLiftOffRate, kDuration);
  expectNear(o.rpy(0.0), kStart, 1e-12);
  expectNear(o.rpyRate(0.0), Eigen::Vector3d::Zero(), 1e-12);
  expectNear(o.rpy(kDuration), kLiftOff, 1e-12);
  expectNear(o.rpyRate(kDuration), kLiftOffRate, 1e-12);
  EXPECT_EQ(o.duration(), kDuration);
  const auto& q = o.bezier().controlPoints();
  EXPECT_EQ(q[1], kStart);
  expectNear(q[2], kLiftOff - kDuration / 3 * kLiftOffRate, 1e-15);
}

TEST(OrientationTrajectory, FromActionUsesItsLiftOffAnglesAndRates) {
  JumpAction a;
  a.liftoff_rpy_rad = kLiftOff;
  a.liftoff_rpy_rate_radps = kLiftOffRate;
  const OrientationTrajectory o(kStart, a, kDuration);
  expectNear(o.rpy(kDuration), kLiftOff, 1e-12);
  expectNear(o.rpyRate(kDuration), kLiftOffRate, 1e-12);
}

TEST(RotationFromRpy, IsRzRyRx) {
  for (const Eigen::Vector3d& rpy : {Eigen::Vector3d(0.3, -0.2, 1.1), Eigen::Vector3d(-0.5, 0.4, -2.9)}) {
    const Eigen::Matrix3d expected = rotZ(rpy.z()) * rotY(rpy.y()) * rotX(rpy.x());
    EXPECT_LE((rotationFromRpy(rpy) - expected).lpNorm<Eigen::Infinity>(), 1e-15);
  }
}

TEST(OrientationTrajectory, AngularVelocityMatchesTheRotationMatrixDerivative) {
  const OrientationTrajectory o(kStart, kLiftOff, kLiftOffRate, kDuration);
  const double h = 1e-6;
  for (double t = 0.02; t < kDuration; t += 0.06) {
    const Eigen::Matrix3d r = o.rotation(t);
    const Eigen::Matrix3d r_dot = (o.rotation(t + h) - o.rotation(t - h)) / (2 * h);
    SCOPED_TRACE(t);
    expectNear(o.angularVelocityWorld(t), vee(r_dot * r.transpose()), 1e-7);  // R' = [w]x R
    expectNear(o.angularVelocityBody(t), vee(r.transpose() * r_dot), 1e-7);   // R' = R [w_b]x
  }
  // At lift-off too, from the left.
  const Eigen::Matrix3d r_end = o.rotation(kDuration);
  const Eigen::Matrix3d r_dot_end =
      (3 * r_end - 4 * o.rotation(kDuration - h) + o.rotation(kDuration - 2 * h)) / (2 * h);
  expectNear(o.liftOffAngularVelocityWorld(), vee(r_dot_end * r_end.transpose()), 1e-6);
  expectNear(o.liftOffAngularVelocityWorld(), o.angularVelocityWorld(kDuration), 1e-12);
}

TEST(OrientationTrajectory, AngularAccelerationIsTheDerivativeOfAngularVelocity) {
  const OrientationTrajectory o(kStart, kLiftOff, kLiftOffRate, kDuration);
  const double h = 1e-6;
  for (double t = 0.02; t < kDuration; t += 0.06) {
    SCOPED_TRACE(t);
    expectNear(o.angularAccelerationWorld(t),
               (o.angularVelocityWorld(t + h) - o.angularVelocityWorld(t - h)) / (2 * h), 1e-6);
    expectNear(o.rpyAcceleration(t), (o.rpyRate(t + h) - o.rpyRate(t - h)) / (2 * h), 1e-6);
  }
}

TEST(OrientationTrajectory, EulerRatesAreNotAngularVelocityWhenTilted) {
  // Pitch rate at 90 deg yaw turns about world -x, not world y; a roll rate at
  // 30 deg pitch has a world z component.
  expectNear(worldAngularVelocity({0, 0, kPi / 2}, {0, 1, 0}), {-1, 0, 0}, 1e-15);
  expectNear(worldAngularVelocity({0, kPi / 6, 0}, {1, 0, 0}), {std::cos(kPi / 6), 0, -0.5}, 1e-15);
  expectNear(bodyAngularVelocity({0, kPi / 6, 0}, {1, 0, 0}), {1, 0, 0}, 1e-15);
}

TEST(OrientationTrajectory, YawOnlyTwistStaysLevelAndTurnsAboutZ) {
  const Eigen::Vector3d start(0, 0, 0), lift_off(0, 0, kPi / 4), rate(0, 0, 4.0);
  const OrientationTrajectory o(start, lift_off, rate, 0.8);
  for (double t = 0.0; t <= 0.8; t += 0.05) {
    SCOPED_TRACE(t);
    const Eigen::Vector3d rpy = o.rpy(t);
    EXPECT_EQ(rpy.x(), 0.0);
    EXPECT_EQ(rpy.y(), 0.0);
    expectNear(o.angularVelocityWorld(t), {0, 0, o.rpyRate(t).z()}, 1e-15);
    expectNear(o.angularVelocityBody(t), {0, 0, o.rpyRate(t).z()}, 1e-15);
    EXPECT_LE((o.rotation(t) - rotZ(rpy.z())).lpNorm<Eigen::Infinity>(), 1e-15);
  }
  EXPECT_NEAR(o.rpy(0.8).z(), kPi / 4, 1e-12);
  expectNear(o.liftOffAngularVelocityWorld(), {0, 0, 4.0}, 1e-15);
}

TEST(OrientationTrajectory, LiftOffYawIsTakenNearestTheStartYaw) {
  // Start facing 3.0 rad, lift-off at -3.0 rad: the same as 2 pi - 3.0, a 0.28 rad
  // turn, not 6 rad the long way round.
  const OrientationTrajectory o({0, 0, 3.0}, {0, 0, -3.0}, {0, 0, 0}, 0.5);
  EXPECT_NEAR(o.liftOffRpy().z(), 2 * kPi - 3.0, 1e-12);
  EXPECT_LE((o.rotation(0.5) - rotZ(-3.0)).lpNorm<Eigen::Infinity>(), 1e-12);
  for (double t = 0.0; t <= 0.5; t += 0.05) {
    EXPECT_GE(o.rpy(t).z(), 3.0 - 1e-12);
    EXPECT_LE(o.rpy(t).z(), 2 * kPi - 3.0 + 1e-12);
  }
  // Within pi of the start nothing moves.
  const OrientationTrajectory near({0, 0, 0.1}, {0, 0, -0.7}, {0, 0, 0}, 0.5);
  EXPECT_EQ(near.liftOffRpy().z(), -0.7);
}

TEST(OrientationTrajectory, ClampsTimeAndRejectsBadInput) {
  const OrientationTrajectory o(kStart, kLiftOff, kLiftOffRate, kDuration);
  expectNear(o.rpy(kDuration + 0.2), kLiftOff, 1e-12);  // holds, does not extrapolate
  expectNear(o.rpy(-0.1), kStart, 0.0);
  EXPECT_THROW(OrientationTrajectory(kStart, kLiftOff, kLiftOffRate, 0.0), std::invalid_argument);
  EXPECT_THROW(OrientationTrajectory(kStart, Eigen::Vector3d(0, std::nan(""), 0), kLiftOffRate, kDuration),
               std::invalid_argument);
}

}  // namespace
}  // namespace pronk::jump
