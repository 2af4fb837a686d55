// A Gaussian policy: an MLP gives the mean action, a learnable log-std per
// action (state-independent, as rsl_rl's) the spread:
//   pi(a | x) = N(a; mean(x), diag(exp(log_std))^2).
// Log-probabilities, entropy and their gradients are written out by hand, for
// the PPO loss. Batches have one column per sample, as Mlp's.
#pragma once

#include <Eigen/Core>

#include "pronk/mlp.h"
#include "pronk/policy.h"
#include "pronk/rng.h"

namespace pronk {

class GaussianPolicy {
 public:
  // log_std has one finite value per output of mean_network.
  GaussianPolicy(Mlp mean_network, Eigen::VectorXd log_std);

  const Mlp& meanNetwork() const { return mean_network_; }
  const Eigen::VectorXd& logStd() const { return log_std_; }
  void setLogStd(Eigen::VectorXd log_std);
  int inputSize() const { return mean_network_.inputSize(); }
  int actionSize() const { return mean_network_.outputSize(); }

  // Flat parameters: the mean network's (Mlp layout), then the log-std.
  int parameterCount() const { return mean_network_.parameterCount() + actionSize(); }
  Eigen::VectorXd parameters() const;
  void setParameters(const Eigen::VectorXd& parameters);

  // The mean action (bit for bit MlpPolicy::act's for one input).
  Eigen::VectorXd mean(const Eigen::VectorXd& input) const { return mean_network_.evaluate(input); }
  // One column per input.
  Eigen::MatrixXd means(const Eigen::MatrixXd& inputs, Mlp::Tape* tape = nullptr) const {
    return mean_network_.forward(inputs, tape);
  }
  // means + std * standard normals, drawn column by column, action by action.
  Eigen::MatrixXd sample(const Eigen::MatrixXd& means, Rng& rng) const;

  // log pi(a | x) per column: sum_i -(a_i - m_i)^2 / (2 s_i^2) - log s_i - log(2 pi) / 2.
  Eigen::VectorXd logProb(const Eigen::MatrixXd& means, const Eigen::MatrixXd& actions) const;
  // sum_i log s_i + log(2 pi e) / 2, the same for every state; d/dlog_std = 1.
  double entropy() const;

  // Gradient of sum_j weights_j * logProb_j: with respect to the means
  // (weights_j (a - m) / s^2, per column) and to the log-std
  // (sum_j weights_j ((a - m)^2 / s^2 - 1)).
  struct LogProbGradient {
    Eigen::MatrixXd mean;
    Eigen::VectorXd log_std;
  };
  LogProbGradient logProbGradient(const Eigen::MatrixXd& means, const Eigen::MatrixXd& actions,
                                  const Eigen::VectorXd& weights) const;

  // Gradient in the flat layout of parameters(), from dLoss/dmean over the
  // tape's batch and dLoss/dlog_std.
  Eigen::VectorXd backward(const Mlp::Tape& tape, const Eigen::MatrixXd& mean_gradient,
                           const Eigen::VectorXd& log_std_gradient) const;

  // KL(old || new) per column, for two Gaussians with diagonal covariance.
  static Eigen::VectorXd klDivergence(const Eigen::MatrixXd& old_means, const Eigen::VectorXd& old_log_std,
                                      const Eigen::MatrixXd& new_means, const Eigen::VectorXd& new_log_std);

 private:
  Mlp mean_network_;
  Eigen::VectorXd log_std_;
};

}  // namespace pronk
