// A fixed affine scaling of observations before a network: (o - mean) / std,
// element by element, with mean and std chosen from the task region (not
// learned from data, so a policy means the same thing all through training).
// It is what a policy file calls observation_normalization.
#pragma once

#include <Eigen/Core>

namespace pronk {

class ObservationScaling {
 public:
  // mean and std of one size, finite, std > 0; throws pronk::Error otherwise.
  ObservationScaling(Eigen::VectorXd mean, Eigen::VectorXd std);
  // mean 0, std 1: observations pass unchanged.
  static ObservationScaling identity(int size);
  // The box [low, high] onto [-1, 1]; a component with low == high is only
  // shifted (std 1).
  static ObservationScaling fromBox(const Eigen::VectorXd& low, const Eigen::VectorXd& high);

  int size() const { return static_cast<int>(mean_.size()); }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& std() const { return std_; }

  // The arithmetic of MlpPolicy::act, so both give the same bits.
  Eigen::VectorXd apply(const Eigen::VectorXd& observation) const;
  // One column per observation.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& observations) const;

 private:
  Eigen::VectorXd mean_, std_;
};

}  // namespace pronk
