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

Eigen::Matrix3Xd distributeWeight(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                  double mass, const Eigen::Vector3d& gravity_world) {
  return distributeWrench(contact_points_world, com_world, -mass * gravity_world, Eigen::Vector3d::Zero());
}

}  // namespace pronk::jump
