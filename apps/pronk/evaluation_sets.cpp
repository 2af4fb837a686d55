#include "evaluation_sets.h"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "pronk/controller_factory.h"
#include "run_jumps.h"

namespace pronk::cli {

void addSets(std::vector<SetToRun>& sets, const std::string& file, const Scenario& s,
             const std::vector<std::string>& wanted) {
  if (!s.environment) throw InputError({file, 0}, "needs an <environment> (the jumps' environment)");
  std::vector<std::string> names;
  if (!s.targets.empty()) names.push_back("targets");
  for (const SweepSpec& sweep : s.sweeps) names.push_back(sweep.name);
  if (!wanted.empty()) {
    std::vector<std::string> chosen;
    for (const std::string& w : wanted)
      if (std::find(names.begin(), names.end(), w) != names.end()) chosen.push_back(w);
    names = chosen;
  }
  if (names.empty()) {
    throw InputError({file, 0}, wanted.empty() ? "no <targets> and no <sweeps>: nothing to run"
                                               : "none of the --sweep sets is in this file");
  }
  const std::string stem = std::filesystem::path(file).stem().string();
  for (const std::string& set : names) {
    std::string name = stem + "-" + set;
    for (const SetToRun& other : sets)
      if (other.name == name) name += "-" + std::to_string(sets.size());  // two files of one stem
    sets.push_back({file, s, set, name});
  }
}

std::unique_ptr<SetRollout> prepareSet(const CommonOptions& common, const SetToRun& set, const std::string& policy,
                                       int jobs, const std::atomic<bool>* stop) {
  auto out = std::make_unique<SetRollout>();
  const EnvironmentSpec& spec = *set.scenario.environment;
  out->policy = policy.empty() ? spec.policy : policy;
  if (out->policy.empty()) {
    throw InputError(spec.where, "<environment>: no policy: give --policy ballistic or --policy FILE");
  }
  ControllerSpec as_controller{spec.factory, spec.plugin, spec.params, spec.where};
  loadPlugins(out->registry, common.plugin_paths, &as_controller);
  RolloutSetup setup = environmentSetup(set.scenario, out->registry, {}, out->policy);
  for (const std::string& w : setup.warnings) std::cerr << "warning: " << w << "\n";
  out->cases = set.set == "targets" ? targetCases(set.scenario) : sweepCases(set.scenario, set.set);
  RolloutOptions rollout;
  rollout.threads = std::min<int>(jobsOf(jobs), static_cast<int>(std::max<size_t>(out->cases.size(), 1)));
  rollout.stop = stop;
  out->pool = std::make_unique<RolloutPool>(std::move(setup), rollout);
  for (const std::string& w : out->pool->robot().warnings) std::cerr << "warning: " << w << "\n";
  return out;
}

}  // namespace pronk::cli
