// Triangle meshes for drawing: URDF visual meshes through assimp (DAE, STL,
// OBJ ...) and primitives (box, sphere, cylinder) built here.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pronk/robot_description.h"

namespace pronk::render {

struct TriangleMesh {
  std::vector<float> positions;  // x y z per vertex
  std::vector<float> normals;    // unit, per vertex
  std::vector<unsigned> indices; // three per triangle
  Eigen::Vector3d min_corner = Eigen::Vector3d::Zero(), max_corner = Eigen::Vector3d::Zero();
};

TriangleMesh boxMesh(const Eigen::Vector3d& size);
TriangleMesh sphereMesh(double radius, int slices = 16, int stacks = 10);
TriangleMesh cylinderMesh(double radius, double length, int slices = 20);  // axis z, centred
TriangleMesh primitiveMesh(const Shape& shape);

// Loads meshes once per path and scale. A file assimp cannot read yields
// nullptr; the caller falls back to a primitive and warns.
class MeshLibrary {
 public:
  const TriangleMesh* load(const std::string& path, const Eigen::Vector3d& scale);

 private:
  std::map<std::string, std::unique_ptr<TriangleMesh>> cache_;
};

}  // namespace pronk::render
