// Owners of plugin instances: create() and destroy() paired, status codes and
// the plugin's messages turned into pronk::Error on the host side.
#include <cmath>
#include <cstring>

#include "plugin_call.h"
#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

constexpr size_t kMessageSize = 1024;

struct Message {
  char text[kMessageSize] = "";
  std::string str() const {
    std::string s(text, strnlen(text, kMessageSize));
    return s.empty() ? "no message" : s;
  }
};

std::string describeFactory(const pronk_factory& f, const std::string& origin) {
  return factoryKindName(f.kind) + " '" + f.name + "' (from '" + origin + "')";
}

void* create(const pronk_factory& f, const std::string& origin, const pronk_host_api& host,
             const ResolvedParams& params, pronk_factory_kind kind) {
  if (f.kind != static_cast<uint32_t>(kind) || !f.create ||
      (kind == PRONK_FACTORY_CONTROLLER ? !f.controller : !f.environment)) {
    throw Error(describeFactory(f, origin) + " is not a " + factoryKindName(kind));
  }
  void* instance = nullptr;
  Message m;
  const PluginCallScope call(origin.c_str(), f.name, "create");
  const pronk_status st = f.create(&host, params.data(), params.size(), &instance, m.text, kMessageSize);
  if (st != PRONK_OK || !instance) {
    throw Error(describeFactory(f, origin) + " could not be created: " +
                (st == PRONK_OK ? std::string("create() returned no instance") : m.str()));
  }
  return instance;
}

}  // namespace

ControllerInstance::ControllerInstance(const pronk_factory& factory, const std::string& origin,
                                       const pronk_host_api& host, const ResolvedParams& params)
    : factory_(factory), origin_(origin), instance_(create(factory, origin, host, params, PRONK_FACTORY_CONTROLLER)) {}

ControllerInstance::~ControllerInstance() {
  const PluginCallScope call(origin_.c_str(), factory_.name, "destroy");
  factory_.controller->destroy(instance_);
}

std::string ControllerInstance::describe() const { return describeFactory(factory_, origin_); }

void ControllerInstance::reset(const pronk_robot_state& state) {
  if (!factory_.controller->reset) return;
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "reset");
  if (factory_.controller->reset(instance_, &state, m.text, kMessageSize) != PRONK_OK) {
    throw Error(describe() + ": reset failed: " + m.str());
  }
}

void ControllerInstance::compute(const pronk_robot_state& state, double* torque) {
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "compute");
  if (factory_.controller->compute(instance_, &state, torque, m.text, kMessageSize) != PRONK_OK) {
    throw Error(describe() + ": compute failed at t = " + std::to_string(state.time) + " s: " + m.str());
  }
}

EnvironmentInstance::EnvironmentInstance(const pronk_factory& factory, const std::string& origin,
                                         const pronk_host_api& host, const ResolvedParams& params)
    : factory_(factory), origin_(origin), instance_(create(factory, origin, host, params, PRONK_FACTORY_ENVIRONMENT)) {}

EnvironmentInstance::~EnvironmentInstance() {
  const PluginCallScope call(origin_.c_str(), factory_.name, "destroy");
  factory_.environment->destroy(instance_);
}

std::string EnvironmentInstance::describe() const { return describeFactory(factory_, origin_); }

std::vector<double> EnvironmentInstance::reset(const std::vector<double>& task, uint64_t seed,
                                               const pronk_robot_state& state) {
  std::vector<double> observation(static_cast<size_t>(factory_.observation_size), 0.0);
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "reset");
  if (factory_.environment->reset(instance_, task.data(), static_cast<int32_t>(task.size()), seed, &state,
                                  observation.data(), m.text, kMessageSize) != PRONK_OK) {
    throw Error(describe() + ": reset failed: " + m.str());
  }
  reset_seed_ = seed;
  reset_state_ = &state;
  return observation;
}

std::vector<double> EnvironmentInstance::retask(const std::vector<double>& task) {
  if (!reset_state_) throw Error(describe() + ": retask() needs a reset() before it and no act() since");
  return reset(task, reset_seed_, *reset_state_);
}

std::optional<std::string> EnvironmentInstance::act(const std::vector<double>& action) {
  if (static_cast<int32_t>(action.size()) != factory_.action_size) {
    throw Error(describe() + " takes " + std::to_string(factory_.action_size) + " action numbers, got " +
                std::to_string(action.size()));
  }
  reset_state_ = nullptr;  // the episode starts: no retask() now
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "act");
  const pronk_status st = factory_.environment->act(instance_, action.data(), m.text, kMessageSize);
  if (st == PRONK_REJECTED) return m.str();
  if (st != PRONK_OK) throw Error(describe() + ": act failed: " + m.str());
  return std::nullopt;
}

bool EnvironmentInstance::hasPriorAction() const { return factory_.environment->prior_action != nullptr; }

std::vector<double> EnvironmentInstance::priorAction(const std::vector<double>& observation) {
  return prior(observation).action;
}

EnvironmentInstance::PriorAction EnvironmentInstance::prior(const std::vector<double>& observation) {
  if (!hasPriorAction()) throw Error(describe() + " offers no prior action (analytic policy)");
  if (static_cast<int32_t>(observation.size()) != factory_.observation_size) {
    throw Error(describe() + " observes " + std::to_string(factory_.observation_size) + " numbers, got " +
                std::to_string(observation.size()));
  }
  PriorAction out;
  out.action.assign(static_cast<size_t>(factory_.action_size), 0.0);
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "prior_action");
  const pronk_status status =
      factory_.environment->prior_action(instance_, observation.data(), out.action.data(), m.text, kMessageSize);
  if (status == PRONK_REJECTED) {
    out.infeasible = m.str();
  } else if (status != PRONK_OK) {
    throw Error(describe() + ": prior_action failed: " + m.str());
  }
  for (double a : out.action) {
    if (!std::isfinite(a)) throw Error(describe() + ": prior_action returned a number that is not finite");
  }
  return out;
}

bool EnvironmentInstance::step(const pronk_robot_state& state, double* torque) {
  int32_t done = 0;
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "step");
  if (factory_.environment->step(instance_, &state, torque, &done, m.text, kMessageSize) != PRONK_OK) {
    throw Error(describe() + ": step failed at t = " + std::to_string(state.time) + " s: " + m.str());
  }
  return done != 0;
}

double EnvironmentInstance::finish(const pronk_robot_state& state) {
  double reward = 0;
  Message m;
  const PluginCallScope call(origin_.c_str(), factory_.name, "finish");
  if (factory_.environment->finish(instance_, &state, &reward, m.text, kMessageSize) != PRONK_OK) {
    throw Error(describe() + ": finish failed: " + m.str());
  }
  if (!std::isfinite(reward)) throw Error(describe() + ": finish returned a reward that is not finite");
  return reward;
}

}  // namespace pronk
