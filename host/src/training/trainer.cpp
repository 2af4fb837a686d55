// trainPolicy: the training loop of `pronk train` (pronk/training.h): targets
// and noise drawn on the calling thread, the jumps through one RolloutPool,
// PPO on the residuals, validation of the mean policy, the log, checkpoints
// and policy files. Under `mpirun` rank 0 runs this loop and learns; every
// rank rolls out a share of each batch (docs/training.md, "Across processes").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

#include <Eigen/Core>

#include "pronk/communicator.h"
#include "pronk/error.h"
#include "pronk/ppo.h"
#include "pronk/report.h"
#include "pronk/rollout.h"
#include "pronk/training.h"
#include "case_result.h"
#include "hindsight.h"
#include "training_files.h"
#include "training_streams.h"

namespace pronk {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// What the rollout's policy reads: set on the calling thread before pool.run
// and left alone while it runs.
struct PolicyState {
  const PpoLearner* learner = nullptr;
  bool residual = true;  // action = prior_action(observation) + network
  bool aim = false;      // action = prior_action(observation + network)
  const Eigen::MatrixXd* noise = nullptr;  // action x cases standard normals; null: the mean policy
  std::vector<CaseDraw>* draws = nullptr;  // one per case; null: nothing recorded
};

// The network's output u = mean(observation) + std * noise[case]; the action is
// prior_action(observation) + u (residual), prior_action(observation + u) (aim)
// or u.
Policy explorationPolicy(std::shared_ptr<const PolicyState> state) {
  return [state](const std::vector<double>& observation, EnvironmentInstance& env, uint64_t seed) {
    const PolicyState& s = *state;
    Eigen::VectorXd residual = s.learner->mean(
        Eigen::Map<const Eigen::VectorXd>(observation.data(), static_cast<Eigen::Index>(observation.size())));
    if (s.noise) {
      if (seed >= static_cast<uint64_t>(s.noise->cols())) throw Error("training: a case without its noise");
      const Eigen::VectorXd& log_std = s.learner->actor().logStd();
      for (Eigen::Index i = 0; i < residual.size(); ++i) {
        residual[i] += std::exp(log_std[i]) * (*s.noise)(i, static_cast<Eigen::Index>(seed));
      }
    }
    if (s.aim) {
      // As makePolicy's aim correction: an aim without a feasible plan falls back to the task.
      std::vector<double> aimed = observation;
      for (size_t i = 0; i < aimed.size(); ++i) aimed[i] += residual[static_cast<Eigen::Index>(i)];
      EnvironmentInstance::PriorAction p = env.prior(aimed);
      Eigen::VectorXd taken = residual;
      if (p.infeasible) {
        p.action = env.priorAction(observation);
        taken.setZero();
      } else {
        env.retask(aimed);
      }
      if (s.draws) (*s.draws)[seed] = CaseDraw{true, std::move(residual), Eigen::VectorXd(), std::move(taken)};
      return p.action;
    }
    std::vector<double> action(static_cast<size_t>(residual.size()), 0.0);
    if (s.residual) action = env.priorAction(observation);
    Eigen::VectorXd prior = Eigen::Map<const Eigen::VectorXd>(action.data(), static_cast<Eigen::Index>(action.size()));
    for (size_t i = 0; i < action.size(); ++i) action[i] += residual[static_cast<Eigen::Index>(i)];
    if (s.draws) (*s.draws)[seed] = CaseDraw{true, std::move(residual), std::move(prior), Eigen::VectorXd()};
    return action;
  };
}

// Standard normals, one column per case, drawn column by column.
Eigen::MatrixXd drawNoise(Rng& rng, int rows, int cases) {
  Eigen::MatrixXd z(rows, cases);
  for (int c = 0; c < cases; ++c)
    for (int i = 0; i < rows; ++i) z(i, c) = rng.normal();
  return z;
}

// Landing figures of a jump set, as the report judges each jump.
class FiguresSink {
 public:
  // The report's judgement of the jump, for the caller too (none for a case
  // that could not be set up).
  std::optional<JumpOutcome> add(const CaseResult& r) {
    ++f_.jumps;
    if (!r.outcome) {
      ++f_.setup_errors;
      return std::nullopt;
    }
    const JumpOutcome& o = *r.outcome;
    if (o.status == "failed") ++f_.failed;
    if (o.status == "rejected") ++f_.rejected;
    if (o.status == "ok" || o.status == "missed") {
      ++f_.landed;
      errors_.push_back(o.landing.error);
      if (o.landing.error <= 0.2) ++within_;
    }
    return o;
  }
  JumpSetFigures figures() const {
    JumpSetFigures f = f_;
    f.error_median = median(errors_);
    f.error_mean = errors_.empty() ? kNaN : std::accumulate(errors_.begin(), errors_.end(), 0.0) / errors_.size();
    f.within_02 = f.jumps > 0 ? static_cast<double>(within_) / f.jumps : kNaN;
    return f;
  }

