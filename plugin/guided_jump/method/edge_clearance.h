// The terrain's edges under a jump, and whether the flight passes them high
// enough: what the planner raises its flight for and the safety filter refuses.
// Frame: the start frame S of thrust_trajectory.h; distances along the jump's
// horizontal direction from the polar origin (the take-off surface below the
// start CoM), heights above it. The model and its numbers:
// docs/method-planner.md, step 13.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "method/explosive_phase.h"

namespace pronk::jump {

struct TerrainEdges {
  // Where the surface's height changes along the jump line, and the higher
  // side's height.
  struct Edge {
    double distance = 0.0;  // m
    double top = 0.0;       // m
  };
  std::vector<Edge> edges;  // empty: flat, nothing to clear
  // While the CoM is within body_reach_m of an edge (horizontally, along the
  // jump), the body's lowest point passes clearance_m above it: the hips and
  // tucked knees, hip_depth_m below the CoM, from lift-off on; the tucked feet,
  // tuck_depth_m below it, from tuck_time_s after lift-off (the tuck done).
  double body_reach_m = 0.21;
  double hip_depth_m = 0.06;
  double tuck_depth_m = 0.17;
  double tuck_time_s = 0.1;
  double clearance_m = 0.03;

  // Throws std::invalid_argument naming the field on a bad value.
  void check() const;
};

// How far (m) the body's lowest point passes below an edge's clearance on the
// flight from lift-off (c_e, v) down to the height of c_tg, whose horizontal
// direction from `origin` is the jump's (> 0: too low; -inf: no edge spanned),
// and which edge is the worst.
struct EdgePass {
  double shortfall = -std::numeric_limits<double>::infinity();
  std::optional<TerrainEdges::Edge> edge;
  bool clears() const { return !(shortfall > 0.0); }
};
EdgePass edgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_e,
                  const Eigen::Vector3d& v, const Eigen::Vector3d& c_tg, const Eigen::Vector3d& gravity);

// The same on the thrust, before lift-off: while the CoM on the thrust's path
// is within body_reach_m of an edge, the hips (hip_depth_m below it) must be
// clearance_m above it: a push that carries the trunk's front over a box's edge
// below its top drives a hip into its face. 40 samples of the path.
EdgePass thrustEdgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const ThrustPlan& thrust,
                        const Eigen::Vector3d& c_tg);

// "the flight passes the edge D m along the jump (top H m) S m too low for the
// tucked legs to clear it by C m"; empty when it clears.
std::string edgeProblem(const TerrainEdges& terrain, const EdgePass& pass);
// "the thrust carries the hips over the edge D m along the jump (top H m) S m too low ..."
std::string thrustEdgeProblem(const TerrainEdges& terrain, const EdgePass& pass);

}  // namespace pronk::jump
