// Adam and gradient-norm clipping.
#include <gtest/gtest.h>

#include <cmath>

#include "pronk/adam.h"
#include "pronk/gradient_clipping.h"

namespace {

TEST(Adam, ConvergesToTheMinimumOfAQuadratic) {
  // f(x) = 1/2 (x - c)^T D (x - c), badly scaled: D = diag(100, 1, 0.01).
  Eigen::VectorXd c(3), d(3);
  c << 1, -2, 3;
  d << 100, 1, 0.01;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  pronk::Adam adam(3);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::VectorXd gradient = d.cwiseProduct(x - c);
    adam.step(x, gradient, i < 4000 ? 0.05 : 0.005);
  }
  EXPECT_LT((x - c).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_EQ(adam.state().step, 5000);
}

TEST(Adam, FirstStepHasTheLearningRateAsItsSize) {
  // With bias correction, m_hat = g and v_hat = g^2 after one step, so each
  // parameter moves by lr * g / (|g| + eps): lr, whatever the gradient's scale.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2), g(2);
  g << 1e-3, -50;
  pronk::Adam adam(2);
  adam.step(x, g, 0.1);
  EXPECT_NEAR(x[0], -0.1, 1e-6);
  EXPECT_NEAR(x[1], 0.1, 1e-9);
}

TEST(Adam, StateRoundTripsAndContinuesIdentically) {
  Eigen::VectorXd x = Eigen::VectorXd::Ones(2), g(2);
  g << 0.3, -0.7;
  pronk::Adam a(2), b(2);
  a.step(x, g, 0.01);
  b.setState(a.state());
  Eigen::VectorXd xa = x, xb = x;
  a.step(xa, g, 0.01);
  b.step(xb, g, 0.01);
  EXPECT_EQ(xa, xb);
  EXPECT_THROW(b.setState(pronk::Adam::State{Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), 0}), std::exception);
}

TEST(GradientClipping, ScalesALongGradientToTheMaxNormAndLeavesAShortOne) {
  Eigen::VectorXd long_gradient(2), short_gradient(2);
  long_gradient << 3, 4;
  short_gradient << 0.3, 0.4;
  EXPECT_EQ(pronk::clipGradientNorm(long_gradient, 1.0), 5.0);
  EXPECT_NEAR(long_gradient.norm(), 1.0, 1e-6);
  EXPECT_NEAR(long_gradient[0] / long_gradient[1], 0.75, 1e-15);  // direction kept
  EXPECT_NEAR(pronk::clipGradientNorm(short_gradient, 1.0), 0.5, 1e-15);
  EXPECT_EQ(short_gradient[0], 0.3);
}

}  // namespace
