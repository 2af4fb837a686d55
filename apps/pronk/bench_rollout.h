// `pronk bench --rollout`: the rollout engine's throughput, lever by lever.
#pragma once

#include "commands.h"

namespace pronk::cli {

int rolloutBench(const CommonOptions& common, const BenchOptions& options);

}  // namespace pronk::cli
