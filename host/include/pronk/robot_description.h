// A robot as the host needs it, read from a URDF: rigid bodies after lumping
// fixed joints, the joints between them, collision shapes and visual meshes.
// Nothing here depends on Simbody; multibody_builder turns it into a model.
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "pronk/error.h"

namespace pronk {

enum class ShapeType { Sphere, Box, Cylinder };

// A primitive shape fixed to a body. Boxes are full sizes; cylinders have their
// axis along the shape frame's z (URDF convention).
struct Shape {
  ShapeType type = ShapeType::Sphere;
  Eigen::Isometry3d pose_body = Eigen::Isometry3d::Identity();  // shape frame in body frame
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();          // m, full extents
  double radius = 0;                                           // m, sphere and cylinder
  double length = 0;                                           // m, cylinder
};

struct CollisionShape {
  Shape shape;
  std::string link;         // URDF link it came from (before lumping)
  bool from_mesh = false;   // a mesh replaced by its bounding box
};

// What the renderer draws for a link: a mesh file (resolved path) or a primitive.
struct VisualShape {
  std::string link;
  Eigen::Isometry3d pose_body = Eigen::Isometry3d::Identity();
  std::optional<std::string> mesh_path;   // absolute, resolved; empty when missing
  std::string mesh_uri;                   // as written in the URDF
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
  std::optional<Shape> primitive;         // for primitives, and the fallback of a missing mesh
  Eigen::Vector4d rgba{0.7, 0.7, 0.7, 1.0};
};

// Mass properties about the body origin's frame: mass, centre of mass in the
// body frame and the inertia about the centre of mass, in body axes.
struct MassProperties {
  double mass = 0;
  Eigen::Vector3d com_body = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();
};

// A rigid body after fixed children were lumped into it.
struct Body {
  std::string name;                 // the URDF link that owns the frame
  std::vector<std::string> lumped_links;  // links merged into it (with their frames below)
  std::vector<std::pair<std::string, Eigen::Isometry3d>> link_frames;  // link -> pose in body
  MassProperties mass;
  int parent = -1;                  // index in RobotDescription::bodies, -1 for the root
  int joint = -1;                   // index in RobotDescription::joints (the inboard joint)
  std::vector<CollisionShape> collisions;
  std::vector<VisualShape> visuals;
};

enum class JointType { Revolute, Continuous, Prismatic };

// A moving joint between a parent and child body. Fixed joints do not appear.
struct Joint {
  std::string name;
  JointType type = JointType::Revolute;
  int parent_body = -1;
  int child_body = -1;
  Eigen::Isometry3d pose_in_parent = Eigen::Isometry3d::Identity();  // joint frame in parent body
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, in the joint frame
  bool has_position_limits = false;
  double lower = 0, upper = 0;      // rad or m
  double velocity_limit = 0;        // rad/s or m/s; 0 = none given
  double effort_limit = 0;          // N m or N; 0 = none given
  double damping = 0;               // URDF <dynamics damping>
  double friction = 0;              // URDF <dynamics friction>
};

struct RobotDescription {
  std::string name;
  std::string urdf_path;
  std::vector<Body> bodies;   // bodies[0] is the root (floating base)
  std::vector<Joint> joints;  // parent bodies come before child bodies
  std::vector<std::string> warnings;  // e.g. a missing mesh replaced by a primitive

  int findBody(const std::string& name) const;   // -1 if absent
  int findJoint(const std::string& name) const;  // -1 if absent
  // The body a link ended up in after lumping and the link's pose in it.
  std::optional<std::pair<int, Eigen::Isometry3d>> locateLink(const std::string& link) const;
  double totalMass() const;
};

struct UrdfOptions {
  // Directories searched for package://NAME/... URIs: a directory D matches
  // when D/NAME exists (ROS convention) or when D's own name is NAME.
  std::vector<std::string> package_paths;
};

// Reads a URDF file. Throws InputError naming the file (and line where urdfdom
// or tinyxml2 tells one) for malformed files, missing inertials on moving
// links, unsupported joint types (floating, planar) and kinematic loops.
RobotDescription loadUrdf(const std::string& path, const UrdfOptions& options = {});

// Same from a string; `origin` names it in messages and anchors relative URIs.
RobotDescription parseUrdf(const std::string& xml, const std::string& origin,
                           const UrdfOptions& options = {});

}  // namespace pronk
