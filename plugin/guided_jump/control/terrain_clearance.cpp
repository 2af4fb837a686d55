#include "control/terrain_clearance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "control/robot_state.h"
#include "method/leg_ik.h"

namespace pronk::guided_jump {

namespace {
// A surface this much above the landing one (or the one under the point) is an
// obstacle: the feet's contact sinks them a few mm, and the start frame's ground
// is where they stood.
constexpr double kSameSurface = 0.02;  // m
}  // namespace

double TerrainClearance::shortfall(const pronk_robot_state& s, const Eigen::Matrix3d& R, int f, const Eigen::Vector3d& q,
                                   double landing_surface) const {
  const Eigen::Vector3d base = vec(s.base_position);
  const pronk_host_api* host = drive_.host();
  const double radius = host->foot_radius ? host->foot_radius(host->host, f) : 0.0;
  // The leg's points in the trunk frame and how far above the terrain each must
  // be: along the thigh and the calf, densely enough that an edge between two
  // of them cannot pass more than a few mm above the segment between.
  constexpr int kThighPoints = 3, kCalfPoints = 6;
  std::array<Eigen::Vector3d, kThighPoints + kCalfPoints> points;
  std::array<double, kThighPoints + kCalfPoints> below{};  // the point's own reach below it (the foot sphere's radius)
  int count = 0;
  const double foot_radius = std::isfinite(radius) ? radius : 0.0;
  if (drive_.legs() && f < jump::kLegCount) {
    const jump::LegGeometry& leg = (*drive_.legs())[f];
    const Eigen::Vector3d hip = leg.hipPosition();  // the thigh starts near it
    const Eigen::Vector3d knee = jump::kneePosition(leg, q), foot = jump::footPosition(leg, q);
    for (int i = 1; i <= kThighPoints; ++i) points[count++] = hip + (knee - hip) * (static_cast<double>(i) / kThighPoints);
    for (int i = 1; i <= kCalfPoints; ++i) points[count++] = knee + (foot - knee) * (static_cast<double>(i) / kCalfPoints);
    below[count - 1] = foot_radius;
  } else {
    points[0] = footInTrunk(f, q);
    below[0] = foot_radius;
    count = 1;
  }
  const Eigen::Vector2d travel(s.com_velocity[0], s.com_velocity[1]);
  const double g = drive_.gravity().z();  // m/s^2, negative
  double worst = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d w = base + R * points[i];
    std::optional<double> under;  // the top under the point now
    for (int k = 0; k < kLookaheadSteps; ++k) {
      // Where the trunk's ballistic flight carries the point within the look-ahead.
      const double tau = kLookahead * k / (kLookaheadSteps - 1);
      const Eigen::Vector2d at = w.head<2>() + travel * tau;
      const double z = w.z() + (s.com_velocity[2] + 0.5 * g * tau) * tau;
      const std::optional<TerrainTop> top = terrainTop(host, at.x(), at.y());
      if (!top) return 0.0;  // an older host, or nothing below: nothing to clear
      if (!under) under = top->height;
      // An obstacle: a surface above the landing one, or a step up ahead.
      const bool obstacle = top->height > landing_surface + kSameSurface || top->height > *under + kSameSurface;
      if (obstacle) worst = std::max(worst, top->height + kClearance + below[i] - z);
    }
  }
  return worst;
}

Eigen::Vector3d TerrainClearance::footInTrunk(int f, const Eigen::Vector3d& q) const {
  if (drive_.legs() && f < jump::kLegCount) return jump::footPosition((*drive_.legs())[f], q);
  Eigen::VectorXd all = drive_.q_ref();
  all.segment<3>(3 * f) = q;
  return drive_.feetAt(all).col(f);
}

double TerrainClearance::apply(const pronk_robot_state& s, const JumpPlan& plan) {
  const double landing_surface = plan.origin.z() + plan.landing_height;
  const Eigen::Matrix3d R = rotationOf(s);
  // Ahead: the trunk's horizontal travel (none for a jump in place).
  const Eigen::Vector2d travel(s.com_velocity[0], s.com_velocity[1]);
  const int swings = travel.norm() > kMinTravel ? kSwingSteps : 0;
  const Eigen::Vector3d ahead =
      swings > 0 ? Eigen::Vector3d(travel.x(), travel.y(), 0.0).normalized() : Eigen::Vector3d::Zero();
  double largest = 0.0;
  for (int f = 0; f < drive_.footCount(); ++f) {
    if (s.foot_in_contact[f]) continue;
    Eigen::Vector3d q = drive_.q_ref().segment<3>(3 * f);
    double moved = 0.0;
    for (int pass = 0; pass < kPasses; ++pass) {
      const double dip = shortfall(s, R, f, q, landing_surface);
      if (!(dip > 1e-4)) break;
      // The foot raised by the shortfall (a step up ahead), or swung ahead along
      // the travel (the box being left: a trailing knee reaches behind its hip,
      // and its reach, not its height, is what meets the edge), or both: the
      // smallest move that clears, else the one that leaves the least shortfall.
      const Eigen::Vector3d foot = footInTrunk(f, q);
      Eigen::Vector3d best_q = q;
      double best_dip = dip, best_move = 0.0;
      for (int k = 0; k <= swings; ++k) {
        for (const double up : {0.0, dip}) {
          if (k == 0 && up == 0.0) continue;
          const Eigen::Vector3d move = ahead * (kSwingStep * k) + Eigen::Vector3d(0, 0, up);
          const Eigen::Vector3d q_try = drive_.legIk(f, foot + R.transpose() * move);
          const double left = std::max(shortfall(s, R, f, q_try, landing_surface), 0.0);
          const bool better = left < best_dip - 1e-6 || (left <= 1e-4 && best_dip <= 1e-4 && move.norm() < best_move);
          if (better) {
            best_q = q_try;
            best_dip = left;
            best_move = move.norm();
          }
        }
      }
      if (best_q == q) break;  // nothing helps: keep the reference
      q = best_q;
      moved += best_move;
    }
    drive_.q_ref().segment<3>(3 * f) = q;
    largest = std::max(largest, moved);
  }
  return largest;
}

}  // namespace pronk::guided_jump
