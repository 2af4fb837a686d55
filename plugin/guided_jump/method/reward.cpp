#include "method/reward.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pronk::jump {

namespace {


void requireSize(Eigen::Index size, Eigen::Index expected, const char* what, int tick) {
  if (size == expected) return;
  if (tick < 0) {
    throw std::invalid_argument(fmt::format("JumpRecord: {} has {} entries, expected {}", what, static_cast<long>(size),
                                       static_cast<long>(expected)));
  }
  throw std::invalid_argument(fmt::format("JumpRecord: tick {}: {} has {} entries, expected {}", tick, what,
                                     static_cast<long>(size), static_cast<long>(expected)));
}

void requireSetting(bool ok, const char* name, double value, const char* domain) {
  if (!ok) throw std::invalid_argument(fmt::format("RewardSettings: {} = {:g} must be {}", name, value, domain));
}

}  // namespace

// ---------------------------------------------------------------------------
// Settings

void RewardSettings::check() const {
  const struct {
    const char* name;
    double value;
  } weight_list[] = {{"weights.joint_position_limits", weights.joint_position_limits},
                     {"weights.joint_velocity_limits", weights.joint_velocity_limits},
                     {"weights.torque_saturation", weights.torque_saturation},
                     {"weights.friction_cone", weights.friction_cone},
                     {"weights.unilaterality", weights.unilaterality},
                     {"weights.workspace", weights.workspace},
                     {"weights.target_orientation", weights.target_orientation},
                     {"weights.lift_off_position", weights.lift_off_position},
                     {"weights.lift_off_orientation", weights.lift_off_orientation},
                     {"weights.lift_off_linear_velocity", weights.lift_off_linear_velocity},
                     {"weights.lift_off_angular_velocity", weights.lift_off_angular_velocity},
                     {"weights.touchdown_bounce", weights.touchdown_bounce},
                     {"weights.touchdown_angular_velocity", weights.touchdown_angular_velocity},
                     {"weights.action_limit", weights.action_limit}};
  for (const auto& w : weight_list) requireSetting(std::isfinite(w.value) && w.value >= 0.0, w.name, w.value, ">= 0");
  requireSetting(soft_limit_factor > 0.0 && soft_limit_factor <= 1.0, "soft_limit_factor", soft_limit_factor,
                 "in (0, 1]");
  requireSetting(velocity_excess_cap >= 0.0, "velocity_excess_cap", velocity_excess_cap, ">= 0");
  requireSetting(std::isfinite(friction_coefficient) && friction_coefficient >= 0.0, "friction_coefficient",
                 friction_coefficient, "finite and >= 0");
  requireSetting(std::isfinite(workspace_half_width) && workspace_half_width >= 0.0, "workspace_half_width",
                 workspace_half_width, "finite and >= 0");
  requireSetting(std::isfinite(workspace_z_min), "workspace_z_min", workspace_z_min, "finite");
  requireSetting(std::isfinite(workspace_z_max) && workspace_z_max >= workspace_z_min, "workspace_z_max",
                 workspace_z_max, "finite and >= workspace_z_min");
  requireSetting(std::isfinite(raw_action_limit) && raw_action_limit > 0.0, "raw_action_limit", raw_action_limit,
                 "finite and > 0");
  requireSetting(std::isfinite(error_scale) && error_scale > 0.0, "error_scale", error_scale, "finite and > 0");
  requireSetting(std::isfinite(distance_scale) && distance_scale > 0.0, "distance_scale", distance_scale,
                 "finite and > 0");
  requireSetting(std::isfinite(z_dead_band) && z_dead_band >= 0.0, "z_dead_band", z_dead_band, "finite and >= 0");
  requireSetting(std::isfinite(foot_radius) && foot_radius >= 0.0, "foot_radius", foot_radius, "finite and >= 0");
  requireSetting(std::isfinite(penalty_scale) && penalty_scale > 0.0, "penalty_scale", penalty_scale, "finite and > 0");
  requireSetting(std::isfinite(missing_touchdown_bounce) && missing_touchdown_bounce >= 0.0, "missing_touchdown_bounce",
                 missing_touchdown_bounce, "finite and >= 0");
  requireSetting(std::isfinite(missing_touchdown_angular_velocity) && missing_touchdown_angular_velocity >= 0.0,
                 "missing_touchdown_angular_velocity", missing_touchdown_angular_velocity, "finite and >= 0");
  requireSetting(std::isfinite(reference_tick_s) && reference_tick_s > 0.0, "reference_tick_s", reference_tick_s,
                 "finite and > 0");
}

RewardSettings go1RewardSettings() { return RewardSettings(); }

RewardSettings aliengoRewardSettings() {
  RewardSettings s;
  s.workspace_z_min = 0.20;
  s.workspace_z_max = 0.60;
  s.foot_radius = 0.0265;  // the collision sphere of assets/robots/aliengo (the reference code uses 0.02)
  return s;
}

// ---------------------------------------------------------------------------
// Terms

