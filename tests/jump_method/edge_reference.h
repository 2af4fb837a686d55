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
// from `lift_off` down to `landing_z`, the jump along `u` from `origin`.
inline double leastClearanceOver(const TerrainEdges& terrain, const TerrainEdges::Edge& edge, const FlightState& lift_off,
                                 double landing_z, const Eigen::Vector3d& origin, const Eigen::Vector2d& u,
                                 const Eigen::Vector3d& gravity) {
  const BallisticFlight flight(lift_off, gravity);
  const double T = flight.landingTime(landing_z).value_or(0.0);
  double least = std::numeric_limits<double>::infinity();
  for (double t = 0.0; t <= T; t += 1e-4) {
    const Eigen::Vector3d c = flight.state(t).position;
    const double yaw = terrain.turn_rad * t / T;
    for (const TerrainEdges::BodyPoint& p : terrain.body) {
      if (p.tucked && t < terrain.tuck_time_s) continue;
      const Eigen::Vector2d xy(std::cos(yaw) * p.at.x() - std::sin(yaw) * p.at.y(),
                               std::sin(yaw) * p.at.x() + std::cos(yaw) * p.at.y());
      const double along = (c - origin).head<2>().dot(u) + xy.dot(u);
      const double side = edge.rising ? along - edge.distance : edge.distance - along;
      if (side + p.radius + terrain.clearance_m <= 0.0) continue;  // over the lower side, clear of the face
      least = std::min(least, c.z() + p.at.z() - p.radius - (origin.z() + edge.top));
    }
  }
  return least;
}

}  // namespace pronk::jump::reference
