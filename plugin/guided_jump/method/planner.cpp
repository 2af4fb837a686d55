#include "method/planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "method/fixed_point.h"

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRangeTolerance = 1e-12;  // a value this far outside its range is clamped, not rejected
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The lift-off offset's fixed point is solved to |F(a) - a| <= this times the
// horizontal target distance: relative, because near-vertical jumps (a few
// microns) are as sensitive to the offset as wide ones are to a fixed 1e-13 m.
constexpr double kOffsetTolerance = 1e-13;

using P = ActionParameter;

[[noreturn]] void configError(const std::string& what) { throw std::invalid_argument("planner config: " + what); }

// One candidate of the rule's search (docs/method-planner.md).
struct Candidate {
  double rise = 0.0;
  double ahead = 0.0;
  double thrust_duration = 0.0;
  double yaw_fraction = 0.0;
};

// The lift-off velocity member of the rule for lift-off point c_e.
struct Member {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  bool ok = true;
  bool terrain = false;  // !ok because of an edge (PlanLimit::kTerrain)
  std::string problem;  // when !ok
};


// lambda^2 of the sideways rule (docs/method-planner.md, step 3): lambda is the
// squared sine of the jump plane's azimuth off the trunk's heading halfway
// through the turn. The lift-off point lies on the jump plane, so the direction
// from it to the target is the azimuth itself, the same for every candidate.
double sidewaysWeight(double azimuth, double target_yaw) {
  const double off_heading = std::sin(azimuth - 0.5 * target_yaw);
  const double lambda = off_heading * off_heading;
  return lambda * lambda;
}

// `sideways_weight` is lambda^2 of the sideways rule (sidewaysWeight): how far
// the elevation moves from the least-speed one towards sideways_elevation_rad.
Member chooseMember(const Eigen::Vector3d& c_e, const Eigen::Vector3d& c_tg, bool in_place, double sideways_weight,
                    const PlannerConfig& cfg) {
  Member m;
  const double g = -cfg.gravity.z();
  if (in_place) {
    const double apex = std::max(c_e.z(), c_tg.z()) + cfg.in_place_apex_rise_m;
    m.velocity = {0.0, 0.0, std::sqrt(2.0 * g * (apex - c_e.z()))};
    return m;
  }
  const LiftOffHyperbola hyp(c_e, c_tg, cfg.gravity);
  const ParameterRange& el = cfg.ranges[P::kVelocityElevation];
  const double h = hyp.horizontalDistance();
  const double slope = hyp.heightChange() / h;
  // Least-speed elevation, clamped into the range, kept strictly inside the
  // hyperbola's open elevation interval. A down target takes the elevation of a
  // jump to the take-off height: flatter, the arc would pass low over the
  // take-off edge and the trailing feet would land on it.
  const double take_off_com_z = cfg.polarOrigin().z() + cfg.standingHeight();
  double theta = kPi / 4.0 + std::atan2(std::max(c_tg.z(), take_off_com_z) - c_e.z(), h) / 2.0;
  if (cfg.sideways_elevation_rad > theta) theta += (cfg.sideways_elevation_rad - theta) * sideways_weight;
  theta = std::clamp(theta, el.min, el.max);
  const double lowest = hyp.minimumElevation() + 1e-9;
  const double highest = kPi / 2.0 - 1e-9;
  theta = std::clamp(theta, lowest, highest);
  // Apex at least min_apex_rise above the lift-off point: v_z >= V. On the
  // branch above the least-speed elevation v_z grows with tan(theta) = t and
  // g h t^2 - 2 V^2 t + 2 V^2 slope = 0 gives the elevation where v_z = V.
  const double V2 = 2.0 * g * cfg.min_apex_rise_m;
  const double t_now = std::tan(theta);
  const double vz2_now = g * h * t_now * t_now / (2.0 * (t_now - slope));
  bool raised = false;
  if (vz2_now < V2) {
    const double before = theta;
    const double disc = V2 * V2 - 2.0 * g * h * V2 * slope;
    if (disc >= 0.0) theta = std::max(theta, std::atan((V2 + std::sqrt(disc)) / (g * h)));
    theta = std::min(theta, highest);
    raised = !(theta == before);
  }
  std::optional<LiftOffVelocity> v = hyp.atElevation(theta, raised ? std::tan(theta) : t_now);
  if (!v) {  // cannot happen after the clamps above; kept as a guard
    m.ok = false;
    m.problem = "no ballistic solution at the chosen elevation";
    return m;
  }
  if (!cfg.terrain.edges.empty()) {
    // Steeper until the body clears every edge it spans in flight, no faster
    // than the thrust can lift off (the Bezier speed cap times the largest
    // speed ratio).
    constexpr double kElevationStep = 0.005;  // rad
    const double steepest = std::min(el.max, highest);
    const double fastest = std::min(cfg.max_bezier_speed_mps, cfg.ranges[P::kLiftOffSpeed].max) *
                           cfg.ranges[P::kSpeedRatio].max;
    const Eigen::Vector3d o = cfg.polarOrigin();
    EdgePass pass = edgePass(cfg.terrain, o, c_e, v->velocity, c_tg, cfg.gravity);
    while (!pass.clears() && theta + kElevationStep <= steepest) {
      const std::optional<LiftOffVelocity> steeper =
          hyp.atElevation(theta + kElevationStep, std::tan(theta + kElevationStep));
      if (!steeper || steeper->velocity.norm() > fastest) break;
      theta += kElevationStep;
      v = steeper;
      pass = edgePass(cfg.terrain, o, c_e, v->velocity, c_tg, cfg.gravity);
    }
    if (!pass.clears()) {
      std::ostringstream msg;
      msg << edgeProblem(cfg.terrain, pass) << " at the steepest lift-off the thrust can give (velocity elevation "
          << theta << " rad, " << v->velocity.norm() << " m/s)";
      m.ok = false;
      m.terrain = true;
      m.problem = msg.str();
      return m;
    }
  }
  m.velocity = v->velocity;
  return m;
}

