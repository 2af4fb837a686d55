// Leg IK for the planner, the safety filter and the controller: the thrust
// path's reach and its joint torques and speeds, and the joints' references (the
// paper's "Control" maps the CoM/trunk reference to joints by IK too;
// control/leg_drive.h, LegDrive::legIk, falls back to Newton steps on the host's
// leg kinematics where this exact solution has no answer).
// Analytic kinematics of a Unitree-style 3-DoF leg, everything in ONE frame,
// the trunk frame (x forward, y left, z up, origin at the trunk centre):
//
//   hip abduction joint at H = (front * hip_x, side * hip_y, 0), axis +x, angle q0;
//   thigh joint offset from it by (0, side * thigh_offset, 0), axis +y, angle q1;
//   knee joint at (0, 0, -thigh_length) in the thigh frame, axis +y, angle q2;
//   foot centre at (0, 0, -calf_length) in the calf frame.
//   At q = 0 all frames are parallel to the trunk and the leg hangs straight down.
//
//   foot(q) = H + Rx(q0) * (x', side * thigh_offset, z'),
//   x' = -l1 sin(q1) - l2 sin(q1 + q2),   z' = -l1 cos(q1) - l2 cos(q1 + q2).
//
// Unitree sign convention: q1 > 0 swings the foot back; the knee points
// backward, so q2 < 0 (the "knee-backward" branch); q0 > 0 moves a left foot
// outward. Angles in rad, lengths in m, the Jacobian in m/rad.
// Equations as implemented: docs/method-ballistics-ik-reward.md.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>

namespace pronk::jump {

// Unitree order (URDF, SDK): FR, FL, RR, RL.
enum class Leg : int { kFrontRight = 0, kFrontLeft, kRearRight, kRearLeft };
constexpr int kLegCount = 4;
const char* legName(Leg leg);  // "FR", "FL", "RR", "RL"
constexpr bool isLeftLeg(Leg leg) { return leg == Leg::kFrontLeft || leg == Leg::kRearLeft; }
constexpr bool isFrontLeg(Leg leg) { return leg == Leg::kFrontRight || leg == Leg::kFrontLeft; }

struct JointRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool contains(double q, double tolerance = 0.0) const { return q >= min - tolerance && q <= max + tolerance; }
};

struct LegGeometry {
  // Magnitudes (>= 0, m); `side` and `front` give the signs.
  double hip_x = 0.0;                  // trunk centre -> hip abduction joint, along x
  double hip_y = 0.0;                  // trunk centre -> hip abduction joint, along y
  double thigh_offset = 0.0;           // hip joint -> thigh joint, along y
  double thigh_length = 0.0;           // l1: thigh joint -> knee
  double calf_length = 0.0;            // l2: knee -> foot centre
  double side = 1.0;                   // +1 left legs (FL, RL), -1 right legs (FR, RR)
  double front = 1.0;                  // +1 front legs, -1 rear legs
  std::array<JointRange, 3> limits{};  // hip, thigh, calf position limits, rad

  Eigen::Vector3d hipPosition() const;  // H, trunk frame
  // Throws std::invalid_argument naming the field when a length is negative or
  // not finite, l1 or l2 is zero, side/front is not +-1, or a range has min > max.
  void check() const;
};

// From reference/robots.md (unitree_ros xacro constants and URDF limits):
// Go1:     hip (0.1881, 0.04675), thigh offset 0.08, l1 = l2 = 0.213;
//          limits hip +-0.863, thigh [-0.686, 4.501], calf [-2.818, -0.888].
// Aliengo: hip (0.2407, 0.051), thigh offset 0.0868, l1 = l2 = 0.25;
//          limits hip +-70 deg, thigh [-120, 240] deg (the xacro constants, as in
//          assets/robots/aliengo; unitree_ros's URDF joint is continuous),
//          calf [-2.7751, -0.6458] rad.
LegGeometry go1Leg(Leg leg);
LegGeometry aliengoLeg(Leg leg);
std::array<LegGeometry, kLegCount> go1Legs();  // in Leg order
std::array<LegGeometry, kLegCount> aliengoLegs();

// Forward kinematics: foot centre in the trunk frame.
Eigen::Vector3d footPosition(const LegGeometry& leg, const Eigen::Vector3d& q);

// Forward kinematics of the knee joint (the calf joint's origin), trunk frame.
Eigen::Vector3d kneePosition(const LegGeometry& leg, const Eigen::Vector3d& q);

// The legs' mean length, thigh + calf (m): what the robot's lengths scale by.
double meanLegLength(const std::array<LegGeometry, kLegCount>& legs);

// d footPosition / d q (columns: hip, thigh, calf), trunk frame, analytic.
Eigen::Matrix3d footJacobian(const LegGeometry& leg, const Eigen::Vector3d& q);

