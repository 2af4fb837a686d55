// The policies `pronk run --policy` knows: the environment's analytic prior, or
// a policy file (docs/policy-format.md).
#include <memory>

#include "pronk/policy.h"
#include "pronk/rollout.h"

namespace pronk {

Policy makePolicy(const std::string& name, const pronk_factory& factory) {
  if (name == "ballistic") {
    if (factory.environment->prior_action == nullptr) {
      throw Error(std::string("--policy ballistic: environment '") + factory.name +
                  "' has no analytic policy (prior_action)");
    }
    return [](const std::vector<double>& observation, EnvironmentInstance& env) { return env.priorAction(observation); };
  }
  auto network = std::make_shared<const MlpPolicy>(loadPolicy(name));
  if (network->observationSize() != factory.observation_size || network->actionSize() != factory.action_size) {
    throw InputError(SourceLocation{name, 0}, "the policy maps " + std::to_string(network->observationSize()) +
                                                  " numbers to " + std::to_string(network->actionSize()) +
                                                  "; environment '" + factory.name + "' observes " +
                                                  std::to_string(factory.observation_size) + " and takes " +
                                                  std::to_string(factory.action_size));
  }
  return [network](const std::vector<double>& observation, EnvironmentInstance&) {
    const Eigen::VectorXd a =
        network->act(Eigen::Map<const Eigen::VectorXd>(observation.data(), static_cast<Eigen::Index>(observation.size())));
    return std::vector<double>(a.data(), a.data() + a.size());
  };
}

}  // namespace pronk
