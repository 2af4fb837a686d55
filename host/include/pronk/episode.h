// Running one episode: a controller drives a World for a duration, every tick
// recorded in a Trace. Contact changes (lift-off, touchdown) and failures
// become trace events.
#pragma once

#include <optional>

#include "pronk/controller.h"
#include "pronk/trace.h"
#include "pronk/world.h"

namespace pronk {

struct EpisodeOptions {
  double duration = 1.5;           // s
  bool record_body_poses = false;  // per-sample poses of every body (for video)
};

struct EpisodeResult {
  Trace trace;
  std::optional<Failure> failure;
  double wall_seconds = 0;         // time spent stepping
  StepStatistics statistics;
};

// Resets nothing: runs from the World's current state. Controller errors
// (pronk::Error) end the episode as a failure with reason "controller".
EpisodeResult runEpisode(World& world, Controller& controller, const EpisodeOptions& options);

}  // namespace pronk
