// Adam: one step, and its state for checkpoints.
#include "pronk/adam.h"

#include <cmath>
#include <string>

#include "pronk/error.h"

namespace pronk {

Adam::Adam(int parameter_count, AdamConfig config) : config_(config) {
  state_.first_moment = Eigen::VectorXd::Zero(parameter_count);
  state_.second_moment = Eigen::VectorXd::Zero(parameter_count);
}

void Adam::step(Eigen::VectorXd& parameters, const Eigen::VectorXd& gradient, double learning_rate) {
  const Eigen::Index n = state_.first_moment.size();
  if (parameters.size() != n || gradient.size() != n) {
    throw Error("adam: " + std::to_string(parameters.size()) + " parameters and " + std::to_string(gradient.size()) +
                " gradients, expected " + std::to_string(n));
  }
  ++state_.step;
  Eigen::VectorXd& m = state_.first_moment;
  Eigen::VectorXd& v = state_.second_moment;
  m = config_.beta1 * m + (1 - config_.beta1) * gradient;
  v = config_.beta2 * v + (1 - config_.beta2) * gradient.cwiseAbs2();
  const double t = static_cast<double>(state_.step);
  const double correction1 = 1 - std::pow(config_.beta1, t);
  const double correction2 = 1 - std::pow(config_.beta2, t);
  // PyTorch's arrangement of the same formula.
  const Eigen::ArrayXd denominator = v.array().sqrt() / std::sqrt(correction2) + config_.epsilon;
  parameters.array() -= (learning_rate / correction1) * m.array() / denominator;
}

void Adam::setState(State state) {
  const Eigen::Index n = state_.first_moment.size();
  if (state.first_moment.size() != n || state.second_moment.size() != n || state.step < 0) {
    throw Error("adam: a state of " + std::to_string(state.first_moment.size()) + " and " +
                std::to_string(state.second_moment.size()) + " moments at step " + std::to_string(state.step) +
                ", expected " + std::to_string(n) + " each and step >= 0");
  }
  state_ = std::move(state);
}

}  // namespace pronk