 private:
  JumpSetFigures f_;
  std::vector<double> errors_;
  int within_ = 0;
};

// Each penalty's mean over the jumps that reported it, and the mean per jump
// of their sum (over the jumps that reported any).
class PenaltyMeans {
 public:
  explicit PenaltyMeans(size_t count) : sums_(count, 0.0), counts_(count, 0) {}
  void add(const std::vector<double>& values) {
    double sum = 0;
    bool any = false;
    for (size_t i = 0; i < values.size() && i < sums_.size(); ++i) {
      if (!std::isfinite(values[i])) continue;
      sums_[i] += values[i];
      ++counts_[i];
      sum += values[i];
      any = true;
    }
    if (any) total_ += sum, ++jumps_;
  }
  std::vector<double> means() const {
    std::vector<double> m(sums_.size(), kNaN);
    for (size_t i = 0; i < sums_.size(); ++i)
      if (counts_[i] > 0) m[i] = sums_[i] / counts_[i];
    return m;
  }
  double sumMean() const { return jumps_ > 0 ? total_ / jumps_ : kNaN; }

 private:
  std::vector<double> sums_;
  std::vector<int> counts_;
  double total_ = 0;
  int jumps_ = 0;
};

PpoConfig ppoConfigOf(const TrainingSpec& t) {
  PpoConfig c;
  c.actor_hidden_sizes = t.actor_hidden_sizes;
  c.critic_hidden_sizes = t.critic_hidden_sizes;
  c.actor_init.zero_last_layer = t.residual || t.aim;  // iteration 0 is exactly the prior
  c.initial_std = t.initial_std;
  c.loss.clip = t.clip;
  c.loss.entropy_coefficient = t.entropy_coefficient;
  c.epochs = t.epochs;
  c.minibatches = t.minibatches;
  c.learning_rate = t.learning_rate;
  c.desired_kl = t.desired_kl;
  c.update_actor = t.ppo_actor;
  return c;
}

// The settings a resumed run must share with the checkpoint's to continue it.
json settingsJson(const TrainingSpec& t) {
  return {{"seed", t.seed},
          {"jumps_per_iteration", t.jumps_per_iteration},
          {"region", {t.x.min, t.x.max, t.y.min, t.y.max, t.z.min, t.z.max, t.yaw.min, t.yaw.max}},
          {"flat_share", t.flat_share},
          {"actor_hidden_sizes", t.actor_hidden_sizes},
          {"critic_hidden_sizes", t.critic_hidden_sizes},
          {"epochs", t.epochs},
          {"minibatches", t.minibatches},
          {"learning_rate", t.learning_rate},
          {"clip", t.clip},
          {"entropy_coefficient", t.entropy_coefficient},
          {"desired_kl", t.desired_kl},
          {"initial_std", t.initial_std},
          {"residual", t.residual},
          {"aim", t.aim},
          {"critic_warmup", t.critic_warmup},
          {"critic_warmup_epochs", t.critic_warmup_epochs},
          {"ppo_actor", t.ppo_actor},
          {"hindsight", t.hindsight},
          {"hindsight_epochs", t.hindsight_epochs},
          {"hindsight_samples", t.hindsight_samples},
          {"hindsight_minibatch", t.hindsight_minibatch},
          {"hindsight_learning_rate", t.hindsight_learning_rate},
          {"hindsight_prior_step", t.hindsight_prior_step},
          {"mirror", t.mirror},
          {"oversample", t.oversample}};
}

// Observation scaling: the task region onto [-1, 1] when the observation is
// the task (x, y, z, yaw, roll, pitch) as the jump environment's is; otherwise none.
ObservationScaling scalingOf(const TrainingSpec& t, int observation_size) {
  if (observation_size != 6) return ObservationScaling::identity(observation_size);
  Eigen::VectorXd low(6), high(6);
  low << t.x.min, t.y.min, t.z.min, t.yaw.min, 0, 0;
  high << t.x.max, t.y.max, t.z.max, t.yaw.max, 0, 0;
  return ObservationScaling::fromBox(low, high);
}

class Trainer {
 public:
  Trainer(const Scenario& scenario, const PluginRegistry& registry, const TrainingRunOptions& options,
          const TrainingProgress& on_row, const std::atomic<bool>* stop)
      : scenario_(scenario), options_(options), on_row_(on_row), stop_(stop), spec_(specOf(scenario, options)),
        sampler_(spec_), target_rng_(training_streams::targetSeed(spec_.seed)),
        noise_rng_(training_streams::noiseSeed(spec_.seed)), hindsight_(spec_.hindsight_samples) {
    RolloutSetup setup = environmentSetup(scenario, registry, {}, "");
    factory_name_ = setup.factory->name;
    for (const MetricSpec& m : setup.schema.metrics)
      if (m.kind == MetricSpec::Kind::Penalty) penalty_names_.push_back(m.name);
    origin_ = setup.origin;
    if ((spec_.residual || spec_.aim) && setup.factory->environment->prior_action == nullptr) {
      throw InputError(spec_.where, std::string("<training>: ") + (spec_.aim ? "aim" : "residual") +
                                        "=\"true\" needs the environment's prior_action as its prior; environment '" +
                                        factory_name_ + "' has none (write <guidance residual=\"false\" aim=\"false\">)");
    }
    observation_size_ = setup.factory->observation_size;
    // The network's outputs: an offset of the observation for an aim correction.
    action_size_ = spec_.aim ? observation_size_ : setup.factory->action_size;
    if (spec_.mirror) {
      // The mirror image of an aim pair is the pair with every task number (and its
      // offset) times the environment's mirror signs: both live in task space.
      if (static_cast<int>(setup.schema.task_mirror.size()) != observation_size_) {
        throw InputError(spec_.where, "<training>: mirror=\"true\", but environment '" + factory_name_ +
                                          "' declares no task mirror (plugin ABI 1.5 pronk_factory::task_mirror)");
      }
      mirror_ = Eigen::Map<const Eigen::VectorXd>(setup.schema.task_mirror.data(), observation_size_);
    }
    state_ = std::make_shared<PolicyState>();
    state_->residual = spec_.residual;
    state_->aim = spec_.aim;
    setup.policy = explorationPolicy(state_);
    paths_.policy = options.policy_path;
    paths_.checkpoint = checkpointPathFor(options.policy_path);
    paths_.log = trainingLogPathFor(options.policy_path);
    // Under mpirun only rank 0 reads the checkpoint: the others get the policy with each round.
    if (!options.resume.empty() && Communicator::world().root()) {
      resume(options.resume);
    } else {
      learner_ = std::make_unique<PpoLearner>(ppoConfigOf(spec_), scalingOf(spec_, observation_size_), action_size_,
                                              spec_.seed);
    }
    state_->learner = learner_.get();
    RolloutOptions rollout;
    rollout.threads = std::max(1, options.threads);
    pool_ = std::make_unique<RolloutPool>(std::move(setup), rollout);
    if (scenario.step_platforms == StepPlatforms::edge) {
      // Real boxes: each case places its edge, and a target with no room for
      // one between the stances is drawn again.
      sampler_.placeEdges([this](const EpisodeCase& c) {
        try {
          applyCase(scenario_, c, pool_->footprint());
          return true;
        } catch (const InputError&) {
          return false;
        }
      });
    }
    validation_ = validationCases(spec_, sampler_);
  }

