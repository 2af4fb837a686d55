// Running one episode: a controller drives a World for a duration, every tick
// recorded in a Trace. Contact changes (lift-off, touchdown) and failures
// become trace events.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pronk/controller.h"
#include "pronk/trace.h"
#include "pronk/world.h"

namespace pronk {

struct EpisodeOptions {
  double duration = 1.5;           // s
  // A sample per tick; otherwise the first and the final sample only (the
  // landing's inputs), and the loop allocates nothing for samples.
  bool record_samples = true;
  bool record_body_poses = false;  // per-sample poses of every body (for video)
  // The robot is at rest after a flight when, after a touchdown, every foot is
  // down, the CoM is slower than kRestSpeed and the trunk turns slower than
  // kRestRate; the trace's event "at_rest" marks when it last came to rest (and
  // stayed so to the end). > 0: end the episode once it has stayed at rest this
  // long (s); what would follow moves the landing by under a millimetre
  // (docs/performance.md).
  double end_at_rest = 0;
  // The paper's test terrain for a target with a height: once the trunk's
  // centre of mass starts to fall after the lift-off, the terrain becomes the
  // ground plane at `floor` plus this platform (ApexPlatform); the trace gets
  // an "apex_platform" event with the top's height.
  std::optional<ApexPlatform> apex_platform;
  // When it becomes true (a signal handler's flag) the episode ends at the next
  // control tick, as if its duration had passed, with a "stopped" event.
  const std::atomic<bool>* stop = nullptr;
};

// When, and with its top at what height, the apex platform appeared in an
// episode (the trace's "apex_platform" event), or nullopt. For videos that
// draw it.
struct ApexPlatformEvent {
  double time = 0;
  double top = 0;  // world z, m
};
std::optional<ApexPlatformEvent> apexPlatformEvent(const Trace& trace);

inline constexpr double kRestSpeed = 0.05;  // m/s, CoM
inline constexpr double kRestRate = 0.1;    // rad/s, trunk angular velocity

struct EpisodeResult {
  Trace trace;
  std::optional<Failure> failure;
  double wall_seconds = 0;         // time spent stepping
  StepStatistics statistics;
};

// Resets nothing: runs from the World's current state, until `duration` or the
// controller says it has finished. Controller errors (pronk::Error) end the
// episode as a failure with reason "controller".
EpisodeResult runEpisode(World& world, Controller& controller, const EpisodeOptions& options);

// One episode of an environment factory (one action per episode): reset with a
// task, the policy's action for the observation, act (the environment may
// reject the action: nothing is simulated), the ticks until the environment
// says done (at most options.duration), finish. The environment's events and
// metrics land in the episode trace.
struct EnvironmentEpisodeResult {
  std::vector<double> task, observation, action;
  std::optional<std::string> rejected;  // the environment's reason; then nothing ran
  EpisodeResult episode;                // samples and events (an empty trace when rejected)
  // finish()'s reward; 0 when the episode failed (non-foot contact, divergence,
  // controller error) or was rejected.
  double reward = 0;
  double environment_reward = 0;        // finish()'s value even for a failed episode
};

// A policy: observation -> action; it may ask the environment (e.g. for its
// prior_action). `seed` is the episode's (RolloutPool: its case index), so that
// an exploring policy can take the case's own noise, whichever thread runs it.
using Policy = std::function<std::vector<double>(const std::vector<double>& observation, EnvironmentInstance& env,
                                                 uint64_t seed)>;

EnvironmentEpisodeResult runEnvironmentEpisode(World& world, const pronk_factory& factory, const std::string& origin,
                                               const ResolvedParams& params, const std::vector<double>& task,
                                               uint64_t seed, const Policy& policy, const EpisodeOptions& options);

}  // namespace pronk
