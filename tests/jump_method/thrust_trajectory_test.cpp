// Thrust Bezier for the CoM: boundary states from the action's polar
// parameters, analytic velocity and acceleration, agreement with the Bernstein
// definition of the paper.
#include "method/thrust_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).lpNorm<Eigen::Infinity>(), tol)
      << "actual (" << actual.transpose() << ") expected (" << expected.transpose() << ")";
}

// A typical forward-left lift-off from a Go1-like standing CoM.
struct Fixture {
  Eigen::Vector3d com_start{-0.013, 0.002, 0.308};
  PointState liftoff{{0.12, 0.09, 0.36}, {1.1, 0.8, 1.9}};
  double duration = 0.7;
  CubicBezier bezier = comThrustBezier(com_start, liftoff, duration);
};

TEST(CubicBezier, HitsTheBoundaryStates) {
  const Fixture f;
  expectNear(f.bezier.position(0.0), f.com_start, 1e-12);
  expectNear(f.bezier.velocity(0.0), Eigen::Vector3d::Zero(), 1e-12);
  expectNear(f.bezier.position(f.duration), f.liftoff.position, 1e-12);
  expectNear(f.bezier.velocity(f.duration), f.liftoff.velocity, 1e-12);
}

TEST(CubicBezier, ControlPointsStartAtRestAndEndAlongTheLiftOffVelocity) {
  const Fixture f;
  const auto& p = f.bezier.controlPoints();
  EXPECT_EQ(p[0], f.com_start);
  EXPECT_EQ(p[1], f.com_start);
  expectNear(p[2], f.liftoff.position - f.duration / 3.0 * f.liftoff.velocity, 1e-15);
  EXPECT_EQ(p[3], f.liftoff.position);
}

TEST(CubicBezier, HermiteFormHonoursANonZeroStartVelocity) {
  const PointState start{{0.0, 0.0, 0.3}, {0.2, -0.1, 0.4}};
  const PointState end{{0.1, 0.0, 0.35}, {1.0, 0.0, 2.0}};
  const CubicBezier b = CubicBezier::fromBoundaryStates(start, end, 0.45);
  expectNear(b.velocity(0.0), start.velocity, 1e-12);
  expectNear(b.velocity(0.45), end.velocity, 1e-12);
}

TEST(CubicBezier, VelocityIsTheDerivativeOfPosition) {
  const Fixture f;
  const double h = 1e-6;
  for (double t = 0.01; t < f.duration; t += 0.0491) {
    const Eigen::Vector3d fd = (f.bezier.position(t + h) - f.bezier.position(t - h)) / (2 * h);
    SCOPED_TRACE(t);
    expectNear(f.bezier.velocity(t), fd, 1e-7);
  }
}

TEST(CubicBezier, AccelerationIsTheDerivativeOfVelocity) {
  const Fixture f;
  const double h = 1e-6;
  for (double t = 0.01; t < f.duration; t += 0.0491) {
    const Eigen::Vector3d fd = (f.bezier.velocity(t + h) - f.bezier.velocity(t - h)) / (2 * h);
    SCOPED_TRACE(t);
    expectNear(f.bezier.acceleration(t), fd, 1e-6);
  }
}

// The paper's definition: B(t) = sum_i C(n, i) s^i (1 - s)^(n - i) P_i, its
// derivative the degree n-1 curve on P'_i = n / T (P_{i+1} - P_i).
Eigen::Vector3d bernstein(const std::vector<Eigen::Vector3d>& points, double s) {
  const int n = static_cast<int>(points.size()) - 1;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i <= n; ++i) {
    double binomial = 1.0;
    for (int j = 1; j <= i; ++j) binomial = binomial * (n - i + j) / j;
    sum += binomial * std::pow(s, i) * std::pow(1.0 - s, n - i) * points[i];
  }
  return sum;
}

std::vector<Eigen::Vector3d> derivativePoints(const std::vector<Eigen::Vector3d>& points, double duration) {
  const int n = static_cast<int>(points.size()) - 1;
  std::vector<Eigen::Vector3d> d;
  for (int i = 0; i < n; ++i) d.push_back(n / duration * (points[i + 1] - points[i]));
  return d;
}

