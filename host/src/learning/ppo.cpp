// PpoLearner: sampling, and one PPO iteration over a batch of one-step
// episodes (advantage r - V(s), no bootstrap: see ppo.h).
#include "pronk/ppo.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "pronk/error.h"
#include "pronk/gradient_clipping.h"

namespace pronk {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("ppo: " + message);
}

void checkConfig(const PpoConfig& c) {
  require(c.epochs >= 1, "epochs must be >= 1");
  require(c.minibatches >= 1, "minibatches must be >= 1");
  require(c.loss.clip > 0, "loss.clip must be > 0");
  require(c.initial_std > 0 && std::isfinite(c.initial_std), "initial_std must be a finite number > 0");
  require(c.min_learning_rate > 0 && c.min_learning_rate <= c.max_learning_rate,
          "0 < min_learning_rate <= max_learning_rate expected");
  require(c.learning_rate > 0 && std::isfinite(c.learning_rate), "learning_rate must be a finite number > 0");
  require(c.desired_kl > 0, "desired_kl must be > 0");
  require(c.max_gradient_norm > 0, "max_gradient_norm must be > 0");
}

void checkFinite(const Eigen::MatrixXd& m, const char* what) {
  require(m.allFinite(), std::string(what) + ": a value is not finite");
}

// The columns `indices` of m.
Eigen::MatrixXd columns(const Eigen::MatrixXd& m, const std::vector<Eigen::Index>& indices) {
  return m(Eigen::all, indices);
}
Eigen::VectorXd entries(const Eigen::VectorXd& v, const std::vector<Eigen::Index>& indices) { return v(indices); }

// One epoch's minibatches: the samples 0 .. n-1 shuffled (Fisher-Yates from
// rng) and cut into `count` runs whose sizes differ by at most one.
std::vector<std::vector<Eigen::Index>> shuffledMinibatches(Eigen::Index n, Eigen::Index count, Rng& rng) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  std::vector<std::vector<Eigen::Index>> out;
  out.reserve(static_cast<std::size_t>(count));
  for (Eigen::Index k = 0; k < count; ++k) {
    const std::size_t begin = static_cast<std::size_t>(n * k / count);
    const std::size_t end = static_cast<std::size_t>(n * (k + 1) / count);
    out.emplace_back(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return out;
}

}  // namespace

double adaptLearningRate(double learning_rate, double kl, const PpoConfig& config) {
  if (kl > 2 * config.desired_kl) return std::max(config.min_learning_rate, learning_rate / 1.5);
  if (kl < config.desired_kl / 2 && kl > 0) return std::min(config.max_learning_rate, learning_rate * 1.5);
  return learning_rate;
}

PpoLearner::Parts PpoLearner::initialParts(const PpoConfig& config, ObservationScaling scaling, int action_size,
                                           std::uint64_t seed) {
  checkConfig(config);
  Rng rng(seed);
  Mlp mean(scaling.size(), config.actor_hidden_sizes, action_size, config.activation);
  mean.initialize(config.actor_init, rng);
  Mlp critic(scaling.size(), config.critic_hidden_sizes, 1, config.activation);
  critic.initialize(config.critic_init, rng);
  GaussianPolicy actor(std::move(mean), Eigen::VectorXd::Constant(action_size, std::log(config.initial_std)));
  return Parts{config, std::move(scaling), std::move(actor), std::move(critic), rng};
}

PpoLearner::PpoLearner(Parts parts)
    : config_(std::move(parts.config)),
      scaling_(std::move(parts.scaling)),
      actor_(std::move(parts.actor)),
      critic_(std::move(parts.critic)),
      actor_adam_(actor_.parameterCount(), config_.adam),
      critic_adam_(critic_.parameterCount(), config_.adam),
      mean_fit_adam_(actor_.parameterCount(), config_.adam),
      learning_rate_(config_.learning_rate),
      rng_(parts.rng) {
  checkConfig(config_);
  require(actor_.inputSize() == scaling_.size() && critic_.inputSize() == scaling_.size(),
          "the actor, the critic and the observation scaling disagree on the observation size");
  require(critic_.outputSize() == 1, "the critic must have one output");
}

PpoLearner::PpoLearner(const PpoConfig& config, ObservationScaling scaling, int action_size, std::uint64_t seed)
    : PpoLearner(initialParts(config, std::move(scaling), action_size, seed)) {}

PpoLearner::PpoLearner(const PpoConfig& config, int observation_size, int action_size, std::uint64_t seed)
    : PpoLearner(config, ObservationScaling::identity(observation_size), action_size, seed) {}

PpoLearner PpoLearner::fromPolicy(const PpoConfig& config, const MlpPolicy& policy, std::uint64_t seed) {
  Parts parts = initialParts(config,
                             policy.hasObservationNormalization()
                                 ? ObservationScaling(policy.observationMean(), policy.observationStd())
                                 : ObservationScaling::identity(policy.observationSize()),
                             policy.actionSize(), seed);
  parts.actor = GaussianPolicy(Mlp(policy.layers()), policy.hasActionLogStd() ? policy.actionLogStd()
                                                                              : parts.actor.logStd());
  return PpoLearner(std::move(parts));
}

