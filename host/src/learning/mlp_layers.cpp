// Activations, their derivatives, and one input through a list of layers.
#include "mlp_layers.h"

#include <cmath>

namespace pronk::mlp_layers {

void activate(Activation activation, double* x, Eigen::Index n) {
  switch (activation) {
    case Activation::Tanh:  // std::tanh, not Eigen's: the same in every build
      for (Eigen::Index i = 0; i < n; ++i) x[i] = std::tanh(x[i]);
      break;
    case Activation::Relu:
      for (Eigen::Index i = 0; i < n; ++i) x[i] = x[i] > 0 ? x[i] : 0.0;
      break;
    case Activation::Elu:  // alpha = 1; expm1 keeps precision near 0
      for (Eigen::Index i = 0; i < n; ++i) x[i] = x[i] > 0 ? x[i] : std::expm1(x[i]);
      break;
    case Activation::Linear:
      break;
  }
}

void multiplyByDerivative(Activation activation, const double* y, double* gradient, Eigen::Index n) {
  switch (activation) {
    case Activation::Tanh:  // 1 - tanh^2
      for (Eigen::Index i = 0; i < n; ++i) gradient[i] *= 1.0 - y[i] * y[i];
      break;
    case Activation::Relu:  // y > 0 exactly where z > 0; the kink's derivative is taken as 0
      for (Eigen::Index i = 0; i < n; ++i) gradient[i] = y[i] > 0 ? gradient[i] : 0.0;
      break;
    case Activation::Elu:  // e^z = y + 1 for z <= 0
      for (Eigen::Index i = 0; i < n; ++i) gradient[i] *= y[i] > 0 ? 1.0 : y[i] + 1.0;
      break;
    case Activation::Linear:
      break;
  }
}

Eigen::VectorXd evaluate(const std::vector<MlpLayer>& layers, Eigen::VectorXd x) {
  for (const MlpLayer& layer : layers) {
    x = layer.weights * x + layer.bias;
    activate(layer.activation, x.data(), x.size());
  }
  return x;
}

}  // namespace pronk::mlp_layers