std::string formatRangeProblem(ActionParameter p, double value, const ParameterRange& r) {
  std::ostringstream msg;
  msg << actionParameterName(p) << " = " << value << " " << actionParameterUnit(p) << " is outside its range ["
      << r.min << ", " << r.max << "]";
  return msg.str();
}

JumpAction clampToRanges(const JumpAction& a, const ActionRanges& ranges) {
  ActionVector v = toVector(a);
  for (int i = 0; i < kActionSize; ++i) {
    if (!std::isfinite(v[i])) v[i] = 0.5 * (ranges.bounds[i].min + ranges.bounds[i].max);
    v[i] = std::clamp(v[i], ranges.bounds[i].min, ranges.bounds[i].max);
  }
  return fromVector(v);
}

// Fills the prediction of `plan` from its (possibly clamped) action.
void predict(PlannedJump& plan, const PlannerConfig& cfg) {
  const ThrustPlan thrust(plan.action, plan.azimuth_rad, cfg.start_com, cfg.polarOrigin());
  plan.bezier_lift_off = thrust.bezierLiftOff();
  plan.lift_off = thrust.liftOff();
  plan.lift_off_time = thrust.duration();
  plan.explosive_acceleration = thrust.explosive().accelerationAlongPath();
  const BallisticFlight flight(FlightState{plan.lift_off.position, plan.lift_off.velocity}, cfg.gravity);
  plan.apex = flight.apexPoint();
  plan.apex_time = flight.apexTime();
  const std::optional<double> t = flight.landingTime(plan.target_com.z());
  if (t) {
    plan.flight_time = *t;
    plan.touchdown_time = plan.lift_off_time + *t;
    plan.landing_point = *flight.landingPoint(plan.target_com.z());
  } else {
    plan.flight_time = plan.touchdown_time = kNaN;
    plan.landing_point = Eigen::Vector3d::Constant(kNaN);
  }
  plan.touchdown_yaw = plan.action.liftoff_rpy_rad.z() + plan.action.liftoff_rpy_rate_radps.z() * plan.flight_time;
}

// The part of a candidate that does not depend on its yaw split: the lift-off
// state on the ballistic hyperbola and the action without yaw. The fixed point
// below is most of a candidate's cost, so planJump solves it once for all the
// yaw splits of a (rise, ahead, duration).
struct CandidateCore {
  PlannedJump plan;  // azimuth, target CoM, the action without its yaw split
  Eigen::Vector3d c_e = Eigen::Vector3d::Zero();
  Member m;
  double speed = 0.0;
  double bezier_speed = 0.0;        // r_v of the speed split
  double d_needed = 0.0;            // explosive distance the acceleration cap needs
  double rv_cap = 0.0;
  std::optional<double> t_flight;  // lift-off to the target height
  double lowest_elevation = 0.0;   // of a lift-off velocity from c_e that reaches the target (not in place)
  bool in_place = false;
};

// What every candidate of a target shares: its jump plane, target CoM and
// sideways weight, computed once per planJump rather than per candidate.
struct TargetFrame {
  double azimuth = 0.0;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();  // horizontal unit vector of the jump plane
  Eigen::Vector3d target_com = Eigen::Vector3d::Zero();
  double h_total = 0.0;  // horizontal target distance
  bool in_place = false;
  double sideways_weight = 0.0;
};

TargetFrame targetFrame(const JumpTarget& target, const PlannerConfig& cfg) {
  TargetFrame f;
  const Eigen::Vector3d& c0 = cfg.start_com;
  const Eigen::Vector3d& disp = target.displacement;
  f.azimuth = jumpPlaneAzimuth(disp);
  f.u = Eigen::Vector3d(std::cos(f.azimuth), std::sin(f.azimuth), 0.0);
  f.target_com = Eigen::Vector3d(c0.x() + disp.x(), c0.y() + disp.y(), cfg.polarOrigin().z() + disp.z() + cfg.standingHeight());
  f.h_total = std::hypot(disp.x(), disp.y());
  f.in_place = f.h_total < kPureTwistDistance;
  f.sideways_weight = sidewaysWeight(f.azimuth, target.yaw_rad);
  return f;
}

