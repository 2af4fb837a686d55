// A trained policy: a multilayer perceptron mapping an observation to an
// action, stored as a JSON policy file (docs/policy-format.md). Evaluation uses
// the Gaussian policy's mean; the exploration std is only kept so that training
// can resume from a file.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pronk {

enum class Activation { Tanh, Relu, Elu, Linear };

// "tanh", "relu", "elu", "linear": the names used in policy files.
const char* activationName(Activation activation);
std::optional<Activation> activationFromName(const std::string& name);

// output = activation(weights * input + bias); weights has one row per output
// and one column per input.
struct MlpLayer {
  Eigen::MatrixXd weights;
  Eigen::VectorXd bias;
  Activation activation = Activation::Linear;
};

// A policy's prior, the environment's own analytic policy (ABI 1.1
// prior_action, e.g. the jump environment's ballistic planner) of the
// environment named here, in one of two kinds:
//   "prior_action":        a residual: action = prior_action(observation) + network(observation);
//   "prior_action_at_aim": an aim correction: action = prior_action(observation + network(observation)),
//                          the network's outputs an offset of the observation (for an environment
//                          whose observation is its task, a corrected target to plan for).
struct PolicyPrior {
  std::string kind = "prior_action";
  std::string environment;  // the environment factory's name, e.g. "jump"
};
inline constexpr const char* kPriorActionKind = "prior_action";
inline constexpr const char* kAimPriorKind = "prior_action_at_aim";

class MlpPolicy {
 public:
  // Throws pronk::Error when there are no layers, a layer is empty, a bias
  // does not match its weights, consecutive layers do not chain or a number
  // is not finite. The message names the part, e.g. "layers[1].weights: ...".
  explicit MlpPolicy(std::vector<MlpLayer> layers);

  int observationSize() const { return static_cast<int>(layers_.front().weights.cols()); }
  int actionSize() const { return static_cast<int>(layers_.back().weights.rows()); }
  const std::vector<MlpLayer>& layers() const { return layers_; }

  // The mean action for an observation. Throws pronk::Error when the
  // observation has the wrong size or a non-finite value.
  Eigen::VectorXd act(const Eigen::VectorXd& observation) const;

  // observation' = (observation - mean) / std before the first layer. Both of
  // observationSize(), std > 0, all finite; throws pronk::Error otherwise.
  void setObservationNormalization(Eigen::VectorXd mean, Eigen::VectorXd std);
  bool hasObservationNormalization() const { return normalization_.has_value(); }
  const Eigen::VectorXd& observationMean() const;  // requires hasObservationNormalization()
  const Eigen::VectorXd& observationStd() const;   // requires hasObservationNormalization()

  // log of the Gaussian policy's per-action std (actionSize(), finite).
  void setActionLogStd(Eigen::VectorXd log_std);
  bool hasActionLogStd() const { return action_log_std_.has_value(); }
  const Eigen::VectorXd& actionLogStd() const;  // requires hasActionLogStd()

  // Free text, and a free JSON object saying how the policy was made
  // (command, seed, jumps, wall time ...). Both are kept through save/load.
  void setDescription(std::string description) { description_ = std::move(description); }
  const std::string& description() const { return description_; }
  void setProvenance(nlohmann::json provenance);  // must be an object
  const nlohmann::json& provenance() const { return provenance_; }

  // A residual over a prior (policy files of version 2); none: the network's
  // output is the action. Throws pronk::Error for an unknown kind or an empty
  // environment name.
  void setPrior(std::optional<PolicyPrior> prior);
  const std::optional<PolicyPrior>& prior() const { return prior_; }

 private:
  struct Normalization {
    Eigen::VectorXd mean, std;
  };
  std::vector<MlpLayer> layers_;
  std::optional<Normalization> normalization_;
  std::optional<Eigen::VectorXd> action_log_std_;
  std::string description_;
  nlohmann::json provenance_ = nlohmann::json::object();
  std::optional<PolicyPrior> prior_;
};

// Reads a policy file. Every problem (unreadable file, JSON syntax, a missing,
// unknown or ill-shaped key, a non-finite number) throws pronk::InputError
// "path:line: key: message".
MlpPolicy loadPolicy(const std::string& path);
// The same from text; `name` stands for the file in messages.
MlpPolicy parsePolicy(const std::string& text, const std::string& name);

// Writes a policy file that loadPolicy reads back bit for bit: version 2 for a
// residual (it has a prior), version 1 otherwise. The file is
// replaced atomically (written beside it, then renamed), so a reader never
// sees half a policy. Throws pronk::Error when it cannot be written.
void savePolicy(const MlpPolicy& policy, const std::string& path);
// The text savePolicy writes.
std::string policyToJson(const MlpPolicy& policy);

}  // namespace pronk
