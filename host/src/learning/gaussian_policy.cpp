// GaussianPolicy: sampling, log-probability, entropy, KL and their gradients.
#include "pronk/gaussian_policy.h"

#include <cmath>
#include <string>

#include "policy_checks.h"
#include "pronk/error.h"

namespace pronk {

namespace {

constexpr double kLogTwoPi = 1.8378770664093454835606594728112;

void checkBatch(const Eigen::MatrixXd& means, const Eigen::MatrixXd& actions, int action_size) {
  if (means.rows() != action_size || actions.rows() != action_size || means.cols() != actions.cols()) {
    throw Error("gaussian policy: means " + std::to_string(means.rows()) + "x" + std::to_string(means.cols()) +
                " and actions " + std::to_string(actions.rows()) + "x" + std::to_string(actions.cols()) +
                ", expected both " + std::to_string(action_size) + " x batch");
  }
}

}  // namespace

GaussianPolicy::GaussianPolicy(Mlp mean_network, Eigen::VectorXd log_std) : mean_network_(std::move(mean_network)) {
  setLogStd(std::move(log_std));
}

void GaussianPolicy::setLogStd(Eigen::VectorXd log_std) {
  if (auto problem = policy_file::logStdProblem(log_std, actionSize())) throw Error("gaussian policy: " + problem->str());
  log_std_ = std::move(log_std);
}

Eigen::VectorXd GaussianPolicy::parameters() const {
  Eigen::VectorXd out(parameterCount());
  out << mean_network_.parameters(), log_std_;
  return out;
}

void GaussianPolicy::setParameters(const Eigen::VectorXd& parameters) {
  if (parameters.size() != parameterCount()) {
    throw Error("gaussian policy: " + std::to_string(parameters.size()) + " parameters, expected " +
                std::to_string(parameterCount()));
  }
  mean_network_.setParameters(parameters.head(mean_network_.parameterCount()));
  setLogStd(parameters.tail(actionSize()));
}

Eigen::MatrixXd GaussianPolicy::sample(const Eigen::MatrixXd& means, Rng& rng) const {
  if (means.rows() != actionSize()) {
    throw Error("gaussian policy: means with " + std::to_string(means.rows()) + " rows, expected " +
                std::to_string(actionSize()));
  }
  Eigen::MatrixXd actions(means.rows(), means.cols());
  for (Eigen::Index j = 0; j < means.cols(); ++j) {
    for (Eigen::Index i = 0; i < means.rows(); ++i) actions(i, j) = means(i, j) + std::exp(log_std_[i]) * rng.normal();
  }
  return actions;
}

Eigen::VectorXd GaussianPolicy::logProb(const Eigen::MatrixXd& means, const Eigen::MatrixXd& actions) const {
  checkBatch(means, actions, actionSize());
  const Eigen::ArrayXd inverse_variance = (-2.0 * log_std_.array()).exp();
  const double constant = -log_std_.sum() - 0.5 * kLogTwoPi * actionSize();
  const Eigen::ArrayXXd squared = (actions - means).array().square();
  return (-0.5 * (squared.colwise() * inverse_variance).colwise().sum() + constant).transpose().matrix();
}

double GaussianPolicy::entropy() const { return log_std_.sum() + 0.5 * (kLogTwoPi + 1.0) * actionSize(); }

GaussianPolicy::LogProbGradient GaussianPolicy::logProbGradient(const Eigen::MatrixXd& means,
                                                                const Eigen::MatrixXd& actions,
                                                                const Eigen::VectorXd& weights) const {
  checkBatch(means, actions, actionSize());
  if (weights.size() != means.cols()) throw Error("gaussian policy: one weight per sample expected");
  const Eigen::ArrayXd inverse_variance = (-2.0 * log_std_.array()).exp();
  const Eigen::ArrayXXd scaled = (actions - means).array().colwise() * inverse_variance;  // (a - m) / s^2
  LogProbGradient g;
  g.mean = (scaled.rowwise() * weights.transpose().array()).matrix();
  const Eigen::ArrayXXd z2 = scaled * (actions - means).array();  // (a - m)^2 / s^2
  g.log_std = ((z2 - 1.0).rowwise() * weights.transpose().array()).rowwise().sum().matrix();
  return g;
}

Eigen::VectorXd GaussianPolicy::backward(const Mlp::Tape& tape, const Eigen::MatrixXd& mean_gradient,
                                         const Eigen::VectorXd& log_std_gradient) const {
  Eigen::VectorXd out(parameterCount());
  out << mean_network_.backward(tape, mean_gradient), log_std_gradient;
  return out;
}

Eigen::VectorXd GaussianPolicy::klDivergence(const Eigen::MatrixXd& old_means, const Eigen::VectorXd& old_log_std,
                                             const Eigen::MatrixXd& new_means, const Eigen::VectorXd& new_log_std) {
  // sum_i log(s_new / s_old) + (s_old^2 + (m_old - m_new)^2) / (2 s_new^2) - 1/2
  const Eigen::ArrayXd old_variance = (2.0 * old_log_std.array()).exp();
  const Eigen::ArrayXd new_variance = (2.0 * new_log_std.array()).exp();
  const Eigen::ArrayXXd squared = (old_means - new_means).array().square();
  const Eigen::ArrayXXd per_action =
      (squared.colwise() + old_variance).colwise() / (2.0 * new_variance);
  const double constant = (new_log_std - old_log_std).sum() - 0.5 * static_cast<double>(old_log_std.size());
  return (per_action.colwise().sum() + constant).transpose().matrix();
}

}  // namespace pronk
