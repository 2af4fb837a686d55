// PPO for one-step episodes (a contextual bandit): each sample is one
// observation, one action drawn from the Gaussian policy, one reward, and the
// episode ends. This is how the paper's training sees a jump (one action per
// episode); it is generic over environments.
//
// The advantage is A = r - V(s) and the value target is r. DEVIATION from the
// paper's code: there every episode ends as a time-out, so rsl_rl bootstraps
// it (target r + gamma V(s), advantage r - (1 - gamma) V(s) with gamma = 0.99),
// which slows the critic's learning; a one-step episode has no future, so
// nothing is bootstrapped here (docs/training.md).
//
// Otherwise rsl_rl's PPO as the paper ran it: clipped surrogate (0.2), clipped
// value loss (coefficient 1), entropy bonus, epochs x minibatches, advantages
// normalised over the batch, learning rate adapted on the KL. Observations are
// scaled by a fixed ObservationScaling before both networks. Everything random
// comes from the learner's Rng, so a seed fixes the run, and checkpoint()
// carries all of its state.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "pronk/adam.h"
#include "pronk/gaussian_policy.h"
#include "pronk/mlp.h"
#include "pronk/observation_scaling.h"
#include "pronk/policy.h"
#include "pronk/ppo_loss.h"
#include "pronk/rng.h"

namespace pronk {

struct PpoConfig {
  // Actor (mean) and critic, separate networks; the paper's Go1 sizes.
  std::vector<int> actor_hidden_sizes{512, 256, 128};
  std::vector<int> critic_hidden_sizes{512, 256, 128};
  Activation activation = Activation::Elu;
  MlpInit actor_init;   // actor_init.zero_last_layer: a residual policy starts at exactly 0
  MlpInit critic_init;
  double initial_std = 1.0;  // exp(log_std) at the start, every action

  PpoLossSettings loss;
  int epochs = 10;
  int minibatches = 4;
  bool normalize_advantages = true;  // (A - mean) / (std + 1e-8) over the batch
  // false: update() steps the critic only; the actor (mean and log-std) is
  // left to another learner (fitMean), its loss terms still reported.
  bool update_actor = true;

  double learning_rate = 1e-3;  // the start, for both networks
  // rsl_rl's rule, per minibatch: kl > 2 desired_kl -> lr / 1.5; 0 < kl <
  // desired_kl / 2 -> lr * 1.5; kept within [min, max].
  bool adaptive_learning_rate = true;
  double desired_kl = 0.01;
  double min_learning_rate = 1e-5;
  double max_learning_rate = 1e-2;

  // Each network's gradient is clipped on its own (rsl_rl clips both as one
  // vector, so a large value gradient would shrink the policy's step).
  double max_gradient_norm = 1.0;
  AdamConfig adam;
};

// rsl_rl's adaptive schedule, one step of it.
double adaptLearningRate(double learning_rate, double kl, const PpoConfig& config);

// What one iteration collected, one column (or value) per sample.
struct PpoBatch {
  Eigen::MatrixXd observations;  // raw, unscaled
  Eigen::MatrixXd actions;
  Eigen::VectorXd log_probs;     // log pi(a | s) when a was drawn (PpoSample::log_probs)
  Eigen::VectorXd rewards;
};

struct PpoSample {
  Eigen::MatrixXd actions;   // one column per observation
  Eigen::VectorXd log_probs;
};

// Means over the iteration's minibatch updates unless said otherwise.
struct PpoUpdateStats {
  double policy_loss = 0;     // the clipped surrogate
  double value_loss = 0;
  double entropy = 0;
  double kl = 0;
  double clip_fraction = 0;
  double actor_gradient_norm = 0;   // before clipping
  double critic_gradient_norm = 0;
  double learning_rate = 0;   // after the update
  double std_mean = 0;        // mean of exp(log_std), after the update
  double reward_mean = 0;     // of the batch
  double value_mean = 0;      // V(s) of the batch before the update
  int minibatch_updates = 0;
};

class PpoLearner {
 public:
  // Networks from config, initialised from seed; observations scaled by
  // `scaling` (its size is the observation size).
  PpoLearner(const PpoConfig& config, ObservationScaling scaling, int action_size, std::uint64_t seed);
  // The same with observations unscaled.
  PpoLearner(const PpoConfig& config, int observation_size, int action_size, std::uint64_t seed);
  // The actor from a policy (a file, a pretrained network): its layers, its
  // observation normalisation (or none) and log-std (or log(initial_std));
  // the critic from config. Sizes in config.actor_hidden_sizes are ignored.
  static PpoLearner fromPolicy(const PpoConfig& config, const MlpPolicy& policy, std::uint64_t seed);