  TrainingOutcome run() {
    start_ = Clock::now();
    TrainingOutcome out;
    out.policy_path = paths_.policy;
    out.checkpoint_path = paths_.checkpoint;
    out.log_path = paths_.log;
    if (done_ == 0 && log_.empty() && spec_.validation_count > 0) {
      TrainingIteration row = newRow(0);
      const auto t0 = Clock::now();
      row.validated = validate(row.validation);
      row.validation_s = secondsSince(t0);
      if (!row.validated) return finish(out, true);
      finishRow(row);
    }
    // A validation that a signal cut short is run on resuming, into its
    // iteration's row: the validation of the end is never skipped.
    if (done_ > 0 && spec_.validation_count > 0 && validationDue(done_) && !log_.empty() &&
        !training_files::rowValidated(log_.back(), penalty_names_)) {
      JumpSetFigures figures;
      if (!validate(figures)) return finish(out, true);
      training_files::setRowValidation(log_.back(), figures, penalty_names_);
      last_validation_ = training_files::lastValidation(log_, penalty_names_);
      training_files::writeLog(paths_.log, log_, penalty_names_);
    }
    for (int k = done_ + 1; k <= spec_.iterations; ++k) {
      const bool whole = iterate(k);
      if (!whole || stopRequested()) return finish(out, true);
      if (k % spec_.checkpoint_every == 0 && k < spec_.iterations) save();
    }
    return finish(out, false);
  }

 private:
  struct Paths {
    std::string policy, checkpoint, log;
  };

  static TrainingSpec specOf(const Scenario& scenario, const TrainingRunOptions& options) {
    if (!scenario.training) {
      throw InputError({scenario.file, 0}, "no <training> element: nothing to train (docs/scenario-format.md)");
    }
    TrainingSpec t = *scenario.training;
    if (options.iterations) t.iterations = *options.iterations;
    if (options.jumps_per_iteration) t.jumps_per_iteration = *options.jumps_per_iteration;
    if (options.seed) t.seed = *options.seed;
    if (t.iterations < 1) throw Error("--iterations: must be >= 1");
    if (t.jumps_per_iteration < t.minibatches) {
      throw Error("--jumps " + std::to_string(t.jumps_per_iteration) + ": must be >= the <ppo> minibatches (" +
                  std::to_string(t.minibatches) + ")");
    }
    return t;
  }

  bool stopRequested() const { return stop_ && stop_->load(); }
  bool validationDue(int k) const { return k % spec_.validate_every == 0 || k == spec_.iterations; }

  TrainingIteration newRow(int k) const {
    TrainingIteration row;
    row.iteration = k;
    row.iterations = spec_.iterations;
    row.jumps = jumps_;
    for (double* v : {&row.reward_mean, &row.reward_std, &row.critic_warmup_loss, &row.hindsight_pairs,
                      &row.hindsight_added, &row.hindsight_loss, &row.oversampled, &row.policy_loss, &row.value_loss,
                      &row.entropy, &row.kl, &row.clip_fraction, &row.learning_rate, &row.std_mean, &row.value_mean,
                      &row.actor_gradient_norm, &row.critic_gradient_norm, &row.jumps_per_s,
                      &row.batch.error_median, &row.batch.error_mean, &row.batch.within_02,
                      &row.validation.error_median, &row.validation.error_mean, &row.validation.within_02,
                      &row.penalty_sum_mean}) {
      *v = kNaN;
    }
    row.penalty_names = penalty_names_;
    row.penalty_means.assign(penalty_names_.size(), kNaN);
    return row;
  }

