// The guided jump as a phase machine around the stance controller (control/hold_controller.h):
//
//   stand      0 .. start_delay          stance PD + gravity compensation (HoldController)
//   thrust     Bezier part of the ThrustPlan (T_th)      } the whole-body CoM follows the plan,
//   explosive  UARM part of the ThrustPlan (T_e)         } the trunk orientation the Euler Bezier
//   flight     from lift-off (all feet off the ground): 0.1 s smoothstep to a tucked pose, Kp / division,
//              no gravity compensation
//   descend    after the apex, once the predicted fall to the landing surface (landing_height)
//              is down to 0.1 s + kExtensionLead: 0.1 s smoothstep back to the stance, same gains
//   landing    from touchdown (any foot in contact): joint PD towards a level trunk at the stance
//              height over the feet (IK for the feet in contact, the stance joints for the others),
//              Kp back from Kp / division to Kp over kLandingRamp; gravity compensation over
//              the feet in contact, and over all four once every foot has touched down
//
// Thrust and explosive (t = time since the thrust began). The plan lives in the
// start frame S: origin on the ground below the CoM at the thrust start, z up, x
// along the trunk's heading then. Each tick, with c_ref = plan(t) in the world:
//   trunk_des = trunk + (c_ref - c)            (the state's CoM-to-trunk offset)
//   R_des     = Rz(yaw_0) R(rpy_ref(t))
//   foot_des  = R_des^T (p_foot - trunk_des)   per leg, trunk frame (the feet stay put)
//   q_ref     = IK(foot_des)                    Newton steps on the host's leg kinematics
//   qd_ref    = J(q_ref)^-1 R_des^T (-(v_ref + w_ref x (p_foot - trunk_des)))
//   tau       = Kp (q_ref - q) + Kd (qd_ref - qd) - sum_contact J_i^T f_i, clamped
// with f = G^+ (m (a - g), M) while the plan runs: a = 0, M = 0 for feedforward "gravity" (the paper's);
// a = a_ref, M = 0 for "dynamic"; for "dynamic_angular" also M = I alpha_plan +
// w_plan x I w_plan, the orientation plan's rate of angular momentum (I the whole
// body's locked-joint inertia now, host ABI 1.2). With momentum_gain g > 0, R_des and w_ref also carry a turn
// about the horizontal axes at
//   g ((w_ref - I^-1 L) - tilt / T_f)           (whole-body momentum, host ABI 1.2)
// that drives the touchdown roll and pitch error the momentum predicts to zero; the
// error about the vertical goes to the feet as a ground moment (momentum_moment_gain).
// After the plan has ended the reference stays at its end point (no velocity) until
// lift-off, held by joint PD alone (the one or two feet still down do not carry the
// weight, which would turn the robot about them as it leaves);
// without lift-off within kLiftOffWait the jump is abandoned and the controller lands
// (stance) in place.
//
// The descent's landing pose is the stance's feet placed under a level trunk (IK
// against the trunk's measured roll and pitch), so that a trunk that rotated in the
// air still lands on all four feet together.
//
// Every phase change is an event "phase:<name>" through host->emit_event.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/hold_controller.h"
#include "method/explosive_phase.h"
#include "method/leg_ik.h"
#include "method/orientation_trajectory.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

// The thrust's feed-forward (parameter `feedforward`, abi/jump_params.h).
enum class Feedforward { kGravity, kDynamic, kDynamicAngular };

