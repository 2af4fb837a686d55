#include "method/leg_ik.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pronk::jump {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;


// (-pi, pi]
double wrapToPi(double a) {
  double w = std::remainder(a, kTwoPi);  // [-pi, pi]
  if (w <= -kPi) w += kTwoPi;
  return w;
}

// The representative of `a` modulo 2 pi inside `range`, if any; the one nearest
// the middle of the range when several are (ranges wider than 2 pi); otherwise
// the value wrapped to (-pi, pi]. Sets `inside`.
double intoRange(double a, const JointRange& range, bool& inside) {
  constexpr double kTolerance = 1e-12;
  // The common case, first: `a` itself in a range narrower than a turn (then the
  // only representative inside it), without the remainder below.
  if (range.max - range.min < kTwoPi && a > -kPi && a <= kPi && range.contains(a, kTolerance)) {
    inside = true;
    return a;
  }
  const double base = wrapToPi(a);
  bool found = false;
  double best = base;
  double best_distance = 0.0;
  const double middle = (std::isfinite(range.min) && std::isfinite(range.max)) ? 0.5 * (range.min + range.max) : 0.0;
  for (int k = -3; k <= 3; ++k) {
    const double candidate = base + k * kTwoPi;
    if (!range.contains(candidate, kTolerance)) continue;
    const double distance = std::abs(candidate - middle);
    if (!found || distance < best_distance) {
      best = candidate;
      best_distance = distance;
      found = true;
    }
  }
  inside = found;
  return best;
}

LegGeometry unitreeLeg(Leg leg, double hip_x, double hip_y, double thigh_offset, double l1, double l2,
                       const std::array<JointRange, 3>& limits) {
  LegGeometry g;
  g.hip_x = hip_x;
  g.hip_y = hip_y;
  g.thigh_offset = thigh_offset;
  g.thigh_length = l1;
  g.calf_length = l2;
  g.side = isLeftLeg(leg) ? 1.0 : -1.0;
  g.front = isFrontLeg(leg) ? 1.0 : -1.0;
  g.limits = limits;
  return g;
}

}  // namespace

const char* legName(Leg leg) {
  switch (leg) {
    case Leg::kFrontRight:
      return "FR";
    case Leg::kFrontLeft:
      return "FL";
    case Leg::kRearRight:
      return "RR";
    case Leg::kRearLeft:
      return "RL";
  }
  return "?";
}

Eigen::Vector3d LegGeometry::hipPosition() const { return Eigen::Vector3d(front * hip_x, side * hip_y, 0.0); }

void LegGeometry::check() const {
  const struct {
    const char* name;
    double value;
  } lengths[] = {{"hip_x", hip_x},
                 {"hip_y", hip_y},
                 {"thigh_offset", thigh_offset},
                 {"thigh_length", thigh_length},
                 {"calf_length", calf_length}};
  for (const auto& l : lengths) {
    if (!std::isfinite(l.value) || l.value < 0.0) {
      throw std::invalid_argument(fmt::format("LegGeometry: {} = {:g} m must be finite and >= 0", l.name, l.value));
    }
  }
  if (thigh_length == 0.0 || calf_length == 0.0) {
    throw std::invalid_argument(
        fmt::format("LegGeometry: thigh_length {:g} m and calf_length {:g} m must be positive", thigh_length, calf_length));
  }
  if (std::abs(side) != 1.0 || std::abs(front) != 1.0) {
    throw std::invalid_argument(fmt::format("LegGeometry: side {:g} and front {:g} must be +1 or -1", side, front));
  }
  static const char* const kJointNames[] = {"hip", "thigh", "calf"};
  for (int j = 0; j < 3; ++j) {
    if (std::isnan(limits[j].min) || std::isnan(limits[j].max) || limits[j].min > limits[j].max) {
      throw std::invalid_argument(
          fmt::format("LegGeometry: {} limits [{:g}, {:g}] rad are not a range", kJointNames[j], limits[j].min, limits[j].max));
    }
  }
}

LegGeometry go1Leg(Leg leg) {
  return unitreeLeg(leg, 0.1881, 0.04675, 0.08, 0.213, 0.213,
                    {JointRange{-0.863, 0.863}, JointRange{-0.686, 4.501}, JointRange{-2.818, -0.888}});
}

LegGeometry aliengoLeg(Leg leg) {
  return unitreeLeg(
      leg, 0.2407, 0.051, 0.0868, 0.25, 0.25,
      {JointRange{-1.2217304763960306, 1.2217304763960306}, JointRange{-2.0943951023931953, 4.1887902047863905},
       JointRange{-2.775073510670984, -0.6457718232379019}});
}

