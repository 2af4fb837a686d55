// `pronk run` with an environment: jumps to the scenario's targets (or a sweep's
// cases) with a policy, a table, results files and videos.
#pragma once

#include "commands.h"
#include "pronk/rollout.h"
#include "pronk/scenario.h"

namespace pronk::cli {

// True when `pronk run` runs the scenario's environment (it has one and no
// --controller replaces it).
bool runsJumps(const Scenario& scenario, const RunOptions& options);

int runJumps(const CommonOptions& common, const RunOptions& options, const Scenario& scenario);

// `params` with each --param NAME=VALUE of `options` set (replacing one of that
// name); resolveParams then reports a bad name or value against the flag.
std::vector<ParamSetting> withParamOptions(std::vector<ParamSetting> params, const RunOptions& options);

// --jobs: the requested number of worker threads, or (0) the number of cores.
int jobsOf(int requested);

}  // namespace pronk::cli