enum class LegIkStatus {
  kOk,
  kNotFinite,        // the requested foot position has a NaN/inf
  kTooFar,           // farther from the thigh joint than l1 + l2
  kTooClose,         // nearer to the thigh joint than |l1 - l2|
  kInsideHipOffset,  // nearer to the hip (x) axis than the thigh offset
};
const char* legIkStatusName(LegIkStatus status);  // "ok", "too_far", ...

struct LegIkResult {
  LegIkStatus status = LegIkStatus::kOk;
  Eigen::Vector3d q = Eigen::Vector3d::Zero();  // valid when ok()
  bool within_limits = false;                   // q inside leg.limits
  std::string message;                          // empty when ok(); otherwise why, with the numbers
  bool ok() const { return status == LegIkStatus::kOk; }
};

// Analytic IK for a foot position in the trunk frame. Knee-backward branch
// (q2 = -acos(...) in [-pi, 0]). Of the two abduction solutions (foot below or
// above the hip axis in the leg plane) the first whose angles lie within the
// joint limits is returned, the foot-below one first; each angle is shifted by
// 2 pi into its range where that is possible, otherwise wrapped to (-pi, pi].
// When neither solution is within the limits the foot-below one is returned
// with within_limits = false. Out of reach: status != kOk and a message.
LegIkResult solveLegIk(const LegGeometry& leg, const Eigen::Vector3d& foot_in_trunk);

// Joint velocity reference from a desired foot velocity (trunk frame, i.e. the
// time derivative of the trunk-frame foot position): solves J(q) qd = v.
constexpr double kLegSingularityThreshold = 1e-3;  // m/rad, least singular value of J
struct JointVelocityResult {
  Eigen::Vector3d qd = Eigen::Vector3d::Zero();  // rad/s
  bool singular = false;                         // least singular value below the threshold
  double least_singular_value = 0.0;             // of J, m/rad
  std::string message;                           // empty unless singular
};
// When J is singular, qd is the minimum-norm least-squares solution with the
// singular directions (singular values below the threshold) dropped.
JointVelocityResult jointVelocitiesForFootVelocity(const LegGeometry& leg, const Eigen::Vector3d& q,
                                                   const Eigen::Vector3d& foot_velocity_trunk,
                                                   double singularity_threshold = kLegSingularityThreshold);

// Foot velocity relative to the trunk, in the trunk frame, from world-frame
// quantities: R^T (v_foot - v_trunk - w x (p_foot - p_trunk)), R = trunk
// orientation (trunk -> world). A stance foot has v_foot = 0.
Eigen::Vector3d footVelocityInTrunk(const Eigen::Matrix3d& trunk_rotation, const Eigen::Vector3d& trunk_position,
                                    const Eigen::Vector3d& trunk_velocity,
                                    const Eigen::Vector3d& trunk_angular_velocity, const Eigen::Vector3d& foot_position,
                                    const Eigen::Vector3d& foot_velocity);

// solveLegIk's verdict (ok, and with require_within_limits within the joint
// limits) without its angles: each joint angle's cosine against the cosine of
// its range's half width, so no trigonometry per foot. An angle within 1e-7 rad
// of a limit, where that comparison could differ from the IK's rounding, and a
// range this test cannot represent (a full turn or more, beyond +-4 pi) are
// left to solveLegIk itself, so the verdict is always the IK's. Built once per
// leg: it holds the cosines of the ranges.
class LegReachCheck {
 public:
  explicit LegReachCheck(const LegGeometry& leg);
  bool reaches(const Eigen::Vector3d& foot_in_trunk, bool require_within_limits = true) const;

  // Membership of a joint angle in its range modulo 2 pi, as an arc.
  struct Arc {
    bool any_angle = false;  // the range holds every angle
    bool exact_only = false;  // not an arc this test can decide: ask solveLegIk
    double cos_mid = 1.0, sin_mid = 0.0, cos_half_width = 1.0;
  };

 private:
  LegGeometry leg_;
  std::array<Arc, 3> arcs_;
};

// A workspace test for a trunk pose: true when every leg reaches its foot,
// given in the world frame, with the trunk at (position, rotation), and (with
// require_within_limits) the IK solution is within the joint limits. Use it to
// build SafetyCheck::workspace.
bool feetReachable(const std::array<LegGeometry, kLegCount>& legs,
                   const std::array<Eigen::Vector3d, kLegCount>& feet_world, const Eigen::Vector3d& trunk_position,
                   const Eigen::Matrix3d& trunk_rotation, bool require_within_limits = true);
// The same with the legs' checks built once (for many poses of one robot).
bool feetReachable(const std::array<LegReachCheck, kLegCount>& legs,
                   const std::array<Eigen::Vector3d, kLegCount>& feet_world, const Eigen::Vector3d& trunk_position,
                   const Eigen::Matrix3d& trunk_rotation, bool require_within_limits = true);

}  // namespace pronk::jump