std::array<LegGeometry, kLegCount> go1Legs() {
  return {go1Leg(Leg::kFrontRight), go1Leg(Leg::kFrontLeft), go1Leg(Leg::kRearRight), go1Leg(Leg::kRearLeft)};
}

std::array<LegGeometry, kLegCount> aliengoLegs() {
  return {aliengoLeg(Leg::kFrontRight), aliengoLeg(Leg::kFrontLeft), aliengoLeg(Leg::kRearRight),
          aliengoLeg(Leg::kRearLeft)};
}

// ---------------------------------------------------------------------------
// Forward kinematics and Jacobian

namespace {

// A point (x', z') of the leg plane, at the thigh joint's offset, turned by the
// abduction q0 about the hip axis: trunk frame.
Eigen::Vector3d fromLegPlane(const LegGeometry& leg, double q0, double x, double z) {
  const double y = leg.side * leg.thigh_offset;
  const double c0 = std::cos(q0);
  const double s0 = std::sin(q0);
  return leg.hipPosition() + Eigen::Vector3d(x, c0 * y - s0 * z, s0 * y + c0 * z);
}

}  // namespace

Eigen::Vector3d footPosition(const LegGeometry& leg, const Eigen::Vector3d& q) {
  const double l1 = leg.thigh_length;
  const double l2 = leg.calf_length;
  return fromLegPlane(leg, q[0], -l1 * std::sin(q[1]) - l2 * std::sin(q[1] + q[2]),
                      -l1 * std::cos(q[1]) - l2 * std::cos(q[1] + q[2]));
}

double meanLegLength(const std::array<LegGeometry, kLegCount>& legs) {
  double length = 0.0;
  for (const LegGeometry& leg : legs) length += (leg.thigh_length + leg.calf_length) / kLegCount;
  return length;
}

Eigen::Vector3d kneePosition(const LegGeometry& leg, const Eigen::Vector3d& q) {
  return fromLegPlane(leg, q[0], -leg.thigh_length * std::sin(q[1]), -leg.thigh_length * std::cos(q[1]));
}

Eigen::Matrix3d footJacobian(const LegGeometry& leg, const Eigen::Vector3d& q) {
  const double l1 = leg.thigh_length;
  const double l2 = leg.calf_length;
  const double s1 = std::sin(q[1]);
  const double c1 = std::cos(q[1]);
  const double s12 = std::sin(q[1] + q[2]);
  const double c12 = std::cos(q[1] + q[2]);
  const double x = -l1 * s1 - l2 * s12;
  const double z = -l1 * c1 - l2 * c12;
  const double y = leg.side * leg.thigh_offset;
  const double c0 = std::cos(q[0]);
  const double s0 = std::sin(q[0]);

  Eigen::Matrix3d j;
  // Hip: e_x x (foot - H), with foot - H = (x, c0 y - s0 z, s0 y + c0 z).
  j.col(0) << 0.0, -(s0 * y + c0 * z), c0 * y - s0 * z;
  // Thigh: Rx(q0) (dx'/dq1, 0, dz'/dq1) = Rx(q0) (z', 0, -x').
  j.col(1) << z, s0 * x, -c0 * x;
  // Knee: Rx(q0) (-l2 cos(q1+q2), 0, l2 sin(q1+q2)).
  j.col(2) << -l2 * c12, -s0 * l2 * s12, c0 * l2 * s12;
  return j;
}

// ---------------------------------------------------------------------------
// Inverse kinematics

const char* legIkStatusName(LegIkStatus status) {
  switch (status) {
    case LegIkStatus::kOk:
      return "ok";
    case LegIkStatus::kNotFinite:
      return "not_finite";
    case LegIkStatus::kTooFar:
      return "too_far";
    case LegIkStatus::kTooClose:
      return "too_close";
    case LegIkStatus::kInsideHipOffset:
      return "inside_hip_offset";
  }
  return "unknown";
}

