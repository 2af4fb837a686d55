#include "method/safety_filter.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "method/force_distribution.h"
#include "method/orientation_trajectory.h"

namespace pronk::jump {

// ---------------------------------------------------------------------------
// The ballistic check

const char* safetyIssueName(SafetyIssue issue) {
  switch (issue) {
    case SafetyIssue::kNone:
      return "none";
    case SafetyIssue::kNotFinite:
      return "not_finite";
    case SafetyIssue::kApexBelowTarget:
      return "apex_below_target";
    case SafetyIssue::kTargetUnreachable:
      return "target_unreachable";
    case SafetyIssue::kOutsideWorkspace:
      return "outside_workspace";
    case SafetyIssue::kLegWorkspace:
      return "leg_workspace";
    case SafetyIssue::kTorqueLimit:
      return "torque_limit";
    case SafetyIssue::kTerrainEdge:
      return "terrain_edge";
  }
  return "unknown";
}

SafetyVerdict SafetyCheck::operator()(const FlightState& lift_off, const Eigen::Vector3d& target) const {
  const Eigen::Vector3d& p = lift_off.position;
  const Eigen::Vector3d& v = lift_off.velocity;
  if (!p.allFinite() || !v.allFinite() || !target.allFinite()) {
    return {SafetyIssue::kNotFinite,
            fmt::format("lift-off position ({:g}, {:g}, {:g}) m, velocity ({:g}, {:g}, {:g}) m/s or target ({:g}, {:g}, {:g}) m is not finite",
                   p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), target.x(), target.y(), target.z())};
  }
  const BallisticFlight flight(lift_off, gravity);

  const double apex = flight.apexHeight();
  if (apex < target.z() + apex_clearance) {
    return {SafetyIssue::kApexBelowTarget,
            fmt::format("apex at z = {:.4f} m (lift-off z = {:.4f} m, v_z = {:.4f} m/s) is below the target height {:.4f} m + "
                   "clearance {:.4f} m",
                   apex, p.z(), v.z(), target.z(), apex_clearance)};
  }

  const auto landing = flight.landingPoint(target.z());
  if (!landing) {
    return {SafetyIssue::kTargetUnreachable,
            fmt::format("the CoM never comes back down to the target height {:.4f} m (apex {:.4f} m)", target.z(), apex)};
  }
  const double miss = (landing->head<2>() - target.head<2>()).norm();
  if (miss > max_landing_miss) {
    return {SafetyIssue::kTargetUnreachable,
            fmt::format("the CoM comes down through z = {:.4f} m at ({:.4f}, {:.4f}) m, {:.4f} m from the target ({:.4f}, {:.4f}) m; "
                   "at most {:.4f} m is allowed",
                   target.z(), landing->x(), landing->y(), miss, target.x(), target.y(), max_landing_miss)};
  }

  if (workspace && !workspace(p)) {
    return {SafetyIssue::kOutsideWorkspace,
            fmt::format("lift-off position ({:.4f}, {:.4f}, {:.4f}) m is outside the leg workspace", p.x(), p.y(), p.z())};
  }
  const EdgePass pass = edgePass(terrain, terrain_origin, p, v, target, gravity);
  if (!pass.clears()) return {SafetyIssue::kTerrainEdge, edgeProblem(terrain, pass)};
  return {};
}

// ---------------------------------------------------------------------------
// The thrust path against the legs

std::array<LegReachCheck, kLegCount> reachChecks(const LegWorkspace& ws) {
  return {LegReachCheck(ws.legs[0]), LegReachCheck(ws.legs[1]), LegReachCheck(ws.legs[2]), LegReachCheck(ws.legs[3])};
}

namespace {

// The least height of a knee above its stance foot's centre for one trunk pose
// (+inf where a leg has no IK solution: the reach check's finding).
double kneeClearanceAt(const LegWorkspace& ws, const Eigen::Vector3d& trunk, const Eigen::Matrix3d& R) {
  double least = std::numeric_limits<double>::infinity();
  for (int leg = 0; leg < kLegCount; ++leg) {
    const LegIkResult ik = solveLegIk(ws.legs[leg], R.transpose() * (ws.feet[leg] - trunk));
    if (!ik.ok()) continue;
    least = std::min(least, (trunk + R * kneePosition(ws.legs[leg], ik.q)).z() - ws.feet[leg].z());
  }
  return least;
}

}  // namespace

