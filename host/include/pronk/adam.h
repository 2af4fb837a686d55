// Adam (Kingma and Ba 2015) with bias correction, as PyTorch's torch.optim.Adam
// without weight decay. Its state (the two moments and the step count) is
// public so that a checkpoint can carry it and a resumed run continue exactly.
#pragma once

#include <Eigen/Core>

namespace pronk {

struct AdamConfig {
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-8;
};

class Adam {
 public:
  struct State {
    Eigen::VectorXd first_moment;   // m
    Eigen::VectorXd second_moment;  // v
    long long step = 0;             // updates taken
  };

  Adam(int parameter_count, AdamConfig config = {});

  // parameters -= learning_rate * m_hat / (sqrt(v_hat) + epsilon).
  void step(Eigen::VectorXd& parameters, const Eigen::VectorXd& gradient, double learning_rate);

  const AdamConfig& config() const { return config_; }
  const State& state() const { return state_; }
  // Moments of the parameter count, step >= 0; throws pronk::Error otherwise.
  void setState(State state);

 private:
  AdamConfig config_;
  State state_;
};

}  // namespace pronk
