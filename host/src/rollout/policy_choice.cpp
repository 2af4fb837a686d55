// The policies `pronk run --policy` knows: the environment's analytic prior, or
// a policy file (docs/policy-format.md), which may be a residual over that
// prior (version 2: action = prior_action + network, or an aim correction:
// action = prior_action(observation + network)).
#include <memory>

#include "pronk/policy.h"
#include "pronk/rollout.h"

namespace pronk {

Policy makePolicy(const std::string& name, const pronk_factory& factory, const std::string& robot,
                  std::vector<std::string>* warnings) {
  if (name == "ballistic") {
    if (factory.environment->prior_action == nullptr) {
      throw Error(std::string("--policy ballistic: environment '") + factory.name +
                  "' has no analytic policy (prior_action)");
    }
    return [](const std::vector<double>& observation, EnvironmentInstance& env, uint64_t) {
      return env.priorAction(observation);
    };
  }
  auto network = std::make_shared<const MlpPolicy>(loadPolicy(name));
  const nlohmann::json& provenance = network->provenance();
  if (warnings && !robot.empty() && provenance.is_object() && provenance.contains("robot") &&
      provenance["robot"].is_string() && provenance["robot"].get<std::string>() != robot) {
    warnings->push_back(name + " was trained on the " + provenance["robot"].get<std::string>() +
                        "; this scenario's robot is the " + robot + " (a zero-shot transfer)");
  }
  const bool aim = network->prior() && network->prior()->kind == kAimPriorKind;
  // An aim correction's network outputs an offset of the observation.
  const int outputs = aim ? factory.observation_size : factory.action_size;
  if (network->observationSize() != factory.observation_size || network->actionSize() != outputs) {
    throw InputError(SourceLocation{name, 0}, "the policy maps " + std::to_string(network->observationSize()) +
                                                  " numbers to " + std::to_string(network->actionSize()) +
                                                  "; environment '" + factory.name + "' observes " +
                                                  std::to_string(factory.observation_size) + " and takes " +
                                                  std::to_string(factory.action_size) +
                                                  (aim ? " (an aim correction outputs an offset of the observation)"
                                                       : ""));
  }
  const auto act = [network](const std::vector<double>& observation) {
    const Eigen::VectorXd a =
        network->act(Eigen::Map<const Eigen::VectorXd>(observation.data(), static_cast<Eigen::Index>(observation.size())));
    return std::vector<double>(a.data(), a.data() + a.size());
  };
  if (!network->prior()) {
    return [act](const std::vector<double>& observation, EnvironmentInstance&, uint64_t) { return act(observation); };
  }
  const PolicyPrior& prior = *network->prior();
  if (prior.environment != factory.name) {
    throw InputError(SourceLocation{name, 0}, "a residual over environment '" + prior.environment +
                                                  "''s prior_action; this scenario's environment is '" + factory.name +
                                                  "'");
  }
  if (factory.environment->prior_action == nullptr) {
    throw InputError(SourceLocation{name, 0}, "a residual over the prior_action of environment '" + prior.environment +
                                                  "', but that environment (" + factory.name +
                                                  ") has no prior_action");
  }
  if (aim) {
    // The environment takes the aim as its task (its frame, e.g. the jump plane,
    // is the aim's); an aim the prior has no feasible action for falls back to
    // the task itself.
    return [act](const std::vector<double>& observation, EnvironmentInstance& env, uint64_t) {
      std::vector<double> aimed = act(observation);
      for (size_t i = 0; i < aimed.size(); ++i) aimed[i] += observation[i];
      EnvironmentInstance::PriorAction p = env.prior(aimed);
      if (p.infeasible) return env.priorAction(observation);
      env.retask(aimed);
      return std::move(p.action);
    };
  }
  return [act](const std::vector<double>& observation, EnvironmentInstance& env, uint64_t) {
    std::vector<double> action = env.priorAction(observation);
    const std::vector<double> residual = act(observation);
    for (size_t i = 0; i < action.size(); ++i) action[i] += residual[i];
    return action;
  };
}

}  // namespace pronk