namespace {

// The IK up to the knee angle: the part that decides whether the foot is in
// reach, shared by solveLegIk and LegReachCheck so both decide alike.
struct LegReach {
  LegIkStatus status = LegIkStatus::kOk;
  Eigen::Vector3d r = Eigen::Vector3d::Zero();  // hip joint -> foot
  double rho2 = 0.0;                            // squared distance from the hip axis
  double z_mag = 0.0;                           // |z'| in the leg plane
  double reach = 0.0;                           // thigh joint -> foot
  double cos_knee = 0.0;                        // when ok
};

// `quick`: the distance as sqrt(x^2 + z'^2), within 3e-16 (relative) of hypot,
// and hypot itself only where that difference could matter: within 1e-14 of a
// reach bound, or a knee so near straight or folded (|cos| > 1 - 1e-6) that its
// angle is sensitive to the distance's last bits.
LegReach legReach(const LegGeometry& leg, const Eigen::Vector3d& p, bool quick = false) {
  LegReach lr;
  if (!p.allFinite()) {
    lr.status = LegIkStatus::kNotFinite;
    return lr;
  }
  const double l1 = leg.thigh_length;
  const double l2 = leg.calf_length;
  const double d = leg.thigh_offset;
  const double reach_tolerance = 1e-12 * (l1 + l2 + d);
  lr.r = p - leg.hipPosition();

  // Leg plane: rotating about x keeps the distance from the hip axis, so
  // r_y^2 + r_z^2 = d^2 + z'^2.
  lr.rho2 = lr.r.y() * lr.r.y() + lr.r.z() * lr.r.z();
  const double z_sq = lr.rho2 - d * d;
  if (z_sq < -2.0 * d * reach_tolerance) {
    lr.status = LegIkStatus::kInsideHipOffset;
    return lr;
  }
  lr.z_mag = std::sqrt(std::max(z_sq, 0.0));
  const double x = lr.r.x();
  const double farthest = l1 + l2 + reach_tolerance;
  const double closest = std::abs(l1 - l2) - reach_tolerance;
  // The same for both abduction solutions.
  lr.reach = quick ? std::sqrt(x * x + lr.z_mag * lr.z_mag) : std::hypot(x, lr.z_mag);
  if (quick && (std::abs(lr.reach - farthest) <= 1e-14 * farthest || std::abs(lr.reach - closest) <= 1e-14 * farthest)) {
    return legReach(leg, p);
  }
  if (lr.reach > farthest) {
    lr.status = LegIkStatus::kTooFar;
    return lr;
  }
  if (lr.reach < closest) {
    lr.status = LegIkStatus::kTooClose;
    return lr;
  }
  lr.cos_knee = std::clamp((lr.reach * lr.reach - l1 * l1 - l2 * l2) / (2.0 * l1 * l2), -1.0, 1.0);
  if (quick && std::abs(lr.cos_knee) > 1.0 - 1e-6) return legReach(leg, p);
  return lr;
}

}  // namespace

LegIkResult solveLegIk(const LegGeometry& leg, const Eigen::Vector3d& foot_in_trunk) {
  LegIkResult result;
  const Eigen::Vector3d& p = foot_in_trunk;
  const LegReach lr = legReach(leg, p);
  const double l1 = leg.thigh_length;
  const double l2 = leg.calf_length;
  const double d = leg.thigh_offset;
  result.status = lr.status;
  switch (lr.status) {
    case LegIkStatus::kOk:
      break;
    case LegIkStatus::kNotFinite:
      result.message = fmt::format("foot position ({:g}, {:g}, {:g}) m is not finite", p.x(), p.y(), p.z());
      return result;
    case LegIkStatus::kInsideHipOffset:
      result.message = fmt::format("foot ({:.4f}, {:.4f}, {:.4f}) m is {:.4f} m from the hip axis, inside the thigh offset {:.4f} m",
                              p.x(), p.y(), p.z(), std::sqrt(lr.rho2), d);
      return result;
    case LegIkStatus::kTooFar:
      result.message = fmt::format("foot ({:.4f}, {:.4f}, {:.4f}) m is {:.4f} m from the thigh joint; the leg reaches {:.4f} m",
                              p.x(), p.y(), p.z(), lr.reach, l1 + l2);
      return result;
    case LegIkStatus::kTooClose:
      result.message =
          fmt::format("foot ({:.4f}, {:.4f}, {:.4f}) m is {:.4f} m from the thigh joint; the leg folds to {:.4f} m at least", p.x(),
                 p.y(), p.z(), lr.reach, std::abs(l1 - l2));
      return result;
  }
  const Eigen::Vector3d& r = lr.r;
  const double z_mag = lr.z_mag;
  const double x = r.x();

  // Knee-backward branch: q2 in [-pi, 0].
  const double q2 = -std::acos(lr.cos_knee);
  const double a = l1 + l2 * std::cos(q2);
  const double b = l2 * std::sin(q2);
  const double y = leg.side * d;

  auto solve = [&](double z) {
    LegIkResult s;
    // (r_y, r_z) = Rx(q0) (y, z'), and (-z', -x') = Rot(q1) (a, b).
    const double q0 = std::atan2(r.z(), r.y()) - std::atan2(z, y);
    const double q1 = std::atan2(-x, -z) - std::atan2(b, a);
    bool in0 = false;
    bool in1 = false;
    bool in2 = false;
    s.q = Eigen::Vector3d(intoRange(q0, leg.limits[0], in0), intoRange(q1, leg.limits[1], in1),
                          intoRange(q2, leg.limits[2], in2));
    s.within_limits = in0 && in1 && in2;
    return s;
  };

  const LegIkResult below = solve(-z_mag);
  if (below.within_limits || z_mag == 0.0) return below;
  const LegIkResult above = solve(z_mag);
  return above.within_limits ? above : below;
}

