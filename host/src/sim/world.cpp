#include "pronk/world.h"

#include <Simbody.h>

#include <cmath>
#include <limits>

#include "pronk/foot_contact.h"
#include "pronk/multibody.h"

namespace pronk {
namespace {

// A state whose kinetic energy per kilogram exceeds this has blown up: it is a
// whole-body speed of about 32 m/s, ten times a long jump's lift-off speed.
constexpr double kDivergenceEnergyPerKg = 500.0;
// Joint end stops (Simbody MobilityLinearStop, a Hunt-Crossley spring): a motor at
// 35.5 N m (the Go1's calf) holds a joint 0.018 rad past its limit; the
// dissipation (s/rad) damps the impact in proportion to the penetration.
constexpr double kJointStopStiffness = 2000.0;  // N m / rad
constexpr double kJointStopDissipation = 0.5;   // s / rad

// Points of a shape (in the body frame) whose entry into the terrain counts as contact.
std::vector<Eigen::Vector3d> probePoints(const Shape& shape) {
  std::vector<Eigen::Vector3d> points;
  if (shape.type == ShapeType::Box) {
    // Corners and points along the edges, at most 2 cm apart, so a long thin
    // link (a calf) that lies on a box edge is still seen.
    const Eigen::Vector3d h = 0.5 * shape.box_size;
    for (int axis = 0; axis < 3; ++axis) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      const int n = std::max(1, static_cast<int>(std::ceil(shape.box_size(axis) / 0.02)));
      for (int s1 : {-1, 1})
        for (int s2 : {-1, 1})
          for (int k = 0; k <= n; ++k) {
            Eigen::Vector3d p;
            p(axis) = -h(axis) + shape.box_size(axis) * k / n;
            p(a1) = s1 * h(a1);
            p(a2) = s2 * h(a2);
            points.push_back(shape.pose_body * p);
          }
    }
  } else if (shape.type == ShapeType::Cylinder) {
    for (int end : {-1, 1}) {
      for (int k = 0; k < 8; ++k) {
        const double a = 2 * M_PI * k / 8;
        points.push_back(shape.pose_body *
                         Eigen::Vector3d(shape.radius * std::cos(a), shape.radius * std::sin(a), 0.5 * end * shape.length));
      }
    }
  } else {
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d(axis) = sign * shape.radius;
        points.push_back(shape.pose_body * d);
      }
  }
  return points;
}

std::unique_ptr<SimTK::Integrator> makeIntegrator(const SimTK::MultibodySystem& system, const SimSpec& sim) {
  const double period = 1.0 / sim.control_rate;
  std::unique_ptr<SimTK::Integrator> integ;
  const std::string& name = sim.integrator;
  if (name == "semi_explicit_euler") {
    integ = std::make_unique<SimTK::SemiExplicitEulerIntegrator>(system, sim.step);
  } else if (name == "explicit_euler") {
    auto e = std::make_unique<SimTK::ExplicitEulerIntegrator>(system, sim.step);
    e->setFixedStepSize(sim.step);  // last: other setters would make it error-controlled again
    integ = std::move(e);
  } else {
    if (name == "semi_explicit_euler2") {
      integ = std::make_unique<SimTK::SemiExplicitEuler2Integrator>(system);
    } else if (name == "runge_kutta_merson") {
      integ = std::make_unique<SimTK::RungeKuttaMersonIntegrator>(system);
    } else if (name == "runge_kutta_3") {
      integ = std::make_unique<SimTK::RungeKutta3Integrator>(system);
    } else if (name == "verlet") {
      integ = std::make_unique<SimTK::VerletIntegrator>(system);
    } else {
      throw InputError(sim.where, "unknown integrator '" + name + "'");
    }
    integ->setAccuracy(sim.accuracy);
    integ->setMaximumStepSize(period);
  }
  // Steps must end exactly on control ticks: torques change there.
  integ->setAllowInterpolation(false);
  return integ;
}

}  // namespace

