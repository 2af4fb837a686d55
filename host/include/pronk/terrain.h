// Static terrain: an optional ground plane plus boxes (full sizes, yaw about z).
// Pure geometry, shared by the foot contact law and the non-foot contact check.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pronk/scenario.h"

namespace pronk {

// The walkable top surface found under a point.
struct Surface {
  double height = 0;            // z of the top face, m
  std::optional<double> mu;     // friction override of this surface
  int box = -1;                 // index of the box, -1 for the ground
};

class Terrain {
 public:
  Terrain() = default;
  Terrain(bool ground, double ground_height, std::vector<TerrainBox> boxes);

  // The highest top face whose footprint contains (x, y) and that lies at or
  // below z (a foot sphere centre). Box sides are not surfaces: a foot that
  // enters a box from the side only meets its top once its centre is above it.
  std::optional<Surface> surfaceBelow(double x, double y, double z) const;
  // True when the point is below the ground plane or inside a box.
  bool contains(const Eigen::Vector3d& point) const;
  // The highest top face at (x, y) regardless of z (ground if nothing else).
  std::optional<Surface> topAt(double x, double y) const;

  const std::vector<TerrainBox>& boxes() const { return boxes_; }
  bool hasGround() const { return ground_; }
  double groundHeight() const { return ground_height_; }

 private:
  bool insideFootprint(const TerrainBox& box, double x, double y) const;
  bool ground_ = true;
  double ground_height_ = 0;
  std::vector<TerrainBox> boxes_;
};

// The terrain once the paper's apex platform has appeared (ApexPlatform): the
// boxes of `before` and the platform with its top at `top`, on a ground plane
// at the platform's floor. Shared by the episode that swaps it in and the
// videos that draw it.
Terrain withApexPlatform(const Terrain& before, const ApexPlatform& platform, double top);

}  // namespace pronk