  int observationSize() const { return scaling_.size(); }
  int actionSize() const { return actor_.actionSize(); }

  // Actions drawn for a batch of observations (one column each), from the
  // learner's Rng or a given one.
  PpoSample sample(const Eigen::MatrixXd& observations);
  PpoSample sample(const Eigen::MatrixXd& observations, Rng& rng) const;
  // The mean action: for one observation, bit for bit what policy().act gives.
  Eigen::VectorXd mean(const Eigen::VectorXd& observation) const;
  Eigen::MatrixXd means(const Eigen::MatrixXd& observations) const;
  Eigen::VectorXd values(const Eigen::MatrixXd& observations) const;
  Eigen::VectorXd logProbs(const Eigen::MatrixXd& observations, const Eigen::MatrixXd& actions) const;

  // One PPO iteration on a batch (at least config.minibatches samples).
  PpoUpdateStats update(const PpoBatch& batch);

  // Critic warm-up: fits V(s) alone to the rewards (loss mean (V - r)^2, no
  // clipping), `epochs` passes of config.minibatches minibatches reshuffled
  // from the learner's Rng, the critic's gradient clipped and its Adam stepped
  // at the current learning rate. The actor, the learning rate and
  // iteration() are left alone. Returns the mean value loss of the last epoch.
  double fitCritic(const Eigen::MatrixXd& observations, const Eigen::VectorXd& rewards, int epochs);

  // Supervised fit of the actor's mean to given actions (hindsight
  // relabelling, behaviour cloning): loss mean_j ||mean(s_j) - a_j||^2,
  // `epochs` passes over minibatches of at most `minibatch_size` samples
  // reshuffled from the learner's Rng, with its own Adam (meanFitOptimizer)
  // at `learning_rate`, the gradient clipped to config.max_gradient_norm. The
  // log-std, the critic, PPO's learning rate and iteration() are left alone.
  // Returns the mean loss of the last epoch.
  double fitMean(const Eigen::MatrixXd& observations, const Eigen::MatrixXd& actions, int epochs, int minibatch_size,
                 double learning_rate);

  // The actor as a policy file holds it: layers, observation scaling as the
  // normalisation, log-std. Description and provenance are the caller's.
  MlpPolicy policy() const;

  const PpoConfig& config() const { return config_; }
  const ObservationScaling& scaling() const { return scaling_; }
  const GaussianPolicy& actor() const { return actor_; }
  const Mlp& critic() const { return critic_; }
  const Adam& actorOptimizer() const { return actor_adam_; }
  const Adam& criticOptimizer() const { return critic_adam_; }
  const Adam& meanFitOptimizer() const { return mean_fit_adam_; }
  double learningRate() const { return learning_rate_; }
  long long iteration() const { return iteration_; }  // updates done
  const Rng& rng() const { return rng_; }

  // Everything a resumed learner needs to continue bit for bit: config,
  // scaling, both networks, log-std, the three Adam states, learning rate,
  // iteration, Rng state (ppo_checkpoint.cpp; docs/training.md).
  nlohmann::json checkpoint() const;
  // Throws pronk::Error naming the key at fault.
  static PpoLearner fromCheckpoint(const nlohmann::json& checkpoint);

 private:
  struct Parts {
    PpoConfig config;
    ObservationScaling scaling;
    GaussianPolicy actor;
    Mlp critic;
    Rng rng;
  };
  explicit PpoLearner(Parts parts);  // checks the config and the sizes; fresh optimisers
  static Parts initialParts(const PpoConfig& config, ObservationScaling scaling, int action_size, std::uint64_t seed);

  PpoConfig config_;
  ObservationScaling scaling_;
  GaussianPolicy actor_;
  Mlp critic_;
  Adam actor_adam_, critic_adam_;
  Adam mean_fit_adam_;  // fitMean's: its steps are not PPO's
  double learning_rate_;
  long long iteration_ = 0;
  Rng rng_;
};

// checkpoint() as a JSON file, replaced atomically; and back (errors
// "path: key: message").
void savePpoCheckpoint(const PpoLearner& learner, const std::string& path);
PpoLearner loadPpoCheckpoint(const std::string& path);

}  // namespace pronk
