// Controllers as the host runs them: built-in ones (stand, scripted_jump) and
// plugin factories behind the same interface.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "pronk/plugin_abi.h"
#include "pronk/plugin_registry.h"
#include "pronk/trace.h"
#include "pronk/world.h"

namespace pronk {

class Controller {
 public:
  virtual ~Controller() = default;
  // Before the first tick of an episode.
  virtual void reset(const RobotState& state) {}
  // One control tick: joint torques in controller order (N m).
  virtual Eigen::VectorXd compute(const RobotState& state) = 0;
  // True once the controller has ended the episode (after the tick that said so).
  virtual bool finished() const { return false; }
};

// Built-in controller names, in one place.
const std::vector<std::string>& builtinControllerNames();

// PD on every joint to the scenario's initial configuration plus gravity
// compensation: the weight is shared over the feet in contact by the
// minimum-norm solution of force and moment balance about the centre of mass,
// and mapped to joint torques through the foot Jacobians.
std::unique_ptr<Controller> makeStandController(const World& world, Trace* trace);

// A jump written in joint space (no plugin): stand, crouch, push, tucked
// flight, extend after the apex, land with gravity compensation. It exists to
// exercise and benchmark the simulation on a whole jump with landing.
std::unique_ptr<Controller> makeScriptedJumpController(const World& world, Trace* trace);

// Creates the built-in controller `name`; throws Error for an unknown name.
std::unique_ptr<Controller> makeBuiltinController(const std::string& name, const World& world, Trace* trace);

// Gravity-compensation torques: -J^T f over the feet in contact, f the
// minimum-norm distribution of m*(-g) (forces and moments about the CoM).
Eigen::VectorXd gravityCompensation(const World& world, const RobotState& state);

// Checks a factory's kind and the sizes it declares (joint count, control
// period) against the world it is to drive; throws Error naming the factory and
// `origin` (its library). Returns the factory.
const pronk_factory& checkFactoryFitsWorld(const pronk_factory& factory, pronk_factory_kind kind,
                                           const std::string& origin, const World& world);

// Binds a World (and the trace events go to) to the plugin ABI's host API.
// The returned object must outlive the plugin instance created with it.
class HostApi {
 public:
  HostApi(const World& world, Trace* trace);
  const pronk_host_api* api() const { return &api_; }
  const World& world() const { return world_; }
  Trace* trace() const { return trace_; }

 private:
  pronk_host_api api_{};
  const World& world_;
  Trace* trace_;
};

// A view of a RobotState in the ABI's layout (valid while `state` lives).
class AbiStateView {
 public:
  explicit AbiStateView(const RobotState& state);
  const pronk_robot_state* get() const { return &view_; }

 private:
  pronk_robot_state view_{};
  std::vector<double> foot_position_, foot_force_;
};

// A plugin controller (factory kind CONTROLLER) driving a World. Checks the
// factory's declared joint count and control period against the world, then
// owns the instance. `origin` names the library in messages.
class PluginController : public Controller {
 public:
  PluginController(const pronk_factory& factory, const std::string& origin, const ResolvedParams& params,
                   const World& world, Trace* trace);
  void reset(const RobotState& state) override;
  Eigen::VectorXd compute(const RobotState& state) override;

 private:
  HostApi host_;
  std::unique_ptr<ControllerInstance> instance_;
};

}  // namespace pronk
