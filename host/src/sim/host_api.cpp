// The plugin ABI's host side: the kinematics a plugin asks for, computed by the
// World, and plugin controller instances behind the host's Controller interface.
#include <atomic>
#include <cmath>
#include <optional>
#include <cstring>

#include "pronk/controller.h"

namespace pronk {
namespace {

const HostApi& self(void* host) { return *static_cast<const HostApi*>(host); }

// A plugin's warnings and errors also go into the episode's trace as events
// ("plugin_warning", "plugin_error": results.json says which jump had them).
// stderr gets every error but only the first kPrintedLogLines info and warning
// lines of a process, then one line saying so: a sweep or a training run would
// otherwise print a line for every infeasible plan.
constexpr int kPrintedLogLines = 10;
std::atomic<int> g_printed_log_lines{0};

void log(void* host, int32_t level, const char* message) {
  static const char* prefix[] = {"info", "warning", "error"};
  const int l = std::clamp(level, 0, 2);
  const char* text = message ? message : "";
  if (l >= 1 && host) {
    const HostApi& h = self(host);
    if (Trace* t = h.trace()) t->addEvent(h.world().time(), l == 1 ? "plugin_warning" : "plugin_error", text);
  }
  if (l < 2) {
    const int n = g_printed_log_lines.fetch_add(1);
    if (n > kPrintedLogLines) return;
    if (n == kPrintedLogLines) {
      std::fprintf(stderr, "plugin: further info and warning lines are not printed; each jump's warnings are "
                           "events of its results (plugin_warning)\n");
      return;
    }
  }
  std::fprintf(stderr, "plugin %s: %s\n", prefix[l], text);
}
bool validFoot(void* host, int32_t foot) { return foot >= 0 && foot < self(host).world().footCount(); }

int32_t jointCount(void* host) { return self(host).world().jointCount(); }
int32_t footCount(void* host) { return self(host).world().footCount(); }

const char* jointName(void* host, int32_t joint) {
  const auto& names = self(host).world().jointNames();
  return joint >= 0 && joint < static_cast<int32_t>(names.size()) ? names[joint].c_str() : nullptr;
}

pronk_status jointLimits(void* host, int32_t joint, double* lower, double* upper, double* velocity, double* effort) {
  const World& w = self(host).world();
  if (joint < 0 || joint >= w.jointCount()) return PRONK_ERROR_INVALID_ARGUMENT;
  const Joint& j = w.joint(joint);
  const double inf = std::numeric_limits<double>::infinity();
  if (lower) *lower = j.has_position_limits ? j.lower : -inf;
  if (upper) *upper = j.has_position_limits ? j.upper : inf;
  if (velocity) *velocity = j.velocity_limit > 0 ? j.velocity_limit : inf;
  if (effort) *effort = w.effortLimit(joint);
  return PRONK_OK;
}

double totalMass(void* host) { return self(host).world().totalMass(); }

void gravity(void* host, double g[3]) {
  const Eigen::Vector3d v = self(host).world().gravity();
  for (int i = 0; i < 3; ++i) g[i] = v(i);
}

double footRadius(void* host, int32_t foot) { return validFoot(host, foot) ? self(host).world().footRadius(foot) : 0; }

pronk_status footPositionWorld(void* host, int32_t foot, double p[3]) {
  if (!validFoot(host, foot)) return PRONK_ERROR_INVALID_ARGUMENT;
  const Eigen::Vector3d& v = self(host).world().state().foot_position[foot];
  for (int i = 0; i < 3; ++i) p[i] = v(i);
  return PRONK_OK;
}

// Kinematics callbacks run Simbody code, which may throw: no exception may cross
// into the plugin, so they become a status.
template <typename F>
pronk_status guarded(void* host, F&& f) {
  try {
    f();
    return PRONK_OK;
  } catch (const std::exception& e) {
    log(host, 2, e.what());
    return PRONK_ERROR_FAILED;
  }
}

pronk_status footJacobianWorld(void* host, int32_t foot, double* jacobian) {
  if (!validFoot(host, foot) || !jacobian) return PRONK_ERROR_INVALID_ARGUMENT;
  return guarded(host, [&] {
  const Eigen::MatrixXd J = self(host).world().footJacobianWorld(foot);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobian, J.rows(), J.cols()) = J;
  });
}

pronk_status footPositionBase(void* host, int32_t foot, const double* q, double p[3]) {
  if (!validFoot(host, foot) || !q) return PRONK_ERROR_INVALID_ARGUMENT;
  return guarded(host, [&] {
    const World& w = self(host).world();
    const Eigen::Vector3d v = w.footPositionBase(foot, Eigen::Map<const Eigen::VectorXd>(q, w.jointCount()));
    for (int i = 0; i < 3; ++i) p[i] = v(i);
  });
}

pronk_status legJacobianBase(void* host, int32_t foot, const double* q, double* jacobian) {
  if (!validFoot(host, foot) || !q || !jacobian) return PRONK_ERROR_INVALID_ARGUMENT;
  const World& w = self(host).world();
  if (w.legJoints()[foot].size() != 3) return PRONK_ERROR_UNSUPPORTED;
  return guarded(host, [&] {
    const Eigen::MatrixXd J = w.legJacobianBase(foot, Eigen::Map<const Eigen::VectorXd>(q, w.jointCount()));
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> out(jacobian);
    out = J;
  });
}

pronk_status centroidalMomentum(void* host, double angular[3], double inertia[9]) {
  return guarded(host, [&] {
    const World::CentroidalMomentum m = self(host).world().centroidalMomentum();
    if (angular) Eigen::Map<Eigen::Vector3d>{angular} = m.angular;
    if (inertia) Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>{inertia} = m.locked_inertia;
  });
}

pronk_status terrainTop(void* host, double x, double y, double* height, int32_t* surface) {
  if (!std::isfinite(x) || !std::isfinite(y)) return PRONK_ERROR_INVALID_ARGUMENT;
  const std::optional<Surface> top = self(host).world().terrain().topAt(x, y);
  if (!top) return PRONK_ERROR_UNSUPPORTED;
  if (height) *height = top->height;
  if (surface) *surface = top->box;
  return PRONK_OK;
}

void emitEvent(void* host, double time, const char* name, const char* detail) {
  if (Trace* t = self(host).trace()) t->addEvent(time, name ? name : "", detail ? detail : "");
}

void reportMetric(void* host, const char* name, double value) {
  if (!name || !*name) return;
  if (Trace* t = self(host).trace()) t->setMetric(name, value);
}


}  // namespace

