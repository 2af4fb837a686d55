#include "pronk/multibody.h"

namespace pronk {

SimTK::Vec3 toVec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d toEigen(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }

SimTK::Transform toTransform(const Eigen::Isometry3d& pose) {
  SimTK::Mat33 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = pose.linear()(i, j);
  return SimTK::Transform(SimTK::Rotation(r, true), toVec3(pose.translation()));
}

SimTK::MassProperties toSimbody(const MassProperties& m) {
  const Eigen::Matrix3d& I = m.inertia_com;
  const SimTK::Inertia central(I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
  const SimTK::Vec3 com = toVec3(m.com_body);
  // Simbody wants the inertia about the body origin.
  return SimTK::MassProperties(m.mass, com, central.shiftFromMassCenter(com, m.mass));
}

RobotMultibody addRobot(SimTK::SimbodyMatterSubsystem& matter, const RobotDescription& robot,
                        double root_mass_offset) {
  RobotMultibody mb;
  mb.bodies.resize(robot.bodies.size());
  for (size_t i = 0; i < robot.bodies.size(); ++i) {
    MassProperties mass = robot.bodies[i].mass;
    if (i == 0 && root_mass_offset != 0) {
      const double scale = (mass.mass + root_mass_offset) / mass.mass;
      mass.mass += root_mass_offset;
      mass.inertia_com *= scale;
    }
    const SimTK::Body::Rigid body(toSimbody(mass));
    if (i == 0) {
      mb.bodies[0] = SimTK::MobilizedBody::Free(matter.Ground(), SimTK::Transform(), body, SimTK::Transform());
      continue;
    }
    const Joint& joint = robot.joints[robot.bodies[i].joint];
    SimTK::MobilizedBody& parent = mb.bodies[joint.parent_body];
    const SimTK::Transform X_PJ = toTransform(joint.pose_in_parent);
    // Pins turn about z of their frames, Sliders move along x: align that axis
    // with the joint axis in both frames, so q = 0 keeps the URDF zero pose.
    const SimTK::CoordinateAxis moving_axis =
        joint.type == JointType::Prismatic ? SimTK::CoordinateAxis(SimTK::XAxis) : SimTK::CoordinateAxis(SimTK::ZAxis);
    const SimTK::Rotation R_JM(SimTK::UnitVec3(toVec3(joint.axis)), moving_axis);
    const SimTK::Transform X_PF(X_PJ.R() * R_JM, X_PJ.p());
    const SimTK::Transform X_BM(R_JM, SimTK::Vec3(0));
    if (joint.type == JointType::Prismatic) {
      mb.bodies[i] = SimTK::MobilizedBody::Slider(parent, X_PF, body, X_BM);
    } else {
      mb.bodies[i] = SimTK::MobilizedBody::Pin(parent, X_PF, body, X_BM);
    }
  }
  return mb;
}

}  // namespace pronk
