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
  for (const BodyPoint& p : body) {
    if (!p.at.allFinite() || !(std::isfinite(p.radius) && p.radius >= 0.0)) {
      bad("body: a point must be finite, its radius >= 0");
    }
  }
  for (const auto& [name, value] : {std::pair{"tuck_time_s", tuck_time_s}, std::pair{"clearance_m", clearance_m}}) {
    if (!(std::isfinite(value) && value >= 0.0)) bad(std::string(name) + " must be finite and >= 0");
  }
  if (!std::isfinite(turn_rad)) bad("turn_rad must be finite");
}

namespace {

// The worst shortfall of the body's points not tucked (trunk frame, turned by
// yaw in S) about the CoM c over the higher side of an edge; u is the jump's
// horizontal direction.
void hipsOverEdges(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector2d& u,
                   const Eigen::Vector3d& c, double yaw, EdgePass* pass) {
  const double x_com = (c - origin).head<2>().dot(u);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  for (const TerrainEdges::BodyPoint& p : terrain.body) {
    if (p.tucked) continue;
    const double along = x_com + (cy * p.at.x() - sy * p.at.y()) * u.x() + (sy * p.at.x() + cy * p.at.y()) * u.y();
    const double bottom = c.z() + p.at.z() - p.radius;
    for (const TerrainEdges::Edge& e : terrain.edges) {
      // Over the higher side, or within the clearance of its face.
      const double reach = p.radius + terrain.clearance_m;
      const bool over_top = e.rising ? along + reach > e.distance : along - reach < e.distance;
      if (!over_top) continue;
      const double shortfall = origin.z() + e.top + terrain.clearance_m - bottom;
      if (shortfall > pass->shortfall) {
        pass->shortfall = shortfall;
        pass->edge = e;
      }
    }
  }
}

}  // namespace

EdgePass edgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_e,
                  const Eigen::Vector3d& v, const Eigen::Vector3d& c_tg, const Eigen::Vector3d& gravity) {
  constexpr int kSamples = 60;
  EdgePass pass;
  if (terrain.edges.empty()) return pass;
  const Eigen::Vector2d towards = (c_tg - origin).head<2>();
  if (!(towards.norm() > 0.0)) return pass;
  const Eigen::Vector2d u = towards.normalized();
  const BallisticFlight flight(FlightState{c_e, v}, gravity);
  const double T = flight.landingTime(c_tg.z()).value_or(0.0);
  // A point's distance along the jump and its bottom's height at time t.
  const auto at = [&](const TerrainEdges::BodyPoint& p, double t) {
    const Eigen::Vector3d c = flight.position(t);
    const double yaw = T > 0.0 ? terrain.turn_rad * t / T : 0.0;
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    const double along = (c - origin).head<2>().dot(u) + (cy * p.at.x() - sy * p.at.y()) * u.x() +
                         (sy * p.at.x() + cy * p.at.y()) * u.y();
    return std::pair{along, c.z() + p.at.z() - p.radius};
  };
  const auto record = [&](const TerrainEdges::Edge& e, double bottom) {
    const double shortfall = origin.z() + e.top + terrain.clearance_m - bottom;
    if (shortfall > pass.shortfall) {
      pass.shortfall = shortfall;
      pass.edge = e;
    }
  };
  // Between two samples a point's distance along the jump is taken as linear
  // (exact without a turn) and its height is a parabola, lowest at an end of
  // the span it is over an edge's higher side: a sample end or the moment it
  // comes over (or within the clearance of) the edge's face.
  for (const TerrainEdges::BodyPoint& p : terrain.body) {
    const double t_first = p.tucked ? std::min(terrain.tuck_time_s, T) : 0.0;
    for (int i = 0; i < kSamples; ++i) {
      const double t0 = t_first + (T - t_first) * i / kSamples, t1 = t_first + (T - t_first) * (i + 1) / kSamples;
      const auto [a0, z0] = at(p, t0);
      const auto [a1, z1] = at(p, t1);
      const double reach = p.radius + terrain.clearance_m;
      for (const TerrainEdges::Edge& e : terrain.edges) {
        // > 0: over the higher side (or within reach of its face).
        const double s0 = (e.rising ? a0 - e.distance : e.distance - a0) + reach;
        const double s1 = (e.rising ? a1 - e.distance : e.distance - a1) + reach;
        if (s0 > 0.0) record(e, z0);
        if (s1 > 0.0) record(e, z1);
        if ((s0 > 0.0) != (s1 > 0.0)) record(e, at(p, t0 + (t1 - t0) * s0 / (s0 - s1)).second);
      }
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
    hipsOverEdges(terrain, origin, u, thrust.position(thrust.duration() * i / kSamples), 0.0, &pass);
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
