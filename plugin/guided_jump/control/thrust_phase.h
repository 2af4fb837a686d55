// The thrust and its explosive end (t = time since the thrust began). The
// whole-body CoM follows the plan, the trunk the orientation plan. Each tick,
// with c_ref = plan(t) in the world:
//   trunk_des = trunk + (c_ref - c)            (the state's CoM-to-trunk offset)
//   R_des     = Rz(yaw_0) R(rpy_ref(t))
//   foot_des  = R_des^T (p_foot - trunk_des)   per leg, trunk frame (the feet stay put)
//   q_ref     = IK(foot_des)
//   qd_ref    = J(q_ref)^-1 R_des^T (-(v_ref + w_ref x (p_foot - trunk_des)))
//   tau       = Kp (q_ref - q) + Kd (qd_ref - qd) - sum_contact J_i^T f_i, clamped
// with f = G^+ (m (a - g), M) while the plan runs: a = 0, M = 0 for feedforward
// "gravity" (the paper's); a = a_ref, M = 0 for "dynamic"; for "dynamic_angular"
// also M = I alpha_plan + w_plan x I w_plan (I the whole body's locked-joint
// inertia now, host ABI 1.2). With momentum_gain g > 0, R_des and w_ref also
// carry a turn about the horizontal axes at
//   g ((w_ref - I^-1 L) - tilt / T_f)           (whole-body momentum, host ABI 1.2)
// that drives the touchdown roll and pitch error the momentum predicts to zero;
// the error about the vertical goes to the feet as a ground moment
// (momentum_moment_gain). After the plan has ended the reference stays at its end
// point (no velocity) until lift-off, held by joint PD alone: the one or two feet
// still down do not carry the weight, which would turn the robot about them as it
// leaves (docs/method.md).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/jump_plan.h"
#include "control/leg_drive.h"
#include "control/param_reader.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// The thrust's feed-forward (parameter `feedforward`).
enum class Feedforward { kGravity, kDynamic, kDynamicAngular };

struct ThrustSettings {
  // The planned acceleration in the feed-forward: the PD alone lags a hard
  // thrust (the Go1's 0.7 m jump: 0.2 m/s short at lift-off, 11 cm off instead of 3).
  Feedforward feedforward = Feedforward::kDynamic;
  // The trunk turns against the whole-body attitude error predicted for the
  // touchdown, (w_plan - I^-1 L) T_f minus the turn already added, at this rate
  // per rad/s (1/s; 0: the paper's kinematic thrust), about the horizontal axes
  // only: about the vertical it asks the thrust for more twist than the
  // saturated legs give and the body leaves pitching nose-down.
  double momentum_gain = 10.0;
  // A moment about the world's vertical of this gain times the whole-body
  // momentum error (I w_plan - L)_z joins the feet's feed-forward wrench (1/s; 0: off).
  double momentum_moment_gain = 50.0;
  // That moment only as far as the feet's forces for the feed-forward wrench stay
  // within this friction coefficient (0: all of it). Past the cone the feet slip,
  // lift early, and the pair left pushes the body off pitching.
  double momentum_moment_friction = 0.6;
  // Each stance foot's IK target is where that foot stood when the thrust began
  // (true), or where it is now (false, the paper's). A foot the thrust has
  // unloaded then presses back down instead of floating with its leg.
  bool anchored_stance_feet = true;

  // feedforward, momentum_gain, momentum_moment_gain, momentum_moment_friction, stance_feet.
  static const std::vector<pronk_param_decl>& parameters();
  // Throws InvalidArgument naming the parameter for a name it does not know.
  static ThrustSettings read(const ParamReader& read);
};

class ThrustPhase {
 public:
  ThrustPhase(LegDrive& drive, const ThrustSettings& settings) : drive_(drive), settings_(settings) {}

  // At the thrust start: no momentum turn yet.
  void begin(const pronk_robot_state& s);
  // The tick's torques, t seconds into the thrust (past the plan's end: hold its end point).
  void compute(const pronk_robot_state& s, const JumpPlan& plan, double t, double* torque);
  // The turn (rotation vector, world) the momentum feedback has added to R_des.
  const Eigen::Vector3d& momentumTurn() const { return momentum_tilt_; }

 private:
  // Where stance foot f's IK target lies in the world (settings_.anchored_stance_feet).
  Eigen::Vector3d stanceFoot(const pronk_robot_state& s, const JumpPlan& plan, int f) const;
  // The share of the ground twist the feet in contact hold within
  // momentum_moment_friction, beside the feed-forward acceleration and moment.
  double twistShareWithinFriction(const pronk_robot_state& s, const Eigen::Vector3d& com_acceleration,
                                  const Eigen::Vector3d& moment, const Eigen::Vector3d& twist) const;

  LegDrive& drive_;
  ThrustSettings settings_;
  Eigen::Vector3d momentum_tilt_ = Eigen::Vector3d::Zero();  // rotation vector (world) added to R_des
  double last_time_ = 0;
};

// "gravity", "dynamic", "dynamic_angular"; throws InvalidArgument naming the
// parameter for any other name.
Feedforward feedforwardFromName(const std::string& name);

}  // namespace pronk::guided_jump
