#include "pronk/terrain.h"

#include <algorithm>
#include <cmath>

namespace pronk {

Terrain::Terrain(bool ground, double ground_height, std::vector<TerrainBox> boxes)
    : ground_(ground), ground_height_(ground_height), boxes_(std::move(boxes)) {}

bool Terrain::insideFootprint(const TerrainBox& box, double x, double y) const {
  // Rotate the point into the box frame (yaw only).
  const double dx = x - box.position[0], dy = y - box.position[1];
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const double bx = c * dx + s * dy, by = -s * dx + c * dy;
  return std::abs(bx) <= 0.5 * box.size[0] && std::abs(by) <= 0.5 * box.size[1];
}

std::optional<Surface> Terrain::surfaceBelow(double x, double y, double z) const {
  std::optional<Surface> best;
  if (ground_ && ground_height_ <= z) best = Surface{ground_height_, std::nullopt, -1};
  for (size_t i = 0; i < boxes_.size(); ++i) {
    const TerrainBox& b = boxes_[i];
    const double top = b.position[2] + 0.5 * b.size[2];
    if (top > z || !insideFootprint(b, x, y)) continue;
    if (!best || top > best->height) best = Surface{top, b.mu, static_cast<int>(i)};
  }
  return best;
}

std::optional<Surface> Terrain::topAt(double x, double y) const {
  return surfaceBelow(x, y, 1e300);
}

bool Terrain::contains(const Eigen::Vector3d& p) const {
  if (ground_ && p.z() < ground_height_) return true;
  for (const TerrainBox& b : boxes_) {
    const double half_z = 0.5 * b.size[2];
    if (std::abs(p.z() - b.position[2]) <= half_z && insideFootprint(b, p.x(), p.y())) return true;
  }
  return false;
}

Terrain withApexPlatform(const Terrain& before, const ApexPlatform& platform, double top) {
  TerrainBox box;
  box.name = "apex_platform";
  const double thickness = std::max(top - platform.floor, 0.01);
  box.size = {platform.size, platform.size, thickness};
  box.position = {platform.x, platform.y, top - thickness / 2};
  box.yaw = platform.yaw;
  std::vector<TerrainBox> boxes = before.boxes();
  boxes.push_back(box);
  return Terrain(before.hasGround(), platform.floor, std::move(boxes));
}

}  // namespace pronk