struct World::Impl {
  RobotDescription robot;
  PlatformSpec platform;
  SimSpec sim;
  Terrain terrain;

  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  std::unique_ptr<SimTK::Force::Gravity> gravity;
  std::unique_ptr<SimTK::Force::DiscreteForces> torques;
  FootContactForce* contact = nullptr;
  RobotMultibody mb;
  std::unique_ptr<SimTK::Integrator> integ;
  bool adaptive = false;  // error-controlled integrator
  mutable SimTK::State scratch;  // for kinematics at arbitrary joint positions
  // The joint positions the scratch state is realized at with the trunk at the
  // origin (empty: posed otherwise). A controller asks for a foot's position
  // and then its Jacobian at the same q; the second realize is skipped.
  mutable Eigen::VectorXd scratch_q;
  // Realizes the scratch state at q with the trunk at the origin, unless it is.
  void poseScratchAtOrigin(const Eigen::VectorXd& q) const {
    if (scratch_q.size() == q.size() && scratch_q == q) return;
    for (size_t i = 0; i < q_of.size(); ++i) scratch.updQ()[q_of[i]] = q(static_cast<Eigen::Index>(i));
    mb.root().setQToFitTransform(scratch, SimTK::Transform());
    system.realize(scratch, SimTK::Stage::Position);
    scratch_q = q;
  }

  // Controller order.
  std::vector<int> joint_of;               // controller joint -> description joint
  std::vector<int> u_of;                   // controller joint -> generalized speed index
  std::vector<int> q_of;                   // controller joint -> generalized coordinate index
  std::vector<std::string> joint_names;
  std::vector<double> effort;
  std::vector<std::vector<int>> leg_joints;
  std::vector<FootSphere> feet;
  std::vector<std::string> foot_links;
  std::vector<int> foot_body;              // description body of each foot
  struct Probe {
    int body;
    std::string link;
    std::vector<Eigen::Vector3d> points;
  };
  std::vector<Probe> probes;               // non-foot collision shapes
  double mass = 0;            // reported (without unreported_trunk_mass)
  double simulated_mass = 0;  // what the dynamics carry
};

World::World(const Scenario& scenario)
    : World(
          [&] {
            UrdfOptions options;
            options.package_paths = scenario.platform.package_paths;
            return loadUrdf(scenario.platform.urdf, options);
          }(),
          scenario.platform, scenario.sim, Terrain(scenario.ground, scenario.ground_height, scenario.terrain)) {}

