// The edge model (method/edge_clearance.h) on its own inputs: which of the
// body's points meet which side of an edge, held to the dense reference of
// edge_reference.h.
#include "method/edge_clearance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "edge_reference.h"
#include "method/ballistics.h"

namespace pronk::jump {
namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// A lift-off from (0.1, 0, 0.36) that lands its CoM at x_land on the surface
// `landing` below the start (the CoM 0.31 above it), after flight_time s.
FlightState liftOffTo(double x_land, double landing, double flight_time) {
  const Eigen::Vector3d c(0.1, 0.0, 0.36);
  const double z_land = landing + 0.31;
  return {c, Eigen::Vector3d((x_land - c.x()) / flight_time, 0.0,
                             (z_land - c.z()) / flight_time + 0.5 * 9.81 * flight_time)};
}

// A body point that keeps its place about the CoM through the landing.
TerrainEdges::BodyPoint fixedPoint(const Eigen::Vector3d& at, double radius, bool tucked = false) {
  return {at, at, radius, tucked};
}

double shortfall(const TerrainEdges& terrain, const FlightState& lo, const Eigen::Vector3d& target) {
  return edgePass(terrain, Eigen::Vector3d::Zero(), lo.position, lo.velocity, target, kGravity).shortfall;
}

TEST(EdgeClearance, MatchesTheDenseReferenceOnADropAndAStep) {
  for (const auto& [edge, landing] : {std::pair{TerrainEdges::Edge{0.45, 0.0, false}, -0.3},
                                      std::pair{TerrainEdges::Edge{0.5, 0.3, true}, 0.3}}) {
    for (const double flight_time : {0.3, 0.4, 0.5}) {
      TerrainEdges terrain;
      terrain.edges = {edge};
      const double x_land = edge.rising ? 0.9 : 1.0;
      const FlightState lo = liftOffTo(x_land, landing, flight_time);
      const Eigen::Vector3d target(x_land, 0.0, landing + 0.31);
      const double reference = reference::leastClearanceOver(terrain, edge, lo, target.z(), Eigen::Vector3d::Zero(),
                                                           Eigen::Vector2d::UnitX(), kGravity);
      // edgePass samples 60 points of the flight; the reference every 0.1 ms.
      EXPECT_NEAR(shortfall(terrain, lo, target), terrain.clearance_m - reference, 0.01)
          << "edge " << edge.distance << " flight " << flight_time;
    }
  }
}

TEST(EdgeClearance, MatchesTheDenseReferenceThroughTheLandingSwing) {
  // The legs swing to the landing pose over the descent, carried along by the
  // landing's stop and reaching an extension below the stance.
  for (const auto& [edge, landing] : {std::pair{TerrainEdges::Edge{0.55, 0.0, false}, -0.3},
                                      std::pair{TerrainEdges::Edge{0.6, 0.3, true}, 0.3}}) {
    for (const double extension : {0.0, 0.1}) {
      for (const double stop : {0.0, 0.12}) {
        TerrainEdges terrain;
        terrain.edges = {edge};
        terrain.landing_extension_m = extension;
        terrain.landing_stop = [stop](const Eigen::Vector3d& v) -> Eigen::Vector2d {
          return stop * v.head<2>().normalized();
        };
        const double x_land = 1.0;
        const FlightState lo = liftOffTo(x_land, landing, 0.45);
        const Eigen::Vector3d target(x_land, 0.0, landing + 0.31);
        const double reference = reference::leastClearanceOver(terrain, edge, lo, target.z(), Eigen::Vector3d::Zero(),
                                                             Eigen::Vector2d::UnitX(), kGravity);
        EXPECT_NEAR(shortfall(terrain, lo, target), terrain.clearance_m - reference, 0.01)
            << "edge " << edge.distance << " extension " << extension << " stop " << stop;
      }
    }
  }
}

TEST(EdgeClearance, AFootLandsOnAStepsTopOnceItHasComeOverTheFace) {
  // One foot, tucked 0.15 m under the CoM and landing 0.29 m under it, on a
  // jump to 0.9 m onto a step 0.3 m up whose face is 0.5 m ahead.
  TerrainEdges terrain;
  terrain.edges = {{0.5, 0.3, true}};
  terrain.body = {{{0.0, 0.0, -0.15}, {0.0, 0.0, -0.29}, 0.02, true, true}};
  const Eigen::Vector3d target(0.9, 0.0, 0.61);
  // A high flight: the foot comes over the face well above the top, then lands on it.
  const FlightState high = liftOffTo(0.9, 0.3, 0.5);
  EXPECT_LT(shortfall(terrain, high, target), 0.0);
  EXPECT_NEAR(shortfall(terrain, high, target),
              terrain.clearance_m - reference::leastClearanceOver(terrain, terrain.edges[0], high, target.z(),
                                                                  Eigen::Vector3d::Zero(), Eigen::Vector2d::UnitX(),
                                                                  kGravity),
              0.01);
  // The same point as a knee, which must stay above the top: it ends 0.14 m
  // above the touchdown's sole height, below the top plus the clearance.
  terrain.body[0].foot = false;
  EXPECT_GT(shortfall(terrain, high, target), 0.0);
  // A face 0.1 m short of the target on a flat flight: the foot, swung down
  // for the landing, meets it below the top.
  terrain.body[0].foot = true;
  terrain.edges = {{0.8, 0.3, true}};
  const FlightState flat = liftOffTo(0.9, 0.3, 0.3);
  const double low = shortfall(terrain, flat, target);
  EXPECT_GT(low, 0.0);
  EXPECT_NEAR(low,
              terrain.clearance_m - reference::leastClearanceOver(terrain, terrain.edges[0], flat, target.z(),
                                                                  Eigen::Vector3d::Zero(), Eigen::Vector2d::UnitX(),
                                                                  kGravity),
              0.01);
}

TEST(EdgeClearance, TheLandingStopCarriesTheTrailingLegsOffTheBoxBeingLeft) {
  // Down 0.3 m from a box whose edge is 0.6 m ahead to 1.0 m. The legs swing to
  // the landing pose at the landing's stop beyond the touchdown point: placed
  // 0.15 m further along, the trailing leg is off the box sooner.
  TerrainEdges terrain;
  terrain.edges = {{0.6, 0.0, false}};
  const FlightState lo = liftOffTo(1.0, -0.3, 0.4);
  const Eigen::Vector3d target(1.0, 0.0, 0.01);
  const double under_the_stance = shortfall(terrain, lo, target);
  terrain.landing_stop = [](const Eigen::Vector3d& v) -> Eigen::Vector2d { return 0.15 * v.head<2>().normalized(); };
  const double carried = shortfall(terrain, lo, target);
  EXPECT_GT(under_the_stance, 0.0);
  EXPECT_LT(carried, under_the_stance - 0.01);
  EXPECT_NEAR(carried,
              terrain.clearance_m - reference::leastClearanceOver(terrain, terrain.edges[0], lo, target.z(),
                                                                  Eigen::Vector3d::Zero(), Eigen::Vector2d::UnitX(),
                                                                  kGravity),
              0.01);
}

TEST(EdgeClearance, ATrailingKneeMustClearTheBoxBeingLeft) {
  // Down 0.3 m from a box whose edge lies 0.45 m ahead to 0.9 m: a 0.4 s
  // flight carries the tucked rear knees, 0.4 m behind the CoM, over the box's
  // top below it; the hips alone would clear.
  TerrainEdges terrain;
  terrain.edges = {{0.45, 0.0, false}};
  const FlightState lo = liftOffTo(0.9, -0.3, 0.4);
  const Eigen::Vector3d target(0.9, 0.0, 0.01);
  const EdgePass pass = edgePass(terrain, Eigen::Vector3d::Zero(), lo.position, lo.velocity, target, kGravity);
  EXPECT_GT(pass.shortfall, 0.0);
  ASSERT_TRUE(pass.edge);
  EXPECT_EQ(pass.edge->distance, 0.45);
  EXPECT_NE(edgeProblem(terrain, pass).find("the edge 0.45 m along the jump (top 0 m)"), std::string::npos);
  TerrainEdges hips_only = terrain;
  hips_only.body.erase(std::remove_if(hips_only.body.begin(), hips_only.body.end(),
                                     [](const TerrainEdges::BodyPoint& p) { return p.at.z() < -0.01; }),
                      hips_only.body.end());
  EXPECT_LT(shortfall(hips_only, lo, target), 0.0);
  // Landing 0.2 m further, they are past it in time.
  EXPECT_LT(shortfall(terrain, liftOffTo(1.1, -0.3, 0.4), Eigen::Vector3d(1.1, 0.0, 0.01)), 0.0);
}

TEST(EdgeClearance, OnlyThePointsOverTheHigherSideCount) {
  // A step 0.3 m up, 0.5 m ahead: below its top, a point behind the edge is
  // free, one ahead of it (or within the clearance of its face) is not.
  TerrainEdges terrain;
  terrain.edges = {{0.5, 0.3, true}};
  terrain.body = {fixedPoint({0.0, 0.0, 0.0}, 0.0)};
  const Eigen::Vector3d target(2.0, 0.0, 0.31);
  const FlightState still{{0.1, 0.0, 0.2}, Eigen::Vector3d(0.0, 0.0, 0.0)};
  // The CoM at 0.1 m (behind the edge, 0.1 m below the top): nothing over the top.
  EXPECT_FALSE(edgePass(terrain, Eigen::Vector3d::Zero(), still.position, Eigen::Vector3d(1e-3, 0, 0), target, kGravity)
                   .shortfall > 0.0);
  // The point reaching 0.45 m ahead of the CoM: 0.05 m short of the face, within
  // the clearance plus its 0.03 m radius: it counts.
  terrain.body = {fixedPoint({0.42, 0.0, 0.0}, 0.03)};
  const double reach = edgePass(terrain, Eigen::Vector3d::Zero(), still.position, Eigen::Vector3d(1e-3, 0, 0), target,
                                kGravity).shortfall;
  EXPECT_NEAR(reach, 0.3 + 0.03 - (0.2 - 0.03), 1e-9);
  // A drop behind instead: the same point ahead is over the lower side.
  terrain.edges = {{0.5, 0.3, false}};
  terrain.body = {fixedPoint({0.45, 0.0, 0.0}, 0.0)};
  EXPECT_FALSE(edgePass(terrain, Eigen::Vector3d::Zero(), still.position, Eigen::Vector3d(1e-3, 0, 0), target, kGravity)
                   .shortfall > 0.0);
}

TEST(EdgeClearance, TheTrunkTurnsItsPointsOverTheFlight) {
  // One point 0.4 m behind the CoM, a drop 0.45 m ahead of a 0.9 m jump.
  // Without a turn it trails the CoM over the edge too low; turned a quarter
  // over the flight it points sideways by the time the CoM is past the edge.
  TerrainEdges terrain;
  terrain.edges = {{0.45, 0.0, false}};
  terrain.body = {fixedPoint({-0.4, 0.0, -0.05}, 0.0, true)};
  terrain.tuck_time_s = 0.0;
  const FlightState lo = liftOffTo(0.9, -0.3, 0.4);
  const Eigen::Vector3d target(0.9, 0.0, 0.01);
  const double straight = shortfall(terrain, lo, target);
  terrain.turn_rad = M_PI / 2.0;
  const double turned = shortfall(terrain, lo, target);
  EXPECT_GT(straight, 0.0);
  EXPECT_LT(turned, 0.0);
  EXPECT_NEAR(turned, terrain.clearance_m - reference::leastClearanceOver(terrain, terrain.edges[0], lo, target.z(),
                                                                         Eigen::Vector3d::Zero(),
                                                                         Eigen::Vector2d::UnitX(), kGravity),
              0.01);
}

TEST(EdgeClearance, CheckNamesABadField) {
  TerrainEdges terrain;
  terrain.body.push_back(fixedPoint({NAN, 0.0, 0.0}, 0.0));
  EXPECT_THROW(terrain.check(), std::invalid_argument);
  terrain = TerrainEdges{};
  terrain.turn_rad = INFINITY;
  EXPECT_THROW(terrain.check(), std::invalid_argument);
  terrain = TerrainEdges{};
  terrain.tuck_time_s = -1.0;
  try {
    terrain.check();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tuck_time_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pronk::jump