std::optional<std::string> workspaceProblem(const ThrustPlan& thrust, const JumpAction& action, const LegWorkspace& ws,
                                            const std::array<LegReachCheck, kLegCount>& reach, bool explain) {
  const OrientationTrajectory orient(Eigen::Vector3d::Zero(), action, thrust.duration());
  const int n = std::max(ws.path_samples, 1);
  const bool knees = ws.knee_clearance > -std::numeric_limits<double>::infinity();
  enum class Finding { kNone, kFootOutOfReach, kKneeLow };
  // The lift-off end first: the stretched legs there are where most plans fail,
  // and a search over many candidates then rejects them after one sample.
  // Then every fourth sample, then the rest: a path that leaves the workspace
  // for a while is found after a few samples.
  auto finding = [&](int i) {
    const double t = thrust.duration() * i / n;
    const Eigen::Matrix3d R = orient.rotation(t);
    const Eigen::Vector3d trunk = thrust.position(t) + R * ws.com_to_trunk;
    if (!feetReachable(reach, ws.feet, trunk, R, ws.require_within_limits)) return Finding::kFootOutOfReach;
    if (knees && kneeClearanceAt(ws, trunk, R) < ws.knee_clearance) return Finding::kKneeLow;
    return Finding::kNone;
  };
  auto problem = [&](int i, Finding f) -> std::string {
    if (!explain) return std::string();
    const double t = thrust.duration() * i / n;
    std::ostringstream msg;
    if (f == Finding::kKneeLow) {
      const Eigen::Matrix3d R = orient.rotation(t);
      msg << "a knee comes down to " << kneeClearanceAt(ws, thrust.position(t) + R * ws.com_to_trunk, R)
          << " m above its stance foot (less than the knee clearance " << ws.knee_clearance << " m) at t = " << t
          << " s of the " << thrust.duration() << " s thrust (CoM " << thrust.position(t).transpose() << ")";
    } else {
      msg << "a stance foot is out of the leg workspace at t = " << t << " s of the " << thrust.duration()
          << " s thrust (CoM " << thrust.position(t).transpose() << ")";
    }
    return msg.str();
  };
  if (const Finding f = finding(n); f != Finding::kNone) return problem(n, f);
  for (int i = 0; i < n; i += 4) {
    if (const Finding f = finding(i); f != Finding::kNone) return problem(i, f);
  }
  for (int i = 1; i < n; ++i) {
    if (i % 4 == 0) continue;
    if (const Finding f = finding(i); f != Finding::kNone) return problem(i, f);
  }
  return std::nullopt;
}

double thrustKneeClearance(const ThrustPlan& thrust, const JumpAction& action, const LegWorkspace& ws) {
  const OrientationTrajectory orient(Eigen::Vector3d::Zero(), action, thrust.duration());
  const int n = std::max(ws.path_samples, 1);
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const double t = thrust.duration() * i / n;
    const Eigen::Matrix3d R = orient.rotation(t);
    least = std::min(least, kneeClearanceAt(ws, thrust.position(t) + R * ws.com_to_trunk, R));
  }
  return least;
}

std::optional<std::string> supportProblem(const ThrustPlan& thrust, const std::array<Eigen::Vector3d, kLegCount>& feet,
                                          const Eigen::Vector3d& gravity, double min_share, int path_samples,
                                          bool explain) {
  double ground = 0.0;
  // Rows: total vertical force, and its moments about the x and y axes; the
  // minimum-norm shares are A^T (A A^T)^-1 b.
  Eigen::Matrix<double, 3, kLegCount> A;
  for (int i = 0; i < kLegCount; ++i) {
    A.col(i) << 1.0, feet[i].x(), feet[i].y();
    ground += feet[i].z() / kLegCount;
  }
  const Eigen::Matrix3d AAt = A * A.transpose();
  const Eigen::Matrix3d AAt_inv = AAt.inverse();
  const int n = std::max(path_samples, 1);
  for (int i = 0; i <= n; ++i) {
    const double t = thrust.duration() * i / n;
    const Eigen::Vector3d c = thrust.position(t), a = thrust.acceleration(t);
    const double vertical = a.z() - gravity.z();  // per unit mass
    if (!(vertical > 0.0)) {
      if (!explain) return std::string();
      std::ostringstream msg;
      msg << "the feet would have to pull the CoM down at t = " << t << " s of the thrust (vertical acceleration "
          << a.z() << " m/s^2)";
      return msg.str();
    }
    const Eigen::Vector2d zmp = c.head<2>() - (c.z() - ground) * a.head<2>() / vertical;
    const Eigen::Vector3d b(1.0, zmp.x(), zmp.y());
    const Eigen::Matrix<double, kLegCount, 1> share = A.transpose() * (AAt_inv * b) * kLegCount;  // 1 = the mean
    Eigen::Index foot = 0;
    if (share.minCoeff(&foot) < min_share) {
      if (!explain) return std::string();
      std::ostringstream msg;
      msg << "stance foot " << legName(static_cast<Leg>(foot)) << " would carry " << share(foot)
          << " of the mean vertical force at t = " << t << " s of the thrust (zero-moment point "
          << zmp.transpose() << ", CoM " << c.transpose() << ")";
      return msg.str();
    }
  }
  return std::nullopt;
}