World::World(const RobotDescription& robot, const PlatformSpec& platform, const SimSpec& sim, const Terrain& terrain)
    : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.robot = robot;
  w.platform = platform;
  w.sim = sim;
  w.terrain = terrain;
  if (platform.joints.armature != 0) {
    throw InputError(platform.where,
                     "armature (reflected rotor inertia) is not supported: Simbody has no per-joint armature; "
                     "set it to 0 (see docs/physics.md)");
  }
  w.mb = addRobot(w.matter, w.robot, platform.trunk_mass_offset + platform.unreported_trunk_mass);
  w.mass = w.robot.totalMass() + platform.trunk_mass_offset;  // what controllers are told
  w.simulated_mass = w.mass + platform.unreported_trunk_mass;

  // Feet and their legs, in the scenario's order.
  if (platform.feet.empty()) throw InputError(platform.feet_where, "no foot links given");
  std::vector<bool> joint_used(w.robot.joints.size(), false);
  for (const std::string& link : platform.feet) {
    const auto located = w.robot.locateLink(link);
    if (!located) throw InputError(platform.feet_where, "foot link '" + link + "' is not in " + w.robot.urdf_path);
    const auto [body, pose] = *located;
    if (body == 0) throw InputError(platform.feet_where, "foot link '" + link + "' is fixed to the root body");
    const CollisionShape* sphere = nullptr;
    for (const CollisionShape& c : w.robot.bodies[body].collisions) {
      if (c.link == link && c.shape.type == ShapeType::Sphere) sphere = &c;
    }
    if (!sphere) {
      throw InputError(platform.feet_where, "foot link '" + link + "' has no collision sphere in " + w.robot.urdf_path);
    }
    w.feet.push_back({w.mb.bodies[body].getMobilizedBodyIndex(), toVec3(sphere->shape.pose_body.translation()),
                      sphere->shape.radius});
    w.foot_links.push_back(link);
    w.foot_body.push_back(body);
    std::vector<int> chain;
    for (int b = body; b != 0; b = w.robot.bodies[b].parent) chain.insert(chain.begin(), w.robot.bodies[b].joint);
    std::vector<int> leg;
    for (int j : chain) {
      if (joint_used[j]) {
        throw InputError(platform.feet_where, "joint '" + w.robot.joints[j].name + "' is on the legs of two feet");
      }
      joint_used[j] = true;
      leg.push_back(static_cast<int>(w.joint_of.size()));
      w.joint_of.push_back(j);
    }
    w.leg_joints.push_back(leg);
  }
  // Joints on no leg (a tail, a head) come last.
  for (size_t j = 0; j < w.robot.joints.size(); ++j) {
    if (!joint_used[j]) w.joint_of.push_back(static_cast<int>(j));
  }

  // Non-foot collision shapes are probed against the terrain each tick.
  for (size_t b = 0; b < w.robot.bodies.size(); ++b) {
    for (const CollisionShape& c : w.robot.bodies[b].collisions) {
      bool is_foot = false;
      for (const std::string& f : w.foot_links) is_foot = is_foot || (c.link == f && c.shape.type == ShapeType::Sphere);
      if (is_foot) continue;
      // Points inside a foot sphere of the same body are the foot's business.
      std::vector<Eigen::Vector3d> points;
      for (const Eigen::Vector3d& p : probePoints(c.shape)) {
        bool in_foot = false;
        for (size_t f = 0; f < w.feet.size(); ++f) {
          if (w.foot_body[f] == static_cast<int>(b) && (p - toEigen(w.feet[f].center_body)).norm() < w.feet[f].radius)
            in_foot = true;
        }
        if (!in_foot) points.push_back(p);
      }
      w.probes.push_back({static_cast<int>(b), c.link, points});
    }
  }

  // Forces: gravity, joint torques (held per tick), foot contact, joint damping.
  const Vec3& g = sim.gravity;
  w.gravity = std::make_unique<SimTK::Force::Gravity>(w.forces, w.matter, SimTK::Vec3(g[0], g[1], g[2]));
  w.torques = std::make_unique<SimTK::Force::DiscreteForces>(w.forces, w.matter);
  auto* contact = new FootContactForce(w.matter, w.forces, w.feet, w.terrain, sim.contact);
  SimTK::Force::Custom(w.forces, contact);  // the force subsystem owns it
  w.contact = contact;
  for (int j : w.joint_of) {
    const Joint& joint = w.robot.joints[j];
    const double damping = platform.joints.damping >= 0 ? platform.joints.damping : joint.damping;
    if (damping > 0) {
      SimTK::Force::MobilityLinearDamper(w.forces, w.mb.bodies[joint.child_body], SimTK::MobilizerUIndex(0), damping);
    }
    // The URDF's position limits as physical stops: without them a landing could
    // bend a knee through its mechanical end and still count as standing.
    if (joint.has_position_limits && joint.lower < joint.upper) {
      SimTK::Force::MobilityLinearStop(w.forces, w.mb.bodies[joint.child_body], SimTK::MobilizerQIndex(0),
                                       kJointStopStiffness, kJointStopDissipation, joint.lower, joint.upper);
    }
  }

  w.system.realizeTopology();
  for (int j : w.joint_of) {
    const Joint& joint = w.robot.joints[j];
    const SimTK::MobilizedBody& mobod = w.mb.bodies[joint.child_body];
    w.u_of.push_back(mobod.getFirstUIndex(w.system.getDefaultState()));
    w.q_of.push_back(mobod.getFirstQIndex(w.system.getDefaultState()));
    w.joint_names.push_back(joint.name);
    double effort = joint.effort_limit > 0 ? joint.effort_limit * platform.joints.effort_scale
                                           : std::numeric_limits<double>::infinity();
    for (const auto& o : platform.joints.overrides) {
      if (o.joint == joint.name && o.effort) effort = *o.effort;
    }
    w.effort.push_back(effort);
  }
  for (const auto& o : platform.joints.overrides) {
    if (w.robot.findJoint(o.joint) < 0) throw InputError(o.where, "no joint named '" + o.joint + "' in the robot");
  }
  for (const auto& [name, value] : platform.joint_positions) {
    const auto at = platform.joint_position_where.find(name);
    if (w.robot.findJoint(name) < 0) {
      throw InputError(at != platform.joint_position_where.end() ? at->second : platform.where,
                       "no joint named '" + name + "' in the robot");
    }
  }
  for (const auto& leg : w.leg_joints) {
    if (!platform.stance.empty() && platform.stance.size() != leg.size()) {
      throw InputError(platform.initial_where.file.empty() ? platform.where : platform.initial_where, "stance has " + std::to_string(platform.stance.size()) +
                                           " values but a leg has " + std::to_string(leg.size()) + " joints");
    }
  }
  w.scratch = w.system.getDefaultState();
  w.scratch_q.resize(0);
  reset();
  if (sim.contact.implicit) {
    if (w.adaptive) {
      throw InputError(sim.contact.where, "<contact implicit=\"true\"> needs a fixed-step integrator "
                                          "(semi_explicit_euler or explicit_euler), not " + sim.integrator);
    }
    // Each foot's apparent mass, (J M^-1 J^T)^-1 along the ground and the
    // normal, in the initial stance: the mass the contact's springs and
    // dampers push against.
    const SimTK::State& s0 = w.integ->getState();
    std::vector<double> tangential, normal;
    for (const FootSphere& foot : w.feet) {
      SimTK::Matrix J;
      w.matter.calcStationJacobian(s0, foot.body, foot.center_body, J);
      SimTK::Matrix inverse_mass(3, 3);
      for (int r = 0; r < 3; ++r) {
        SimTK::Vector column(J.ncol()), Minv_column;
        for (int u = 0; u < J.ncol(); ++u) column[u] = J(r, u);
        w.matter.multiplyByMInv(s0, column, Minv_column);
        for (int c = 0; c < 3; ++c) {
          double dot = 0;
          for (int u = 0; u < J.ncol(); ++u) dot += J(c, u) * Minv_column[u];
          inverse_mass(c, r) = dot;
        }
      }
      tangential.push_back(2.0 / (inverse_mass(0, 0) + inverse_mass(1, 1)));
      normal.push_back(1.0 / inverse_mass(2, 2));
    }
    w.contact->setImplicitStep(sim.step, tangential, normal);
    foot_masses_ = {tangential, normal};
  }
}

