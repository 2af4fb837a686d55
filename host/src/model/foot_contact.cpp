#include "pronk/foot_contact.h"

#include <cmath>

namespace pronk {

using SVec3 = SimTK::Vec3;

FootContactForce::FootContactForce(const SimTK::SimbodyMatterSubsystem& matter,
                                   const SimTK::GeneralForceSubsystem& forces, std::vector<FootSphere> feet,
                                   const Terrain& terrain, const ContactSpec& params)
    : matter_(matter), forces_(forces), feet_(std::move(feet)), terrain_(terrain), params_(params) {}

void FootContactForce::realizeTopology(SimTK::State& state) const {
  SimTK::Vector initial(kPerFoot * static_cast<int>(feet_.size()), 0.0);
  anchors_index_ = state.allocateAutoUpdateDiscreteVariable(
      forces_.getMySubsystemIndex(), SimTK::Stage::Dynamics, new SimTK::Value<SimTK::Vector>(initial),
      SimTK::Stage::Velocity);
}

void FootContactForce::setImplicitStep(double step, std::vector<double> tangential_mass,
                                       std::vector<double> normal_mass) {
  implicit_step_ = step;
  tangential_mass_ = std::move(tangential_mass);
  normal_mass_ = std::move(normal_mass);
}

void FootContactForce::clearAnchors(SimTK::State& state) const {
  auto& v = SimTK::Value<SimTK::Vector>::updDowncast(
      state.updDiscreteVariable(forces_.getMySubsystemIndex(), anchors_index_));
  v.upd() = 0;
}

void FootContactForce::compute(const SimTK::State& state, const SimTK::Vector& anchors,
                               std::vector<FootContactState>& out, SimTK::Vector* next) const {
  out.assign(feet_.size(), FootContactState{});
  if (next) *next = 0;
  for (size_t i = 0; i < feet_.size(); ++i) {
    const FootSphere& foot = feet_[i];
    const SimTK::MobilizedBody& body = matter_.getMobilizedBody(foot.body);
    const SimTK::Transform& X_GB = body.getBodyTransform(state);
    const SVec3 center = X_GB * foot.center_body;
    const auto surface = terrain_.surfaceBelow(center[0], center[1], center[2]);
    if (!surface) continue;
    const double depth = surface->height - (center[2] - foot.radius);
    if (depth <= 0) continue;

    // The contact point: the sphere's lowest point projected on the surface.
    const SVec3 contact_world(center[0], center[1], surface->height);
    const SVec3 contact_body = ~X_GB * contact_world;
    const SVec3 contact_velocity = body.findStationVelocityInGround(state, contact_body);
    const double depth_rate = -contact_velocity[2];
    const double h = implicit_step_;
    double fn = params_.stiffness * depth * (1 + params_.dissipation * depth_rate);
    if (h > 0) {
      // Spring k and damper b taken at the step's end (implicit Euler) on a point
      // of the foot's apparent mass m: the velocity term becomes (b + h k) v with
      // v the step's end velocity, v_end ~ v m / (m + h (b + h k)) when the
      // other forces balance the spring's (a loaded foot at rest stays put).
      const double k = params_.stiffness, b = params_.stiffness * params_.dissipation * depth;
      const double damping = b + h * k;
      fn = k * depth + damping * depth_rate / (1 + h * damping / normal_mass_[i]);
    }
    if (fn <= 0) continue;

    const double mu_s = surface->mu ? *surface->mu : params_.mu_static;
    const double mu_k = surface->mu ? std::min(*surface->mu, params_.mu_dynamic) : params_.mu_dynamic;
    const int k = kPerFoot * static_cast<int>(i);
    const bool was_active = anchors[k] > 0.5;
    const bool was_sliding = anchors[k + 1] > 0.5;

    // Bristle deflection s from the anchor and the velocity of the anchored material point.
    double sx = 0, sy = 0, vx = contact_velocity[0], vy = contact_velocity[1];
    if (was_active) {
      const SVec3 point_body(anchors[k + 2], anchors[k + 3], anchors[k + 4]);
      const SVec3 point_world = X_GB * point_body;
      const SVec3 point_velocity = body.findStationVelocityInGround(state, point_body);
      sx = point_world[0] - anchors[k + 5];
      sy = point_world[1] - anchors[k + 6];
      vx = point_velocity[0];
      vy = point_velocity[1];
    }
    double fx = -params_.tangential_stiffness * sx - params_.tangential_damping * vx;
    double fy = -params_.tangential_stiffness * sy - params_.tangential_damping * vy;
    if (h > 0) {
      const double k = params_.tangential_stiffness, damping = params_.tangential_damping + h * k;
      const double scale = 1.0 / (1 + h * damping / tangential_mass_[i]);
      fx = -k * sx - damping * vx * scale;
      fy = -k * sy - damping * vy * scale;
    }
    const double trial = std::hypot(fx, fy);
    const double limit = (was_sliding ? mu_k : mu_s) * fn;
    bool sliding = false;
    if (trial > limit && trial > 0) {
      sliding = true;
      const double scale = mu_k * fn / trial;
      fx *= scale;
      fy *= scale;
      // Reset the deflection so the spring alone carries the sliding force.
      sx = -fx / params_.tangential_stiffness;
      sy = -fy / params_.tangential_stiffness;
    }

    FootContactState& result = out[i];
    result.in_contact = true;
    result.sliding = sliding;
    result.force_world = SVec3(fx, fy, fn);
    result.penetration = depth;
    if (next) {
      // Re-anchor on the current contact point, keeping the deflection (the sphere may roll).
      (*next)[k] = 1;
      (*next)[k + 1] = sliding ? 1 : 0;
      (*next)[k + 2] = contact_body[0];
      (*next)[k + 3] = contact_body[1];
      (*next)[k + 4] = contact_body[2];
      (*next)[k + 5] = contact_world[0] - sx;
      (*next)[k + 6] = contact_world[1] - sy;
    }
  }
}

std::vector<FootContactState> FootContactForce::evaluate(const SimTK::State& state) const {
  const auto& anchors = SimTK::Value<SimTK::Vector>::downcast(
                            state.getDiscreteVariable(forces_.getMySubsystemIndex(), anchors_index_))
                            .get();
  std::vector<FootContactState> out;
  compute(state, anchors, out, nullptr);
  return out;
}

void FootContactForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                                 SimTK::Vector_<SVec3>&, SimTK::Vector&) const {
  const SimTK::SubsystemIndex sub = forces_.getMySubsystemIndex();
  const auto& anchors =
      SimTK::Value<SimTK::Vector>::downcast(state.getDiscreteVariable(sub, anchors_index_)).get();
  auto& next = SimTK::Value<SimTK::Vector>::updDowncast(state.updDiscreteVarUpdateValue(sub, anchors_index_)).upd();
  std::vector<FootContactState> out;
  compute(state, anchors, out, &next);
  state.markDiscreteVarUpdateValueRealized(sub, anchors_index_);
  for (size_t i = 0; i < feet_.size(); ++i) {
    if (!out[i].in_contact) continue;
    const SimTK::MobilizedBody& body = matter_.getMobilizedBody(feet_[i].body);
    const SimTK::Transform& X_GB = body.getBodyTransform(state);
    const SVec3 center = X_GB * feet_[i].center_body;
    const SVec3 contact_world(center[0], center[1], center[2] - feet_[i].radius + out[i].penetration);
    body.applyForceToBodyPoint(state, ~X_GB * contact_world, out[i].force_world, body_forces);
  }
}

}  // namespace pronk