CandidateCore solveCandidateCore(const TargetFrame& frame, const PlannerConfig& cfg, const Candidate& cand) {
  const ActionRanges& ranges = cfg.ranges;
  CandidateCore core;
  PlannedJump& plan = core.plan;
  const Eigen::Vector3d o = cfg.polarOrigin();
  const Eigen::Vector3d& c0 = cfg.start_com;
  const double hs = cfg.standingHeight();
  plan.azimuth_rad = frame.azimuth;
  const Eigen::Vector3d& u = frame.u;
  plan.target_com = frame.target_com;
  const double h_total = frame.h_total;
  const bool in_place = frame.in_place;
  const double lift_off_z = o.z() + hs + cand.rise;
  const double sideways_weight = frame.sideways_weight;

  const ParameterRange& rv_range = ranges[P::kLiftOffSpeed];
  const ParameterRange& d_range = ranges[P::kExplosiveDistance];
  const double rv_cap = std::max(rv_range.min, std::min(cfg.max_bezier_speed_mps, rv_range.max));

  // Bezier speed, speed ratio and explosive distance for a lift-off speed.
  struct Split {
    double r_v, k, d, d_needed;
  };
  auto splitSpeed = [&](double speed) {
    Split s;
    s.r_v = std::clamp(speed, rv_range.min, rv_cap);
    s.k = speed / s.r_v;
    s.d_needed = std::max(0.0, (speed * speed - s.r_v * s.r_v) / (2.0 * cfg.max_explosive_acceleration));
    s.d = std::max(d_range.min, s.d_needed);
    return s;
  };
  // The rule's lift-off offset along the jump plane for a lift-off velocity of
  // elevation cosine cos_theta and speed `speed`, and explosive distance d.
  auto aheadFor = [&](double cos_theta, double speed, double d) {
    if (in_place) return 0.0;
    // A still start: the Bezier lift-off is T/3 v_b ahead of the start CoM, so
    // P2 is above P0 and the CoM starts without horizontal acceleration.
    const double still = (cand.thrust_duration / 3.0 * splitSpeed(speed).r_v + d) * cos_theta;
    return std::min(std::isnan(cand.ahead) ? still : std::max(cand.ahead, d * cos_theta), 0.5 * h_total);
  };
  auto liftOffPoint = [&](double ahead) {
    Eigen::Vector3d c = c0 + ahead * u;
    c.z() = lift_off_z;
    return c;
  };

  // Fixed point on the lift-off offset: the member depends on its lift-off
  // point, and the lift-off point on the member only through the offset rule,
  // i.e. through one number a = F(a). The ballistic solution below is exact
  // either way. The secant steps of solveFixedPoint1D mostly need 4 to 6 members (1
  // where a fixed offset is not raised) where plain iteration on (theta, speed, d)
  // needed 12 to 18; the plans agree with it to 1e-12. The member of the last
  // evaluation (at the solution) is kept. The first guess is plain iteration's:
  // elevation pi/4, speed 0, d at its minimum.
  Member m;
  auto offsetMap = [&](double ahead) {
    m = chooseMember(liftOffPoint(ahead), plan.target_com, in_place, sideways_weight, cfg);
    if (!m.ok) return kNaN;  // stops the solver
    const double speed = m.velocity.norm();
    const double d = std::min(splitSpeed(speed).d, d_range.max);
    return aheadFor(m.velocity.dot(u) / speed, speed, d);  // cos(theta) = v_h / |v|
  };
  const double first_guess = aheadFor(std::cos(kPi / 4.0), 0.0, d_range.min);
  const FixedPoint1D fixed =
      in_place ? FixedPoint1D{0.0, offsetMap(0.0), 1, 0, true}  // the offset is 0
               : solveFixedPoint1D(offsetMap, first_guess, 0.0, 0.5 * h_total, kOffsetTolerance * h_total, 200);
  const Eigen::Vector3d c_e = liftOffPoint(fixed.x);
  const double speed = m.velocity.norm();
  const Split split = splitSpeed(speed);
  const double d = std::min(split.d, d_range.max);
  const Eigen::Vector3d v_hat = m.velocity / speed;
  const Eigen::Vector3d c_b = c_e - d * v_hat;
  const Eigen::Vector3d rel = c_b - o;
  const double rel_h = rel.dot(u);

  JumpAction& a = plan.action;
  a.thrust_duration_s = cand.thrust_duration;
  a.liftoff_radius_m = std::hypot(rel_h, rel.z());
  a.liftoff_elevation_rad = std::atan2(rel.z(), rel_h);
  a.liftoff_speed_mps = speed / split.k;
  a.velocity_elevation_rad = in_place ? kPi / 2.0 : std::atan2(m.velocity.z(), m.velocity.dot(u));
  a.speed_ratio = split.k;
  a.explosive_distance_m = d;

  // Flight time to the target height, for the yaw split.
  const BallisticFlight flight(FlightState{c_e, m.velocity}, cfg.gravity);
  core.t_flight = flight.landingTime(plan.target_com.z());
  // Computed here once for all the yaw splits (planCandidate checks it).
  if (!in_place) {
    core.lowest_elevation =
        std::atan2(plan.target_com.z() - c_e.z(), (plan.target_com - c_e).head<2>().norm());
  }
  core.c_e = c_e;
  core.m = m;
  core.speed = speed;
  core.bezier_speed = split.r_v;
  core.d_needed = split.d_needed;
  core.rv_cap = rv_cap;
  core.in_place = in_place;
  return core;
}