World::~World() = default;

double World::controlPeriod() const { return 1.0 / impl_->sim.control_rate; }
int World::jointCount() const { return static_cast<int>(impl_->joint_of.size()); }
int World::footCount() const { return static_cast<int>(impl_->feet.size()); }
const std::vector<std::string>& World::jointNames() const { return impl_->joint_names; }
const std::vector<std::string>& World::footLinks() const { return impl_->foot_links; }
const std::vector<std::vector<int>>& World::legJoints() const { return impl_->leg_joints; }
const Joint& World::joint(int i) const { return impl_->robot.joints[impl_->joint_of[i]]; }
double World::effortLimit(int i) const { return impl_->effort[i]; }
double World::footRadius(int foot) const { return impl_->feet[foot].radius; }
double World::totalMass() const { return impl_->mass; }
Eigen::Vector3d World::gravity() const {
  const Vec3& g = impl_->sim.gravity;
  return {g[0], g[1], g[2]};
}
const RobotDescription& World::robot() const { return impl_->robot; }
const Terrain& World::terrain() const { return impl_->terrain; }
const PlatformSpec& World::platform() const { return impl_->platform; }
const SimSpec& World::sim() const { return impl_->sim; }

Eigen::VectorXd World::initialJointPositions() const {
  const Impl& w = *impl_;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(jointCount());
  for (const auto& leg : w.leg_joints) {
    for (size_t k = 0; k < leg.size() && k < w.platform.stance.size(); ++k) q(leg[k]) = w.platform.stance[k];
  }
  for (int i = 0; i < jointCount(); ++i) {
    auto it = w.platform.joint_positions.find(w.joint_names[i]);
    if (it != w.platform.joint_positions.end()) q(i) = it->second;
  }
  return q;
}