// The landing's body wrench (parameters landing_*): a critically damped stop of
// the CoM and a levelling of the trunk. The trunk gains are per kg of the robot's
// mass, so the defaults (tuned on the Go1) carry over to another robot's mass.
struct LandingSettings {
  double frequency = 5.0;      // rad/s: natural frequency of the CoM's stop
  double friction = 0.6;       // the share of the normal force the stop may ask sideways
  double tilt = 4.0;           // N m / rad / kg: levelling stiffness
  double tilt_damping = 0.4;   // N m s / rad / kg: levelling damping
  double yaw_damping = 1.5;    // N m s / rad / kg: damping of the turn about the vertical
  double yaw_gain = 10.0;      // N m / rad / kg: towards the plan's touchdown heading
  // rad/s of the vertical stop (0: frequency), which the legs' reference follows
  // down: with the reference at the standing height at once, the compressed legs
  // throw the robot back into the air.
  double vertical_frequency = 10.0;
  // The descent's landing pose: its feet turn against the trunk's tilt by this
  // multiple of it (1: the feet as under a level trunk; 0: the trunk's frame).
  double pose_levelling = 1.5;
  // m the descent's landing pose reaches below the stance feet: a leg that
  // touches down longer has more stroke to stop the fall in before a thigh
  // comes down to the ground (0: the stance pose). Below 0: derived from the
  // robot (jump::landingExtension; 0 without an analytic leg model).
  double extension = -1.0;
};

struct JumpSettings {
  HoldSettings hold;                 // gains, stance (= landing pose), gravity compensation
  std::vector<double> action;        // empty: hold the stance; else 13 physical numbers (ActionParameter order)
  double azimuth = 0.0;              // rad: the jump plane's direction in the start frame (from the target)
  double start_delay = 0.2;          // s of standing before the thrust
  Feedforward feedforward = Feedforward::kDynamic;
  double flight_kp_division = 3.0;   // Kp in flight and descent = kp / this
  double landing_height = 0.0;       // m: the landing surface above the take-off surface
  // Thrust: the trunk turns against the whole-body attitude error predicted for the
  // touchdown, (w_plan - I^-1 L) T_f minus the turn already added, at this rate per
  // rad/s (1/s; 0: off, the paper's kinematic thrust), about the horizontal axes
  // only: about the vertical it asks the thrust for more twist than the saturated
  // legs give and the body leaves pitching nose-down. Needs a host with ABI 1.2.
  double momentum_gain = 10.0;
  // Thrust: a moment about the world's vertical of this gain times the whole-body
  // momentum error (I w_plan - L)_z joins the feet's feed-forward wrench (1/s; 0: off).
  double momentum_moment_gain = 50.0;
  // That moment only as far as the feet's forces for the feed-forward wrench stay
  // within this friction coefficient (0: all of it). Past the cone the feet slip,
  // lift early, and the pair left pushes the body off pitching.
  double momentum_moment_friction = 0.6;
  std::array<double, 3> tuck{0.0, 1.38, -2.4};  // rad per leg: flight pose (hip, thigh, calf)
  // The analytic leg model (from the host's kinematics, abi/host_leg_geometry.h);
  // none: the IK takes Newton steps on the host's kinematics.
  // Thrust: each stance foot's IK target is where that foot stood when the thrust
  // began (true), or where it is now (false, the paper's). A foot the thrust has
  // unloaded then presses back down instead of floating with its leg.
  bool anchored_stance_feet = true;
  std::optional<std::array<jump::LegGeometry, jump::kLegCount>> legs;
  LandingSettings landing;
};

enum class JumpPhase { kHold, kStand, kThrust, kExplosive, kFlight, kDescend, kLanding };
const char* jumpPhaseName(JumpPhase phase);  // "hold", "stand", "thrust", ...

// Cubic smoothstep 3 s^2 - 2 s^3 of s clamped to [0, 1].
double smoothstep(double s);

// ZYX Euler angles (roll, pitch, yaw) of a rotation R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R);

// A frame on the take-off surface: origin below the CoM at the mean height of
// the feet in contact less their radius (all feet when none is), z up, x along
// the trunk's heading. The jump's start frame S.
struct StartFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // world
  Eigen::Matrix3d heading = Eigen::Matrix3d::Identity();  // S -> world
  Eigen::Vector3d point(const double* world) const {
    return heading.transpose() * (Eigen::Vector3d(world[0], world[1], world[2]) - origin);
  }
  Eigen::Vector3d direction(const double* world) const {
    return heading.transpose() * Eigen::Vector3d(world[0], world[1], world[2]);
  }
};
StartFrame takeOffFrame(const pronk_host_api* host, const pronk_robot_state& state);

