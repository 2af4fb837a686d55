// ObservationScaling: checks and the element-wise map.
#include "pronk/observation_scaling.h"

#include <string>

#include "policy_checks.h"
#include "pronk/error.h"

namespace pronk {

ObservationScaling::ObservationScaling(Eigen::VectorXd mean, Eigen::VectorXd std)
    : mean_(std::move(mean)), std_(std::move(std)) {
  if (auto problem = policy_file::normalizationProblem(mean_, std_, static_cast<int>(mean_.size()))) {
    throw Error("observation scaling: " + problem->str());
  }
}

ObservationScaling ObservationScaling::identity(int size) {
  return ObservationScaling(Eigen::VectorXd::Zero(size), Eigen::VectorXd::Ones(size));
}

ObservationScaling ObservationScaling::fromBox(const Eigen::VectorXd& low, const Eigen::VectorXd& high) {
  if (low.size() != high.size()) {
    throw Error("observation scaling: low has " + std::to_string(low.size()) + " values, high " +
                std::to_string(high.size()));
  }
  Eigen::VectorXd mean = 0.5 * (low + high), std = 0.5 * (high - low);
  for (Eigen::Index i = 0; i < std.size(); ++i) {
    if (std[i] == 0) std[i] = 1;
  }
  return ObservationScaling(std::move(mean), std::move(std));
}

Eigen::VectorXd ObservationScaling::apply(const Eigen::VectorXd& observation) const {
  if (observation.size() != mean_.size()) {
    throw Error("observation scaling: an observation of " + std::to_string(observation.size()) + " values, expected " +
                std::to_string(mean_.size()));
  }
  return (observation - mean_).cwiseQuotient(std_);
}

Eigen::MatrixXd ObservationScaling::apply(const Eigen::MatrixXd& observations) const {
  if (observations.rows() != mean_.size()) {
    throw Error("observation scaling: observations with " + std::to_string(observations.rows()) +
                " rows, expected " + std::to_string(mean_.size()) + " (one column per observation)");
  }
  return (observations.colwise() - mean_).array().colwise() / std_.array();
}

}  // namespace pronk