namespace reward_terms {

double activation(double x, double lo, double hi) { return std::abs(std::min(x - lo, 0.0) + std::max(x - hi, 0.0)); }

double jointPositionExcess(const Eigen::VectorXd& q, const JointLimits& limits, double soft_limit_factor) {
  double sum = 0.0;
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    const double lo = limits.position_min[j], hi = limits.position_max[j];
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      // A continuous joint (the vendor Aliengo's thighs), or one bound only: no
      // soft band around a middle that does not exist; the hard bound that is there.
      sum += activation(q[j], lo, hi);
      continue;
    }
    const double middle = 0.5 * (lo + hi), half = 0.5 * (hi - lo) * soft_limit_factor;
    sum += activation(q[j], middle - half, middle + half);
  }
  return sum;
}

double jointVelocityExcess(const Eigen::VectorXd& qd, const JointLimits& limits, double cap) {
  double sum = 0.0;
  for (Eigen::Index j = 0; j < qd.size(); ++j) {
    sum += std::min(std::max(std::abs(qd[j]) - limits.velocity_max[j], 0.0), cap);
  }
  return sum;
}

double torqueSaturation(const Eigen::VectorXd& tau_commanded, const Eigen::VectorXd& tau_applied) {
  return (tau_commanded - tau_applied).cwiseAbs().sum();
}

double frictionConeExcess(const std::vector<Eigen::Vector3d>& forces, const std::vector<bool>& in_contact, double mu) {
  double sum = 0.0;
  for (std::size_t i = 0; i < forces.size(); ++i) {
    if (!in_contact[i]) continue;
    sum += std::max(forces[i].head<2>().norm() - mu * forces[i].z(), 0.0);
  }
  return sum;
}

double pullingForce(const std::vector<Eigen::Vector3d>& forces, const std::vector<bool>& in_contact) {
  double sum = 0.0;
  for (std::size_t i = 0; i < forces.size(); ++i) {
    if (in_contact[i]) sum += std::max(-forces[i].z(), 0.0);
  }
  return sum;
}

double workspaceExcess(const Eigen::Vector3d& base_position, const Eigen::Vector3d& start_base_position,
                       const RewardSettings& settings) {
  const double w = settings.workspace_half_width;
  return activation(base_position.x() - start_base_position.x(), -w, w) +
         activation(base_position.y() - start_base_position.y(), -w, w) +
         activation(base_position.z(), settings.workspace_z_min, settings.workspace_z_max);
}

double rotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.normalized().angularDistance(b.normalized());
}

double actionExcess(const Eigen::VectorXd& raw_action, double limit) {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < raw_action.size(); ++i) sum += std::max(std::abs(raw_action[i]) - limit, 0.0);
  return sum;
}

double landingTargetReward(double error, double distance, const RewardSettings& settings) {
  return std::exp(-error / settings.error_scale) * std::exp(distance / settings.distance_scale);
}

}  // namespace reward_terms

// ---------------------------------------------------------------------------
// Breakdown

std::vector<const RewardTerm*> RewardBreakdown::terms() const {
  return {&joint_position_limits,
          &joint_velocity_limits,
          &torque_saturation,
          &friction_cone,
          &unilaterality,
          &workspace,
          &target_orientation,
          &lift_off_position,
          &lift_off_orientation,
          &lift_off_linear_velocity,
          &lift_off_angular_velocity,
          &touchdown_bounce,
          &touchdown_angular_velocity,
          &action_limit};
}

std::map<std::string, double> RewardBreakdown::asMap() const {
  std::map<std::string, double> out;
  for (const RewardTerm* t : terms()) out[t->name] = t->cost();
  out["landing_error"] = landing_error;
  out["landing_reward"] = landing_reward;
  out["running_cost"] = running_cost;
  out["terminal_cost"] = terminal_cost;
  out["total_cost"] = total_cost;
  out["penalty_gate"] = penalty_gate;
  out["reward"] = reward;
  return out;
}

