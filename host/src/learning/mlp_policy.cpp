// MlpPolicy: construction with shape checks, and evaluation.
#include <cassert>
#include <cmath>

#include "mlp_layers.h"
#include "policy_checks.h"
#include "pronk/error.h"
#include "pronk/policy.h"

namespace pronk {

namespace {

constexpr Activation kActivations[] = {Activation::Tanh, Activation::Relu, Activation::Elu, Activation::Linear};

void throwIf(const std::optional<policy_file::Problem>& problem) {
  if (problem) throw Error("policy: " + problem->str());
}

}  // namespace

const char* activationName(Activation activation) {
  switch (activation) {
    case Activation::Tanh:
      return "tanh";
    case Activation::Relu:
      return "relu";
    case Activation::Elu:
      return "elu";
    case Activation::Linear:
      return "linear";
  }
  return "?";
}

std::optional<Activation> activationFromName(const std::string& name) {
  for (Activation a : kActivations) {
    if (name == activationName(a)) return a;
  }
  return std::nullopt;
}

MlpPolicy::MlpPolicy(std::vector<MlpLayer> layers) : layers_(std::move(layers)) {
  throwIf(policy_file::layersProblem(layers_));
}

Eigen::VectorXd MlpPolicy::act(const Eigen::VectorXd& observation) const {
  if (observation.size() != observationSize()) {
    throw Error("policy: the observation has " + policy_file::counted(observation.size(), "value") + ", expected " +
                std::to_string(observationSize()));
  }
  for (Eigen::Index i = 0; i < observation.size(); ++i) {
    if (!std::isfinite(observation[i])) {
      throw Error("policy: observation[" + std::to_string(i) + "] is " + policy_file::numberText(observation[i]) +
                  ", expected a finite number");
    }
  }
  Eigen::VectorXd x = observation;
  if (normalization_) x = (x - normalization_->mean).cwiseQuotient(normalization_->std);
  return mlp_layers::evaluate(layers_, std::move(x));
}

void MlpPolicy::setObservationNormalization(Eigen::VectorXd mean, Eigen::VectorXd std) {
  throwIf(policy_file::normalizationProblem(mean, std, observationSize()));
  normalization_ = Normalization{std::move(mean), std::move(std)};
}

const Eigen::VectorXd& MlpPolicy::observationMean() const {
  assert(normalization_);
  return normalization_->mean;
}

const Eigen::VectorXd& MlpPolicy::observationStd() const {
  assert(normalization_);
  return normalization_->std;
}

void MlpPolicy::setActionLogStd(Eigen::VectorXd log_std) {
  throwIf(policy_file::logStdProblem(log_std, actionSize()));
  action_log_std_ = std::move(log_std);
}

const Eigen::VectorXd& MlpPolicy::actionLogStd() const {
  assert(action_log_std_);
  return *action_log_std_;
}

void MlpPolicy::setPrior(std::optional<PolicyPrior> prior) {
  if (prior && prior->kind != kPriorActionKind && prior->kind != kAimPriorKind) {
    throw Error("policy: prior.kind: unknown prior \"" + prior->kind + "\" (known: " + kPriorActionKind + ", " +
                kAimPriorKind + ")");
  }
  if (prior && prior->environment.empty()) throw Error("policy: prior.environment: empty");
  prior_ = std::move(prior);
}

void MlpPolicy::setProvenance(nlohmann::json provenance) {
  if (!provenance.is_object()) {
    throw Error("policy: provenance: expected a JSON object, got " + std::string(provenance.type_name()));
  }
  provenance_ = std::move(provenance);
}

namespace policy_file {

std::string numberText(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return nlohmann::json(value).dump();  // shortest text that reads back exactly
}

std::string counted(long long n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

namespace {

std::optional<Problem> nonFinite(const Eigen::VectorXd& v, const JsonPath& path) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return Problem{path.index(i), numberText(v[i]) + " is not a finite number"};
  }
  return std::nullopt;
}

std::optional<Problem> sizeProblem(const Eigen::VectorXd& v, const JsonPath& path, int expected,
                                   const std::string& what) {
  if (v.size() == expected) return std::nullopt;
  return Problem{path, counted(v.size(), "value") + ", expected " + std::to_string(expected) + " (" + what + ")"};
}

}  // namespace

std::optional<Problem> layersProblem(const std::vector<MlpLayer>& layers) {
  const JsonPath root = JsonPath().key("layers");
  if (layers.empty()) return Problem{root, "no layers; a policy needs at least one"};
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const MlpLayer& layer = layers[l];
    const JsonPath at = root.index(l);
    const JsonPath weights = at.key("weights");
    if (layer.weights.rows() == 0) return Problem{weights, "no rows (one row per output)"};
    if (layer.weights.cols() == 0) return Problem{weights, "no columns (one column per input)"};
    if (l > 0 && layer.weights.cols() != layers[l - 1].weights.rows()) {
      return Problem{weights, counted(layer.weights.cols(), "column") + " (inputs), expected " +
                                  std::to_string(layers[l - 1].weights.rows()) + " (the rows of layers[" +
                                  std::to_string(l - 1) + "].weights)"};
    }
    if (layer.bias.size() != layer.weights.rows()) {
      return Problem{at.key("bias"), counted(layer.bias.size(), "value") + ", expected " +
                                         std::to_string(layer.weights.rows()) + " (the rows of " +
                                         weights.str() + ")"};
    }
    for (Eigen::Index r = 0; r < layer.weights.rows(); ++r) {
      if (auto p = nonFinite(layer.weights.row(r).transpose(), weights.index(r))) return p;
    }
    if (auto p = nonFinite(layer.bias, at.key("bias"))) return p;
  }
  return std::nullopt;
}

std::optional<Problem> normalizationProblem(const Eigen::VectorXd& mean, const Eigen::VectorXd& std,
                                            int observation_size) {
  const JsonPath root = JsonPath().key("observation_normalization");
  if (auto p = sizeProblem(mean, root.key("mean"), observation_size, "observation_size")) return p;
  if (auto p = sizeProblem(std, root.key("std"), observation_size, "observation_size")) return p;
  if (auto p = nonFinite(mean, root.key("mean"))) return p;
  if (auto p = nonFinite(std, root.key("std"))) return p;
  for (Eigen::Index i = 0; i < std.size(); ++i) {
    if (!(std[i] > 0)) return Problem{root.key("std").index(i), numberText(std[i]) + " must be > 0"};
  }
  return std::nullopt;
}

std::optional<Problem> logStdProblem(const Eigen::VectorXd& log_std, int action_size) {
  const JsonPath path = JsonPath().key("action_log_std");
  if (auto p = sizeProblem(log_std, path, action_size, "action_size")) return p;
  return nonFinite(log_std, path);
}

}  // namespace policy_file
}  // namespace pronk
