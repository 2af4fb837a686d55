// The PPO loss's hand-written gradient against finite differences, with some
// ratios and values inside the clip band and some outside it.
#include <gtest/gtest.h>

#include <cmath>

#include "gradient_check.h"
#include "pronk/ppo_loss.h"

namespace {

using pronk::GaussianPolicy;
using pronk::Mlp;
using pronk_test::numericalGradient;
using pronk_test::randomMatrix;
using pronk_test::relativeError;

struct LossCase {
  GaussianPolicy actor;
  Mlp critic;
  pronk::PpoMinibatch batch;
};

LossCase makeLossCase() {
  const int n = 12;
  pronk::Rng rng(21);
  Mlp mean(3, {8, 6}, 2);
  mean.initialize(pronk::MlpInit{}, rng);
  Mlp critic(3, {8}, 1, pronk::Activation::Tanh);
  critic.initialize(pronk::MlpInit{}, rng);
  Eigen::VectorXd log_std(2);
  log_std << -0.2, 0.1;
  LossCase s{GaussianPolicy(mean, log_std), critic, {}};
  pronk::PpoMinibatch& b = s.batch;
  b.inputs = randomMatrix(3, n, 22);
  b.actions = randomMatrix(2, n, 23);
  b.old_means = s.actor.means(b.inputs) + 0.1 * randomMatrix(2, n, 24);
  b.old_log_std = log_std.array() + 0.05;
  // Old log-probs spread so that the ratio falls on both sides of [0.8, 1.2].
  b.old_log_probs = s.actor.logProb(s.actor.means(b.inputs), b.actions) + 0.4 * randomMatrix(n, 1, 25);
  b.old_values = s.critic.forward(b.inputs).row(0).transpose() + 0.3 * randomMatrix(n, 1, 26);
  b.advantages = randomMatrix(n, 1, 27);
  b.returns = randomMatrix(n, 1, 28);
  return s;
}

class PpoLossGradient : public ::testing::TestWithParam<bool> {};

TEST_P(PpoLossGradient, MatchesCentralDifferences) {
  LossCase s = makeLossCase();
  pronk::PpoLossSettings settings;
  settings.clip_value_loss = GetParam();
  settings.entropy_coefficient = 0.05;
  settings.value_loss_coefficient = 0.7;

  Eigen::VectorXd actor_gradient, critic_gradient;
  const pronk::PpoLossTerms terms = pronk::ppoLoss(s.actor, s.critic, s.batch, settings, &actor_gradient,
                                                   &critic_gradient);
  // The check means something only if both branches of the clips are taken.
  EXPECT_GT(terms.clip_fraction, 0.1);
  EXPECT_LT(terms.clip_fraction, 0.9);

  const Eigen::VectorXd fd_actor = numericalGradient(
      [&](const Eigen::VectorXd& theta) {
        GaussianPolicy actor = s.actor;
        actor.setParameters(theta);
        return pronk::ppoLoss(actor, s.critic, s.batch, settings).total;
      },
      s.actor.parameters());
  EXPECT_LT(relativeError(actor_gradient, fd_actor), 1e-6);

  const Eigen::VectorXd fd_critic = numericalGradient(
      [&](const Eigen::VectorXd& theta) {
        Mlp critic = s.critic;
        critic.setParameters(theta);
        return pronk::ppoLoss(s.actor, critic, s.batch, settings).total;
      },
      s.critic.parameters());
  EXPECT_LT(relativeError(critic_gradient, fd_critic), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(ValueLoss, PpoLossGradient, ::testing::Values(true, false),
                         [](const auto& info) { return std::string(info.param ? "Clipped" : "Plain"); });

TEST(PpoLoss, ClippedValueLossTakesTheLargerOfTheTwoErrors) {
  // One sample, critic output = its bias: V = 1, V_old = 0, target R = 2.
  // Vc = 0 + clip(1, -0.2, 0.2) = 0.2: (V - R)^2 = 1, (Vc - R)^2 = 3.24.
  LossCase s = makeLossCase();
  Mlp critic({pronk::MlpLayer{Eigen::MatrixXd::Zero(1, 3), Eigen::VectorXd::Ones(1), pronk::Activation::Linear}});
  pronk::PpoMinibatch b;
  b.inputs = randomMatrix(3, 1, 30);
  b.actions = randomMatrix(2, 1, 31);
  b.old_means = s.actor.means(b.inputs);
  b.old_log_std = s.actor.logStd();
  b.old_log_probs = s.actor.logProb(b.old_means, b.actions);
  b.old_values = Eigen::VectorXd::Zero(1);
  b.advantages = Eigen::VectorXd::Ones(1);
  b.returns = Eigen::VectorXd::Constant(1, 2.0);
  EXPECT_NEAR(pronk::ppoLoss(s.actor, critic, b, {}).value, 3.24, 1e-12);
  EXPECT_NEAR(pronk::ppoLoss(s.actor, critic, b, {}).kl, 0.0, 1e-15);
  pronk::PpoLossSettings plain;
  plain.clip_value_loss = false;
  EXPECT_NEAR(pronk::ppoLoss(s.actor, critic, b, plain).value, 1.0, 1e-12);
}

}  // namespace
