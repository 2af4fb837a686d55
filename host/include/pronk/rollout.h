// The rollout engine: cases -> worlds -> episodes, on worker threads. The one
// loop that `pronk run`, eval, check and train share; what they differ in is
// the sink that consumes the records.
//
//   RolloutPool pool(setup, options);      // parses the URDF once
//   pool.run(cases, [](EpisodeRecord& r) { ... });   // records in case order
//
// Each worker owns one World, built from the one parsed RobotDescription and
// reused from case to case: a case that only moves the start or changes the
// terrain (step platforms) resets the state and swaps the terrain; a case that
// changes the robot or the simulation (a sweep's mass offset, damping,
// friction ...) gets a new World. An episode's seed is its case index, never
// its worker, and records reach the sink in case order, on the calling thread:
// results do not depend on the number of threads.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pronk/episode.h"
#include "pronk/plugin_registry.h"
#include "pronk/robot_description.h"
#include "pronk/scenario.h"

namespace pronk {

class World;

// What every episode of a run shares.
struct RolloutSetup {
  Scenario scenario;                       // the base; each case applies on top (applyCase)
  const pronk_factory* factory = nullptr;  // the environment
  std::string origin;                      // its library, for messages
  ResolvedParams params;                   // the environment's parameters
  EnvironmentSchema schema;                // what its metrics mean (ABI 1.3 declarations)
  // Called from the worker threads, concurrently: it must not share mutable
  // state between calls (an MlpPolicy is const; `ballistic` asks its own env).
  Policy policy;
  // What a user should hear before the run: a policy trained on another robot.
  std::vector<std::string> warnings;
};

struct RolloutOptions {
  int threads = 1;
  // Every tick's sample in the record's trace; otherwise the first and the last
  // only (what the landing needs), and no allocation per tick for samples.
  bool record_samples = false;
  bool record_body_poses = false;   // per-sample body poses (video); implies record_samples
  bool reuse_worlds = true;         // false: a World built from the URDF per case (the bench's baseline)
  double max_episode_s = 120;       // the environment ends an episode; this bounds a runaway one
  // End an episode once the robot is at rest after landing, held this long (s;
  // EpisodeOptions::end_at_rest); 0 runs every episode to the environment's end.
  double end_at_rest = 0.2;
  // When it becomes true (a signal handler's flag), no further case is handed
  // out: the running episodes finish and run() returns what was delivered.
  const std::atomic<bool>* stop = nullptr;
};

// One finished episode, as the sinks (report, learner, video) receive it.
struct EpisodeRecord {
  size_t index = 0;                 // case index = the episode's seed
  EpisodeCase episode;
  EnvironmentEpisodeResult result;  // task, observation, action, reward, trace, failure
  // The case could not be set up: nothing ran, the rest of the run goes on. A
  // case whose environment or policy throws pronk::Error fails alone too:
  // result.episode.failure, reason "error".
  std::optional<std::string> setup_error;
  // The setup refused the case's geometry (a step platform with no room for its
  // edge between the two stances): reported as a refused jump, not a failure.
  bool setup_refused = false;
};

using EpisodeSink = std::function<void(EpisodeRecord& record)>;

class RolloutPool {
 public:
  // Parses the platform's URDF once. Throws InputError for a robot that cannot be built.
  RolloutPool(RolloutSetup setup, RolloutOptions options);
  ~RolloutPool();
  RolloutPool(const RolloutPool&) = delete;
  RolloutPool& operator=(const RolloutPool&) = delete;

  // Runs every case (threads() at a time) and hands each record to `sink` in
  // case order, on the calling thread. An exception from the sink stops the run
  // after the running episodes and is rethrown. Returns the number of records
  // delivered (fewer than cases.size() only after stop()).
  size_t run(const std::vector<EpisodeCase>& cases, const EpisodeSink& sink);
  // The same for the cases `which` names (indices into `cases`, each the
  // record's index and seed, as in a whole run), delivered in the order of
  // `which`: a resumed evaluation runs what is left and gets what a whole run
  // would have given for those cases.
  size_t run(const std::vector<EpisodeCase>& cases, const std::vector<size_t>& which, const EpisodeSink& sink);
  // The environment's prior_action for each task, each from an environment
  // reset with that task on the base scenario's start pose (its own World,
  // built once; nothing is simulated), on the calling thread: what an
  // exploring policy's env.priorAction gives for that task in a case that only
  // moves the target. std::nullopt where the environment fails to give one.
  std::vector<std::optional<std::vector<double>>> priorActions(const std::vector<std::vector<double>>& tasks);

  // Asks a running run() to hand out no more cases (safe from any thread).
  void stop() { stop_ = true; }

  const RobotDescription& robot() const { return *robot_; }
  // Where the robot stands (World::footprint()): the cases' step platforms keep clear of it.
  const Footprint& footprint() const { return footprint_; }
  const RolloutSetup& setup() const { return setup_; }
  int threads() const { return options_.threads; }
  // Worlds built so far (for the bench: reuse means one per worker).
  size_t worldsBuilt() const { return worlds_built_; }

 private:
  struct Worker;
  EpisodeRecord runCase(Worker& worker, size_t index, const EpisodeCase& episode);

  RolloutSetup setup_;
  RolloutOptions options_;
  std::shared_ptr<const RobotDescription> robot_;
  Footprint footprint_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::unique_ptr<World> planning_world_;  // priorActions'
  std::atomic<bool> stop_{false};
  std::atomic<size_t> worlds_built_{0};
};

// The environment run a scenario asks for: its <environment> factory found in
// `registry`, its parameters resolved with `overrides` set over the file's
// (each reported against its own location), and the policy `policy_name`
// ("ballistic" or a policy file; "" leaves setup.policy to the caller, e.g.
// training's exploring policy). Throws InputError naming the file or flag.
RolloutSetup environmentSetup(const Scenario& scenario, const PluginRegistry& registry,
                              const std::vector<ParamSetting>& overrides, const std::string& policy_name);

// "ballistic": the environment's prior_action; otherwise a policy file, which
// for a residual (a version-2 file with a prior) gives prior_action + network.
// Throws InputError naming the file when it cannot be used with `factory` (its
// sizes, or a residual over another environment or one without prior_action).
// `robot`: the scenario's platform; a policy file trained on another one adds a
// warning naming both to `warnings` (a zero-shot transfer is allowed).
Policy makePolicy(const std::string& name, const pronk_factory& factory, const std::string& robot = "",
                  std::vector<std::string>* warnings = nullptr);

}  // namespace pronk