// ---------------------------------------------------------------------------
// Velocities

JointVelocityResult jointVelocitiesForFootVelocity(const LegGeometry& leg, const Eigen::Vector3d& q,
                                                   const Eigen::Vector3d& foot_velocity_trunk,
                                                   double singularity_threshold) {
  JointVelocityResult result;
  const Eigen::Matrix3d j = footJacobian(leg, q);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(j, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();  // descending
  result.least_singular_value = sigma[2];
  if (sigma[2] >= singularity_threshold) {
    result.qd = j.partialPivLu().solve(foot_velocity_trunk);
    return result;
  }
  result.singular = true;
  result.message = fmt::format(
      "leg Jacobian is singular at q = ({:.4f}, {:.4f}, {:.4f}) rad: least singular value {:.3g} m/rad "
      "< {:.3g}; joint velocities are the least-squares solution without the singular directions",
      q[0], q[1], q[2], sigma[2], singularity_threshold);
  const Eigen::Vector3d ut_v = svd.matrixU().transpose() * foot_velocity_trunk;
  Eigen::Vector3d scaled = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (sigma[i] >= singularity_threshold) scaled[i] = ut_v[i] / sigma[i];
  }
  result.qd = svd.matrixV() * scaled;
  return result;
}

Eigen::Vector3d footVelocityInTrunk(const Eigen::Matrix3d& trunk_rotation, const Eigen::Vector3d& trunk_position,
                                    const Eigen::Vector3d& trunk_velocity,
                                    const Eigen::Vector3d& trunk_angular_velocity, const Eigen::Vector3d& foot_position,
                                    const Eigen::Vector3d& foot_velocity) {
  return trunk_rotation.transpose() *
         (foot_velocity - trunk_velocity - trunk_angular_velocity.cross(foot_position - trunk_position));
}

// ---------------------------------------------------------------------------
// Reach without the angles

namespace {

// Far enough from a limit that the IK's rounding (about 1e-15 rad) cannot put
// the angle on the other side of it.
constexpr double kArcMargin = 1e-7;

LegReachCheck::Arc arcOf(const JointRange& range) {
  LegReachCheck::Arc arc;
  if (range.min == -std::numeric_limits<double>::infinity() && range.max == std::numeric_limits<double>::infinity()) {
    arc.any_angle = true;
    return arc;
  }
  // intoRange tries the representatives within 3 turns of (-pi, pi]: a range
  // inside +-4 pi narrower than a turn is then the arc of its angles mod 2 pi.
  const double width = range.max - range.min;
  if (!(std::isfinite(width) && width < kTwoPi - 1e-6 && std::abs(range.min) <= 4.0 * kPi &&
        std::abs(range.max) <= 4.0 * kPi)) {
    arc.exact_only = true;
    return arc;
  }
  const double mid = 0.5 * (range.min + range.max);
  arc.cos_mid = std::cos(mid);
  arc.sin_mid = std::sin(mid);
  arc.cos_half_width = std::cos(0.5 * width);
  return arc;
}

enum class Verdict { kNo, kYes, kUnsure };

Verdict both(Verdict a, Verdict b) {
  if (a == Verdict::kNo || b == Verdict::kNo) return Verdict::kNo;
  return a == Verdict::kYes && b == Verdict::kYes ? Verdict::kYes : Verdict::kUnsure;
}

Verdict either(Verdict a, Verdict b) {
  if (a == Verdict::kYes || b == Verdict::kYes) return Verdict::kYes;
  return a == Verdict::kNo && b == Verdict::kNo ? Verdict::kNo : Verdict::kUnsure;
}

// Whether the angle of the vector (c, s), of length `norm`, lies on `arc`:
// cos(angle - mid) against cos(half width), with kArcMargin either side.
Verdict onArc(const LegReachCheck::Arc& arc, double c, double s, double norm) {
  if (arc.any_angle) return Verdict::kYes;
  if (arc.exact_only) return Verdict::kUnsure;
  const double excess = c * arc.cos_mid + s * arc.sin_mid - arc.cos_half_width * norm;
  if (excess > kArcMargin * norm) return Verdict::kYes;
  if (excess < -kArcMargin * norm) return Verdict::kNo;
  return Verdict::kUnsure;
}

}  // namespace