  // The mean policy over the validation set; false when stopped.
  bool validate(JumpSetFigures& figures) {
    state_->noise = nullptr;
    state_->draws = nullptr;
    FiguresSink sink;
    const bool whole = rollout(
        validation_, [&] { return json{{"round", "validate"}, {"ppo", learner_->checkpoint()}}; },
        [&](const CaseResult& r) { sink.add(r); });
    figures = sink.figures();
    return whole && !stopRequested();
  }

  // A batch's cases (the last share oversampled) and exploration noise, drawn
  // from the two streams as they stand: rank 0 and every other rank draw the
  // same batch from the same states.
  struct Batch {
    std::vector<EpisodeCase> cases;
    Eigen::MatrixXd noise;
    int oversampled = 0;
  };
  Batch drawBatch(int k) {
    Batch b;
    b.cases = sampler_.cases(target_rng_, spec_.jumps_per_iteration, "iteration " + std::to_string(k));
    b.oversampled = oversample(b.cases);
    b.noise = drawNoise(noise_rng_, action_size_, spec_.jumps_per_iteration);
    return b;
  }

  // The oversampling pool as a checkpoint and a round carry it, and back.
  json hardTargetsJson() const {
    json hard = json::array();
    for (const TargetSpec& t : hard_) hard.push_back({t.x, t.y, t.z, t.yaw});
    return hard;
  }
  void readHardTargets(const training_files::JsonReader& read, const json& holder) {
    hard_.clear();
    const json& hard = read.at(holder, "hard_targets");
    if (!hard.is_array()) read.fail("hard_targets", "expected an array of [x, y, z, yaw]");
    for (const json& h : hard) {
      if (!h.is_array() || h.size() != 4 || !std::all_of(h.begin(), h.end(), [](const json& v) { return v.is_number(); })) {
        read.fail("hard_targets", "expected an array of [x, y, z, yaw]");
      }
      TargetSpec t;
      t.x = h[0].get<double>();
      t.y = h[1].get<double>();
      t.z = h[2].get<double>();
      t.yaw = h[3].get<double>();
      t.where = spec_.region_where;
      hard_.push_back(t);
    }
  }