// The whole body's angular momentum L about its CoM and its locked-joint
// rotational inertia I about it (world), from the host (ABI 1.2); nullopt from an
// older host or a non-finite answer.
struct CentroidalMomentum {
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
std::optional<CentroidalMomentum> centroidalMomentum(const pronk_host_api* host);
// I^-1 L; nullopt when it is not finite.
std::optional<Eigen::Vector3d> averageRate(const CentroidalMomentum& momentum);

// The whole body's average angular velocity I^-1 L about its CoM (world) at the
// current tick, from the host (ABI 1.2); nullopt from an older host. In flight it
// is what the attitude does on average, whatever the legs do.
std::optional<Eigen::Vector3d> wholeBodyRate(const pronk_host_api* host);

class JumpController {
 public:
  static constexpr double kBlendTime = 0.1;     // s, tuck and extension smoothsteps
  static constexpr double kExtensionLead = 0.06;  // s: the landing extension ends this long before touchdown
  static constexpr double kLiftOffWait = 0.15;  // s after the plan's end before giving up on lift-off
  static constexpr double kLandingRamp = 0.3;   // s from touchdown until Kp is fully back
  static constexpr double kGroundReach = 0.01;  // m below the feet that are down, for a foot still in the air

  // Where the landing brings the CoM to rest, from the touchdown point
  // (jump::landingStopOffset with the landing's friction share and frequency).
  // The airborne feet land that far ahead of the CoM, the landing wrench stops
  // the CoM there, and the ballistic prior aims short by it.
  static Eigen::Vector2d landingStop(const LandingSettings& landing, const Eigen::Vector3d& touchdown_velocity);

  // Throws InvalidArgument for an action of the wrong size or one the method rejects.
  JumpController(const pronk_host_api* host, const JumpSettings& settings);

  void reset(const pronk_robot_state& state);
  void compute(const pronk_robot_state& state, double* torque);

  JumpPhase phase() const { return phase_; }
  bool jumping() const { return has_action_; }
  // From the thrust start on: the plan (start frame S) and S in the world.
  const jump::ThrustPlan* plan() const { return plan_.get(); }
  const Eigen::Vector3d& startOrigin() const { return origin_; }    // S origin, world
  const Eigen::Matrix3d& startHeading() const { return heading_; }  // S -> world
  double thrustStartTime() const { return thrust_start_; }
  // The last tick's torques before the motors clamp them (what the controller asked for).
  const Eigen::VectorXd& commandedTorque() const { return commanded_; }

