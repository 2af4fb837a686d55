// The simulated world: a robot built from its URDF, static terrain, the foot
// contact law and gravity, stepped by a fixed control period with joint
// torques held constant over each period (zero-order hold, as on a robot).
// A World knows nothing about jumping; controllers see it through RobotState
// and the kinematics queries below.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pronk/robot_description.h"
#include "pronk/scenario.h"
#include "pronk/terrain.h"

namespace SimTK {
class State;
}

namespace pronk {

// Everything a controller may read at a control tick (world frame, SI units).
struct RobotState {
  double time = 0;
  Eigen::VectorXd q, qd;                     // controller joint order
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();
  Eigen::Vector4d base_quaternion{1, 0, 0, 0};  // w, x, y, z
  Eigen::Vector3d base_linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d base_angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> foot_position;  // sphere centres
  std::vector<Eigen::Vector3d> foot_force;     // force of the terrain on each foot, N
  std::vector<uint8_t> foot_in_contact;
};

// Why an episode stopped early.
struct Failure {
  double time = 0;
  std::string reason;   // "non_foot_contact", "diverged"
  std::string detail;   // e.g. "body 'FR_calf' touched the terrain"
};

// Measured integration work, for benchmarks.
struct StepStatistics {
  long integrator_steps = 0;
  long control_ticks = 0;
};

class World {
 public:
  // Builds the model. Throws InputError for a URDF or foot link problem.
  World(const Scenario& scenario);
  World(const RobotDescription& robot, const PlatformSpec& platform, const SimSpec& sim,
        const Terrain& terrain);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Back to the scenario's initial pose at rest, time 0.
  void reset();
  // Another episode in the same Simbody system: a new start (base position and
  // yaw, as PlatformSpec's) and terrain, then reset(). What the system is built
  // from (robot, gains, damping, contact law) stays; the terrain is geometry
  // that the contact and the probes read each step, so it may change.
  void restart(const Vec3& base_position, double base_yaw, Terrain terrain);
  // Replaces the terrain without touching the robot's state, for terrain that
  // changes during an episode (an apex platform). The contact reads it from the
  // next step on; a foot in contact then meets the new surface under it.
  void replaceTerrain(Terrain terrain);
  // Sets the initial pose explicitly: base position and yaw, joint positions.
  void resetTo(const Eigen::Vector3d& base_position, double base_yaw, const Eigen::VectorXd& q,
               bool place_on_ground);

  // Gives the base a velocity (world frame) at the current time, joints keep theirs.
  void setBaseVelocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular);

  // Advances one control period with `torque` (controller order, N m) held
  // constant. Torques are clamped to the joint effort limits. Returns false
  // (and sets failure()) when the robot touched the terrain with a non-foot
  // body or the simulation diverged; the world then stays where it was.
  bool step(const Eigen::VectorXd& torque);

  const RobotState& state() const { return state_; }
  const std::optional<Failure>& failure() const { return failure_; }
  double time() const { return state_.time; }
  double controlPeriod() const;
  const StepStatistics& statistics() const { return stats_; }

  // --- the robot, in controller order ---
  int jointCount() const;
  int footCount() const;
  const std::vector<std::string>& jointNames() const;
  const std::vector<std::string>& footLinks() const;
  // Joint indices (controller order) of each foot's leg, trunk outwards.
  const std::vector<std::vector<int>>& legJoints() const;
  const Joint& joint(int i) const;            // URDF data of controller joint i
  double effortLimit(int i) const;            // after the scenario's scaling and overrides
  double footRadius(int foot) const;
  // The mass controllers are told (URDF + trunk_mass_offset; an unreported
  // trunk mass is simulated but not counted here).
  double totalMass() const;
  Eigen::Vector3d gravity() const;
  const RobotDescription& robot() const;
  const Terrain& terrain() const;
  const PlatformSpec& platform() const;
  const SimSpec& sim() const;
  // The initial joint configuration from the scenario (controller order).
  Eigen::VectorXd initialJointPositions() const;
  // The feet and the knees (the origins of the bodies that carry the feet) in
  // the trunk frame at the initial joints: where the robot stands (the step
  // platforms' edges keep clear of it, applyCase).
  Footprint footprint() const;

  // --- kinematics at the current state ---
  // 3 x (6 + joints): d(foot velocity, world)/d(u), u = [base angular velocity
  // (world), base linear velocity (world), joint velocities].
  Eigen::MatrixXd footJacobianWorld(int foot) const;
  // Whole-body angular momentum about the centre of mass (world, N m s) and the
  // rotational inertia about it with the joints locked (world, kg m^2).
  struct CentroidalMomentum {
    Eigen::Vector3d angular = Eigen::Vector3d::Zero();
    Eigen::Matrix3d locked_inertia = Eigen::Matrix3d::Zero();
  };
  CentroidalMomentum centroidalMomentum() const;
  // Joint torques (controller order) J^T f for forces f (world) at the given
  // feet: what the legs must apply to exert those forces, with the sign of J^T.
  Eigen::VectorXd footForcesToJointTorques(const std::vector<int>& feet,
                                           const std::vector<Eigen::Vector3d>& forces) const;
  // Forward kinematics in the trunk frame for joint positions q (any state).
  Eigen::Vector3d footPositionBase(int foot, const Eigen::VectorXd& q) const;
  // d(foot position in trunk frame)/d(q of that leg's joints), 3 x leg size.
  Eigen::MatrixXd legJacobianBase(int foot, const Eigen::VectorXd& q) const;
  // With an implicit contact: each foot's apparent mass (tangential, normal; kg)
  // in the initial stance, which the contact uses (empty otherwise).
  const std::pair<std::vector<double>, std::vector<double>>& footApparentMasses() const;
  // World poses of every description body (for traces and rendering).
  std::vector<Eigen::Isometry3d> bodyPoses() const;
  // The same for a given base pose and joint positions (any state), and the
  // foot sphere centres there: re-creates a recorded frame without simulating.
  std::vector<Eigen::Isometry3d> bodyPosesAt(const Eigen::Vector3d& base_position, const Eigen::Vector4d& base_quaternion,
                                             const Eigen::VectorXd& q, std::vector<Eigen::Vector3d>* feet = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  RobotState state_;
  std::optional<Failure> failure_;
  StepStatistics stats_;
  std::pair<std::vector<double>, std::vector<double>> foot_masses_;
  void readState();
  std::vector<Eigen::Isometry3d> posesIn(const SimTK::State& state) const;
};

}  // namespace pronk
