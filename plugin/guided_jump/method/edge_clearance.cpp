#include "method/edge_clearance.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

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
  for (const BodyPoint& p : body) {
    if (!p.landing.allFinite()) bad("body: a point's landing pose must be finite");
  }
  for (const auto& [name, value] :
       {std::pair{"tuck_time_s", tuck_time_s}, std::pair{"clearance_m", clearance_m}, std::pair{"descent_s", descent_s},
        std::pair{"descent_blend_s", descent_blend_s}, std::pair{"landing_extension_m", landing_extension_m}}) {
    if (!(std::isfinite(value) && value >= 0.0)) bad(std::string(name) + " must be finite and >= 0");
  }
  if (!std::isfinite(turn_rad)) bad("turn_rad must be finite");
}

namespace {

// The jump's horizontal direction from `origin` towards c_tg; none when there
// is nothing to check (no edges, or a jump in place).
std::optional<Eigen::Vector2d> jumpDirection(const TerrainEdges& terrain, const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& c_tg) {
  if (terrain.edges.empty()) return std::nullopt;
  const Eigen::Vector2d towards = (c_tg - origin).head<2>();
  if (!(towards.norm() > 0.0)) return std::nullopt;
  return towards.normalized();
}

// Point `at` of the body about the CoM c, the trunk turned by yaw in S and the
// point moved by `shift` (S, horizontal): its distance along the jump (u) and
// the height of its ball's bottom.
std::pair<double, double> pointAt(const Eigen::Vector3d& at, double radius, const Eigen::Vector3d& origin,
                                  const Eigen::Vector2d& u, const Eigen::Vector3d& c, double yaw,
                                  const Eigen::Vector2d& shift) {
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const double along = (c - origin).head<2>().dot(u) + (cy * at.x() - sy * at.y()) * u.x() +
                       (sy * at.x() + cy * at.y()) * u.y() + shift.dot(u);
  return {along, c.z() + at.z() - radius};
}

double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// > 0: a point `along` the jump is over edge e's higher side, or within
// `reach` of its face.
double overTop(const TerrainEdges::Edge& e, double along, double reach) {
  return (e.rising ? along - e.distance : e.distance - along) + reach;
}

// Keeps the worst shortfall of a point's bottom below e's clearance.
void record(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const TerrainEdges::Edge& e, double bottom,
            EdgePass* pass) {
  const double shortfall = origin.z() + e.top + terrain.clearance_m - bottom;
  if (shortfall > pass->shortfall) {
    pass->shortfall = shortfall;
    pass->edge = e;
  }
}

}  // namespace

EdgePass edgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_e,
                  const Eigen::Vector3d& v, const Eigen::Vector3d& c_tg, const Eigen::Vector3d& gravity) {
  constexpr int kFlightSpans = 60, kDescentSpans = 20;
  EdgePass pass;
  const std::optional<Eigen::Vector2d> u = jumpDirection(terrain, origin, c_tg);
  if (!u) return pass;
  const BallisticFlight flight(FlightState{c_e, v}, gravity);
  const double T = flight.landingTime(c_tg.z() + terrain.landing_extension_m)
                       .value_or(flight.landingTime(c_tg.z()).value_or(0.0));
  const double descent = std::max(0.0, T - terrain.descent_s);
  Eigen::Vector2d ahead = Eigen::Vector2d::Zero();
  if (terrain.landing_stop && T > 0.0) ahead = terrain.landing_stop(flight.state(T).velocity);
  // The pose's share of the landing pose at time t: 0 in flight, 1 from the
  // swing's end to touchdown.
  const auto landed = [&](double t) { return smoothstep01((t - descent) / terrain.descent_blend_s); };
  const auto at = [&](const TerrainEdges::BodyPoint& p, double t) {
    const double w = t > descent ? landed(t) : 0.0;  // a 0 s swing: the landing pose at once
    return pointAt(p.at + w * (p.landing - p.at), p.radius, origin, *u, flight.position(t),
                   T > 0.0 ? terrain.turn_rad * t / T : 0.0, w * ahead);
  };
  // Between two samples a point's distance along the jump is taken as linear
  // (exact in flight without a turn). In flight its height is a parabola, lowest
  // at an end of the span it is over an edge's higher side: a sample end or the
  // moment it comes over (or within the clearance of) the edge's face. A foot
  // over a step's top counts only where it comes over the face.
  for (const TerrainEdges::BodyPoint& p : terrain.body) {
    const double t_first = p.tucked ? std::min(terrain.tuck_time_s, T) : 0.0;
    const double t_descent = std::max(t_first, descent);
    const double reach = p.radius + terrain.clearance_m;
    const auto time = [&](int i) {
      return i <= kFlightSpans ? t_first + (t_descent - t_first) * i / kFlightSpans
                               : t_descent + (T - t_descent) * (i - kFlightSpans) / kDescentSpans;
    };
    const auto [a_first, z_first] = at(p, t_first);
    for (const TerrainEdges::Edge& e : terrain.edges) {
      if (overTop(e, a_first, reach) > 0.0) record(terrain, origin, e, z_first, &pass);
    }
    double a0 = a_first;
    for (int i = 0; i < kFlightSpans + kDescentSpans; ++i) {
      const double t0 = time(i), t1 = time(i + 1);
      const auto [a1, z1] = at(p, t1);
      for (const TerrainEdges::Edge& e : terrain.edges) {
        const double s0 = overTop(e, a0, reach), s1 = overTop(e, a1, reach);
        const bool lands_on_top = p.foot && e.rising;
        if (s1 > 0.0 && !lands_on_top) record(terrain, origin, e, z1, &pass);
        if ((s0 > 0.0) != (s1 > 0.0)) record(terrain, origin, e, at(p, t0 + (t1 - t0) * s0 / (s0 - s1)).second, &pass);
      }
      a0 = a1;
    }
  }
  return pass;
}

EdgePass thrustEdgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const ThrustPlan& thrust,
                        const Eigen::Vector3d& c_tg) {
  constexpr int kSamples = 40;
  EdgePass pass;
  const std::optional<Eigen::Vector2d> u = jumpDirection(terrain, origin, c_tg);
  if (!u) return pass;
  for (int i = 0; i <= kSamples; ++i) {
    const Eigen::Vector3d c = thrust.position(thrust.duration() * i / kSamples);
    for (const TerrainEdges::BodyPoint& p : terrain.body) {
      if (p.tucked) continue;  // the legs tuck only in flight
      const auto [along, bottom] = pointAt(p.at, p.radius, origin, *u, c, 0.0, Eigen::Vector2d::Zero());
      for (const TerrainEdges::Edge& e : terrain.edges) {
        if (overTop(e, along, p.radius + terrain.clearance_m) > 0.0) record(terrain, origin, e, bottom, &pass);
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