TorqueVerdict torqueVerdict(const ThrustPlan& thrust, const JumpAction& action, const LegWorkspace& ws,
                            const Eigen::Vector3d& gravity) {
  TorqueVerdict verdict;
  const OrientationTrajectory orient(Eigen::Vector3d::Zero(), action, thrust.duration());
  Eigen::Matrix3Xd feet(3, kLegCount);
  for (int i = 0; i < kLegCount; ++i) feet.col(i) = ws.feet[i];
  const int n = std::max(ws.path_samples, 1);
  const double dt = thrust.duration() / n;
  for (int k = 0; k <= n; ++k) {
    const double t = thrust.duration() * k / n;
    const Eigen::Vector3d c = thrust.position(t);
    const Eigen::Matrix3d R = orient.rotation(t);
    const Eigen::Vector3d w = orient.angularVelocityWorld(t);
    const Eigen::Vector3d trunk_offset = R * ws.com_to_trunk;
    const Eigen::Vector3d trunk = c + trunk_offset, trunk_velocity = thrust.velocity(t) + w.cross(trunk_offset);
    const Eigen::Vector3d push = thrust.acceleration(t) - gravity;  // per unit mass
    const Eigen::Matrix3Xd forces = distributeWrench(feet, c, ws.mass * push, Eigen::Vector3d::Zero());
    // The share of the planned ground force the motors deliver at this sample:
    // the least over the joints of available / needed torque.
    double scale = 1.0;
    for (int i = 0; i < kLegCount; ++i) {
      const Eigen::Vector3d foot_from_trunk = ws.feet[i] - trunk;
      const LegIkResult ik = solveLegIk(ws.legs[i], R.transpose() * foot_from_trunk);
      if (!ik.ok()) continue;  // out of reach: the workspace check's finding, not this one's
      const Eigen::Matrix3d J = footJacobian(ws.legs[i], ik.q);
      const Eigen::Vector3d tau = -J.transpose() * (R.transpose() * forces.col(i));
      // The stance foot is still in the world, so in the trunk frame it moves at
      // d/dt R^T (f - p) = -R^T (w x (f - p) + p').
      const Eigen::Vector3d qd = J.partialPivLu().solve(-R.transpose() * (w.cross(foot_from_trunk) + trunk_velocity));
      for (int j = 0; j < 3; ++j) {
        const double speed = std::isfinite(qd(j)) ? qd(j) : 0.0;  // a singular leg: the workspace check's finding
        const TorqueRange range = availableTorque(ws.motor, ws.joint_motors[j], speed);
        const double have = tau(j) > 0.0 ? range.upper : -range.lower;
        if (std::abs(tau(j)) <= have) continue;
        const double joint_scale = have / std::abs(tau(j));
        if (joint_scale < scale) scale = joint_scale;
        if (joint_scale < verdict.scale) {
          verdict.scale = joint_scale;
          verdict.t = t;
          verdict.need = std::abs(tau(j));
          verdict.have = have;
          verdict.speed = speed;
          verdict.leg = i;
          verdict.joint = j;
        }
      }
    }
    verdict.shortfall += (1.0 - scale) * push.norm() * ((k == 0 || k == n) ? dt / 2.0 : dt);
  }
  return verdict;
}

