// A trainable multilayer perceptron: forward over a batch, backward by hand
// (backprop) to the gradient of a scalar loss, parameters as one flat vector
// for the optimiser, clipping, checkpoints and broadcast. Double precision.
// Its layers are policy.h's MlpLayer, so a trained network becomes an
// MlpPolicy (evaluation, policy files) and comes back without loss.
//
// Batches are matrices with ONE COLUMN PER SAMPLE (inputs x batch), the
// orientation of MlpLayer's weights (one row per output): layer l computes
// Y = activation(W X + b 1^T).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "pronk/policy.h"
#include "pronk/rng.h"

namespace pronk {

// How initialize() draws the parameters.
struct MlpInit {
  enum class Scheme {
    // W and b uniform in +-gain / sqrt(fan_in); gain 1 is PyTorch's nn.Linear
    // default, hence what the paper's rsl_rl networks started from.
    ScaledUniform,
    // W a random orthogonal matrix times gain (sqrt(2) hidden, output_gain
    // last), b = 0: the CleanRL/Stable-Baselines PPO start.
    Orthogonal,
  };
  Scheme scheme = Scheme::ScaledUniform;
  double hidden_gain = 1.0;  // ScaledUniform: 1; Orthogonal: use sqrt(2)
  double output_gain = 1.0;
  // Last layer's W and b exactly 0, so the network outputs exactly 0 (a
  // residual policy starts at its prior).
  bool zero_last_layer = false;

  // The orthogonal start with its usual gains: sqrt(2) hidden, output_gain last
  // (CleanRL: 0.01 for a policy's mean, 1 for a value).
  static MlpInit orthogonal(double output_gain);
};

class Mlp {
 public:
  // What backward() needs from a forward pass: the input and every layer's
  // output (values[l] is layer l's input; values.back() the network's output).
  struct Tape {
    std::vector<Eigen::MatrixXd> values;
  };

  // input -> hidden_sizes... -> output, hidden layers with hidden_activation,
  // the last with output_activation; all parameters 0 until initialize().
  Mlp(int input_size, const std::vector<int>& hidden_sizes, int output_size, Activation hidden_activation = Activation::Elu,
      Activation output_activation = Activation::Linear);
  // The layers of an MlpPolicy (MlpPolicy::layers()). Throws pronk::Error as
  // MlpPolicy's constructor does.
  explicit Mlp(std::vector<MlpLayer> layers);

  void initialize(const MlpInit& init, Rng& rng);

  int inputSize() const { return static_cast<int>(layers_.front().weights.cols()); }
  int outputSize() const { return static_cast<int>(layers_.back().weights.rows()); }
  const std::vector<MlpLayer>& layers() const { return layers_; }

  // Flat parameters: layer by layer, W column-major, then b. Gradients from
  // backward() have the same layout.
  int parameterCount() const { return parameter_count_; }
  Eigen::VectorXd parameters() const;
  void setParameters(const Eigen::VectorXd& parameters);  // parameterCount() values

  // One input: the same arithmetic as MlpPolicy::act, to the bit.
  Eigen::VectorXd evaluate(const Eigen::VectorXd& input) const;
  // A batch (inputSize() x n), optionally keeping the tape for backward().
  // Equal to evaluate() column by column up to rounding (matrix products sum
  // in another order), and identical between runs.
  Eigen::MatrixXd forward(const Eigen::MatrixXd& inputs, Tape* tape = nullptr) const;

  // Gradient of a scalar loss with respect to the parameters, given
  // output_gradient = dLoss/dOutput (outputSize() x n, the tape's batch):
  // contributions of all samples are summed, so a mean over the batch belongs
  // in output_gradient. input_gradient, when given, receives dLoss/dInput.
  Eigen::VectorXd backward(const Tape& tape, const Eigen::MatrixXd& output_gradient,
                           Eigen::MatrixXd* input_gradient = nullptr) const;

 private:
  void countParameters();
  std::vector<MlpLayer> layers_;
  int parameter_count_ = 0;
};

}  // namespace pronk
