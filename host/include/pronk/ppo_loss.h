// The PPO loss of one minibatch (Schulman et al. 2017, with rsl_rl's clipped
// value loss) and its gradient for the actor and the critic:
//   loss = mean_j max(-A_j rho_j, -A_j clip(rho_j, 1 - eps, 1 + eps))
//        + value_loss_coefficient * mean_j max((V_j - R_j)^2, (Vc_j - R_j)^2)
//        - entropy_coefficient * H,
// rho_j = exp(log pi(a_j | x_j) - log pi_old(a_j | x_j)),
// Vc_j = V_old_j + clip(V_j - V_old_j, -eps, eps).
// Batches have one column per sample.
#pragma once

#include <Eigen/Core>

#include "pronk/gaussian_policy.h"
#include "pronk/mlp.h"

namespace pronk {

struct PpoLossSettings {
  double clip = 0.2;                    // eps, for the ratio and the value
  double value_loss_coefficient = 1.0;
  bool clip_value_loss = true;          // false: plain (V - R)^2
  double entropy_coefficient = 0.01;
};

// A minibatch as the loss sees it.
struct PpoMinibatch {
  Eigen::MatrixXd inputs;         // network inputs (scaled observations)
  Eigen::MatrixXd actions;        // the actions taken
  Eigen::VectorXd old_log_probs;  // log pi_old(a | x), when the action was drawn
  Eigen::MatrixXd old_means;      // the policy's mean when the batch was collected (for the KL)
  Eigen::VectorXd old_log_std;
  Eigen::VectorXd old_values;     // V_old(x), for the clipped value loss
  Eigen::VectorXd advantages;     // A
  Eigen::VectorXd returns;        // R, the value targets
};

struct PpoLossTerms {
  double surrogate = 0;      // the clipped policy loss
  double value = 0;          // the (clipped) value loss, before its coefficient
  double entropy = 0;        // H
  double total = 0;
  double kl = 0;             // mean KL(old || current): for the adaptive learning rate, no gradient
  double clip_fraction = 0;  // share of samples with |rho - 1| > eps
};

// The loss at the current parameters; the gradients (flat, in the layouts of
// actor.parameters() and critic.parameters()) when asked for.
PpoLossTerms ppoLoss(const GaussianPolicy& actor, const Mlp& critic, const PpoMinibatch& batch,
                     const PpoLossSettings& settings, Eigen::VectorXd* actor_gradient = nullptr,
                     Eigen::VectorXd* critic_gradient = nullptr);

}  // namespace pronk
