// `pronk run` with an environment: jumps to the scenario's targets (or a sweep's
// cases) with a policy, a table, results files and videos.
#pragma once

#include "commands.h"
#include "pronk/episode.h"
#include "pronk/scenario.h"

namespace pronk::cli {

// True when `pronk run` runs the scenario's environment (it has one and no
// --controller replaces it).
bool runsJumps(const Scenario& scenario, const RunOptions& options);

int runJumps(const CommonOptions& common, const RunOptions& options, const Scenario& scenario);

// `params` with each --param NAME=VALUE of `options` set (replacing one of that
// name); resolveParams then reports a bad name or value against the flag.
std::vector<ParamSetting> withParamOptions(std::vector<ParamSetting> params, const RunOptions& options);

// "ballistic": the environment's prior_action; otherwise a policy file.
// Throws InputError for a file that cannot be used with `factory`.
Policy makePolicy(const std::string& name, const pronk_factory& factory);

}  // namespace pronk::cli
