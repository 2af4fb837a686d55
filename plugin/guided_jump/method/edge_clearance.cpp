#include "method/edge_clearance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "method/ballistics.h"

namespace pronk::jump {

void TerrainEdges::check() const {
  auto bad = [](const std::string& what) { throw std::invalid_argument("terrain edges: " + what); };
  for (const Edge& e : edges) {
    if (!std::isfinite(e.distance) || !std::isfinite(e.top)) bad("an edge's distance and top must be finite");
  }
  for (const auto& [name, value] : {std::pair{"body_reach_m", body_reach_m}, std::pair{"hip_depth_m", hip_depth_m},
                                    std::pair{"tuck_depth_m", tuck_depth_m}, std::pair{"tuck_time_s", tuck_time_s},
                                    std::pair{"clearance_m", clearance_m}}) {
    if (!(std::isfinite(value) && value >= 0.0)) bad(std::string(name) + " must be finite and >= 0");
  }
}

EdgePass edgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_e,
                  const Eigen::Vector3d& v, const Eigen::Vector3d& c_tg, const Eigen::Vector3d& gravity) {
  EdgePass pass;
  if (terrain.edges.empty()) return pass;
  const Eigen::Vector2d towards = (c_tg - origin).head<2>();
  if (!(towards.norm() > 0.0)) return pass;
  const Eigen::Vector2d u = towards.normalized();
  const double x0 = (c_e - origin).head<2>().dot(u), speed = v.head<2>().dot(u);
  if (!(speed > 0.0)) return pass;
  const BallisticFlight flight(FlightState{c_e, v}, gravity);
  const double T = flight.landingTime(c_tg.z()).value_or(0.0);
  const double g = -gravity.z();
  const auto z = [&](double t) { return c_e.z() + v.z() * t - 0.5 * g * t * t; };
  for (const TerrainEdges::Edge& e : terrain.edges) {
    // The times the body spans the edge, within the flight; its lowest point
    // is the hips' until the tuck is done, the tucked feet's after. A parabola
    // is lowest at an end of an interval.
    const double t1 = std::max(0.0, (e.distance - terrain.body_reach_m - x0) / speed);
    const double t2 = std::min(T, (e.distance + terrain.body_reach_m - x0) / speed);
    if (t1 > t2) continue;
    const double clear = origin.z() + e.top + terrain.clearance_m;
    double shortfall = -std::numeric_limits<double>::infinity();
    const double tuck = std::clamp(terrain.tuck_time_s, t1, t2);
    if (tuck > t1) shortfall = std::max(shortfall, clear + terrain.hip_depth_m - std::min(z(t1), z(tuck)));
    if (t2 > tuck || tuck == t1) shortfall = std::max(shortfall, clear + terrain.tuck_depth_m - std::min(z(tuck), z(t2)));
    if (shortfall > pass.shortfall) {
      pass.shortfall = shortfall;
      pass.edge = e;
    }
  }
  return pass;
}

EdgePass thrustEdgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const ThrustPlan& thrust,
                        const Eigen::Vector3d& c_tg) {
  constexpr int kSamples = 40;
  EdgePass pass;
  if (terrain.edges.empty()) return pass;
  const Eigen::Vector2d towards = (c_tg - origin).head<2>();
  if (!(towards.norm() > 0.0)) return pass;
  const Eigen::Vector2d u = towards.normalized();
  for (int i = 0; i <= kSamples; ++i) {
    const Eigen::Vector3d c = thrust.position(thrust.duration() * i / kSamples);
    const double x = (c - origin).head<2>().dot(u);
    for (const TerrainEdges::Edge& e : terrain.edges) {
      if (std::abs(x - e.distance) > terrain.body_reach_m) continue;
      const double shortfall = origin.z() + e.top + terrain.clearance_m + terrain.hip_depth_m - c.z();
      if (shortfall > pass.shortfall) {
        pass.shortfall = shortfall;
        pass.edge = e;
      }
    }
  }
  return pass;
}

std::string thrustEdgeProblem(const TerrainEdges& terrain, const EdgePass& pass) {
  if (pass.clears() || !pass.edge) return "";
  return fmt::format("the thrust carries the hips over the edge {:.3g} m along the jump (top {:.3g} m) {:.3f} m too "
                     "low to clear it by {:.3g} m",
                     pass.edge->distance, pass.edge->top, pass.shortfall, terrain.clearance_m);
}

std::string edgeProblem(const TerrainEdges& terrain, const EdgePass& pass) {
  if (pass.clears() || !pass.edge) return "";
  return fmt::format("the flight passes the edge {:.3g} m along the jump (top {:.3g} m) {:.3f} m too low for the "
                     "tucked legs to clear it by {:.3g} m",
                     pass.edge->distance, pass.edge->top, pass.shortfall, terrain.clearance_m);
}

}  // namespace pronk::jump
