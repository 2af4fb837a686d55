// The legs in the air kept clear of the terrain they fly over. Each tick, for
// every foot out of contact, points along its thigh and calf and the foot
// sphere (at the joints' PD reference, with the trunk where it is) stay
// kClearance above every obstacle under them, now and where the trunk's
// ballistic flight carries them within kLookahead: a surface higher than the
// one the jump lands on (the box being left) or higher than the one under the
// point now (the edge of a box ahead). A leg that would dip into one is
// moved: its foot raised, in the world's vertical, by the deepest
// shortfall, or swung ahead along the trunk's travel (a trailing knee that
// reaches back over the box being left), whichever clears with the smallest
// move, and solved again by IK. Over flat ground there is no obstacle,
// and without the host's terrain (ABI < 1.6) it does nothing.
#pragma once

#include "control/jump_plan.h"
#include "control/leg_drive.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

class TerrainClearance {
 public:
  static constexpr double kClearance = 0.03;  // m above an obstacle
  static constexpr double kLookahead = 0.1;   // s of the trunk's horizontal travel looked ahead
  static constexpr int kLookaheadSteps = 4;   // samples over it, the present included
  static constexpr int kPasses = 3;           // move-and-solve rounds per leg
  static constexpr double kSwingStep = 0.03;  // m: a foot swung ahead moves in these steps
  static constexpr int kSwingSteps = 5;       // up to 0.15 m ahead
  static constexpr double kMinTravel = 0.05;  // m/s: slower, nothing is ahead

  explicit TerrainClearance(LegDrive& drive) : drive_(drive) {}

  // Moves the reference of every leg out of contact that dips into the terrain
  // (drive.q_ref()). Returns the largest move of a foot, m (0: none).
  double apply(const pronk_robot_state& s, const JumpPlan& plan);

 private:
  // The deepest shortfall of foot f's leg at joints q, with the trunk at s and
  // turned by R (m, <= 0 when clear).
  double shortfall(const pronk_robot_state& s, const Eigen::Matrix3d& R, int f, const Eigen::Vector3d& q,
                   double landing_surface) const;

  // Foot f at its leg's joints q, trunk frame (the analytic leg model when there is one).
  Eigen::Vector3d footInTrunk(int f, const Eigen::Vector3d& q) const;

  LegDrive& drive_;
};

}  // namespace pronk::guided_jump
