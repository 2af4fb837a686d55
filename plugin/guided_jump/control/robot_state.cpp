#include "control/robot_state.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Cholesky>

namespace pronk::guided_jump {

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

Eigen::Matrix3d headingOf(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(std::atan2(R(1, 0), R(0, 0)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

StartFrame takeOffFrame(const pronk_host_api* host, const pronk_robot_state& s) {
  StartFrame S;
  S.heading = Eigen::AngleAxisd(rpyFromRotation(rotationOf(s)).z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  double ground = 0;
  int counted = 0;
  for (int pass = 0; pass < 2 && counted == 0; ++pass) {  // feet in contact; all feet when none is
    for (int f = 0; f < s.foot_count; ++f) {
      if (pass == 0 && !s.foot_in_contact[f]) continue;
      const double r = host->foot_radius ? host->foot_radius(host->host, f) : 0.0;
      ground += s.foot_position[3 * f + 2] - (std::isfinite(r) ? r : 0.0);
      ++counted;
    }
  }
  S.origin = Eigen::Vector3d(s.com_position[0], s.com_position[1], counted ? ground / counted : 0.0);
  return S;
}

std::optional<CentroidalMomentum> centroidalMomentum(const pronk_host_api* host) {
  if (host->struct_size < offsetof(pronk_host_api, centroidal_momentum) + sizeof(host->centroidal_momentum) ||
      !host->centroidal_momentum) {
    return std::nullopt;
  }
  CentroidalMomentum m;
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> I;
  if (host->centroidal_momentum(host->host, m.angular.data(), I.data()) != PRONK_OK) return std::nullopt;
  m.inertia = I;
  if (!m.angular.allFinite() || !m.inertia.allFinite()) return std::nullopt;
  return m;
}

std::optional<Eigen::Vector3d> averageRate(const CentroidalMomentum& m) {
  const Eigen::Vector3d w = m.inertia.ldlt().solve(m.angular);
  return w.allFinite() ? std::optional<Eigen::Vector3d>(w) : std::nullopt;
}

std::optional<Eigen::Vector3d> wholeBodyRate(const pronk_host_api* host) {
  const std::optional<CentroidalMomentum> m = centroidalMomentum(host);
  return m ? averageRate(*m) : std::nullopt;
}

std::optional<TerrainTop> terrainTop(const pronk_host_api* host, double x, double y) {
  if (host->struct_size < offsetof(pronk_host_api, terrain_top) + sizeof(host->terrain_top) || !host->terrain_top) {
    return std::nullopt;
  }
  TerrainTop top;
  int32_t surface = -1;
  if (host->terrain_top(host->host, x, y, &top.height, &surface) != PRONK_OK || !std::isfinite(top.height)) {
    return std::nullopt;
  }
  top.surface = surface;
  return top;
}

}  // namespace pronk::guided_jump