std::string torqueProblem(const TorqueVerdict& v, const LegWorkspace& ws, double thrust_duration) {
  static const char* const kJointNames[3] = {"hip", "thigh", "calf"};
  std::ostringstream msg;
  msg << "the motors would leave the lift-off " << v.shortfall << " m/s slower than planned (allowed "
      << ws.max_speed_shortfall << "); the tightest: " << legName(static_cast<Leg>(v.leg)) << " "
      << kJointNames[v.joint] << " would need " << v.need << " N m, its motor delivers " << v.have << " at "
      << v.speed << " rad/s, t = " << v.t << " s of the " << thrust_duration << " s thrust";
  return msg.str();
}

std::optional<std::string> thrustLeavesWorkspace(const JumpAction& action, double azimuth,
                                                 const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                                 const LegWorkspace& ws) {
  return workspaceProblem(ThrustPlan(action, azimuth, com_start, polar_origin), action, ws, reachChecks(ws), true);
}

std::optional<std::string> thrustLeavesSupport(const JumpAction& action, double azimuth,
                                               const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                               const std::array<Eigen::Vector3d, kLegCount>& feet,
                                               const Eigen::Vector3d& gravity, double min_share, int path_samples) {
  return supportProblem(ThrustPlan(action, azimuth, com_start, polar_origin), feet, gravity, min_share, path_samples,
                        true);
}

double thrustSpeedShortfall(const JumpAction& action, double azimuth, const Eigen::Vector3d& com_start,
                            const Eigen::Vector3d& polar_origin, const LegWorkspace& ws, const Eigen::Vector3d& gravity) {
  if (!(ws.mass > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return torqueVerdict(ThrustPlan(action, azimuth, com_start, polar_origin), action, ws, gravity).shortfall;
}

std::optional<std::string> thrustExceedsTorque(const JumpAction& action, double azimuth,
                                               const Eigen::Vector3d& com_start, const Eigen::Vector3d& polar_origin,
                                               const LegWorkspace& ws, const Eigen::Vector3d& gravity) {
  if (!(ws.mass > 0.0)) return std::nullopt;
  const ThrustPlan thrust(action, azimuth, com_start, polar_origin);
  const TorqueVerdict verdict = torqueVerdict(thrust, action, ws, gravity);
  if (verdict.shortfall <= ws.max_speed_shortfall) return std::nullopt;
  return torqueProblem(verdict, ws, thrust.duration());
}

LegWorkspace standingWorkspace(const std::array<LegGeometry, kLegCount>& legs, const Eigen::Vector3d& stance_q,
                               const Eigen::Vector3d& start_com, const Eigen::Vector3d& com_to_trunk) {
  LegWorkspace ws;
  ws.legs = legs;
  ws.com_to_trunk = com_to_trunk;
  const Eigen::Vector3d trunk = start_com + com_to_trunk;
  for (int i = 0; i < kLegCount; ++i) ws.feet[i] = trunk + footPosition(legs[i], stance_q);
  return ws;
}

// ---------------------------------------------------------------------------
// The whole filter

SafetyFilterResult safetyFilter(const JumpAction& action, const ThrustPlan& thrust, const Eigen::Vector3d& target_com,
                                const SafetyCheck& ballistic, const std::optional<LegWorkspace>& workspace) {
  SafetyFilterResult result;
  const PointState& lift_off = thrust.liftOff();
  result.verdict = ballistic({lift_off.position, lift_off.velocity}, target_com);
  if (result.verdict) {
    const EdgePass pass = thrustEdgePass(ballistic.terrain, ballistic.terrain_origin, thrust, target_com);
    if (!pass.clears()) result.verdict = {SafetyIssue::kTerrainEdge, thrustEdgeProblem(ballistic.terrain, pass)};
  }
  if (!result.verdict || !workspace) return result;
  const LegWorkspace& ws = *workspace;
  if (std::optional<std::string> out = workspaceProblem(thrust, action, ws, reachChecks(ws), true)) {
    result.verdict = {SafetyIssue::kLegWorkspace, *out};
    return result;
  }
  if (!(ws.mass > 0.0)) {
    result.speed_shortfall = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  const TorqueVerdict torque = torqueVerdict(thrust, action, ws, ballistic.gravity);
  result.speed_shortfall = torque.shortfall;
  if (torque.shortfall > ws.max_speed_shortfall) {
    result.verdict = {SafetyIssue::kTorqueLimit, torqueProblem(torque, ws, thrust.duration())};
  }
  return result;
}

}  // namespace pronk::jump
