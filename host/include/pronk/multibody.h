// RobotDescription -> Simbody mobilized bodies. A Free mobilizer carries the
// root; revolute and continuous joints become Pins, prismatic joints Sliders,
// with their frames rotated so that q = 0 is the URDF's zero pose.
#pragma once

#include <Simbody.h>

#include <vector>

#include "pronk/robot_description.h"

namespace pronk {

struct RobotMultibody {
  std::vector<SimTK::MobilizedBody> bodies;   // one per RobotDescription body, same order
  SimTK::MobilizedBody root() const { return bodies.front(); }
};

SimTK::Transform toTransform(const Eigen::Isometry3d& pose);
SimTK::Vec3 toVec3(const Eigen::Vector3d& v);
Eigen::Vector3d toEigen(const SimTK::Vec3& v);

// Simbody mass properties (inertia about the body origin) of a description body.
SimTK::MassProperties toSimbody(const MassProperties& mass);

// Adds the robot under Ground. `root_mass_offset` (kg) is added to the root
// body at its centre of mass, scaling its inertia with it (robustness sweeps).
RobotMultibody addRobot(SimTK::SimbodyMatterSubsystem& matter, const RobotDescription& robot,
                        double root_mass_offset = 0);

}  // namespace pronk
