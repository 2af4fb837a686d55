// The arithmetic of MlpLayer, shared by MlpPolicy (evaluation) and Mlp
// (training) so that a trained network and its policy file give the same
// action to the last bit.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "pronk/policy.h"

namespace pronk::mlp_layers {

// x = activation(x), element by element, over n contiguous values.
void activate(Activation activation, double* x, Eigen::Index n);

// gradient *= activation'(z), where y = activation(z) is what activate gave:
// each derivative follows from the output alone, so backprop keeps only y.
void multiplyByDerivative(Activation activation, const double* y, double* gradient, Eigen::Index n);

// The layers applied in order to one input vector.
Eigen::VectorXd evaluate(const std::vector<MlpLayer>& layers, Eigen::VectorXd x);

}  // namespace pronk::mlp_layers