Footprint World::footprint() const {
  // The feet and the origins of the bodies that carry them (a quadruped's
  // knees, which a Go1 or an Aliengo holds behind its feet), at the trunk at
  // the origin.
  Footprint footprint;
  std::vector<Eigen::Vector3d> feet;
  const std::vector<Eigen::Isometry3d> poses =
      bodyPosesAt(Eigen::Vector3d::Zero(), Eigen::Vector4d(1, 0, 0, 0), initialJointPositions(), &feet);
  for (int f = 0; f < footCount(); ++f) {
    const Eigen::Vector3d knee = poses[static_cast<size_t>(impl_->foot_body[f])].translation();
    footprint.points.push_back({feet[f].x(), feet[f].y(), feet[f].z()});
    footprint.points.push_back({knee.x(), knee.y(), knee.z()});
  }
  return footprint;
}

void World::reset() {
  const PlatformSpec& p = impl_->platform;
  resetTo(Eigen::Vector3d(p.base_position[0], p.base_position[1], p.base_position[2]), p.base_yaw,
          initialJointPositions(), p.on_ground);
}

const std::pair<std::vector<double>, std::vector<double>>& World::footApparentMasses() const { return foot_masses_; }

void World::restart(const Vec3& base_position, double base_yaw, Terrain terrain) {
  impl_->platform.base_position = base_position;
  impl_->platform.base_yaw = base_yaw;
  impl_->terrain = std::move(terrain);  // in place: the contact force holds a reference to it
  reset();
}

void World::replaceTerrain(Terrain terrain) { impl_->terrain = std::move(terrain); }

void World::resetTo(const Eigen::Vector3d& base_position, double base_yaw, const Eigen::VectorXd& q,
                    bool place_on_ground) {
  Impl& w = *impl_;
  SimTK::State state = w.system.getDefaultState();
  for (int i = 0; i < jointCount(); ++i) state.updQ()[w.q_of[i]] = q(i);
  const SimTK::Rotation yaw(base_yaw, SimTK::ZAxis);
  w.mb.root().setQToFitTransform(state, SimTK::Transform(yaw, toVec3(base_position)));
  if (place_on_ground) {
    w.system.realize(state, SimTK::Stage::Position);
    double lift = std::numeric_limits<double>::infinity();
    for (const FootSphere& foot : w.feet) {
      const SimTK::Vec3 c = w.matter.getMobilizedBody(foot.body).getBodyTransform(state) * foot.center_body;
      const auto top = w.terrain.topAt(c[0], c[1]);
      const double surface = top ? top->height : 0.0;
      lift = std::min(lift, c[2] - foot.radius - surface);
    }
    Eigen::Vector3d placed = base_position;
    placed.z() -= lift;  // the lowest foot just touches its surface
    w.mb.root().setQToFitTransform(state, SimTK::Transform(yaw, toVec3(placed)));
  }
  state.updU() = 0;
  state.setTime(0);
  w.system.realize(state, SimTK::Stage::Position);
  w.contact->clearAnchors(state);
  w.torques->clearAllForces(state);
  w.integ = makeIntegrator(w.system, w.sim);
  // stepTo returns after this many steps, so that the step budget is checked
  // within a control period too.
  w.integ->setInternalStepLimit(std::max(1, static_cast<int>(std::ceil(w.sim.max_steps_per_second / w.sim.control_rate))));
  w.adaptive = w.sim.integrator != "semi_explicit_euler" && w.sim.integrator != "explicit_euler";
  w.integ->initialize(state);
  failure_.reset();
  stats_ = {};
  readState();
}

