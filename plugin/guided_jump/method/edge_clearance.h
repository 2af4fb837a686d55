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

#include "method/ballistics.h"
#include "method/explosive_phase.h"

namespace pronk::jump {

struct TerrainEdges {
  // Where the surface's height changes along the jump line, the higher side's
  // height, and on which side of the edge it lies.
  struct Edge {
    double distance = 0.0;  // m
    double top = 0.0;       // m
    bool rising = false;    // the higher side lies ahead (a step up); else behind (a drop)
  };
  std::vector<Edge> edges;  // empty: flat, nothing to clear
  // The body's points that must pass clearance_m above the higher side of an
  // edge while any of them is over it, about the CoM in the trunk's frame (x
  // ahead, z up), each a ball of its radius: the hips, the knees and the feet.
  // In flight the legs hold the tuck (`at`): the knees from lift-off, the feet
  // (`tucked`) from tuck_time_s after it, once the tuck is done. From
  // descent_s before touchdown they swing in descent_blend_s (a smoothstep) to
  // the landing pose (`landing`: the stance's, landing_extension_m lower,
  // moved along by landing_stop of the touchdown velocity when one is given),
  // which they hold to touchdown. A foot over a step's top counts only as it
  // comes over the face: it lands there. The trunk turns from the start's yaw
  // to turn_rad over the flight. The defaults are the Go1's.
  struct BodyPoint {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();       // m, in flight
    Eigen::Vector3d landing = Eigen::Vector3d::Zero();  // m, in the landing pose
    double radius = 0.0;                                // m
    bool tucked = false;                                // from tuck_time_s on
    bool foot = false;                                  // lands on the surface under it
  };
  std::vector<BodyPoint> body = {
      {{0.19, 0.13, 0.0}, {0.19, 0.13, 0.0}, 0.046},
      {{0.19, -0.13, 0.0}, {0.19, -0.13, 0.0}, 0.046},
      {{-0.19, 0.13, 0.0}, {-0.19, 0.13, 0.0}, 0.046},
      {{-0.19, -0.13, 0.0}, {-0.19, -0.13, 0.0}, 0.046},
      {{-0.02, 0.13, -0.05}, {0.04, 0.13, -0.13}, 0.02},
      {{-0.02, -0.13, -0.05}, {0.04, -0.13, -0.13}, 0.02},
      {{-0.40, 0.13, -0.05}, {-0.33, 0.13, -0.13}, 0.02},
      {{-0.40, -0.13, -0.05}, {-0.33, -0.13, -0.13}, 0.02},
      {{0.19, 0.13, -0.15}, {0.19, 0.13, -0.29}, 0.02, true, true},
      {{0.19, -0.13, -0.15}, {0.19, -0.13, -0.29}, 0.02, true, true},
      {{-0.19, 0.13, -0.15}, {-0.19, 0.13, -0.29}, 0.02, true, true},
      {{-0.19, -0.13, -0.15}, {-0.19, -0.13, -0.29}, 0.02, true, true}};
  double tuck_time_s = 0.1;
  double descent_s = 0.16;
  double descent_blend_s = 0.1;
  double landing_extension_m = 0.0;
  LandingStop landing_stop;  // none: the feet land under the stance
  double turn_rad = 0.0;
  double clearance_m = 0.03;

  // Throws std::invalid_argument naming the field on a bad value.
  void check() const;
};

// How far (m) the body's lowest point over the higher side of an edge passes
// below its clearance on the flight from lift-off (c_e, v) down to the height of
// c_tg, whose horizontal direction from `origin` is the jump's (> 0: too low;
// -inf: no point over an edge), and which edge is the worst. The flight ends at
// touchdown, when the CoM is down to c_tg's height plus the landing extension.
// Each point's path is taken in 60 spans, straight along the jump within each
// (exact without a turn), its lowest point over an edge found exactly in
// flight; in the descent's swing, at the spans' ends.
struct EdgePass {
  double shortfall = -std::numeric_limits<double>::infinity();
  std::optional<TerrainEdges::Edge> edge;
  bool clears() const { return !(shortfall > 0.0); }
};
EdgePass edgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const Eigen::Vector3d& c_e,
                  const Eigen::Vector3d& v, const Eigen::Vector3d& c_tg, const Eigen::Vector3d& gravity);

// The same on the thrust, before lift-off, for the points not tucked (at the start's yaw): a
// push that carries the trunk's front over a box's edge below its top drives a
// hip into its face. 40 samples of the path.
EdgePass thrustEdgePass(const TerrainEdges& terrain, const Eigen::Vector3d& origin, const ThrustPlan& thrust,
                        const Eigen::Vector3d& c_tg);

// "the flight passes the edge D m along the jump (top H m) S m too low for the
// tucked legs to clear it by C m"; empty when it clears.
std::string edgeProblem(const TerrainEdges& terrain, const EdgePass& pass);
// "the thrust carries the hips over the edge D m along the jump (top H m) S m too low ..."
std::string thrustEdgeProblem(const TerrainEdges& terrain, const EdgePass& pass);

}  // namespace pronk::jump