// Plans one candidate from its core: the yaw split, then the range checks.
// Range problems make it infeasible; `explain` false leaves the reason empty
// (a search only needs the verdict). The leg checks and the prediction are
// done by the caller.
PlannedJump planCandidate(const JumpTarget& target, const PlannerConfig& cfg, const CandidateCore& core,
                          const Candidate& cand, bool explain) {
  const ActionRanges& ranges = cfg.ranges;
  PlannedJump plan = core.plan;
  JumpAction& a = plan.action;
  const Eigen::Vector3d& c_e = core.c_e;
  const Member& m = core.m;
  const double speed = core.speed;
  const double rv_cap = core.rv_cap;
  const bool in_place = core.in_place;
  const std::optional<double>& t_flight = core.t_flight;
  const ParameterRange& d_range = ranges[P::kExplosiveDistance];
  const ParameterRange& yaw_r = ranges[P::kLiftOffYaw];
  const ParameterRange& rate_r = ranges[P::kLiftOffYawRate];
  double yaw_lo = 0.0, yaw_rate = 0.0;
  if (target.yaw_rad != 0.0 && t_flight && *t_flight > 0.0) {
    yaw_lo = std::clamp(cand.yaw_fraction * target.yaw_rad, yaw_r.min, yaw_r.max);
    yaw_rate = (target.yaw_rad - yaw_lo) / *t_flight;
    if (yaw_rate > rate_r.max || yaw_rate < rate_r.min) {
      yaw_rate = std::clamp(yaw_rate, rate_r.min, rate_r.max);
      yaw_lo = target.yaw_rad - yaw_rate * *t_flight;
    }
  } else if (target.yaw_rad != 0.0) {
    yaw_lo = target.yaw_rad;
  }
  // Roll compensation, from the lift-off velocity across the trunk's lift-off heading.
  const double v_side = -std::sin(yaw_lo) * m.velocity.x() + std::cos(yaw_lo) * m.velocity.y();
  const ParameterRange& roll_rate_r = ranges[P::kLiftOffRollRate];
  const double roll_rate = std::clamp(cfg.sideways_roll_rate_gain * v_side, roll_rate_r.min, roll_rate_r.max);
  a.liftoff_rpy_rad = {0.0, 0.0, yaw_lo};
  a.liftoff_rpy_rate_radps = {roll_rate, 0.0, yaw_rate};

  // Feasibility, first failure wins.
  plan.feasible = true;
  auto fail = [&](PlanLimit limit, std::optional<ActionParameter> p, const std::string& why) {
    if (!plan.feasible) return;
    plan.feasible = false;
    plan.limit = limit;
    plan.limiting_parameter = p;
    plan.reason = why;
  };
  // The reasons are sentences; a rejected candidate that nobody reads skips them.
  auto failQuietly = [&](PlanLimit limit, std::optional<ActionParameter> p) {
    if (!plan.feasible) return false;
    if (explain) return true;
    plan.feasible = false;
    plan.limit = limit;
    plan.limiting_parameter = p;
    return false;
  };
  if (!m.ok) {
    if (m.terrain) fail(PlanLimit::kTerrain, std::nullopt, m.problem);
    else fail(PlanLimit::kActionRange, P::kVelocityElevation, m.problem);
  }
  if (!in_place) {
    const double lowest = core.lowest_elevation;
    if (ranges[P::kVelocityElevation].max <= lowest && failQuietly(PlanLimit::kActionRange, P::kVelocityElevation)) {
      std::ostringstream msg;
      msg << "the target needs a lift-off velocity elevation above " << lowest
          << " rad, beyond the velocity_elevation range max " << ranges[P::kVelocityElevation].max;
      fail(PlanLimit::kActionRange, P::kVelocityElevation, msg.str());
    }
  }
  if (!t_flight) fail(PlanLimit::kActionRange, P::kVelocityElevation, "the CoM never comes down to the target height");
  // Parameter ranges, in the order that names the physical cause first.
  const ActionVector values = toVector(a);
  const ActionParameter order[] = {P::kSpeedRatio,        P::kLiftOffSpeed,   P::kVelocityElevation,
                                   P::kExplosiveDistance, P::kLiftOffRadius,  P::kLiftOffElevation,
                                   P::kThrustDuration,    P::kLiftOffYaw,     P::kLiftOffYawRate,
                                   P::kLiftOffRoll,       P::kLiftOffPitch,   P::kLiftOffRollRate,
                                   P::kLiftOffPitchRate};
  for (ActionParameter p : order) {
    const double v = values[actionIndex(p)];
    const ParameterRange& r = ranges[p];
    if (!(v >= r.min - kRangeTolerance && v <= r.max + kRangeTolerance) && failQuietly(PlanLimit::kActionRange, p)) {
      std::string why = formatRangeProblem(p, v, r);
      if (p == P::kSpeedRatio && v > r.max) {
        std::ostringstream msg;
        msg << "; the lift-off speed " << speed << " m/s exceeds k_max x the Bezier speed cap = " << r.max * rv_cap
            << " m/s";
        why += msg.str();
      }
      std::ostringstream ctx;
      ctx << " (lift-off speed " << speed << " m/s at elevation " << a.velocity_elevation_rad << " rad, r_v "
          << a.liftoff_speed_mps << " m/s, k " << a.speed_ratio << ", d " << a.explosive_distance_m
          << " m, lift-off CoM " << c_e.transpose() << ")";
      fail(PlanLimit::kActionRange, p, why + ctx.str());
    }
  }
  if (core.d_needed > d_range.max + kRangeTolerance && failQuietly(PlanLimit::kExplosive, P::kExplosiveDistance)) {
    std::ostringstream msg;
    msg << "lift-off speed " << speed << " m/s from a Bezier speed of " << core.bezier_speed
        << " m/s needs an explosive distance of " << core.d_needed << " m at the acceleration cap "
        << cfg.max_explosive_acceleration << " m/s^2, beyond the explosive_distance range max " << d_range.max;
    fail(PlanLimit::kExplosive, P::kExplosiveDistance, msg.str());
  }
  a = clampToRanges(a, ranges);
  return plan;  // without its prediction (predict)
}

}  // namespace