 private:
  // landing.extension for a robot whose settings leave it to the robot
  // (jump::landingExtension from its legs, knee efforts and mass).
  double derivedLandingExtension() const;
  void enter(JumpPhase phase, double time, const std::string& detail = "");
  void startThrust(const pronk_robot_state& s);
  void landingReference(const pronk_robot_state& s);
  // The landing's vertical stop: its natural frequency, and the CoM's planned
  // height below its landing height t after touchdown (critically damped).
  double verticalStopFrequency() const;
  double verticalStopSink(double t) const;
  // Where stance foot f's IK target lies in the world (settings_.anchored_stance_feet).
  Eigen::Vector3d stanceFoot(const pronk_robot_state& s, int f) const;
  void thrustTorques(const pronk_robot_state& s, double t, double* torque);
  void jointTorques(const pronk_robot_state& s, double kp, const Eigen::VectorXd& q_ref, const Eigen::VectorXd& qd_ref,
                    bool gravity, const Eigen::Vector3d& com_acceleration, const Eigen::Vector3d& moment,
                    double* torque);
  // The leg's joint angles for a foot position in the trunk frame: the planner's
  // exact IK (jump::solveLegIk) on the analytic leg model when the settings have
  // one and its answer lies within the joint limits; otherwise (no analytic
  // model, out of reach or out of the limits) at most 6 damped Newton steps of
  // at most 0.2 rad on the host's leg kinematics from q_ref_, stopping at a 1 um
  // residual. The Newton steps alone used to be the controller's IK: they
  // differ from the exact one by up to 7e-6 rad where they converge and by up to
  // 0.16 rad where 6 steps are not enough (fast sideways or up thrusts), and
  // cost a quarter of a jump's simulation (docs/method.md, "One leg IK").
  Eigen::Vector3d legIk(int foot, const Eigen::Vector3d& foot_base);
  Eigen::Matrix3d legJacobian(int foot, const Eigen::VectorXd& q);
  // Landing: joint PD plus the body wrench that stops the CoM where it touched
  // down, levels the trunk and carries the weight, spread over the feet (applyBodyWrench).
  void landingTorques(const pronk_robot_state& s, double kp, double* torque);
  // The feet a body wrench is spread over (those in contact; every_foot: all) and,
  // in *points, where they are (world).
  std::vector<int> wrenchFeet(const pronk_robot_state& s, bool every_foot, Eigen::Matrix3Xd* points) const;
  // The share of the thrust's ground twist the feet in contact hold within
  // momentum_moment_friction, beside the feed-forward acceleration and moment.
  double twistShareWithinFriction(const pronk_robot_state& s, const Eigen::Vector3d& com_acceleration,
                                  const Eigen::Vector3d& moment, const Eigen::Vector3d& twist) const;
  // tau -= sum over the feet in contact (every_foot: all feet) of J_i^T f_i, f = the
  // minimum-norm forces that put (force, moment about the CoM) on the body
  // (method/force_distribution.h).
  void applyBodyWrench(const pronk_robot_state& s, const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                       Eigen::Ref<Eigen::VectorXd> tau,
                       bool every_foot = false);
  // Keeps tau as commandedTorque(), then clamps it to what each motor delivers at its speed (throws if not finite).
  void saturate(const pronk_robot_state& state, Eigen::Ref<Eigen::VectorXd> tau);

  const pronk_host_api* host_;
  JumpSettings settings_;
  HoldController hold_;
  bool has_action_ = false;
  jump::JumpAction action_;
  int n_ = 0;
  int feet_ = 0;
  double mass_ = 0;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::vector<jump::MotorLimits> motors_;

  JumpPhase phase_ = JumpPhase::kHold;
  double reset_time_ = 0;
  double phase_start_ = 0;
  double thrust_start_ = 0;
  bool all_down_seen_ = false;  // landing: every foot has touched down
  // The landing stop's goal after a flight: the CoM's touchdown height, and
  // horizontally where the stop ends.
  std::optional<Eigen::Vector3d> touchdown_com_;
  double touchdown_sink_ = 0, touchdown_sink_rate_ = 0;  // CoM below its landing height, and its rate, at touchdown
  double standing_height_ = 0;  // CoM above the ground at the thrust start
  Eigen::Vector3d momentum_tilt_ = Eigen::Vector3d::Zero();  // thrust: rotation vector (world) added to R_des
  double last_thrust_time_ = 0;
  double planned_flight_time_ = 0.2;  // s, lift-off to touchdown
  double planned_touchdown_yaw_ = 0;  // rad, world: the plan's lift-off yaw plus its yaw rate over the flight
  std::unique_ptr<jump::ThrustPlan> plan_;
  std::unique_ptr<jump::OrientationTrajectory> orientation_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();  // S origin, world
  Eigen::Matrix3d heading_ = Eigen::Matrix3d::Identity();  // S -> world rotation
  Eigen::VectorXd q_ref_, qd_ref_, blend_from_, commanded_;
  Eigen::Vector3d stance_offset_ = Eigen::Vector3d::Zero();  // trunk - feet centroid at the thrust start, trunk frame
  Eigen::Matrix3Xd thrust_feet_;  // feet at the thrust start, world
  Eigen::Matrix3Xd stance_feet_;  // feet at the stance joints, trunk frame
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian_;
};

}  // namespace pronk::guided_jump