PpoSample PpoLearner::sample(const Eigen::MatrixXd& observations) { return sample(observations, rng_); }

PpoSample PpoLearner::sample(const Eigen::MatrixXd& observations, Rng& rng) const {
  const Eigen::MatrixXd m = means(observations);
  PpoSample out;
  out.actions = actor_.sample(m, rng);
  out.log_probs = actor_.logProb(m, out.actions);
  return out;
}

Eigen::VectorXd PpoLearner::mean(const Eigen::VectorXd& observation) const {
  return actor_.mean(scaling_.apply(observation));
}

Eigen::MatrixXd PpoLearner::means(const Eigen::MatrixXd& observations) const {
  return actor_.means(scaling_.apply(observations));
}

Eigen::VectorXd PpoLearner::values(const Eigen::MatrixXd& observations) const {
  return critic_.forward(scaling_.apply(observations)).row(0).transpose();
}

Eigen::VectorXd PpoLearner::logProbs(const Eigen::MatrixXd& observations, const Eigen::MatrixXd& actions) const {
  return actor_.logProb(means(observations), actions);
}

PpoUpdateStats PpoLearner::update(const PpoBatch& batch) {
  const Eigen::Index n = batch.observations.cols();
  require(batch.observations.rows() == observationSize(),
          "observations have " + std::to_string(batch.observations.rows()) + " rows, expected " +
              std::to_string(observationSize()) + " (one column per sample)");
  require(batch.actions.rows() == actionSize() && batch.actions.cols() == n && batch.log_probs.size() == n &&
              batch.rewards.size() == n,
          "a batch needs one action column, log-probability and reward per observation");
  require(n >= config_.minibatches, "a batch of " + std::to_string(n) + " samples cannot fill " +
                                        std::to_string(config_.minibatches) + " minibatches");
  checkFinite(batch.observations, "observations");
  checkFinite(batch.actions, "actions");
  checkFinite(batch.log_probs, "log_probs");
  checkFinite(batch.rewards, "rewards");

  // What the policy and critic say before the update: the "old" of PPO.
  PpoMinibatch all;
  all.inputs = scaling_.apply(batch.observations);
  all.actions = batch.actions;
  all.old_log_probs = batch.log_probs;
  all.old_means = actor_.means(all.inputs);
  all.old_log_std = actor_.logStd();
  all.old_values = critic_.forward(all.inputs).row(0).transpose();
  all.returns = batch.rewards;  // a one-step episode: the target is the reward itself
  all.advantages = batch.rewards - all.old_values;
  if (config_.normalize_advantages && n > 1) {
    const double mean = all.advantages.mean();
    const double std = std::sqrt((all.advantages.array() - mean).square().sum() / static_cast<double>(n - 1));
    all.advantages = ((all.advantages.array() - mean) / (std + 1e-8)).matrix();
  }

  PpoUpdateStats stats;
  stats.reward_mean = batch.rewards.mean();
  stats.value_mean = all.old_values.mean();
  for (int epoch = 0; epoch < config_.epochs; ++epoch) {
    for (const std::vector<Eigen::Index>& idx : shuffledMinibatches(n, config_.minibatches, rng_)) {
      PpoMinibatch mb;
      mb.inputs = columns(all.inputs, idx);
      mb.actions = columns(all.actions, idx);
      mb.old_log_probs = entries(all.old_log_probs, idx);
      mb.old_means = columns(all.old_means, idx);
      mb.old_log_std = all.old_log_std;
      mb.old_values = entries(all.old_values, idx);
      mb.advantages = entries(all.advantages, idx);
      mb.returns = entries(all.returns, idx);

      Eigen::VectorXd actor_gradient, critic_gradient;
      const PpoLossTerms terms = ppoLoss(actor_, critic_, mb, config_.loss, &actor_gradient, &critic_gradient);
      // As rsl_rl: the KL of this minibatch sets the rate of its own step.
      if (config_.adaptive_learning_rate) learning_rate_ = adaptLearningRate(learning_rate_, terms.kl, config_);
      stats.actor_gradient_norm += clipGradientNorm(actor_gradient, config_.max_gradient_norm);
      stats.critic_gradient_norm += clipGradientNorm(critic_gradient, config_.max_gradient_norm);

      if (config_.update_actor) {
        Eigen::VectorXd actor_parameters = actor_.parameters();
        actor_adam_.step(actor_parameters, actor_gradient, learning_rate_);
        actor_.setParameters(actor_parameters);
      }
      Eigen::VectorXd critic_parameters = critic_.parameters();
      critic_adam_.step(critic_parameters, critic_gradient, learning_rate_);
      critic_.setParameters(critic_parameters);

      stats.policy_loss += terms.surrogate;
      stats.value_loss += terms.value;
      stats.entropy += terms.entropy;
      stats.kl += terms.kl;
      stats.clip_fraction += terms.clip_fraction;
      ++stats.minibatch_updates;
    }
  }
  const double updates = stats.minibatch_updates;
  for (double* mean : {&stats.policy_loss, &stats.value_loss, &stats.entropy, &stats.kl, &stats.clip_fraction,
                       &stats.actor_gradient_norm, &stats.critic_gradient_norm}) {
    *mean /= updates;
  }
  stats.learning_rate = learning_rate_;
  stats.std_mean = actor_.logStd().array().exp().mean();
  ++iteration_;
  return stats;
}

