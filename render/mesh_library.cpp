#include "render/mesh_library.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>

namespace pronk::render {
namespace {

void addVertex(TriangleMesh& m, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  for (int i = 0; i < 3; ++i) {
    m.positions.push_back(float(p(i)));
    m.normals.push_back(float(n(i)));
  }
}

void updateBounds(TriangleMesh& m) {
  if (m.positions.empty()) return;
  m.min_corner = Eigen::Vector3d::Constant(1e30);
  m.max_corner = Eigen::Vector3d::Constant(-1e30);
  for (size_t i = 0; i + 2 < m.positions.size(); i += 3) {
    const Eigen::Vector3d p(m.positions[i], m.positions[i + 1], m.positions[i + 2]);
    m.min_corner = m.min_corner.cwiseMin(p);
    m.max_corner = m.max_corner.cwiseMax(p);
  }
}

}  // namespace

TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const Eigen::Vector3d h = 0.5 * size;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n(axis) = sign;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const unsigned base = unsigned(m.positions.size() / 3);
      const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        Eigen::Vector3d p;
        p(axis) = sign * h(axis);
        p(a) = c[0] * h(a);
        p(b) = c[1] * h(b);
        addVertex(m, p, n);
      }
      // Counter-clockwise seen from outside.
      if (sign > 0) m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  }
  updateBounds(m);
  return m;
}

TriangleMesh sphereMesh(double r, int slices, int stacks) {
  TriangleMesh m;
  for (int i = 0; i <= stacks; ++i) {
    const double phi = M_PI * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      const double theta = 2 * M_PI * j / slices;
      const Eigen::Vector3d n(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi));
      addVertex(m, r * n, n);
    }
  }
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const unsigned a = unsigned(i * (slices + 1) + j), b = a + unsigned(slices + 1);
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  updateBounds(m);
  return m;
}

TriangleMesh cylinderMesh(double r, double length, int slices) {
  TriangleMesh m;
  const double h = 0.5 * length;
  for (int j = 0; j <= slices; ++j) {  // side
    const double t = 2 * M_PI * j / slices;
    const Eigen::Vector3d n(std::cos(t), std::sin(t), 0);
    addVertex(m, Eigen::Vector3d(r * n.x(), r * n.y(), -h), n);
    addVertex(m, Eigen::Vector3d(r * n.x(), r * n.y(), h), n);
  }
  for (int j = 0; j < slices; ++j) {
    const unsigned a = unsigned(2 * j);
    m.indices.insert(m.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
  for (int sign : {-1, 1}) {  // caps
    const unsigned centre = unsigned(m.positions.size() / 3);
    const Eigen::Vector3d n(0, 0, sign);
    addVertex(m, Eigen::Vector3d(0, 0, sign * h), n);
    for (int j = 0; j <= slices; ++j) {
      const double t = 2 * M_PI * j / slices;
      addVertex(m, Eigen::Vector3d(r * std::cos(t), r * std::sin(t), sign * h), n);
    }
    for (int j = 0; j < slices; ++j) {
      const unsigned a = centre + 1 + unsigned(j);
      if (sign > 0) m.indices.insert(m.indices.end(), {centre, a, a + 1});
      else m.indices.insert(m.indices.end(), {centre, a + 1, a});
    }
  }
  updateBounds(m);
  return m;
}

TriangleMesh primitiveMesh(const Shape& s) {
  switch (s.type) {
    case ShapeType::Box: return boxMesh(s.box_size);
    case ShapeType::Cylinder: return cylinderMesh(s.radius, s.length);
    case ShapeType::Sphere: default: return sphereMesh(s.radius);
  }
}

const TriangleMesh* MeshLibrary::load(const std::string& path, const Eigen::Vector3d& scale) {
  const std::string key = path + "|" + std::to_string(scale.x()) + "," + std::to_string(scale.y()) + "," +
                          std::to_string(scale.z());
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second.get();
  Assimp::Importer importer;
  // The URDF places the mesh in its own file frame: a COLLADA <up_axis> must not rotate it (as the
  // collision bounds in pronk_model). PreTransformVertices bakes the node transforms and units in.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                                                     aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  std::unique_ptr<TriangleMesh> mesh;
  if (scene && scene->mNumMeshes > 0) {
    mesh = std::make_unique<TriangleMesh>();
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
      const aiMesh* in = scene->mMeshes[k];
      const unsigned base = unsigned(mesh->positions.size() / 3);
      for (unsigned v = 0; v < in->mNumVertices; ++v) {
        const Eigen::Vector3d p(in->mVertices[v].x * scale.x(), in->mVertices[v].y * scale.y(),
                                in->mVertices[v].z * scale.z());
        Eigen::Vector3d n = in->HasNormals() ? Eigen::Vector3d(in->mNormals[v].x, in->mNormals[v].y, in->mNormals[v].z)
                                             : Eigen::Vector3d::UnitZ();
        addVertex(*mesh, p, n.normalized());
      }
      for (unsigned f = 0; f < in->mNumFaces; ++f) {
        if (in->mFaces[f].mNumIndices != 3) continue;
        for (int i = 0; i < 3; ++i) mesh->indices.push_back(base + in->mFaces[f].mIndices[i]);
      }
    }
    updateBounds(*mesh);
  }
  const TriangleMesh* result = mesh.get();
  cache_[key] = std::move(mesh);
  return result;
}

}  // namespace pronk::render