void World::setBaseVelocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  Impl& w = *impl_;
  SimTK::State& s = w.integ->updAdvancedState();
  w.mb.root().setUToFitVelocity(s, SimTK::SpatialVec(toVec3(angular), toVec3(linear)));
  w.integ->reinitialize(SimTK::Stage::Velocity, false);
  readState();
}

bool World::step(const Eigen::VectorXd& torque) {
  Impl& w = *impl_;
  if (failure_) return false;
  if (torque.size() != jointCount()) {
    throw Error("World::step: " + std::to_string(torque.size()) + " torques for " + std::to_string(jointCount()) +
                " joints");
  }
  const double period = controlPeriod();
  const double t_next = (stats_.control_ticks + 1) * period;
  try {
    SimTK::State& advanced = w.integ->updAdvancedState();
    SimTK::Vector mobility(advanced.getNU(), 0.0);
    for (int i = 0; i < jointCount(); ++i) {
      const double tau = std::isfinite(torque(i)) ? torque(i) : 0.0;
      if (!std::isfinite(torque(i))) {
        failure_ = Failure{state_.time, "diverged", "controller returned a non-finite torque for joint '" +
                                                        w.joint_names[i] + "'"};
        return false;
      }
      mobility[w.u_of[i]] = std::clamp(tau, -w.effort[i], w.effort[i]);
    }
    w.torques->setAllMobilityForces(advanced, mobility);
    // In flight nothing but this bound limits an error-controlled step, and the
    // first-order methods' flight error grows with it; in stance the contact
    // sets the step (docs/physics.md).
    bool airborne = true;
    for (uint8_t c : state_.foot_in_contact) airborne = airborne && !c;
    if (w.adaptive) w.integ->setMaximumStepSize(airborne ? std::min(period, w.sim.flight_max_step) : period);
    w.integ->reinitialize(SimTK::Stage::Dynamics, false);
    const long steps_before = w.integ->getNumStepsTaken();
    // The budget is an average over the episode so far (at least kBudgetWindow
    // of it): an impact may take a thousand steps in one control period at a
    // tight accuracy, a model too stiff to simulate takes that in every one.
    constexpr double kBudgetWindow = 0.01;
    const double window = std::max(t_next, kBudgetWindow);
    const long budget = static_cast<long>(std::ceil(w.sim.max_steps_per_second * window)) - stats_.integrator_steps;
    while (w.integ->getTime() < t_next - 1e-12) {
      if (w.integ->getNumStepsTaken() - steps_before >= budget) {
        stats_.integrator_steps += w.integ->getNumStepsTaken() - steps_before;
        char text[200];
        std::snprintf(text, sizeof text,
                      "the integrator needed more than %ld steps in the first %g s (max_steps_per_second %g): the "
                      "model is too stiff to simulate",
                      stats_.integrator_steps, window, w.sim.max_steps_per_second);
        failure_ = Failure{w.integ->getTime(), "step_budget", text};
        return false;
      }
      const auto status = w.integ->stepTo(t_next);
      if (status == SimTK::Integrator::EndOfSimulation || w.integ->isSimulationOver()) {
        failure_ = Failure{w.integ->getTime(), "diverged",
                           "the integrator stopped: " +
                               SimTK::Integrator::getTerminationReasonString(w.integ->getTerminationReason())};
        return false;
      }
    }
    stats_.integrator_steps += w.integ->getNumStepsTaken() - steps_before;
  } catch (const std::exception& e) {
    failure_ = Failure{w.integ->getTime(), "diverged", std::string("the integrator failed: ") + e.what()};
    return false;
  }
  ++stats_.control_ticks;

  const SimTK::State& s = w.integ->getState();
  const SimTK::Vector& q = s.getQ();
  const SimTK::Vector& u = s.getU();
  for (int i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i])) {
      failure_ = Failure{s.getTime(), "diverged", "a position became NaN or infinite"};
      return false;
    }
  }
  for (int i = 0; i < u.size(); ++i) {
    if (!std::isfinite(u[i])) {
      failure_ = Failure{s.getTime(), "diverged", "a velocity became NaN or infinite"};
      return false;
    }
  }
  w.system.realize(s, SimTK::Stage::Velocity);
  const double kinetic = w.matter.calcKineticEnergy(s);
  if (kinetic > kDivergenceEnergyPerKg * w.simulated_mass) {
    failure_ = Failure{s.getTime(), "diverged",
                       "kinetic energy " + std::to_string(kinetic) + " J exceeds " +
                           std::to_string(kDivergenceEnergyPerKg * w.simulated_mass) + " J (runaway)"};
    return false;
  }
  readState();
  for (const Impl::Probe& probe : w.probes) {
    const SimTK::Transform& X = w.mb.bodies[probe.body].getBodyTransform(s);
    for (const Eigen::Vector3d& p : probe.points) {
      const Eigen::Vector3d at = toEigen(X * toVec3(p));
      if (w.terrain.contains(at)) {
        char where[96];
        std::snprintf(where, sizeof where, " at (%.3f, %.3f, %.3f)", at.x(), at.y(), at.z());
        failure_ = Failure{s.getTime(), "non_foot_contact",
                           "link '" + probe.link + "' touched the terrain" + where};
        return false;
      }
    }
  }
  return true;
}

