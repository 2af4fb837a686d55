// Checks shared by MlpPolicy (code building a policy) and the policy file
// reader, so that both report the same problem in the same words, naming the
// part by its policy-file path ("layers[1].weights: ...").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "json_text.h"
#include "pronk/policy.h"

namespace pronk::policy_file {

struct Problem {
  JsonPath path;
  std::string message;
  std::string str() const { return path.str() + ": " + message; }
};

// No layers, an empty layer, a bias that does not match its weights, layers
// that do not chain, a non-finite number.
std::optional<Problem> layersProblem(const std::vector<MlpLayer>& layers);
// Sizes (observation_size each), finite numbers, std > 0.
std::optional<Problem> normalizationProblem(const Eigen::VectorXd& mean, const Eigen::VectorXd& std,
                                            int observation_size);
// Size action_size, finite numbers.
std::optional<Problem> logStdProblem(const Eigen::VectorXd& log_std, int action_size);

// The shortest text that reads back as the number ("0.5", "0.1", "nan").
std::string numberText(double value);
// "1 value", "3 values".
std::string counted(long long n, const std::string& noun);

}  // namespace pronk::policy_file
