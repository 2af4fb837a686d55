// The sets `pronk eval` and `pronk check` run: a scenario file's <targets>
// ("targets") and each of its sweeps, each with its environment, policy and
// rollout pool.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "pronk/plugin_registry.h"
#include "pronk/rollout.h"
#include "pronk/scenario.h"

namespace pronk::cli {

struct SetToRun {
  std::string file;
  Scenario scenario;
  std::string set;   // "targets" or a sweep's name
  std::string name;  // <file stem>-<set>, unique among the run's sets
};

// Appends to `sets` the sets `wanted` of `file` (all of them when empty; a
// name the file lacks is skipped). Throws InputError naming the file when it
// has no <environment>, or none of the sets.
void addSets(std::vector<SetToRun>& sets, const std::string& file, const Scenario& scenario,
             const std::vector<std::string>& wanted);

// A set ready to run: its plugin registry (which must outlive the pool), the
// pool with the environment and the policy, the cases.
struct SetRollout {
  PluginRegistry registry;
  std::string policy;  // what runs: "ballistic" or a policy file
  std::vector<EpisodeCase> cases;
  std::unique_ptr<RolloutPool> pool;
};

// `policy` "" = the file's <environment policy>. Throws InputError naming the
// file or the flag.
std::unique_ptr<SetRollout> prepareSet(const CommonOptions& common, const SetToRun& set, const std::string& policy,
                                       int jobs, const std::atomic<bool>* stop);

}  // namespace pronk::cli