void World::readState() {
  Impl& w = *impl_;
  const SimTK::State& s = w.integ->getState();
  w.system.realize(s, SimTK::Stage::Velocity);
  RobotState& r = state_;
  r.time = s.getTime();
  const int n = jointCount();
  r.q.resize(n);
  r.qd.resize(n);
  for (int i = 0; i < n; ++i) {
    r.q(i) = s.getQ()[w.q_of[i]];
    r.qd(i) = s.getU()[w.u_of[i]];
  }
  const SimTK::Transform& X = w.mb.root().getBodyTransform(s);
  r.base_position = toEigen(X.p());
  const SimTK::Quaternion quat = X.R().convertRotationToQuaternion();
  r.base_quaternion = Eigen::Vector4d(quat[0], quat[1], quat[2], quat[3]);
  const SimTK::SpatialVec& V = w.mb.root().getBodyVelocity(s);
  r.base_angular_velocity = toEigen(V[0]);
  r.base_linear_velocity = toEigen(V[1]);
  r.com_position = toEigen(w.matter.calcSystemMassCenterLocationInGround(s));
  r.com_velocity = toEigen(w.matter.calcSystemMassCenterVelocityInGround(s));
  const std::vector<FootContactState> contacts = w.contact->evaluate(s);
  const int feet = footCount();
  r.foot_position.resize(feet);
  r.foot_force.resize(feet);
  r.foot_in_contact.resize(feet);
  for (int f = 0; f < feet; ++f) {
    const FootSphere& foot = w.feet[f];
    r.foot_position[f] = toEigen(w.matter.getMobilizedBody(foot.body).getBodyTransform(s) * foot.center_body);
    r.foot_force[f] = toEigen(contacts[f].force_world);
    r.foot_in_contact[f] = contacts[f].in_contact ? 1 : 0;
  }
}

World::CentroidalMomentum World::centroidalMomentum() const {
  const Impl& w = *impl_;
  const SimTK::State& s = w.integ->getState();
  CentroidalMomentum m;
  m.angular = toEigen(w.matter.calcSystemCentralMomentum(s)[0]);
  const SimTK::Inertia central = w.matter.calcSystemMassPropertiesInGround(s).calcCentralInertia();
  const SimTK::Mat33 I = central.toMat33();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.locked_inertia(r, c) = I(r, c);
  return m;
}

Eigen::MatrixXd World::footJacobianWorld(int foot) const {
  const Impl& w = *impl_;
  const SimTK::State& s = w.integ->getState();
  SimTK::RowVector_<SimTK::Vec3> js;
  w.matter.calcStationJacobian(s, w.feet[foot].body, w.feet[foot].center_body, js);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 6 + jointCount());
  const int base_u = w.mb.root().getFirstUIndex(s);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 6; ++c) J(r, c) = js[base_u + c][r];
    for (int i = 0; i < jointCount(); ++i) J(r, 6 + i) = js[w.u_of[i]][r];
  }
  return J;
}