const char* planLimitName(PlanLimit limit) {
  switch (limit) {
    case PlanLimit::kNone: return "none";
    case PlanLimit::kActionRange: return "action_range";
    case PlanLimit::kExplosive: return "explosive";
    case PlanLimit::kLegWorkspace: return "leg_workspace";
    case PlanLimit::kSupport: return "support";
    case PlanLimit::kTorque: return "torque";
    case PlanLimit::kTerrain: return "terrain";
  }
  return "unknown";
}

PlannerConfig PlannerConfig::scaledToRobot(double scale) const {
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    throw std::invalid_argument("PlannerConfig::scaledToRobot: the scale must be finite and > 0");
  }
  PlannerConfig c = *this;
  if (scale == 1.0) return c;
  const double time = std::sqrt(scale);  // and speed
  for (double& v : c.lift_off_rise_m) v *= scale;
  for (double& v : c.lift_off_ahead_m) v *= scale;
  for (double& v : c.thrust_duration_s) v *= time;
  c.max_bezier_speed_mps *= time;
  c.min_apex_rise_m *= scale;
  c.in_place_apex_rise_m *= scale;
  c.sideways_roll_rate_gain /= scale;
  for (GentlerThrust& g : c.gentler_thrusts) {
    for (double& v : g.lift_off_rise_m) v *= scale;
    for (double& v : g.thrust_duration_s) v *= time;
    g.max_bezier_speed_mps *= time;
  }
  return c;
}

double PlannerConfig::standingHeight() const {
  return std::isnan(standing_com_height) ? start_com.z() : standing_com_height;
}

Eigen::Vector3d PlannerConfig::polarOrigin() const {
  return start_com - standingHeight() * Eigen::Vector3d::UnitZ();
}