  // Iteration k: false when stopped before its update (nothing of it is kept).
  bool iterate(int k) {
    TrainingIteration row = newRow(k);
    const Rng::State target_state = target_rng_.state(), noise_state = noise_rng_.state();
    // What the other ranks need to draw this batch: the streams before it.
    const json target_rng = training_files::rngJson(target_rng_), noise_rng = training_files::rngJson(noise_rng_);
    const auto round = [&] {
      return json{{"round", "iterate"},
                  {"iteration", k},
                  {"target_rng", target_rng},
                  {"noise_rng", noise_rng},
                  {"hard_targets", hardTargetsJson()},
                  {"ppo", learner_->checkpoint()}};
    };
    const int n = spec_.jumps_per_iteration;
    const Batch drawn = drawBatch(k);
    const std::vector<EpisodeCase>& cases = drawn.cases;
    row.oversampled = drawn.oversampled;
    std::vector<CaseDraw> draws(static_cast<size_t>(n));
    state_->noise = &drawn.noise;
    state_->draws = &draws;
    std::vector<std::vector<double>> observations(static_cast<size_t>(n));
    Eigen::VectorXd rewards = Eigen::VectorXd::Zero(n);
    std::vector<std::optional<std::vector<double>>> achieved(static_cast<size_t>(n));
    std::vector<std::vector<double>> taken(static_cast<size_t>(n));
    std::vector<TargetSpec> hard;  // this batch's failed and refused targets
    FiguresSink sink;
    PenaltyMeans penalties(penalty_names_.size());
    const auto t0 = Clock::now();
    const bool whole = rollout(cases, round, [&](const CaseResult& r) {
      const std::optional<JumpOutcome> outcome = sink.add(r);
      penalties.add(r.penalties);
      const TargetSpec& target = cases[r.index].target;
      if (outcome && (outcome->status == "failed" || outcome->status == "rejected")) hard.push_back(target);
      observations[r.index] = r.observation;
      rewards[static_cast<Eigen::Index>(r.index)] = r.reward;
      if (spec_.hindsight && outcome) {
        achieved[r.index] = hindsight::achievedTask(*outcome, target, spec_);
        taken[r.index] = r.action;
      }
      // Another rank's draw: the policy there wrote it, here it comes with the result.
      if (r.draw.ran) draws[r.index] = r.draw;
    });
    state_->noise = nullptr;
    state_->draws = nullptr;
    row.rollout_s = secondsSince(t0);
    if (!whole || stopRequested()) {
      target_rng_.setState(target_state);
      noise_rng_.setState(noise_state);
      return false;
    }
    row.batch = sink.figures();
    row.penalty_means = penalties.means();
    row.penalty_sum_mean = penalties.sumMean();
    row.jumps_per_s = n / std::max(row.rollout_s, 1e-9);
    if (spec_.oversample > 0) {
      for (TargetSpec& t : hard) {
        hard_.push_back(std::move(t));
        if (static_cast<int>(hard_.size()) > spec_.jumps_per_iteration) hard_.pop_front();
      }
    }

    // The batch: the cases whose policy ran (a case that could not be set up has none).
    std::vector<Eigen::Index> used;
    for (int i = 0; i < n; ++i)
      if (draws[static_cast<size_t>(i)].ran) used.push_back(i);
    const Eigen::Index m = static_cast<Eigen::Index>(used.size());
    if (m < spec_.minibatches) {
      throw Error("training: iteration " + std::to_string(k) + ": only " + std::to_string(m) +
                  " jumps could be set up, fewer than the minibatches");
    }
    PpoBatch batch;
    batch.observations.resize(observation_size_, m);
    batch.actions.resize(action_size_, m);
    batch.rewards.resize(m);
    for (Eigen::Index j = 0; j < m; ++j) {
      const size_t i = static_cast<size_t>(used[static_cast<size_t>(j)]);
      batch.observations.col(j) =
          Eigen::Map<const Eigen::VectorXd>(observations[i].data(), static_cast<Eigen::Index>(observations[i].size()));
      batch.actions.col(j) = draws[i].residual;
      batch.rewards[j] = rewards[static_cast<Eigen::Index>(i)];
    }
    batch.log_probs = learner_->logProbs(batch.observations, batch.actions);
    row.reward_mean = batch.rewards.mean();
    row.reward_std = m > 1 ? std::sqrt((batch.rewards.array() - row.reward_mean).square().sum() / (m - 1)) : 0.0;

    const auto t1 = Clock::now();
    if (spec_.critic_warmup && learner_->iteration() == 0) {
      row.critic_warmup_loss = learner_->fitCritic(batch.observations, batch.rewards, spec_.critic_warmup_epochs);
    }
    const PpoUpdateStats s = learner_->update(batch);
    if (spec_.hindsight) fitHindsight(row, used, achieved, taken, draws, observations);
    // A diverged fit (a learning rate far too high) stops the run here, before
    // anything of it is written: the last checkpoint and policy file stay good.
    const bool warmed = spec_.critic_warmup && learner_->iteration() == 1;
    for (const auto& [name, loss] : {std::pair{"PPO's policy loss", s.policy_loss}, std::pair{"PPO's value loss", s.value_loss},
                                     std::pair{"the critic warm-up's loss", warmed ? row.critic_warmup_loss : 0.0},
                                     std::pair{"the hindsight fit's loss", spec_.hindsight && hindsight_.size() > 0
                                                                              ? row.hindsight_loss
                                                                              : 0.0}}) {
      if (!std::isfinite(loss)) {
        throw Error(scenario_.file + ": iteration " + std::to_string(k) + ": " + name + " is " + std::to_string(loss) +
                    ": the fit diverged (lower <ppo learning_rate> or <guidance hindsight_learning_rate>); stopped "
                    "before writing anything of it: " + paths_.checkpoint + " and " + paths_.policy +
                    " hold the last good state, if one was written");
      }
    }
    row.update_s = secondsSince(t1);
    row.policy_loss = s.policy_loss;
    row.value_loss = s.value_loss;
    row.entropy = s.entropy;
    row.kl = s.kl;
    row.clip_fraction = s.clip_fraction;
    row.learning_rate = s.learning_rate;
    row.std_mean = s.std_mean;
    row.value_mean = s.value_mean;
    row.actor_gradient_norm = s.actor_gradient_norm;
    row.critic_gradient_norm = s.critic_gradient_norm;
    done_ = k;
    jumps_ += n;
    row.jumps = jumps_;

    if (spec_.validation_count > 0 && validationDue(k)) {
      const auto t2 = Clock::now();
      row.validated = validate(row.validation);
      row.validation_s = secondsSince(t2);
      if (!row.validated) row.validation = JumpSetFigures{};
    }
    iteration_walls_.push_back(row.rollout_s + row.update_s + row.validation_s);
    finishRow(row);
    return true;
  }

  // Runs `cases` and hands each one's result to `on_case`, in case order, on
  // this thread; false when stopped before every case ran. In one process:
  // this process's pool. Under mpirun (rank 0): `round()` first goes to every
  // rank (what they need to draw the same cases and act as this policy would),
  // rank r runs the cases k with k mod K = r, and rank 0 gathers the results.
  bool rollout(const std::vector<EpisodeCase>& cases, const std::function<json()>& round,
               const std::function<void(const CaseResult&)>& on_case) {
    const Communicator& comm = Communicator::world();
    if (!comm.distributed()) {
      const size_t delivered = pool_->run(cases, [&](EpisodeRecord& r) {
        if (stopRequested()) pool_->stop();
        on_case(caseResultOf(r, nullptr, penalty_names_));  // the draw stays where the policy wrote it
      });
      return delivered == cases.size();
    }
    comm.broadcast(round().dump());
    std::vector<CaseResult> results(cases.size());
    std::vector<bool> have(cases.size(), false);
    std::vector<size_t> all(cases.size());
    std::iota(all.begin(), all.end(), size_t{0});
    pool_->run(cases, casesOfRank(all, comm.rank(), comm.size()), [&](EpisodeRecord& r) {
      if (stopRequested()) pool_->stop();
      results[r.index] = caseResultOf(r, nullptr, penalty_names_);  // rank 0's own draws are in place
      have[r.index] = true;
    });
    const std::vector<std::string> parts = comm.gather("[]");
    for (size_t rank = 1; rank < parts.size(); ++rank) {
      for (const json& j : json::parse(parts[rank])) {
        CaseResult r = caseResultFromJson(j);
        if (r.index >= cases.size()) throw Error("training: rank " + std::to_string(rank) + " sent case " + std::to_string(r.index));
        have[r.index] = true;
        results[r.index] = std::move(r);
      }
    }
    bool whole = true;
    for (size_t i = 0; i < cases.size(); ++i) {
      if (have[i]) {
        on_case(results[i]);
      } else {
        whole = false;
      }
    }
    return whole;
  }

