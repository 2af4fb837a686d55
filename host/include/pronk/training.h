// Training a policy for a scenario's environment with PPO, through the rollout
// engine (`pronk train`, docs/training.md). The scenario's <training> element
// says what: the task region targets are drawn from, the batch, the networks,
// PPO's settings, a fixed validation set and the guidance.
//
// One iteration: draw jumps_per_iteration targets and as many exploration
// noise vectors on the calling thread, run them through one RolloutPool (its
// worlds reused all run long), PPO on (observation, residual, reward), and
// every few iterations the mean policy over the validation set. With
// `residual` the action is the environment's prior_action plus the learned
// residual, whose last layer starts at zero: iteration 0 is the planner.
// With `hindsight`, after PPO's update the actor's mean is fitted to the
// newest (achieved task, action - prior_action(achieved task)) pairs of every
// jump that ended standing (hindsight.h).
//
// Determinism: every random number comes from three Rng streams (the
// targets', the noise's and the learner's), all drawn on the calling thread;
// case i of an iteration takes noise column i whichever worker runs it. A seed
// fixes the run for any number of threads, and a checkpoint carries every
// stream, so that a resumed run continues bit for bit.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pronk/plugin_registry.h"
#include "pronk/rng.h"
#include "pronk/scenario.h"

namespace pronk {

// Targets uniform in the <training> region: x, y, z and yaw independently,
// roll and pitch 0, and z = 0 for the region's flat_share of them. A target
// with a height (z != 0) lies at least kLeastStepDistance from the start
// horizontally (its step platform's edge goes between): closer ones are drawn
// again. With placeEdges (step platforms with edges, <terrain
// step_platforms="true">) each case also draws its edge's place in the room
// between the stances (terrain.edge, uniform in 0 .. 1), and a case that
// cannot be set up (no room for an edge) is drawn again.
class TargetSampler {
 public:
  static constexpr double kLeastStepDistance = 0.15;  // m
  static constexpr int kMaxDraws = 10000;             // per target, before the region is called too narrow
  explicit TargetSampler(const TrainingSpec& spec);
  // `fits`: whether a case can be set up (applyCase with the robot's footprint).
  void placeEdges(std::function<bool(const EpisodeCase&)> fits);
  TargetSpec draw(Rng& rng) const;
  // n targets, named "<prefix> #k".
  std::vector<EpisodeCase> cases(Rng& rng, int n, const std::string& prefix) const;

 private:
  TrainingSpec spec_;
  std::function<bool(const EpisodeCase&)> fits_;  // set: edges are placed
};

// The validation set: validation_count targets of the region from their own
// stream (seeded by validation_seed, apart from the training stream by
// construction), the same for every iteration and every run of the file.
std::vector<EpisodeCase> validationCases(const TrainingSpec& spec, const TargetSampler& sampler);
inline std::vector<EpisodeCase> validationCases(const TrainingSpec& spec) {
  return validationCases(spec, TargetSampler(spec));
}

// What the command line changes of the file's <training>, and where to write.
struct TrainingRunOptions {
  int threads = 1;
  std::optional<int> iterations;           // --iterations: the run's total
  std::optional<int> jumps_per_iteration;  // --jumps
  std::optional<unsigned long> seed;       // --seed
  // The policy file written (at every checkpoint and at the end); the
  // checkpoint (STEM.checkpoint.json) and train_log.csv go beside it.
  std::string policy_path;
  std::string resume;                      // a checkpoint to continue from; "" = start afresh
  std::string command;                     // the command line, for the policy's provenance
  std::string pronk_version, git_commit;   // the build's, for the policy's provenance ("" leaves them out)
};

// A jump set's landing figures (the report's judgement of each jump).
struct JumpSetFigures {
  int jumps = 0, landed = 0, failed = 0, rejected = 0, setup_errors = 0;
  double error_median = 0, error_mean = 0;  // m, over the landed jumps (NaN when none)
  double within_02 = 0;                     // share of all jumps landed within 0.2 m
};

// One row of train_log.csv. Iteration 0 is the starting policy's validation
// (no batch); iteration k >= 1 collected batch k with the policy of k - 1 and
// updated it, and its validation (when validated) is of the policy after the
// update. NaN where a figure was not measured.
struct TrainingIteration {
  int iteration = 0;
  int iterations = 0;                  // the run's total
  long long jumps = 0;                 // training jumps so far
  JumpSetFigures batch;
  double reward_mean = 0, reward_std = 0;
  bool validated = false;
  JumpSetFigures validation;
  double critic_warmup_loss = 0;       // the warm-up's last epoch (NaN without one)
  // Hindsight (NaN without it): pairs in the buffer after this batch's, pairs
  // this batch added, the mean fit's last epoch loss.
  double hindsight_pairs = 0, hindsight_added = 0, hindsight_loss = 0;
  double oversampled = 0;              // targets of the batch drawn again from failed or refused ones
  double policy_loss = 0, value_loss = 0, entropy = 0, kl = 0, clip_fraction = 0;
  double learning_rate = 0, std_mean = 0, value_mean = 0;
  double actor_gradient_norm = 0, critic_gradient_norm = 0;
  double rollout_s = 0, update_s = 0, validation_s = 0;
  double jumps_per_s = 0;              // the batch's, in the rollout's wall time
  double wall_s = 0;                   // the run's so far (over resumes)
  double eta_s = 0;                    // to the run's last iteration
  // The batch's mean of each penalty the environment declares (the reward's
  // terms), over the jumps that reported it, named as the environment names
  // them; and the mean of their sum per jump.
  std::vector<std::string> penalty_names;
  std::vector<double> penalty_means;
  double penalty_sum_mean = 0;
};

struct TrainingOutcome {
  int iterations_done = 0;
  bool interrupted = false;            // stopped by the caller; the checkpoint holds the last whole iteration
  long long jumps = 0;
  double wall_s = 0;
  std::string policy_path, checkpoint_path, log_path;
};

using TrainingProgress = std::function<void(const TrainingIteration& row)>;

// The checkpoint's path beside a policy file: DIR/STEM.checkpoint.json.
std::string checkpointPathFor(const std::string& policy_path);
// The training log's and the curves' paths beside it: DIR/STEM.train_log.csv and
// DIR/STEM.train_curves.png, so that runs into one folder keep their own.
std::string trainingLogPathFor(const std::string& policy_path);
std::string trainingCurvesPathFor(const std::string& policy_path);

// Trains a policy for `scenario`'s environment as its <training> says (throws
// InputError without one). `on_row` is called on the calling thread after
// each row is final (iteration 0 included). When *stop becomes true the run
// ends after the running episodes: the interrupted iteration is dropped, the
// checkpoint and the policy are written as of the last whole iteration.
// Under mpirun a rank other than 0 only rolls out its share of each batch
// until rank 0 ends the run, and gets an empty outcome (docs/training.md).
TrainingOutcome trainPolicy(const Scenario& scenario, const PluginRegistry& registry, const TrainingRunOptions& options,
                            const TrainingProgress& on_row, const std::atomic<bool>* stop = nullptr);

}  // namespace pronk
