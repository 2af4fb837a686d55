// Mlp: initialisation, flat parameters, batch forward and backprop.
#include "pronk/mlp.h"

#include <Eigen/QR>

#include <cmath>
#include <string>

#include "mlp_layers.h"
#include "policy_checks.h"
#include "pronk/error.h"

namespace pronk {

namespace {

// A rows x cols matrix with orthonormal columns (rows >= cols) or rows, from
// the QR of a Gaussian matrix with R's diagonal made positive: uniform over
// such matrices (Mezzadri 2007), as PyTorch's orthogonal_.
Eigen::MatrixXd randomOrthogonal(Eigen::Index rows, Eigen::Index cols, Rng& rng) {
  const bool tall = rows >= cols;
  const Eigen::Index m = tall ? rows : cols, n = tall ? cols : rows;
  Eigen::MatrixXd g(m, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < m; ++i) g(i, j) = rng.normal();
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(g);
  Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(m, n);
  const Eigen::MatrixXd& r = qr.matrixQR();
  for (Eigen::Index j = 0; j < n; ++j) {
    if (r(j, j) < 0) q.col(j) = -q.col(j);
  }
  return tall ? q : Eigen::MatrixXd(q.transpose());
}

}  // namespace

MlpInit MlpInit::orthogonal(double output_gain) {
  MlpInit init;
  init.scheme = Scheme::Orthogonal;
  init.hidden_gain = std::sqrt(2.0);
  init.output_gain = output_gain;
  return init;
}

Mlp::Mlp(int input_size, const std::vector<int>& hidden_sizes, int output_size, Activation hidden_activation,
         Activation output_activation) {
  std::vector<int> sizes{input_size};
  sizes.insert(sizes.end(), hidden_sizes.begin(), hidden_sizes.end());
  sizes.push_back(output_size);
  for (std::size_t l = 0; l < sizes.size(); ++l) {
    if (sizes[l] <= 0) throw Error("mlp: layer size " + std::to_string(sizes[l]) + " at position " + std::to_string(l) + ", expected > 0");
  }
  for (std::size_t l = 0; l + 1 < sizes.size(); ++l) {
    const bool last = l + 2 == sizes.size();
    layers_.push_back(MlpLayer{Eigen::MatrixXd::Zero(sizes[l + 1], sizes[l]), Eigen::VectorXd::Zero(sizes[l + 1]),
                               last ? output_activation : hidden_activation});
  }
  countParameters();
}

Mlp::Mlp(std::vector<MlpLayer> layers) : layers_(std::move(layers)) {
  if (auto problem = policy_file::layersProblem(layers_)) throw Error("mlp: " + problem->str());
  countParameters();
}

void Mlp::countParameters() {
  parameter_count_ = 0;
  for (const MlpLayer& layer : layers_) parameter_count_ += static_cast<int>(layer.weights.size() + layer.bias.size());
}

void Mlp::initialize(const MlpInit& init, Rng& rng) {
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    MlpLayer& layer = layers_[l];
    const bool last = l + 1 == layers_.size();
    const double gain = last ? init.output_gain : init.hidden_gain;
    if (last && init.zero_last_layer) {
      layer.weights.setZero();
      layer.bias.setZero();
    } else if (init.scheme == MlpInit::Scheme::Orthogonal) {
      layer.weights = gain * randomOrthogonal(layer.weights.rows(), layer.weights.cols(), rng);
      layer.bias.setZero();
    } else {
      const double bound = gain / std::sqrt(static_cast<double>(layer.weights.cols()));
      for (Eigen::Index i = 0; i < layer.weights.size(); ++i) layer.weights.data()[i] = bound * (2 * rng.uniform() - 1);
      for (Eigen::Index i = 0; i < layer.bias.size(); ++i) layer.bias[i] = bound * (2 * rng.uniform() - 1);
    }
  }
}

Eigen::VectorXd Mlp::parameters() const {
  Eigen::VectorXd out(parameter_count_);
  Eigen::Index at = 0;
  for (const MlpLayer& layer : layers_) {
    out.segment(at, layer.weights.size()) = layer.weights.reshaped();
    at += layer.weights.size();
    out.segment(at, layer.bias.size()) = layer.bias;
    at += layer.bias.size();
  }
  return out;
}

void Mlp::setParameters(const Eigen::VectorXd& parameters) {
  if (parameters.size() != parameter_count_) {
    throw Error("mlp: " + std::to_string(parameters.size()) + " parameters, expected " + std::to_string(parameter_count_));
  }
  Eigen::Index at = 0;
  for (MlpLayer& layer : layers_) {
    layer.weights.reshaped() = parameters.segment(at, layer.weights.size());
    at += layer.weights.size();
    layer.bias = parameters.segment(at, layer.bias.size());
    at += layer.bias.size();
  }
}

Eigen::VectorXd Mlp::evaluate(const Eigen::VectorXd& input) const {
  if (input.size() != inputSize()) {
    throw Error("mlp: an input of " + std::to_string(input.size()) + " values, expected " + std::to_string(inputSize()));
  }
  return mlp_layers::evaluate(layers_, input);
}

Eigen::MatrixXd Mlp::forward(const Eigen::MatrixXd& inputs, Tape* tape) const {
  if (inputs.rows() != inputSize()) {
    throw Error("mlp: inputs with " + std::to_string(inputs.rows()) + " rows, expected " + std::to_string(inputSize()) +
                " (one column per sample)");
  }
  if (tape) {
    tape->values.resize(layers_.size() + 1);
    tape->values[0] = inputs;
  }
  Eigen::MatrixXd x = inputs;
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    const MlpLayer& layer = layers_[l];
    Eigen::MatrixXd y = layer.weights * x;
    y.colwise() += layer.bias;
    mlp_layers::activate(layer.activation, y.data(), y.size());
    if (tape) tape->values[l + 1] = y;
    x = std::move(y);
  }
  return x;
}

Eigen::VectorXd Mlp::backward(const Tape& tape, const Eigen::MatrixXd& output_gradient,
                              Eigen::MatrixXd* input_gradient) const {
  if (tape.values.size() != layers_.size() + 1 || output_gradient.rows() != outputSize() ||
      output_gradient.cols() != tape.values.back().cols()) {
    throw Error("mlp: backward needs the tape of a forward pass and a gradient of its output's shape");
  }
  Eigen::VectorXd gradient(parameter_count_);
  Eigen::Index at = parameter_count_;  // layers are visited last to first
  Eigen::MatrixXd dy = output_gradient;  // dLoss/d(layer output)
  for (std::size_t l = layers_.size(); l-- > 0;) {
    const MlpLayer& layer = layers_[l];
    const Eigen::MatrixXd& y = tape.values[l + 1];
    mlp_layers::multiplyByDerivative(layer.activation, y.data(), dy.data(), dy.size());  // now dLoss/dZ
    at -= layer.bias.size();
    gradient.segment(at, layer.bias.size()) = dy.rowwise().sum();
    at -= layer.weights.size();
    gradient.segment(at, layer.weights.size()).reshaped(layer.weights.rows(), layer.weights.cols()) =
        dy * tape.values[l].transpose();
    if (l > 0 || input_gradient) dy = layer.weights.transpose() * dy;
  }
  if (input_gradient) *input_gradient = std::move(dy);
  return gradient;
}

}  // namespace pronk
