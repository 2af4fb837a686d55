// Force distribution: the contact forces that hold a wrench on the body with the
// least effort. With feet at p_i and the centre of mass at c, the grasp matrix
//   G = [ I          I          ... ]      (6 x 3k)
//       [ [p_1 - c]x [p_2 - c]x ... ]
// maps the stacked foot forces f (ground on foot, world, N) to the force and the
// moment about c they put on the body. The minimum-norm f with G f = w is
// f = G^+ w. For the robot's own weight w = (-m g, 0): equal shares when the CoM
// is centred over the feet, more on the feet nearer the CoM otherwise, and no net
// moment about the CoM either way.
#pragma once

#include <Eigen/Core>

namespace pronk::jump {

// contact_points_world: 3 x k foot positions; returns 3 x k forces (ground on foot).
// When G has no full row rank (fewer than three feet, or feet in a line) this is the
// least-squares wrench with the least force norm.
Eigen::Matrix3Xd distributeWrench(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                  const Eigen::Vector3d& force_world, const Eigen::Vector3d& moment_about_com);

// The largest share s in [0, 1] of extra_moment that the minimum-norm forces for
// (force, moment + s extra_moment) hold with every foot inside its friction cone
// (|f_t| <= mu f_z, f_z >= 0). 0 when the forces without it already leave a cone.
// Each foot's cone cuts the line of s in one interval, so bisection finds it.
double momentShareWithinFriction(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                 const Eigen::Vector3d& force_world, const Eigen::Vector3d& moment_about_com,
                                 const Eigen::Vector3d& extra_moment, double mu);

// The forces that carry the robot's weight: force -mass * gravity, no moment.
Eigen::Matrix3Xd distributeWeight(const Eigen::Matrix3Xd& contact_points_world, const Eigen::Vector3d& com_world,
                                  double mass, const Eigen::Vector3d& gravity_world);

}  // namespace pronk::jump