 public:
  // A rank other than 0 under mpirun: rolls out its share of each round rank 0
  // sends, with the policy and streams that round carries, until the end.
  void serve() {
    const Communicator& comm = Communicator::world();
    const training_files::JsonReader read("the training round of rank 0");
    std::vector<size_t> all;
    for (;;) {
      const json round = json::parse(comm.broadcast(""));
      const std::string kind = read.string(round, "round");
      if (kind == "end") return;
      learner_ = std::make_unique<PpoLearner>(PpoLearner::fromCheckpoint(read.at(round, "ppo")));
      state_->learner = learner_.get();
      std::optional<Batch> batch;
      std::vector<CaseDraw> draws;
      const std::vector<EpisodeCase>* cases = &validation_;
      state_->noise = nullptr;
      state_->draws = nullptr;
      if (kind == "iterate") {
        target_rng_.setState(read.rng(round, "target_rng"));
        noise_rng_.setState(read.rng(round, "noise_rng"));
        readHardTargets(read, round);
        batch = drawBatch(static_cast<int>(read.integer(round, "iteration")));
        cases = &batch->cases;
        draws.resize(cases->size());
        state_->noise = &batch->noise;
        state_->draws = &draws;
      } else if (kind != "validate") {
        read.fail("round", "unknown round '" + kind + "'");
      }
      all.resize(cases->size());
      std::iota(all.begin(), all.end(), size_t{0});
      json mine = json::array();
      pool_->run(*cases, casesOfRank(all, comm.rank(), comm.size()), [&](EpisodeRecord& r) {
        mine.push_back(toJson(caseResultOf(r, state_->draws ? &draws[r.index] : nullptr, penalty_names_)));
      });
      state_->noise = nullptr;
      state_->draws = nullptr;
      comm.gather(mine.dump());
    }
  }

  // Rank 0: tells the other ranks that the run is over.
  static void endRounds() {
    const Communicator& comm = Communicator::world();
    if (comm.distributed() && comm.root()) comm.broadcast(json{{"round", "end"}}.dump());
  }

 private:
  // The last share `oversample` of the batch's cases take a target that failed
  // or was refused before, picked uniformly from the newest ones by the target
  // stream (after the uniform draws, so that a run is fixed by its seed). Returns
  // how many were replaced.
  int oversample(std::vector<EpisodeCase>& cases) {
    if (spec_.oversample <= 0 || hard_.empty()) return 0;
    const int n = static_cast<int>(cases.size());
    const int count = static_cast<int>(std::floor(spec_.oversample * n));
    for (int i = n - count; i < n; ++i) {
      const size_t pick = std::min(hard_.size() - 1, static_cast<size_t>(target_rng_.uniform() * hard_.size()));
      EpisodeCase& c = cases[static_cast<size_t>(i)];
      c.target = hard_[pick];
      c.target.name = c.label + " (again)";
      c.label = c.target.name;
    }
    return count;
  }

