// MlpPolicy built in code: evaluation against hand-computed numbers, and the
// checks on shapes and values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "pronk/error.h"
#include "pronk/policy.h"

namespace {

using pronk::Activation;
using pronk::MlpLayer;
using pronk::MlpPolicy;

MlpLayer layer(Eigen::MatrixXd weights, Eigen::VectorXd bias, Activation activation) {
  return MlpLayer{std::move(weights), std::move(bias), activation};
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

// A single layer 1 -> ... with identity weights, to look at one activation.
MlpPolicy identity(int size, Activation activation) {
  return MlpPolicy({layer(Eigen::MatrixXd::Identity(size, size), Eigen::VectorXd::Zero(size), activation)});
}

// The message of the pronk::Error that f throws, or "" when it throws none.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const pronk::Error& e) {
    return e.what();
  }
  return "";
}

TEST(MlpPolicy, TwoLayerNetworkMatchesHandComputation) {
  Eigen::MatrixXd w0(2, 2), w1(2, 2);
  w0 << 1, 2,
        -1, 1;
  w1 << 2, -1,
        0.5, 3;
  const MlpPolicy policy({layer(w0, vec({0.5, -1}), Activation::Relu), layer(w1, vec({1, 0}), Activation::Linear)});
  EXPECT_EQ(policy.observationSize(), 2);
  EXPECT_EQ(policy.actionSize(), 2);

  // Layer 0: [1 + 4 + 0.5, -1 + 2 - 1] = [5.5, 0], relu keeps both.
  // Layer 1: [2 * 5.5 - 0 + 1, 0.5 * 5.5 + 0] = [12, 2.75].
  const Eigen::VectorXd a = policy.act(vec({1, 2}));
  EXPECT_EQ(a[0], 12.0);
  EXPECT_EQ(a[1], 2.75);

  // x = [-3, 0]: layer 0 gives [-2.5, 2], relu -> [0, 2]; layer 1 -> [-1, 6].
  const Eigen::VectorXd b = policy.act(vec({-3, 0}));
  EXPECT_EQ(b[0], -1.0);
  EXPECT_EQ(b[1], 6.0);
}

TEST(MlpPolicy, Activations) {
  const Eigen::VectorXd x = vec({-2, -0.5, 0, 0.5, 2});
  const Eigen::VectorXd tanh = identity(5, Activation::Tanh).act(x);
  const Eigen::VectorXd relu = identity(5, Activation::Relu).act(x);
  const Eigen::VectorXd elu = identity(5, Activation::Elu).act(x);
  const Eigen::VectorXd linear = identity(5, Activation::Linear).act(x);
  for (int i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(tanh[i], std::tanh(x[i]));
    EXPECT_EQ(relu[i], x[i] > 0 ? x[i] : 0.0);
    EXPECT_DOUBLE_EQ(elu[i], x[i] > 0 ? x[i] : std::exp(x[i]) - 1);  // alpha = 1
    EXPECT_EQ(linear[i], x[i]);
  }
}

TEST(MlpPolicy, ActivationNames) {
  for (Activation a : {Activation::Tanh, Activation::Relu, Activation::Elu, Activation::Linear}) {
    EXPECT_EQ(pronk::activationFromName(pronk::activationName(a)), a);
  }
  EXPECT_FALSE(pronk::activationFromName("sigmoid"));
  EXPECT_FALSE(pronk::activationFromName("Tanh"));
}

TEST(MlpPolicy, NormalizesObservationsBeforeTheFirstLayer) {
  MlpPolicy policy = identity(3, Activation::Linear);
  policy.setObservationNormalization(vec({1, -2, 0.5}), vec({2, 4, 0.25}));
  ASSERT_TRUE(policy.hasObservationNormalization());
  // (obs - mean) / std = [(3 - 1) / 2, (2 + 2) / 4, (1 - 0.5) / 0.25]
  const Eigen::VectorXd a = policy.act(vec({3, 2, 1}));
  EXPECT_EQ(a[0], 1.0);
  EXPECT_EQ(a[1], 1.0);
  EXPECT_EQ(a[2], 2.0);
}

TEST(MlpPolicy, ActRefusesAWrongSizeAndNonFiniteValues) {
  const MlpPolicy policy = identity(3, Activation::Tanh);
  EXPECT_EQ(errorOf([&] { policy.act(vec({1, 2})); }), "policy: the observation has 2 values, expected 3");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(errorOf([&] { policy.act(vec({1, nan, 0})); }),
            "policy: observation[1] is nan, expected a finite number");
  EXPECT_EQ(errorOf([&] { policy.act(vec({1, 0, -inf})); }),
            "policy: observation[2] is -inf, expected a finite number");
}

TEST(MlpPolicy, ConstructorChecksShapesAndValues) {
  EXPECT_EQ(errorOf([] { MlpPolicy({}); }), "policy: layers: no layers; a policy needs at least one");
  // 2 -> 4, then a layer that takes 3 inputs.
  EXPECT_EQ(errorOf([] {
              MlpPolicy({layer(Eigen::MatrixXd::Zero(4, 2), Eigen::VectorXd::Zero(4), Activation::Tanh),
                         layer(Eigen::MatrixXd::Zero(1, 3), Eigen::VectorXd::Zero(1), Activation::Linear)});
            }),
            "policy: layers[1].weights: 3 columns (inputs), expected 4 (the rows of layers[0].weights)");
  EXPECT_EQ(errorOf([] { MlpPolicy({layer(Eigen::MatrixXd::Zero(4, 2), Eigen::VectorXd::Zero(3), Activation::Tanh)}); }),
            "policy: layers[0].bias: 3 values, expected 4 (the rows of layers[0].weights)");
  EXPECT_EQ(errorOf([] { MlpPolicy({layer(Eigen::MatrixXd::Zero(0, 2), Eigen::VectorXd::Zero(0), Activation::Tanh)}); }),
            "policy: layers[0].weights: no rows (one row per output)");
  EXPECT_EQ(errorOf([] {
              Eigen::MatrixXd w = Eigen::MatrixXd::Zero(2, 3);
              w(1, 2) = std::numeric_limits<double>::infinity();
              MlpPolicy({layer(w, Eigen::VectorXd::Zero(2), Activation::Tanh)});
            }),
            "policy: layers[0].weights[1][2]: inf is not a finite number");
}

TEST(MlpPolicy, SettersCheckTheirValues) {
  MlpPolicy policy = identity(2, Activation::Tanh);
  EXPECT_EQ(errorOf([&] { policy.setObservationNormalization(vec({0, 0}), vec({1, -1})); }),
            "policy: observation_normalization.std[1]: -1.0 must be > 0");
  EXPECT_EQ(errorOf([&] { policy.setObservationNormalization(vec({0}), vec({1, 1})); }),
            "policy: observation_normalization.mean: 1 value, expected 2 (observation_size)");
  EXPECT_EQ(errorOf([&] { policy.setActionLogStd(vec({0, 0, 0})); }),
            "policy: action_log_std: 3 values, expected 2 (action_size)");
  EXPECT_EQ(errorOf([&] { policy.setProvenance(nlohmann::json::array()); }),
            "policy: provenance: expected a JSON object, got array");
  EXPECT_FALSE(policy.hasObservationNormalization());
  EXPECT_FALSE(policy.hasActionLogStd());
  EXPECT_TRUE(policy.provenance().is_object());
}

}  // namespace
