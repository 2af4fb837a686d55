// The clearance of the body over an edge's higher side along a flown arc,
// sampled densely (1e-4 s) and written apart from method/edge_clearance.cpp:
// the reference the planner's and the safety filter's edge checks are held to.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "method/ballistics.h"
#include "method/edge_clearance.h"

namespace pronk::jump::reference {

// The least height of a body point's bottom above `edge`'s top while the point
// (or its ball within the clearance) is over the higher side, on the flight
// from `lift_off` down to touchdown (the CoM at `landing_z` plus the landing
// extension), the jump along `u` from `origin`. The legs hold the tuck, then
// swing to the landing pose over the descent; a foot over a step's top counts
// only at the first instant it is there.
inline double leastClearanceOver(const TerrainEdges& terrain, const TerrainEdges::Edge& edge, const FlightState& lift_off,
                                 double landing_z, const Eigen::Vector3d& origin, const Eigen::Vector2d& u,
                                 const Eigen::Vector3d& gravity) {
  const BallisticFlight flight(lift_off, gravity);
  const double T = flight.landingTime(landing_z + terrain.landing_extension_m).value_or(0.0);
  const Eigen::Vector2d shift =
      terrain.landing_stop ? terrain.landing_stop(flight.state(T).velocity) : Eigen::Vector2d::Zero();
  double least = std::numeric_limits<double>::infinity();
  for (const TerrainEdges::BodyPoint& p : terrain.body) {
    bool was_over = false;
    for (double t = p.tucked ? terrain.tuck_time_s : 0.0; t <= T; t += 1e-4) {
      const Eigen::Vector3d c = flight.state(t).position;
      const double yaw = terrain.turn_rad * t / T;
      double w = std::clamp((t - (T - terrain.descent_s)) / terrain.descent_blend_s, 0.0, 1.0);
      w = w * w * (3.0 - 2.0 * w);
      const Eigen::Vector3d at = (1.0 - w) * p.at + w * p.landing;
      const Eigen::Vector2d xy(std::cos(yaw) * at.x() - std::sin(yaw) * at.y(),
                               std::sin(yaw) * at.x() + std::cos(yaw) * at.y());
      const double along = (c - origin).head<2>().dot(u) + xy.dot(u) + w * shift.dot(u);
      const double side = edge.rising ? along - edge.distance : edge.distance - along;
      const bool over = side + p.radius + terrain.clearance_m > 0.0;  // over the higher side, or near its face
      if (over && !(p.foot && edge.rising && was_over)) {
        least = std::min(least, c.z() + at.z() - p.radius - (origin.z() + edge.top));
      }
      was_over = over;
    }
  }
  return least;
}

}  // namespace pronk::jump::reference