Eigen::VectorXd World::footForcesToJointTorques(const std::vector<int>& feet,
                                                const std::vector<Eigen::Vector3d>& forces) const {
  const Impl& w = *impl_;
  const SimTK::State& s = w.integ->getState();
  SimTK::Array_<SimTK::MobilizedBodyIndex> bodies;
  SimTK::Array_<SimTK::Vec3> stations;
  SimTK::Vector_<SimTK::Vec3> f(int(feet.size()));
  for (size_t k = 0; k < feet.size(); ++k) {
    bodies.push_back(w.feet[feet[k]].body);
    stations.push_back(w.feet[feet[k]].center_body);
    f[int(k)] = toVec3(forces[k]);
  }
  SimTK::Vector generalized;
  // O(n) and no Jacobian formed: cheaper than calcStationJacobian per foot.
  w.matter.multiplyByStationJacobianTranspose(s, bodies, stations, f, generalized);
  Eigen::VectorXd tau(jointCount());
  for (int i = 0; i < jointCount(); ++i) tau(i) = generalized[w.u_of[i]];
  return tau;
}

Eigen::Vector3d World::footPositionBase(int foot, const Eigen::VectorXd& q) const {
  const Impl& w = *impl_;
  w.poseScratchAtOrigin(q);
  return toEigen(w.matter.getMobilizedBody(w.feet[foot].body).getBodyTransform(w.scratch) * w.feet[foot].center_body);
}

Eigen::MatrixXd World::legJacobianBase(int foot, const Eigen::VectorXd& q) const {
  const Impl& w = *impl_;
  w.poseScratchAtOrigin(q);
  SimTK::RowVector_<SimTK::Vec3> js;
  w.matter.calcStationJacobian(w.scratch, w.feet[foot].body, w.feet[foot].center_body, js);
  const std::vector<int>& leg = w.leg_joints[foot];
  Eigen::MatrixXd J(3, leg.size());
  for (size_t k = 0; k < leg.size(); ++k)
    for (int r = 0; r < 3; ++r) J(r, k) = js[w.u_of[leg[k]]][r];
  return J;
}

std::vector<Eigen::Isometry3d> World::bodyPosesAt(const Eigen::Vector3d& base_position,
                                                  const Eigen::Vector4d& base_quaternion, const Eigen::VectorXd& q,
                                                  std::vector<Eigen::Vector3d>* feet) const {
  const Impl& w = *impl_;
  SimTK::State& s = w.scratch;
  w.scratch_q.resize(0);  // posed elsewhere than the origin from here on
  for (int i = 0; i < jointCount(); ++i) s.updQ()[w.q_of[i]] = q(i);
  const SimTK::Rotation R(SimTK::Quaternion(base_quaternion(0), base_quaternion(1), base_quaternion(2),
                                            base_quaternion(3)));
  w.mb.root().setQToFitTransform(s, SimTK::Transform(R, toVec3(base_position)));
  w.system.realize(s, SimTK::Stage::Position);
  if (feet) {
    feet->clear();
    for (const FootSphere& foot : w.feet)
      feet->push_back(toEigen(w.matter.getMobilizedBody(foot.body).getBodyTransform(s) * foot.center_body));
  }
  return posesIn(s);
}

std::vector<Eigen::Isometry3d> World::posesIn(const SimTK::State& s) const {
  const Impl& w = *impl_;
  std::vector<Eigen::Isometry3d> poses;
  for (const SimTK::MobilizedBody& b : w.mb.bodies) {
    const SimTK::Transform& X = b.getBodyTransform(s);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) T.linear()(i, j) = X.R()[i][j];
      T.translation()(i) = X.p()[i];
    }
    poses.push_back(T);
  }
  return poses;
}

std::vector<Eigen::Isometry3d> World::bodyPoses() const { return posesIn(impl_->integ->getState()); }

}  // namespace pronk
