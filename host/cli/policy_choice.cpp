// The policies `pronk run --policy` knows.
#include "jump_runs.h"

namespace pronk::cli {

Policy makePolicy(const std::string& name, const pronk_factory& factory) {
  if (name == "ballistic") {
    if (factory.environment->prior_action == nullptr) {
      throw Error(std::string("--policy ballistic: environment '") + factory.name +
                  "' has no analytic policy (prior_action)");
    }
    return [](const std::vector<double>& observation, EnvironmentInstance& env) { return env.priorAction(observation); };
  }
  throw InputError(SourceLocation{name, 0}, "policy files are not readable yet");
}

}  // namespace pronk::cli