  // The batch's hindsight pairs into the buffer, then the actor's mean fitted
  // to the buffer. A pair's action is the residual that reaches the achieved
  // task: the action taken minus the prior there (the taken action itself
  // without a prior).
  void fitHindsight(TrainingIteration& row, const std::vector<Eigen::Index>& used,
                    const std::vector<std::optional<std::vector<double>>>& achieved,
                    const std::vector<std::vector<double>>& taken, const std::vector<CaseDraw>& draws,
                    const std::vector<std::vector<double>>& observations_of) {
    std::vector<size_t> cases;
    std::vector<std::vector<double>> tasks;
    for (Eigen::Index i : used) {
      if (achieved[static_cast<size_t>(i)]) {
        cases.push_back(static_cast<size_t>(i));
        tasks.push_back(*achieved[static_cast<size_t>(i)]);
      }
    }
    std::vector<std::optional<std::vector<double>>> priors(tasks.size());
    if (spec_.residual) priors = pool_->priorActions(tasks);
    int added = 0;
    for (size_t j = 0; j < cases.size(); ++j) {
      if (spec_.residual && !priors[j]) continue;
      Eigen::VectorXd target;
      if (spec_.aim) {
        // To land at the achieved task, aim where this jump aimed: the offset aim - achieved.
        const std::vector<double>& o = observations_of[cases[j]];
        target = Eigen::Map<const Eigen::VectorXd>(o.data(), static_cast<Eigen::Index>(o.size())) +
                 draws[cases[j]].aim_taken -
                 Eigen::Map<const Eigen::VectorXd>(tasks[j].data(), static_cast<Eigen::Index>(tasks[j].size()));
        if (target.size() != action_size_) continue;
        hindsight_.add(tasks[j], target);
        ++added;
        if (spec_.mirror) {
          // The same jump seen in the mirror: it lands at the mirrored task by
          // aiming at the mirrored aim (the robot is left-right symmetric).
          std::vector<double> mirrored = tasks[j];
          for (size_t i = 0; i < mirrored.size(); ++i) mirrored[i] *= mirror_[static_cast<Eigen::Index>(i)];
          hindsight_.add(mirrored, mirror_.cwiseProduct(target));
          ++added;
        }
        continue;
      }
      const std::vector<double>& a = taken[cases[j]];
      target = Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size()));
      if (spec_.residual) {
        const Eigen::Map<const Eigen::VectorXd> there(priors[j]->data(), static_cast<Eigen::Index>(priors[j]->size()));
        const double jump_of_prior = (there - draws[cases[j]].prior).cwiseAbs().maxCoeff();
        if (jump_of_prior > spec_.hindsight_prior_step) continue;
        target -= there;
      }
      if (!target.allFinite() || target.size() != action_size_) continue;
      hindsight_.add(tasks[j], target);
      ++added;
    }
    row.hindsight_added = added;
    row.hindsight_pairs = hindsight_.size();
    if (hindsight_.size() > 0) {
      row.hindsight_loss = learner_->fitMean(hindsight_.observations(), hindsight_.actions(), spec_.hindsight_epochs,
                                             spec_.hindsight_minibatch, spec_.hindsight_learning_rate);
    }
  }

  void finishRow(TrainingIteration& row) {
    row.wall_s = wall_before_ + secondsSince(start_);
    double mean_wall = 0;
    for (double w : iteration_walls_) mean_wall += w / iteration_walls_.size();
    row.eta_s = iteration_walls_.empty() ? kNaN : mean_wall * (spec_.iterations - row.iteration);
    if (row.validated) last_validation_ = row;
    log_.push_back(training_files::logValues(row));
    training_files::writeLog(paths_.log, log_, penalty_names_);
    if (on_row_) on_row_(row);
  }

  void save() {
    writePolicyFile();
    json c;
    c["format"] = training_files::kCheckpointFormat;
    c["version"] = training_files::kCheckpointVersion;
    c["scenario"] = scenario_.file;
    c["environment"] = factory_name_;
    c["settings"] = settingsJson(spec_);
    c["iteration"] = done_;
    c["jumps"] = jumps_;
    c["wall_s"] = wall_before_ + secondsSince(start_);
    c["target_rng"] = training_files::rngJson(target_rng_);
    c["noise_rng"] = training_files::rngJson(noise_rng_);
    c["log_columns"] = training_files::logColumns(penalty_names_);
    c["log"] = log_;
    c["ppo"] = learner_->checkpoint();
    if (spec_.hindsight) c["hindsight"] = hindsight_.toJson();
    if (spec_.oversample > 0) c["hard_targets"] = hardTargetsJson();
    training_files::writeJson(paths_.checkpoint, c, "training checkpoint");
  }

  void resume(const std::string& path) {
    const json c = training_files::readJson(path, "training checkpoint");
    const training_files::JsonReader read(path);
    if (read.string(c, "format") != training_files::kCheckpointFormat) {
      read.fail("format", "not a pronk training checkpoint (\"" + std::string(training_files::kCheckpointFormat) + "\")");
    }
    if (read.integer(c, "version") != training_files::kCheckpointVersion) {
      read.fail("version", "this pronk reads version " + std::to_string(training_files::kCheckpointVersion));
    }
    if (read.string(c, "environment") != factory_name_) {
      read.fail("environment", "the checkpoint trains environment '" + read.string(c, "environment") +
                                   "'; this scenario's is '" + factory_name_ + "'");
    }
    const json& settings = read.at(c, "settings");
    const json wanted = settingsJson(spec_);
    for (const auto& item : wanted.items()) {
      // Checkpoints from before flat_share have none: theirs was 0.
      if (item.key() == "flat_share" && !settings.contains(item.key()) && item.value() == 0.0) continue;
      if (!settings.contains(item.key()) || settings[item.key()] != item.value()) {
        read.fail("settings." + item.key(),
                  (settings.contains(item.key()) ? settings[item.key()].dump() : std::string("missing")) +
                      ", but this run has " + item.value().dump() +
                      " (the training file, --jumps and --seed must be those the checkpoint was made with)");
      }
    }
    done_ = static_cast<int>(read.integer(c, "iteration"));
    if (done_ > spec_.iterations) {
      read.fail("iteration", std::to_string(done_) + " iterations are done already; this run has " +
                                 std::to_string(spec_.iterations) + " (give --iterations N for more)");
    }
    jumps_ = read.integer(c, "jumps");
    wall_before_ = read.number(c, "wall_s");
    target_rng_.setState(read.rng(c, "target_rng"));
    noise_rng_.setState(read.rng(c, "noise_rng"));
    if (read.at(c, "log_columns") != training_files::logColumns(penalty_names_)) {
      read.fail("log_columns", "another pronk's log columns");
    }
    log_ = read.at(c, "log").get<std::vector<std::vector<json>>>();
    last_validation_ = training_files::lastValidation(log_, penalty_names_);
    try {
      learner_ = std::make_unique<PpoLearner>(PpoLearner::fromCheckpoint(read.at(c, "ppo")));
    } catch (const InputError&) {
      throw;
    } catch (const Error& e) {
      throw InputError({path, 0}, std::string("ppo: ") + e.what());
    }
    if (learner_->observationSize() != observation_size_ || learner_->actionSize() != action_size_) {
      read.fail("ppo", "the networks' sizes do not fit environment '" + factory_name_ + "'");
    }
    if (spec_.oversample > 0) readHardTargets(read, c);
    if (spec_.hindsight) {
      try {
        hindsight_.fromJson(read.at(c, "hindsight"), observation_size_, action_size_);
      } catch (const InputError&) {
        throw;
      } catch (const Error& e) {
        throw InputError({path, 0}, e.what());
      }
    }
  }

  void writePolicyFile() const {
    MlpPolicy policy = learner_->policy();
    if (spec_.residual) policy.setPrior(PolicyPrior{kPriorActionKind, factory_name_});
    if (spec_.aim) policy.setPrior(PolicyPrior{kAimPriorKind, factory_name_});
    policy.setDescription(scenario_.name + ": " +
                          (spec_.aim        ? "an aim correction of environment '" + factory_name_ + "''s prior_action"
                           : spec_.residual ? "a residual over environment '" + factory_name_ + "''s prior_action"
                                          : "a policy for environment '" + factory_name_ + "'") +
                          ", trained by pronk train");
    json p;
    p["command"] = options_.command;
    if (!options_.pronk_version.empty()) p["pronk_version"] = options_.pronk_version;
    if (!options_.git_commit.empty()) p["git_commit"] = options_.git_commit;
    p["training_file"] = scenario_.file;
    p["seed"] = spec_.seed;
    p["iterations"] = done_;
    p["jumps"] = jumps_;
    p["wall_time_s"] = wall_before_ + secondsSince(start_);
    p["robot"] = scenario_.platform.name;
    p["urdf"] = fs::path(scenario_.platform.urdf).filename().string();
    p["environment"] = factory_name_;
    p["plugin"] = fs::path(origin_).filename().string();
    p["guidance"] = {{"residual", spec_.residual},
                     {"aim", spec_.aim},
                     {"critic_warmup", spec_.critic_warmup},
                     {"hindsight", spec_.hindsight},
                     {"ppo_actor", spec_.ppo_actor},
                     {"mirror", spec_.mirror}};
    if (last_validation_) {
      const JumpSetFigures& v = last_validation_->validation;
      p["validation"] = {{"iteration", last_validation_->iteration},
                         {"count", spec_.validation_count},
                         {"seed", spec_.validation_seed},
                         {"landed", v.landed},
                         {"failed", v.failed},
                         {"rejected", v.rejected},
                         {"error_median_m", std::isfinite(v.error_median) ? json(v.error_median) : json()},
                         {"error_mean_m", std::isfinite(v.error_mean) ? json(v.error_mean) : json()},
                         {"within_0.2m", std::isfinite(v.within_02) ? json(v.within_02) : json()}};
    }
    policy.setProvenance(p);
    savePolicy(policy, paths_.policy);
  }

  TrainingOutcome finish(TrainingOutcome& out, bool interrupted) {
    save();
    out.iterations_done = done_;
    out.interrupted = interrupted;
    out.jumps = jumps_;
    out.wall_s = wall_before_ + secondsSince(start_);
    return out;
  }

  const Scenario& scenario_;
  TrainingRunOptions options_;
  TrainingProgress on_row_;
  const std::atomic<bool>* stop_;
  TrainingSpec spec_;
  TargetSampler sampler_;
  Rng target_rng_, noise_rng_;
  std::vector<EpisodeCase> validation_;
  hindsight::Buffer hindsight_;
  Eigen::VectorXd mirror_;  // the task's signs in the mirror image (mirror guidance)
  std::deque<TargetSpec> hard_;  // the newest failed or refused targets (oversampling)
  std::string factory_name_, origin_;
  std::vector<std::string> penalty_names_;  // the environment's penalty metrics
  int observation_size_ = 0, action_size_ = 0;
  std::shared_ptr<PolicyState> state_;
  std::unique_ptr<PpoLearner> learner_;
  std::unique_ptr<RolloutPool> pool_;
  Paths paths_;
  int done_ = 0;            // iterations whose update is done
  long long jumps_ = 0;     // training jumps in them
  double wall_before_ = 0;  // wall time of the runs this one resumes
  Clock::time_point start_ = Clock::now();
  std::vector<double> iteration_walls_;
  std::vector<std::vector<json>> log_;
  std::optional<TrainingIteration> last_validation_;
};

}  // namespace