void PlannerConfig::check() const {
  ranges.check();
  if (!gravity.allFinite() || gravity.x() != 0.0 || gravity.y() != 0.0 || !(gravity.z() < 0.0)) {
    configError("gravity must be finite and along -z");
  }
  if (!start_com.allFinite()) configError("start_com must be finite");
  if (!(std::isfinite(standingHeight()) && standingHeight() > 0.0)) configError("standing CoM height must be > 0");
  if (lift_off_rise_m.empty() || lift_off_ahead_m.empty() || thrust_duration_s.empty() ||
      yaw_at_lift_off_fraction.empty()) {
    configError("every candidate list needs at least one value");
  }
  for (double v : lift_off_ahead_m) {
    if (!(std::isfinite(v) && v >= 0.0)) configError("lift_off_ahead_m values must be finite and >= 0");
  }
  for (double v : lift_off_rise_m) {
    if (!std::isfinite(v) || standingHeight() + v <= 0.0) configError("lift_off_rise_m values must keep the CoM above the surface");
  }
  for (double v : thrust_duration_s) {
    if (!(std::isfinite(v) && v > 0.0)) configError("thrust_duration_s values must be finite and > 0");
  }
  for (double v : yaw_at_lift_off_fraction) {
    if (!(std::isfinite(v) && v >= 0.0 && v <= 1.0)) configError("yaw_at_lift_off_fraction values must be in [0, 1]");
  }
  for (const GentlerThrust& g : gentler_thrusts) {
    if (g.lift_off_rise_m.empty() || g.thrust_duration_s.empty()) {
      configError("every gentler thrust needs at least one lift-off rise and one thrust duration");
    }
    for (double v : g.lift_off_rise_m) {
      if (!std::isfinite(v) || standingHeight() + v <= 0.0) {
        configError("gentler thrust lift_off_rise_m values must keep the CoM above the surface");
      }
    }
    for (double v : g.thrust_duration_s) {
      if (!(std::isfinite(v) && v > 0.0)) configError("gentler thrust durations must be finite and > 0");
    }
    if (!(std::isfinite(g.max_bezier_speed_mps) && g.max_bezier_speed_mps > 0.0 &&
          std::isfinite(g.max_explosive_acceleration) && g.max_explosive_acceleration > 0.0)) {
      configError("gentler thrust speed caps and explosive accelerations must be > 0");
    }
  }
  if (!(std::isfinite(max_bezier_speed_mps) && max_bezier_speed_mps > 0.0)) configError("max_bezier_speed_mps must be > 0");
  for (double a : harder_explosive_accelerations) {
    if (!(std::isfinite(a) && a > 0.0)) configError("harder_explosive_accelerations must be finite and > 0");
  }
  if (!(std::isfinite(max_explosive_acceleration) && max_explosive_acceleration > 0.0)) {
    configError("max_explosive_acceleration must be > 0");
  }
  if (!(std::isfinite(min_apex_rise_m) && min_apex_rise_m >= 0.0)) configError("min_apex_rise_m must be >= 0");
  try {
    terrain.check();
  } catch (const std::invalid_argument& e) {
    configError(e.what());
  }
  if (!std::isnan(sideways_elevation_rad) && !(sideways_elevation_rad > 0.0 && sideways_elevation_rad < kPi / 2.0)) {
    configError("sideways_elevation_rad must be in (0, pi/2) rad, or NaN (off)");
  }
  if (!(std::isfinite(in_place_apex_rise_m) && in_place_apex_rise_m > 0.0)) configError("in_place_apex_rise_m must be > 0");
  if (!std::isfinite(min_support_share)) configError("min_support_share must be finite");
  if (workspace) {
    for (const LegGeometry& leg : workspace->legs) leg.check();
    for (const Eigen::Vector3d& f : workspace->feet) {
      if (!f.allFinite()) configError("workspace feet must be finite");
    }
    if (!workspace->com_to_trunk.allFinite()) configError("workspace com_to_trunk must be finite");
    if (!(std::isfinite(workspace->mass) && workspace->mass >= 0.0)) configError("workspace mass must be finite and >= 0");
    for (const MotorLimits& m : workspace->joint_motors) {
      if (!(m.effort > 0.0)) configError("workspace effort limits must be > 0 (infinity: unlimited)");
      if (!(m.velocity > 0.0)) configError("workspace velocity limits must be > 0 (infinity: unlimited)");
    }
    if (!(std::isfinite(workspace->max_speed_shortfall) && workspace->max_speed_shortfall >= 0.0)) {
      configError("workspace max_speed_shortfall must be finite and >= 0");
    }
  }
}