LegReachCheck::LegReachCheck(const LegGeometry& leg) : leg_(leg) {
  for (int j = 0; j < 3; ++j) arcs_[j] = arcOf(leg.limits[j]);
}

bool LegReachCheck::reaches(const Eigen::Vector3d& foot_in_trunk, bool require_within_limits) const {
  const LegReach lr = legReach(leg_, foot_in_trunk, true);
  if (lr.status != LegIkStatus::kOk) return false;
  if (!require_within_limits) return true;
  const double l1 = leg_.thigh_length;
  const double l2 = leg_.calf_length;
  const double d = leg_.thigh_offset;
  // The angles solveLegIk would compute, as vectors: the knee (cos q2, sin q2)
  // with q2 = -acos(cos_knee); the thigh angle q1 = atan2(-x, -z') - atan2(b, a)
  // and the hip angle q0 = atan2(r_z, r_y) - atan2(z', y) as the rotation from
  // the second vector to the first.
  const double scale = l1 + l2 + d;
  const double tiny = 1e-6 * scale;
  const double ck = lr.cos_knee;
  const double sk = -std::sqrt((1.0 - ck) * (1.0 + ck));
  const double a = l1 + l2 * ck;
  const double b = l2 * sk;
  const double ab2 = a * a + b * b;
  const double y = leg_.side * d;
  const double yz2 = y * y + lr.z_mag * lr.z_mag;
  // Short vectors make the IK's angles ill-conditioned: leave those to it.
  if (ab2 < tiny * tiny || lr.reach < tiny || yz2 < tiny * tiny || lr.rho2 < tiny * tiny) {
    return solveLegIk(leg_, foot_in_trunk).within_limits;
  }
  const double hip_norm = std::sqrt(lr.rho2 * yz2);
  const double thigh_norm = lr.reach * std::sqrt(ab2);
  const double x = lr.r.x();
  const double ry = lr.r.y();
  const double rz = lr.r.z();
  auto branch = [&](double z) {
    const Verdict hip = onArc(arcs_[0], ry * y + rz * z, rz * y - ry * z, hip_norm);
    const Verdict thigh = onArc(arcs_[1], -z * a - x * b, -x * a + z * b, thigh_norm);
    return both(hip, thigh);
  };
  const Verdict knee = onArc(arcs_[2], ck, sk, 1.0);
  if (knee == Verdict::kNo) return false;
  // The foot-below solution first, the foot-above one only when z' != 0.
  Verdict within = branch(-lr.z_mag);
  if (within != Verdict::kYes && lr.z_mag != 0.0) within = either(within, branch(lr.z_mag));
  within = both(knee, within);
  if (within == Verdict::kUnsure) return solveLegIk(leg_, foot_in_trunk).within_limits;
  return within == Verdict::kYes;
}

bool feetReachable(const std::array<LegReachCheck, kLegCount>& legs,
                   const std::array<Eigen::Vector3d, kLegCount>& feet_world, const Eigen::Vector3d& trunk_position,
                   const Eigen::Matrix3d& trunk_rotation, bool require_within_limits) {
  for (int i = 0; i < kLegCount; ++i) {
    if (!legs[i].reaches(trunk_rotation.transpose() * (feet_world[i] - trunk_position), require_within_limits)) {
      return false;
    }
  }
  return true;
}

bool feetReachable(const std::array<LegGeometry, kLegCount>& legs,
                   const std::array<Eigen::Vector3d, kLegCount>& feet_world, const Eigen::Vector3d& trunk_position,
                   const Eigen::Matrix3d& trunk_rotation, bool require_within_limits) {
  for (int i = 0; i < kLegCount; ++i) {
    const Eigen::Vector3d foot_in_trunk = trunk_rotation.transpose() * (feet_world[i] - trunk_position);
    const LegIkResult ik = solveLegIk(legs[i], foot_in_trunk);
    if (!ik.ok() || (require_within_limits && !ik.within_limits)) return false;
  }
  return true;
}

}  // namespace pronk::jump