TEST(CubicBezier, MatchesADirectBernsteinEvaluation) {
  const Fixture f;
  const std::vector<Eigen::Vector3d> p(f.bezier.controlPoints().begin(), f.bezier.controlPoints().end());
  const auto dp = derivativePoints(p, f.duration);
  const auto ddp = derivativePoints(dp, f.duration);
  for (int k = 0; k <= 20; ++k) {
    const double s = k / 20.0;
    SCOPED_TRACE(s);
    expectNear(f.bezier.position(s * f.duration), bernstein(p, s), 1e-13);
    expectNear(f.bezier.velocity(s * f.duration), bernstein(dp, s), 1e-12);
    expectNear(f.bezier.acceleration(s * f.duration), bernstein(ddp, s), 1e-11);
  }
}

TEST(CubicBezier, ClampsTimeToItsIntervalInsteadOfExtrapolating) {
  const Fixture f;
  EXPECT_EQ(f.bezier.position(-0.2), f.bezier.position(0.0));
  EXPECT_EQ(f.bezier.velocity(-0.2), f.bezier.velocity(0.0));
  EXPECT_EQ(f.bezier.position(f.duration + 0.3), f.bezier.position(f.duration));
  EXPECT_EQ(f.bezier.velocity(f.duration + 0.3), f.bezier.velocity(f.duration));
  EXPECT_EQ(f.bezier.acceleration(f.duration + 0.3), f.bezier.acceleration(f.duration));
}

TEST(CubicBezier, RejectsANonPositiveOrNonFiniteDurationAndPoints) {
  const PointState a, b{{0.1, 0.0, 0.3}, {1.0, 0.0, 1.0}};
  EXPECT_THROW(CubicBezier::fromBoundaryStates(a, b, 0.0), std::invalid_argument);
  EXPECT_THROW(CubicBezier::fromBoundaryStates(a, b, -0.5), std::invalid_argument);
  EXPECT_THROW(CubicBezier::fromBoundaryStates(a, b, std::nan("")), std::invalid_argument);
  PointState bad = b;
  bad.velocity.x() = std::nan("");
  EXPECT_THROW(CubicBezier::fromBoundaryStates(a, bad, 0.5), std::invalid_argument);
}

TEST(JumpPlaneVector, PolarComponentsInTheJumpPlane) {
  expectNear(jumpPlaneVector(2.0, kPi / 6, 0.0), {2.0 * std::cos(kPi / 6), 0.0, 1.0}, 1e-15);
  expectNear(jumpPlaneVector(2.0, kPi / 6, kPi / 2), {0.0, 2.0 * std::cos(kPi / 6), 1.0}, 1e-15);
  expectNear(jumpPlaneVector(2.0, kPi / 6, kPi), {-2.0 * std::cos(kPi / 6), 0.0, 1.0}, 1e-15);
  expectNear(jumpPlaneVector(0.3, kPi / 2, 1.0), {0.0, 0.0, 0.3}, 1e-15);
  EXPECT_NEAR(jumpPlaneVector(0.37, 0.8, -2.1).norm(), 0.37, 1e-15);
}

TEST(BezierLiftOffState, FromThePolarActionParametersAboutTheSurfacePointBelowTheCoM) {
  JumpAction a;
  a.thrust_duration_s = 0.6;
  a.liftoff_radius_m = 0.3;
  a.liftoff_elevation_rad = kPi / 3;
  a.liftoff_speed_mps = 2.0;
  a.velocity_elevation_rad = kPi / 4;
  const Eigen::Vector3d origin(0.5, -0.25, 0.1);  // take-off surface 0.1 m up
  const double az = 3 * kPi / 4;                    // back-left

  const PointState s = bezierLiftOffState(a, az, origin);
  const double horizontal = 0.3 * 0.5;
  const Eigen::Vector3d offset(horizontal * std::cos(az), horizontal * std::sin(az), 0.3 * std::sqrt(3.0) / 2);
  expectNear(s.position, origin + offset, 1e-15);
  const double vh = 2.0 / std::sqrt(2.0);
  expectNear(s.velocity, {vh * std::cos(az), vh * std::sin(az), vh}, 1e-14);
  // Position and velocity share the jump plane: both horizontal parts point along the azimuth.
  const Eigen::Vector2d dir(std::cos(az), std::sin(az));
  EXPECT_NEAR((s.position - origin).head<2>().dot(Eigen::Vector2d(-dir.y(), dir.x())), 0.0, 1e-15);
  EXPECT_NEAR(s.velocity.head<2>().dot(Eigen::Vector2d(-dir.y(), dir.x())), 0.0, 1e-15);
}

}  // namespace
}  // namespace pronk::jump