double PpoLearner::fitCritic(const Eigen::MatrixXd& observations, const Eigen::VectorXd& rewards, int epochs) {
  const Eigen::Index n = observations.cols();
  require(observations.rows() == observationSize() && rewards.size() == n,
          "fitCritic: one observation column and one reward per sample expected");
  require(n >= config_.minibatches, "fitCritic: a batch of " + std::to_string(n) + " samples cannot fill " +
                                        std::to_string(config_.minibatches) + " minibatches");
  require(epochs >= 1, "fitCritic: epochs must be >= 1");
  checkFinite(observations, "observations");
  checkFinite(rewards, "rewards");
  const Eigen::MatrixXd inputs = scaling_.apply(observations);
  double last_epoch_loss = 0;
  for (int epoch = 0; epoch < epochs; ++epoch) {
    last_epoch_loss = 0;
    for (const std::vector<Eigen::Index>& idx : shuffledMinibatches(n, config_.minibatches, rng_)) {
      const Eigen::MatrixXd x = columns(inputs, idx);
      const Eigen::VectorXd r = entries(rewards, idx);
      Mlp::Tape tape;
      const Eigen::VectorXd v = critic_.forward(x, &tape).row(0).transpose();
      const double m = static_cast<double>(idx.size());
      const Eigen::VectorXd error = v - r;
      last_epoch_loss += error.squaredNorm() / m / config_.minibatches;
      const Eigen::MatrixXd output_gradient = (2.0 / m) * error.transpose();
      Eigen::VectorXd gradient = critic_.backward(tape, output_gradient);
      clipGradientNorm(gradient, config_.max_gradient_norm);
      Eigen::VectorXd parameters = critic_.parameters();
      critic_adam_.step(parameters, gradient, learning_rate_);
      critic_.setParameters(parameters);
    }
  }
  return last_epoch_loss;
}

double PpoLearner::fitMean(const Eigen::MatrixXd& observations, const Eigen::MatrixXd& actions, int epochs,
                           int minibatch_size, double learning_rate) {
  const Eigen::Index n = observations.cols();
  require(observations.rows() == observationSize() && actions.rows() == actionSize() && actions.cols() == n,
          "fitMean: one observation column and one action column per sample expected");
  require(n >= 1, "fitMean: no samples");
  require(epochs >= 1 && minibatch_size >= 1, "fitMean: epochs and minibatch_size must be >= 1");
  require(learning_rate > 0 && std::isfinite(learning_rate), "fitMean: learning_rate must be a finite number > 0");
  checkFinite(observations, "observations");
  checkFinite(actions, "actions");
  const Eigen::MatrixXd inputs = scaling_.apply(observations);
  const Eigen::Index batches = (n + minibatch_size - 1) / minibatch_size;
  const Eigen::VectorXd no_log_std_gradient = Eigen::VectorXd::Zero(actionSize());
  double last_epoch_loss = 0;
  for (int epoch = 0; epoch < epochs; ++epoch) {
    last_epoch_loss = 0;
    for (const std::vector<Eigen::Index>& idx : shuffledMinibatches(n, batches, rng_)) {
      Mlp::Tape tape;
      const Eigen::MatrixXd m = actor_.means(columns(inputs, idx), &tape);
      const Eigen::MatrixXd error = m - columns(actions, idx);
      const double size = static_cast<double>(idx.size());
      last_epoch_loss += error.colwise().squaredNorm().sum() / static_cast<double>(n);
      Eigen::VectorXd gradient = actor_.backward(tape, (2.0 / size) * error, no_log_std_gradient);
      clipGradientNorm(gradient, config_.max_gradient_norm);
      Eigen::VectorXd parameters = actor_.parameters();
      mean_fit_adam_.step(parameters, gradient, learning_rate);
      actor_.setParameters(parameters);
    }
  }
  return last_epoch_loss;
}

MlpPolicy PpoLearner::policy() const {
  MlpPolicy policy(actor_.meanNetwork().layers());
  policy.setObservationNormalization(scaling_.mean(), scaling_.std());
  policy.setActionLogStd(actor_.logStd());
  return policy;
}

}  // namespace pronk
