#include "method/force_distribution.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

namespace pronk::jump {
namespace {

// Four feet on a square of half-side a around the CoM's vertical, the CoM h above.
Eigen::Matrix3Xd squareFeet(double a) {
  Eigen::Matrix3Xd p(3, 4);
  p << a, a, -a, -a,  //
      a, -a, a, -a,   //
      0, 0, 0, 0;
  return p;
}

TEST(ForceDistribution, TheWeightIsSharedEquallyOverCentredFeet) {
  const Eigen::Matrix3Xd f = distributeWeight(squareFeet(0.15), Eigen::Vector3d(0, 0, 0.3), 12.0, Eigen::Vector3d(0, 0, -9.81));
  for (Eigen::Index i = 0; i < 4; ++i) {
    EXPECT_NEAR(f(2, i), 12.0 * 9.81 / 4, 1e-9);
    EXPECT_NEAR(f.col(i).head<2>().norm(), 0.0, 1e-9);
  }
}

TEST(ForceDistribution, ATwistShareStopsWhereTheFirstFootReachesItsFrictionCone) {
  // The weight W on four centred feet and a twist M about the vertical: the
  // minimum-norm forces are W/4 up and M / (4 a sqrt 2) around, at every foot, so
  // the feet stay in the cone mu up to the share s = mu W a sqrt(2) / M.
  const double a = 0.15, W = 120.0, mu = 0.5, M = 30.0;
  const Eigen::Matrix3Xd feet = squareFeet(a);
  const Eigen::Vector3d com(0, 0, 0.3), weight(0, 0, W), twist(0, 0, M);
  const double s = momentShareWithinFriction(feet, com, weight, Eigen::Vector3d::Zero(), twist, mu);
  EXPECT_NEAR(s, mu * W * a * std::sqrt(2.0) / M, 1e-6);
  // At that share the forces still hold the whole wrench.
  const Eigen::Matrix3Xd f = distributeWrench(feet, com, weight, s * twist);
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < 4; ++i) {
    moment += (feet.col(i) - com).cross(f.col(i));
    EXPECT_LE(f.col(i).head<2>().norm(), mu * f(2, i) + 1e-6);
  }
  EXPECT_NEAR(f.rowwise().sum().z(), W, 1e-9);
  EXPECT_NEAR(moment.z(), s * M, 1e-9);
}

TEST(ForceDistribution, ATwistTheConesHoldIsKeptWholeAndNoneIsAddedToAPushBeyondThem) {
  const Eigen::Matrix3Xd feet = squareFeet(0.15);
  const Eigen::Vector3d com(0, 0, 0.3), twist(0, 0, 2.0);
  EXPECT_EQ(momentShareWithinFriction(feet, com, Eigen::Vector3d(0, 0, 120), Eigen::Vector3d::Zero(), twist, 0.5), 1.0);
  // A push of 0.6 W sideways already leaves the cone 0.5 at every foot.
  EXPECT_EQ(momentShareWithinFriction(feet, com, Eigen::Vector3d(72, 0, 120), Eigen::Vector3d::Zero(), twist, 0.5), 0.0);
}

}  // namespace
}  // namespace pronk::jump