HostApi::HostApi(const World& world, Trace* trace) : world_(world), trace_(trace) {
  api_.struct_size = sizeof(pronk_host_api);
  api_.host = this;
  api_.joint_count = jointCount;
  api_.foot_count = footCount;
  api_.joint_name = jointName;
  api_.joint_limits = jointLimits;
  api_.total_mass = totalMass;
  api_.gravity = gravity;
  api_.foot_radius = footRadius;
  api_.foot_position_world = footPositionWorld;
  api_.foot_jacobian_world = footJacobianWorld;
  api_.foot_position_base = footPositionBase;
  api_.leg_jacobian_base = legJacobianBase;
  api_.emit_event = emitEvent;
  api_.log = log;
  api_.report_metric = reportMetric;
  api_.centroidal_momentum = centroidalMomentum;
  api_.terrain_top = terrainTop;
}

AbiStateView::AbiStateView(const RobotState& s) {
  view_.struct_size = sizeof(pronk_robot_state);
  view_.time = s.time;
  view_.joint_count = static_cast<int32_t>(s.q.size());
  view_.q = s.q.data();
  view_.qd = s.qd.data();
  for (int i = 0; i < 3; ++i) {
    view_.base_position[i] = s.base_position(i);
    view_.base_linear_velocity[i] = s.base_linear_velocity(i);
    view_.base_angular_velocity[i] = s.base_angular_velocity(i);
    view_.com_position[i] = s.com_position(i);
    view_.com_velocity[i] = s.com_velocity(i);
  }
  for (int i = 0; i < 4; ++i) view_.base_quaternion[i] = s.base_quaternion(i);
  view_.foot_count = static_cast<int32_t>(s.foot_position.size());
  for (size_t f = 0; f < s.foot_position.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      foot_position_.push_back(s.foot_position[f](i));
      foot_force_.push_back(s.foot_force[f](i));
    }
  }
  view_.foot_position = foot_position_.data();
  view_.foot_force = foot_force_.data();
  view_.foot_in_contact = s.foot_in_contact.data();
}

const pronk_factory& checkFactoryFitsWorld(const pronk_factory& factory, pronk_factory_kind kind,
                                           const std::string& origin, const World& world) {
  const std::string kind_name = factoryKindName(kind);
  const std::string who = kind_name + " '" + factory.name + "' (" + origin + ")";
  const bool has_ops = kind == PRONK_FACTORY_CONTROLLER ? factory.controller != nullptr : factory.environment != nullptr;
  if (factory.kind != static_cast<uint32_t>(kind) || !has_ops) throw Error(who + " is not a " + kind_name);
  if (factory.joint_count != 0 && factory.joint_count != world.jointCount()) {
    throw Error(who + " works with " + std::to_string(factory.joint_count) + " joints; the robot has " +
                std::to_string(world.jointCount()));
  }
  if (factory.control_period != 0 && std::abs(factory.control_period - world.controlPeriod()) > 1e-12) {
    throw Error(who + " runs every " + std::to_string(factory.control_period) +
                " s; the scenario's control period is " + std::to_string(world.controlPeriod()) + " s");
  }
  return factory;
}

PluginController::PluginController(const pronk_factory& factory, const std::string& origin,
                                   const ResolvedParams& params, const World& world, Trace* trace)
    : host_(world, trace),
      instance_(std::make_unique<ControllerInstance>(checkFactoryFitsWorld(factory, PRONK_FACTORY_CONTROLLER, origin, world), origin, *host_.api(),
                                                     params)) {}

void PluginController::reset(const RobotState& state) {
  const AbiStateView view(state);
  instance_->reset(*view.get());
}

Eigen::VectorXd PluginController::compute(const RobotState& state) {
  const AbiStateView view(state);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(state.q.size());
  instance_->compute(*view.get(), tau.data());
  return tau;
}

}  // namespace pronk
