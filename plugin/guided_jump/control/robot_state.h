// What the phases read off the robot's state and the host: the trunk's
// attitude, the take-off frame, the whole body's angular momentum.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

inline Eigen::Vector3d vec(const double* p) { return {p[0], p[1], p[2]}; }

// The trunk's rotation (trunk -> world).
inline Eigen::Matrix3d rotationOf(const pronk_robot_state& s) {
  return Eigen::Quaterniond(s.base_quaternion[0], s.base_quaternion[1], s.base_quaternion[2], s.base_quaternion[3])
      .normalized()
      .toRotationMatrix();
}

// Cubic smoothstep 3 s^2 - 2 s^3 of s clamped to [0, 1].
double smoothstep(double s);

// ZYX Euler angles (roll, pitch, yaw) of a rotation R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R);

// The rotation about z by the heading (yaw) of R.
Eigen::Matrix3d headingOf(const Eigen::Matrix3d& R);

// A frame on the take-off surface: origin below the CoM at the mean height of
// the feet in contact less their radius (all feet when none is), z up, x along
// the trunk's heading. The jump's start frame S.
struct StartFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // world
  Eigen::Matrix3d heading = Eigen::Matrix3d::Identity();  // S -> world
  Eigen::Vector3d point(const double* world) const {
    return heading.transpose() * (Eigen::Vector3d(world[0], world[1], world[2]) - origin);
  }
  Eigen::Vector3d direction(const double* world) const {
    return heading.transpose() * Eigen::Vector3d(world[0], world[1], world[2]);
  }
};
StartFrame takeOffFrame(const pronk_host_api* host, const pronk_robot_state& state);

// The whole body's angular momentum L about its CoM and its locked-joint
// rotational inertia I about it (world), from the host (ABI 1.2); nullopt from an
// older host or a non-finite answer.
struct CentroidalMomentum {
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
std::optional<CentroidalMomentum> centroidalMomentum(const pronk_host_api* host);
// I^-1 L; nullopt when it is not finite.
std::optional<Eigen::Vector3d> averageRate(const CentroidalMomentum& momentum);

// The whole body's average angular velocity I^-1 L about its CoM (world) at the
// current tick, from the host (ABI 1.2); nullopt from an older host. In flight it
// is what the attitude does on average, whatever the legs do.
std::optional<Eigen::Vector3d> wholeBodyRate(const pronk_host_api* host);

// The terrain's top face over a world point (x, y), from the host (ABI 1.6):
// its height (world z, m) and which part of the terrain it is (-1 the ground);
// nullopt from an older host or over no surface.
struct TerrainTop {
  double height = 0.0;
  int surface = -1;
};
std::optional<TerrainTop> terrainTop(const pronk_host_api* host, double x, double y);

}  // namespace pronk::guided_jump
