#include "method/force_distribution.h"

#include <Eigen/QR>

namespace pronk::jump {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(),  //
      r.z(), 0, -r.x(),   //
      -r.y(), r.x(), 0;
  return m;
}

}  // namespace

Eigen::Matrix3Xd distributeWrench(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                  const Eigen::Vector3d& force_world, const Eigen::Vector3d& moment_about_com) {
  const Eigen::Index k = contact_points_world.cols();
  if (k == 0) return Eigen::Matrix3Xd(3, 0);
  Eigen::MatrixXd G(6, 3 * k);
  for (Eigen::Index i = 0; i < k; ++i) {
    G.block<3, 3>(0, 3 * i).setIdentity();
    G.block<3, 3>(3, 3 * i) = skew(contact_points_world.col(i) - com_world);
  }
  Eigen::Matrix<double, 6, 1> w;
  w << force_world, moment_about_com;
  // The complete orthogonal decomposition's solve() is G^+ w: the minimum-norm
  // least-squares solution, also when G is rank deficient.
  const Eigen::VectorXd f = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(G).solve(w);
  return Eigen::Map<const Eigen::Matrix3Xd>(f.data(), 3, k);
}

double momentShareWithinFriction(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                 const Eigen::Vector3d& force_world, const Eigen::Vector3d& moment_about_com,
                                 const Eigen::Vector3d& extra_moment, double mu) {
  const Eigen::Matrix3Xd base = distributeWrench(contact_points_world, com_world, force_world, moment_about_com);
  const Eigen::Matrix3Xd extra =
      distributeWrench(contact_points_world, com_world, Eigen::Vector3d::Zero(), extra_moment);  // linear in w
  const auto within = [&](double s) {
    for (Eigen::Index i = 0; i < base.cols(); ++i) {
      const Eigen::Vector3d f = base.col(i) + s * extra.col(i);
      if (f.z() < 0.0 || f.head<2>().norm() > mu * f.z()) return false;
    }
    return true;
  };
  if (within(1.0)) return 1.0;
  if (!within(0.0)) return 0.0;
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (within(mid) ? lo : hi) = mid;
  }
  return lo;
}

Eigen::Matrix3Xd distributeWeight(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                  double mass, const Eigen::Vector3d& gravity_world) {
  return distributeWrench(contact_points_world, com_world, -mass * gravity_world, Eigen::Vector3d::Zero());
}

}  // namespace pronk::jump
