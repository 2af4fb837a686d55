// Mlp: backprop against finite differences for every activation, the flat
// parameter layout, initialisation (zero last layer, orthogonal), and the
// conversion to MlpPolicy and back without loss.
#include <gtest/gtest.h>

#include <cmath>

#include "gradient_check.h"
#include "pronk/mlp.h"
#include "pronk/policy.h"
#include "pronk/rng.h"

namespace {

using pronk::Activation;
using pronk::Mlp;
using pronk::MlpInit;
using pronk_test::numericalGradient;
using pronk_test::randomMatrix;
using pronk_test::relativeError;

// A scalar loss with a nonlinear dependence on the output:
// L = sum(C .* Y) + 0.5 sum(Y .^ 2), dL/dY = C + Y.
double loss(const Eigen::MatrixXd& y, const Eigen::MatrixXd& c) {
  return (c.array() * y.array()).sum() + 0.5 * y.squaredNorm();
}

Mlp randomNet(Activation hidden, Activation output, unsigned seed) {
  Mlp mlp(3, {5, 4}, 2, hidden, output);
  pronk::Rng rng(seed);
  mlp.initialize(MlpInit{}, rng);
  // Biases and weights of order 1, so every activation works away from 0 too.
  mlp.setParameters(mlp.parameters() + 0.5 * randomMatrix(mlp.parameterCount(), 1, seed + 1));
  return mlp;
}

class MlpGradient : public ::testing::TestWithParam<Activation> {};

TEST_P(MlpGradient, BackpropMatchesCentralDifferences) {
  const Activation a = GetParam();
  for (Activation output : {Activation::Linear, a}) {
    Mlp mlp = randomNet(a, output, 5);
    const Eigen::MatrixXd x = randomMatrix(3, 7, 6);  // a batch of 7
    const Eigen::MatrixXd c = randomMatrix(2, 7, 8);

    Mlp::Tape tape;
    const Eigen::MatrixXd y = mlp.forward(x, &tape);
    Eigen::MatrixXd input_gradient;
    const Eigen::VectorXd g = mlp.backward(tape, c + y, &input_gradient);

    const Eigen::VectorXd fd = numericalGradient(
        [&](const Eigen::VectorXd& p) {
          Mlp copy = mlp;
          copy.setParameters(p);
          return loss(copy.forward(x), c);
        },
        mlp.parameters());
    EXPECT_LT(relativeError(g, fd), 1e-6) << pronk::activationName(a);

    const Eigen::VectorXd fd_input = numericalGradient(
        [&](const Eigen::VectorXd& flat) { return loss(mlp.forward(Eigen::MatrixXd(flat.reshaped(3, 7))), c); },
        x.reshaped());
    EXPECT_LT(relativeError(input_gradient.reshaped(), fd_input), 1e-6) << pronk::activationName(a);
  }
}

INSTANTIATE_TEST_SUITE_P(AllActivations, MlpGradient,
                         ::testing::Values(Activation::Elu, Activation::Tanh, Activation::Relu, Activation::Linear),
                         [](const auto& info) { return std::string(pronk::activationName(info.param)); });

TEST(Mlp, FlatParametersAreWeightsColumnMajorThenBiasPerLayer) {
  Mlp mlp(2, {3}, 1);
  Eigen::VectorXd p(mlp.parameterCount());
  ASSERT_EQ(p.size(), 2 * 3 + 3 + 3 * 1 + 1);
  for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = static_cast<double>(i);
  mlp.setParameters(p);
  const auto& l0 = mlp.layers()[0];
  EXPECT_EQ(l0.weights(0, 0), 0);
  EXPECT_EQ(l0.weights(1, 0), 1);  // down the first column
  EXPECT_EQ(l0.weights(0, 1), 3);
  EXPECT_EQ(l0.bias[0], 6);
  EXPECT_EQ(mlp.layers()[1].weights(0, 2), 11);
  EXPECT_EQ(mlp.layers()[1].bias[0], 12);
  EXPECT_EQ(mlp.parameters(), p);
}

TEST(Mlp, ZeroLastLayerGivesExactlyZeroOutput) {
  for (auto scheme : {MlpInit::Scheme::ScaledUniform, MlpInit::Scheme::Orthogonal}) {
    Mlp mlp(4, {16, 8}, 3);
    MlpInit init;
    init.scheme = scheme;
    init.zero_last_layer = true;
    pronk::Rng rng(1);
    mlp.initialize(init, rng);
    EXPECT_NE(mlp.layers()[0].weights.norm(), 0.0);  // the rest is random
    const Eigen::MatrixXd y = mlp.forward(10 * randomMatrix(4, 9, 2));
    for (Eigen::Index i = 0; i < y.size(); ++i) {
      EXPECT_EQ(y.data()[i], 0.0);
      EXPECT_FALSE(std::signbit(y.data()[i]));  // +0, not -0
    }
  }
}

TEST(Mlp, OrthogonalInitHasOrthonormalRowsOrColumnsTimesGain) {
  Mlp mlp(3, {6}, 2);
  pronk::Rng rng(9);
  mlp.initialize(MlpInit::orthogonal(0.5), rng);
  const Eigen::MatrixXd& tall = mlp.layers()[0].weights;   // 6 x 3: orthonormal columns
  const Eigen::MatrixXd& wide = mlp.layers()[1].weights;   // 2 x 6: orthonormal rows
  EXPECT_LT((tall.transpose() * tall - 2.0 * Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-12);  // gain sqrt(2)
  EXPECT_LT((wide * wide.transpose() - 0.25 * Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-12);
  EXPECT_EQ(mlp.layers()[0].bias.norm(), 0.0);
}

TEST(Mlp, ScaledUniformStaysWithinItsBoundAndDependsOnTheSeed) {
  Mlp a(16, {8}, 1), b(16, {8}, 1), c(16, {8}, 1);
  pronk::Rng ra(4), rb(4), rc(5);
  a.initialize(MlpInit{}, ra);
  b.initialize(MlpInit{}, rb);
  c.initialize(MlpInit{}, rc);
  EXPECT_EQ(a.parameters(), b.parameters());
  EXPECT_NE(a.parameters(), c.parameters());
  EXPECT_LE(a.layers()[0].weights.cwiseAbs().maxCoeff(), 1.0 / 4);  // 1 / sqrt(16)
  EXPECT_GT(a.layers()[0].weights.cwiseAbs().maxCoeff(), 0.2);
}

TEST(Mlp, ConvertsToMlpPolicyAndBackWithoutLoss) {
  const Mlp mlp = randomNet(Activation::Elu, Activation::Linear, 12);
  const pronk::MlpPolicy policy(mlp.layers());
  const Mlp back(policy.layers());
  EXPECT_EQ(back.parameters(), mlp.parameters());
  const Eigen::MatrixXd x = randomMatrix(3, 5, 13);
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const Eigen::VectorXd a = mlp.evaluate(x.col(j));
    EXPECT_EQ(a, policy.act(x.col(j)));  // bit for bit
    EXPECT_LT((a - mlp.forward(x).col(j)).norm(), 1e-14);  // the batch path, up to rounding
  }
}

}  // namespace