RewardBreakdown computeReward(const JumpRecord& record, const RewardSettings& settings) {
  settings.check();
  if (!(record.tick_s > 0.0) || !std::isfinite(record.tick_s)) {
    throw std::invalid_argument(fmt::format("JumpRecord: tick_s = {:g} s must be positive and finite", record.tick_s));
  }
  const JointLimits& limits = record.joint_limits;
  const Eigen::Index joints = limits.position_min.size();
  requireSize(limits.position_max.size(), joints, "joint_limits.position_max", -1);
  requireSize(limits.velocity_max.size(), joints, "joint_limits.velocity_max", -1);
  if (record.final_foot_positions.empty()) {
    throw std::invalid_argument("JumpRecord: final_foot_positions is empty; the landing height needs the feet");
  }

  const RewardWeights& w = settings.weights;
  RewardBreakdown b;
  b.joint_position_limits.weight = w.joint_position_limits;
  b.joint_velocity_limits.weight = w.joint_velocity_limits;
  b.torque_saturation.weight = w.torque_saturation;
  b.friction_cone.weight = w.friction_cone;
  b.unilaterality.weight = w.unilaterality;
  b.workspace.weight = w.workspace;
  b.target_orientation.weight = w.target_orientation;
  b.lift_off_position.weight = w.lift_off_position;
  b.lift_off_orientation.weight = w.lift_off_orientation;
  b.lift_off_linear_velocity.weight = w.lift_off_linear_velocity;
  b.lift_off_angular_velocity.weight = w.lift_off_angular_velocity;
  b.touchdown_bounce.weight = w.touchdown_bounce;
  b.touchdown_angular_velocity.weight = w.touchdown_angular_velocity;
  b.action_limit.weight = w.action_limit;

  // Running terms: every tick up to lift-off, each counting for tick_s of the
  // reference's 5 ms step.
  b.lifted_off = record.lift_off.has_value();
  const double tick_scale = record.tick_s / settings.reference_tick_s;
  for (std::size_t k = 0; k < record.ticks.size(); ++k) {
    const TickSample& s = record.ticks[k];
    const int tick = static_cast<int>(k);
    if (b.lifted_off && s.time > record.lift_off->time) continue;
    requireSize(s.q.size(), joints, "q", tick);
    requireSize(s.qd.size(), joints, "qd", tick);
    requireSize(s.tau_commanded.size(), joints, "tau_commanded", tick);
    requireSize(s.tau_applied.size(), joints, "tau_applied", tick);
    requireSize(static_cast<Eigen::Index>(s.foot_in_contact.size()), static_cast<Eigen::Index>(s.foot_force.size()),
                "foot_in_contact", tick);
    b.joint_position_limits.value +=
        tick_scale * reward_terms::jointPositionExcess(s.q, limits, settings.soft_limit_factor);
    b.joint_velocity_limits.value +=
        tick_scale * reward_terms::jointVelocityExcess(s.qd, limits, settings.velocity_excess_cap);
    b.torque_saturation.value += tick_scale * reward_terms::torqueSaturation(s.tau_commanded, s.tau_applied);
    b.friction_cone.value +=
        tick_scale * reward_terms::frictionConeExcess(s.foot_force, s.foot_in_contact, settings.friction_coefficient);
    b.unilaterality.value += tick_scale * reward_terms::pullingForce(s.foot_force, s.foot_in_contact);
    b.workspace.value +=
        tick_scale * reward_terms::workspaceExcess(s.base_position, record.start_base_position, settings);
    ++b.thrust_ticks;
  }

  // Terminal terms.
  const BodyState& final_state = record.final_state;
  const BodyState& lift_off = b.lifted_off ? *record.lift_off : final_state;
  const JumpPlan& plan = record.plan;
  b.target_orientation.value = reward_terms::rotationAngle(final_state.orientation, record.target.orientation);
  b.lift_off_position.value = (plan.lift_off_com_position - lift_off.com_position).norm();
  b.lift_off_orientation.value = reward_terms::rotationAngle(plan.lift_off_orientation, lift_off.orientation);
  b.lift_off_linear_velocity.value = (plan.lift_off_com_velocity - lift_off.com_velocity).norm();
  b.lift_off_angular_velocity.value = (plan.lift_off_angular_velocity - lift_off.angular_velocity).norm();
  b.touched_down = record.touchdown.has_value();
  if (b.touched_down) {
    b.touchdown_bounce.value = (record.touchdown->base_position.head<2>() - final_state.base_position.head<2>()).norm();
    b.touchdown_angular_velocity.value = record.touchdown->angular_velocity.norm();
  } else {
    b.touchdown_bounce.value = settings.missing_touchdown_bounce;
    b.touchdown_angular_velocity.value = settings.missing_touchdown_angular_velocity;
  }
  b.action_limit.value = reward_terms::actionExcess(record.raw_action, settings.raw_action_limit);

  // Landing target reward.
  const Eigen::Vector3d& target = record.target.displacement;
  const Eigen::Vector2d landed_xy = final_state.base_position.head<2>() - record.start_base_position.head<2>();
  double feet_z = 0.0;
  for (const Eigen::Vector3d& f : record.final_foot_positions) feet_z += f.z();
  const double landed_z = feet_z / static_cast<double>(record.final_foot_positions.size()) - settings.foot_radius;
  b.landing_error_xy = (target.head<2>() - landed_xy).norm();
  const double z_error = std::abs(target.z() - landed_z);
  b.landing_error_z = z_error > settings.z_dead_band ? z_error : 0.0;
  b.landing_error = b.landing_error_xy + b.landing_error_z;
  b.jump_distance = target.norm();
  b.landing_reward = reward_terms::landingTargetReward(b.landing_error, b.jump_distance, settings);

  const std::vector<const RewardTerm*> all = b.terms();
  for (std::size_t i = 0; i < all.size(); ++i) (i < 6 ? b.running_cost : b.terminal_cost) += all[i]->cost();
  b.total_cost = b.running_cost + b.terminal_cost;
  b.penalty_gate = std::exp(-b.total_cost * b.total_cost / settings.penalty_scale);
  b.reward = b.landing_reward * b.penalty_gate;
  return b;
}

}  // namespace pronk::jump