namespace {

// A rejected candidate that planJump may return. Only the verdict is found
// during the search; the reason (a sentence with numbers) and the prediction
// are written for the one candidate returned: most targets find a feasible
// candidate and never read them.
struct Rejection {
  PlannedJump plan;  // the verdict; no reason or prediction yet
  CandidateCore core;
  Candidate cand;
};

PlannedJump explained(const Rejection& r, const JumpTarget& target, const PlannerConfig& cfg) {
  PlannedJump plan = r.plan;
  const JumpAction& a = plan.action;
  const Eigen::Vector3d o = cfg.polarOrigin();
  switch (plan.limit) {
    case PlanLimit::kLegWorkspace:
      plan.reason = "every candidate lift-off loses a stance foot; the first: " +
                    *thrustLeavesWorkspace(a, plan.azimuth_rad, cfg.start_com, o, *cfg.workspace);
      break;
    case PlanLimit::kSupport:
      plan.reason = "every candidate in the leg workspace needs a foot to pull; the first: " +
                    *thrustLeavesSupport(a, plan.azimuth_rad, cfg.start_com, o, cfg.workspace->feet, cfg.gravity,
                                         cfg.min_support_share, cfg.workspace->path_samples);
      break;
    case PlanLimit::kTorque:
      plan.reason = "every candidate in reach and support needs more torque than the motors have; the first: " +
                    *thrustExceedsTorque(a, plan.azimuth_rad, cfg.start_com, o, *cfg.workspace, cfg.gravity);
      break;
    default:  // the action ranges
      plan = planCandidate(target, cfg, r.core, r.cand, true);
  }
  predict(plan, cfg);
  return plan;
}

// One pass of the candidate search (docs/method-planner.md, step 10) over the
// config's lists; planJump runs it again for each gentler thrust.
PlannedJump searchCandidates(const JumpTarget& target, const PlannerConfig& config) {
  const ParameterRange& t_range = config.ranges[P::kThrustDuration];
  const Eigen::Vector3d polar_origin = config.polarOrigin();
  const TargetFrame frame = targetFrame(target, config);
  // The first rejected candidate of each kind, in case planJump returns it.
  std::optional<Rejection> first_failure;  // the action ranges
  std::optional<Rejection> leg_failure;
  std::optional<Rejection> support_failure;
  std::optional<Rejection> torque_failure;
  std::optional<std::string> terrain_failure;  // the thrust reaches over an edge too low
  std::optional<std::array<LegReachCheck, kLegCount>> reach;
  if (config.workspace) reach = reachChecks(*config.workspace);
  // Candidates in order: each rise, with the still start first (when enabled),
  // then the fixed offsets.
  std::vector<std::pair<double, double>> placements;  // (rise, ahead); NaN ahead: the still start
  for (double rise : config.lift_off_rise_m) {
    if (config.still_start_first) placements.emplace_back(rise, kNaN);
    for (double ahead : config.lift_off_ahead_m) placements.emplace_back(rise, ahead);
  }
  for (const auto& [rise, ahead] : placements) {
    // Only the still start's lift-off point depends on the thrust duration: a
    // fixed offset solves its fixed point once for every duration.
    const bool core_per_duration = std::isnan(ahead);
    std::optional<CandidateCore> placement_core;
    for (double duration : config.thrust_duration_s) {
      std::optional<CandidateCore> core;  // shared by the yaw splits
      // So are the thrust and the support verdict: the yaw split only turns the trunk.
      std::optional<ThrustPlan> thrust;
      std::optional<bool> leaves_support;
      for (double yaw_fraction : config.yaw_at_lift_off_fraction) {
        // Without a yaw change every fraction gives the same plan.
        if (target.yaw_rad == 0.0 && yaw_fraction != config.yaw_at_lift_off_fraction.front()) continue;
        const Candidate cand{rise, ahead, std::clamp(duration, t_range.min, t_range.max), yaw_fraction};
        if (!core && !core_per_duration && placement_core) {
          core = placement_core;
          core->plan.action.thrust_duration_s = cand.thrust_duration;
        }
        if (!core) placement_core = core = solveCandidateCore(frame, config, cand);
        PlannedJump plan = planCandidate(target, config, *core, cand, false);
        if (plan.feasible && !config.terrain.edges.empty()) {
          // The thrust's path must keep the hips above the edges it reaches over.
          if (!thrust) thrust.emplace(plan.action, plan.azimuth_rad, config.start_com, polar_origin);
          const EdgePass pass = thrustEdgePass(config.terrain, polar_origin, *thrust, plan.target_com);
          if (!pass.clears()) {
            plan.feasible = false;
            plan.limit = PlanLimit::kTerrain;
            if (!terrain_failure) terrain_failure = thrustEdgeProblem(config.terrain, pass);
            if (!first_failure) first_failure = Rejection{plan, *core, cand};
            continue;
          }
        }
        if (plan.feasible && config.workspace) {
          // The leg checks, in order; the first that fails classifies the candidate.
          auto reject = [&](PlanLimit limit, std::optional<Rejection>& first_of_kind) {
            plan.feasible = false;
            plan.limit = limit;
            if (!first_of_kind) first_of_kind = Rejection{plan, *core, cand};
          };
          const LegWorkspace& ws = *config.workspace;
          if (!thrust) thrust.emplace(plan.action, plan.azimuth_rad, config.start_com, polar_origin);
          auto leavesSupport = [&] {
            if (!leaves_support) {
              leaves_support =
                  supportProblem(*thrust, ws.feet, config.gravity, config.min_support_share, ws.path_samples, false)
                      .has_value();
            }
            return *leaves_support;
          };
          // Once a rejection of both kinds is held, which check names a candidate
          // that needs a foot to pull no longer matters: the support check (no IK)
          // then goes first and spares the path IK.
          const bool support_first = leg_failure && support_failure;
          if (support_first && leavesSupport()) continue;
          if (workspaceProblem(*thrust, plan.action, ws, *reach, false)) {
            reject(PlanLimit::kLegWorkspace, leg_failure);
          } else if (!support_first && leavesSupport()) {
            reject(PlanLimit::kSupport, support_failure);
          } else if (ws.mass > 0.0) {
            plan.speed_shortfall = torqueVerdict(*thrust, plan.action, ws, config.gravity).shortfall;
            if (plan.speed_shortfall > ws.max_speed_shortfall) reject(PlanLimit::kTorque, torque_failure);
          }
          if (!plan.feasible) continue;
        }
        if (plan.feasible) {
          predict(plan, config);
          return plan;
        }
        if (!first_failure) first_failure = Rejection{plan, *core, cand};
      }
    }
  }
  if (torque_failure) return explained(*torque_failure, target, config);
  if (support_failure) return explained(*support_failure, target, config);
  if (leg_failure) return explained(*leg_failure, target, config);
  if (terrain_failure) {
    // Every candidate that passed the ranges reaches over an edge too low.
    PlannedJump plan = explained(*first_failure, target, config);
    plan.feasible = false;
    plan.limit = PlanLimit::kTerrain;
    plan.limiting_parameter.reset();
    plan.reason = *terrain_failure;
    return plan;
  }
  return explained(*first_failure, target, config);
}

}  // namespace

