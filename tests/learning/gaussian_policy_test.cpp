// GaussianPolicy: log-probability and entropy against their closed forms, and
// their gradients (by the means, the log-std, and through the network) against
// finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "gradient_check.h"
#include "pronk/gaussian_policy.h"

namespace {

using pronk::GaussianPolicy;
using pronk::Mlp;
using pronk_test::numericalGradient;
using pronk_test::randomMatrix;
using pronk_test::relativeError;

const double kPi = 3.14159265358979323846;

GaussianPolicy randomPolicy(unsigned seed) {
  Mlp mean(3, {6}, 2, pronk::Activation::Tanh);
  pronk::Rng rng(seed);
  mean.initialize(pronk::MlpInit{}, rng);
  Eigen::VectorXd log_std(2);
  log_std << -0.3, 0.4;
  return GaussianPolicy(std::move(mean), log_std);
}

TEST(GaussianPolicy, LogProbAndEntropyMatchTheNormalDensity) {
  const GaussianPolicy policy = randomPolicy(1);
  Eigen::MatrixXd means(2, 1), actions(2, 1);
  means << 0.5, -1.0;
  actions << 0.1, 0.7;
  double expected = 0;
  for (int i = 0; i < 2; ++i) {
    const double s = std::exp(policy.logStd()[i]);
    expected += std::log(std::exp(-0.5 * std::pow((actions(i) - means(i)) / s, 2)) / (s * std::sqrt(2 * kPi)));
  }
  EXPECT_NEAR(policy.logProb(means, actions)[0], expected, 1e-14);
  const double s0 = std::exp(-0.3), s1 = std::exp(0.4);
  EXPECT_NEAR(policy.entropy(), std::log(s0 * std::sqrt(2 * kPi * std::exp(1.0))) +
                                    std::log(s1 * std::sqrt(2 * kPi * std::exp(1.0))), 1e-14);
}

TEST(GaussianPolicy, SamplesHaveTheMeanAndStd) {
  const GaussianPolicy policy = randomPolicy(2);
  const int n = 100000;
  pronk::Rng rng(3);
  const Eigen::MatrixXd means = Eigen::MatrixXd::Constant(2, n, 1.5);
  const Eigen::MatrixXd a = policy.sample(means, rng);
  for (int i = 0; i < 2; ++i) {
    const double s = std::exp(policy.logStd()[i]);
    const double mean = a.row(i).mean();
    EXPECT_NEAR(mean, 1.5, 5 * s / std::sqrt(n));
    EXPECT_NEAR(std::sqrt((a.row(i).array() - mean).square().mean()), s, 0.01 * s);
  }
}

TEST(GaussianPolicy, LogProbGradientMatchesCentralDifferences) {
  GaussianPolicy policy = randomPolicy(4);
  const Eigen::MatrixXd means = randomMatrix(2, 5, 5), actions = randomMatrix(2, 5, 6);
  const Eigen::VectorXd weights = randomMatrix(5, 1, 7);
  const auto g = policy.logProbGradient(means, actions, weights);

  const Eigen::VectorXd fd_mean = numericalGradient(
      [&](const Eigen::VectorXd& m) { return weights.dot(policy.logProb(Eigen::MatrixXd(m.reshaped(2, 5)), actions)); },
      means.reshaped());
  EXPECT_LT(relativeError(g.mean.reshaped(), fd_mean), 1e-6);

  const Eigen::VectorXd fd_log_std = numericalGradient(
      [&](const Eigen::VectorXd& ls) {
        GaussianPolicy p = policy;
        p.setLogStd(ls);
        return weights.dot(p.logProb(means, actions));
      },
      policy.logStd());
  EXPECT_LT(relativeError(g.log_std, fd_log_std), 1e-6);

  const Eigen::VectorXd fd_entropy = numericalGradient(
      [&](const Eigen::VectorXd& ls) {
        GaussianPolicy p = policy;
        p.setLogStd(ls);
        return p.entropy();
      },
      policy.logStd());
  EXPECT_LT(relativeError(Eigen::VectorXd::Ones(2), fd_entropy), 1e-6);  // dH/dlog_std = 1
}

TEST(GaussianPolicy, GradientThroughTheNetworkMatchesCentralDifferences) {
  GaussianPolicy policy = randomPolicy(8);
  const Eigen::MatrixXd x = randomMatrix(3, 6, 9), actions = randomMatrix(2, 6, 10);
  const Eigen::VectorXd weights = randomMatrix(6, 1, 11);
  // L = sum_j w_j log pi(a_j | x_j) + 0.3 H
  const auto objective = [&](const GaussianPolicy& p) {
    return weights.dot(p.logProb(p.means(x), actions)) + 0.3 * p.entropy();
  };
  Mlp::Tape tape;
  const Eigen::MatrixXd means = policy.means(x, &tape);
  const auto g = policy.logProbGradient(means, actions, weights);
  const Eigen::VectorXd gradient = policy.backward(tape, g.mean, g.log_std + 0.3 * Eigen::VectorXd::Ones(2));
  const Eigen::VectorXd fd = numericalGradient(
      [&](const Eigen::VectorXd& theta) {
        GaussianPolicy p = policy;
        p.setParameters(theta);
        return objective(p);
      },
      policy.parameters());
  EXPECT_LT(relativeError(gradient, fd), 1e-6);
}

TEST(GaussianPolicy, KlDivergenceIsZeroForEqualPoliciesAndMatchesTheClosedForm) {
  const Eigen::MatrixXd m = randomMatrix(2, 3, 12);
  Eigen::VectorXd ls(2);
  ls << 0.1, -0.2;
  EXPECT_LT(GaussianPolicy::klDivergence(m, ls, m, ls).cwiseAbs().maxCoeff(), 1e-15);
  // One dimension: KL(N(0, 1) || N(1, 2^2)) = log 2 + (1 + 1) / 8 - 1/2.
  Eigen::MatrixXd m0(1, 1), m1(1, 1);
  m0 << 0;
  m1 << 1;
  Eigen::VectorXd l0(1), l1(1);
  l0 << 0;
  l1 << std::log(2.0);
  EXPECT_NEAR(GaussianPolicy::klDivergence(m0, l0, m1, l1)[0], std::log(2.0) + 0.25 - 0.5, 1e-15);
}

}  // namespace
