// The foot contact law, as a Simbody Force::Custom on the foot spheres:
//  - normal: Hunt-Crossley, fn = k d (1 + c ddot), clamped >= 0, d the sphere's
//    penetration into the top surface below it;
//  - tangential: an elasto-plastic "bristle": a spring-damper from a ground
//    anchor to a material point of the foot while it sticks (|f| <= mu_s fn),
//    Coulomb sliding at mu_k fn otherwise, with the anchor dragged along so
//    the spring alone carries the sliding force.
// The anchors are an auto-update discrete variable: calcForce writes the next
// anchors, the integrator swaps them in at the start of each step. This gives
// true stiction (no creep while standing) at the cost of an O(h) delay when a
// foot goes from slip to stick. Measurements: docs/physics.md.
#pragma once

#include <Simbody.h>

#include <vector>

#include "pronk/scenario.h"
#include "pronk/terrain.h"

namespace pronk {

struct FootSphere {
  SimTK::MobilizedBodyIndex body;
  SimTK::Vec3 center_body;  // sphere centre in the body frame, m
  double radius = 0;        // m
};

// Per-foot outcome of the contact law at one state.
struct FootContactState {
  bool in_contact = false;
  bool sliding = false;
  SimTK::Vec3 force_world{0};  // force of the terrain on the foot, N
  double penetration = 0;      // m
};

class FootContactForce : public SimTK::Force::Custom::Implementation {
 public:
  FootContactForce(const SimTK::SimbodyMatterSubsystem& matter, const SimTK::GeneralForceSubsystem& forces,
                   std::vector<FootSphere> feet, const Terrain& terrain, const ContactSpec& params);

  // Forces and flags at `state` (realized to Velocity), without touching the anchors.
  std::vector<FootContactState> evaluate(const SimTK::State& state) const;
  // Forget every anchor (as after a teleport of the robot): call on a state before stepping.
  void clearAnchors(SimTK::State& state) const;
  // Implicit contact (ContactSpec::implicit) over fixed steps of `step` s: each
  // foot's springs and dampers act as on an isolated point of the foot's
  // apparent mass (tangential, normal; kg), solved for the step's end velocity.
  // step 0: explicit, as without the option.
  void setImplicitStep(double step, std::vector<double> tangential_mass, std::vector<double> normal_mass);

  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>& particle_forces, SimTK::Vector& mobility_forces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  void realizeTopology(SimTK::State& state) const override;

 private:
  static constexpr int kPerFoot = 7;  // active, sliding, material point (3), anchor xy (2)
  // Computes forces into `out` and the next anchors into `next`.
  void compute(const SimTK::State& state, const SimTK::Vector& anchors, std::vector<FootContactState>& out,
               SimTK::Vector* next) const;

  const SimTK::SimbodyMatterSubsystem& matter_;
  const SimTK::GeneralForceSubsystem& forces_;
  std::vector<FootSphere> feet_;
  const Terrain& terrain_;
  ContactSpec params_;
  double implicit_step_ = 0;
  std::vector<double> tangential_mass_, normal_mass_;
  mutable SimTK::DiscreteVariableIndex anchors_index_;
};

}  // namespace pronk