PlannedJump planJump(const JumpTarget& target, const PlannerConfig& config) {
  config.check();
  if (!target.displacement.allFinite() || !std::isfinite(target.yaw_rad)) {
    throw std::invalid_argument("planJump: the target displacement and yaw must be finite");
  }
  PlannedJump plan = searchCandidates(target, config);
  // Every candidate loses a stance foot: a stronger explosive phase is shorter,
  // so its Bezier part ends nearer the lift-off and the legs keep their reach.
  for (double acceleration : config.harder_explosive_accelerations) {
    if (plan.feasible || plan.limit != PlanLimit::kLegWorkspace) break;
    PlannerConfig harder = config;
    harder.max_explosive_acceleration = acceleration;
    const PlannedJump next = searchCandidates(target, harder);
    if (next.feasible) plan = next;
  }
  for (const PlannerConfig::GentlerThrust& gentler : config.gentler_thrusts) {
    if (plan.feasible || plan.limit != PlanLimit::kTorque) break;
    PlannerConfig relieved = config;
    relieved.lift_off_rise_m = gentler.lift_off_rise_m;
    relieved.thrust_duration_s = gentler.thrust_duration_s;
    relieved.max_bezier_speed_mps = gentler.max_bezier_speed_mps;
    relieved.max_explosive_acceleration = gentler.max_explosive_acceleration;
    // A gentler pass that finds nothing keeps the first pass's refusal as the report.
    const PlannedJump next = searchCandidates(target, relieved);
    if (next.feasible) plan = next;
  }
  return plan;
}

PlannedJump planPriorJump(const JumpTarget& target, PlannerConfig config, const LandingStop& landing_stop) {
  PlannedJump plan;
  for (double fraction : {0.5, 0.25, 0.75}) {
    config.yaw_at_lift_off_fraction = {fraction};
    plan = planJump(target, config);
    if (plan.feasible) break;
  }
  if (!plan.feasible) {
    config.yaw_at_lift_off_fraction = {0.0};
    plan = planJump(target, config);
  }
  for (int round = 0; round < 4 && plan.feasible; ++round) {
    Eigen::Vector3d v_touchdown = plan.lift_off.velocity;
    v_touchdown.z() += config.gravity.z() * plan.flight_time;
    JumpTarget aimed = target;
    aimed.displacement.head<2>() -= landing_stop(v_touchdown);
    const PlannedJump next = planJump(aimed, config);
    if (!next.feasible) break;
    plan = next;
  }
  return plan;
}

ReplannedJump replanJump(const JumpTarget& target, const PointState& lift_off_error, const PlannerConfig& config,
                         int max_iterations, double tolerance) {
  if (!lift_off_error.position.allFinite() || !lift_off_error.velocity.allFinite()) {
    throw std::invalid_argument("replanJump: the lift-off error must be finite");
  }
  if (max_iterations < 1 || !(tolerance > 0.0)) {
    throw std::invalid_argument("replanJump: max_iterations must be >= 1 and tolerance > 0");
  }
  ReplannedJump out;
  out.commanded = target;
  out.target_com = planJump(target, config).target_com;
  for (int i = 0; i < max_iterations; ++i) {
    out.plan = planJump(out.commanded, config);
    out.iterations = i + 1;
    const FlightState achieved{out.plan.lift_off.position + lift_off_error.position,
                               out.plan.lift_off.velocity + lift_off_error.velocity};
    const std::optional<Eigen::Vector3d> landed =
        BallisticFlight(achieved, config.gravity).landingPoint(out.target_com.z());
    if (!landed) {  // the erroneous state never comes down to the target height
      out.predicted_landing = Eigen::Vector3d::Constant(kNaN);
      out.miss = kNaN;
      out.converged = false;
      return out;
    }
    out.predicted_landing = *landed;
    const Eigen::Vector2d miss = (out.predicted_landing - out.target_com).head<2>();
    out.miss = miss.norm();
    out.converged = out.plan.feasible && out.miss <= tolerance;
    if (out.miss <= tolerance) break;
    out.commanded.displacement.head<2>() -= miss;
  }
  return out;
}

}  // namespace pronk::jump