namespace {
std::string besidePolicy(const std::string& policy_path, const char* suffix) {
  const fs::path p(policy_path);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}
}  // namespace

std::string checkpointPathFor(const std::string& policy_path) { return besidePolicy(policy_path, ".checkpoint.json"); }
std::string trainingLogPathFor(const std::string& policy_path) { return besidePolicy(policy_path, ".train_log.csv"); }
std::string trainingCurvesPathFor(const std::string& policy_path) {
  return besidePolicy(policy_path, ".train_curves.png");
}

TrainingOutcome trainPolicy(const Scenario& scenario, const PluginRegistry& registry, const TrainingRunOptions& options,
                            const TrainingProgress& on_row, const std::atomic<bool>* stop) {
  if (options.policy_path.empty()) throw Error("training: no policy file to write (--out)");
  const fs::path dir = fs::path(options.policy_path).parent_path();
  if (!dir.empty() && Communicator::world().root()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error("--out " + options.policy_path + ": cannot create " + dir.string() + ": " + ec.message());
  }
  Trainer trainer(scenario, registry, options, on_row, stop);
  if (!Communicator::world().root()) {
    trainer.serve();
    return {};  // rank 0 reports the run
  }
  TrainingOutcome outcome = trainer.run();
  Trainer::endRounds();
  return outcome;
}

}  // namespace pronk
