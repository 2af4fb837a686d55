// ppoLoss: the terms, and their gradients written out by hand.
#include "pronk/ppo_loss.h"

#include <algorithm>
#include <cmath>

#include "pronk/error.h"

namespace pronk {

PpoLossTerms ppoLoss(const GaussianPolicy& actor, const Mlp& critic, const PpoMinibatch& batch,
                     const PpoLossSettings& settings, Eigen::VectorXd* actor_gradient,
                     Eigen::VectorXd* critic_gradient) {
  const Eigen::Index m = batch.inputs.cols();
  if (m == 0 || batch.actions.cols() != m || batch.old_log_probs.size() != m || batch.old_means.cols() != m ||
      batch.old_values.size() != m || batch.advantages.size() != m || batch.returns.size() != m ||
      critic.outputSize() != 1) {
    throw Error("ppo loss: a minibatch needs one column or value per sample in every part, and a critic of one output");
  }
  const double eps = settings.clip;
  const double inv_m = 1.0 / static_cast<double>(m);

  Mlp::Tape actor_tape, critic_tape;
  const Eigen::MatrixXd means = actor.means(batch.inputs, actor_gradient ? &actor_tape : nullptr);
  const Eigen::VectorXd values = critic.forward(batch.inputs, critic_gradient ? &critic_tape : nullptr).row(0).transpose();
  const Eigen::VectorXd ratio = (actor.logProb(means, batch.actions) - batch.old_log_probs).array().exp().matrix();

  PpoLossTerms terms;
  Eigen::VectorXd surrogate_by_ratio(m);  // d(surrogate_j)/d(rho_j)
  Eigen::VectorXd value_slope(m);         // d(value loss_j)/d(V_j)
  int clipped = 0;
  for (Eigen::Index j = 0; j < m; ++j) {
    const double a = batch.advantages[j], r = ratio[j];
    const double unclipped = -a * r, limited = -a * std::clamp(r, 1 - eps, 1 + eps);
    terms.surrogate += std::max(unclipped, limited);
    // The max takes the unclipped term (slope -A) unless the clipped one is
    // larger, whose slope is 0 outside the band (inside, both are equal).
    surrogate_by_ratio[j] = unclipped >= limited ? -a : 0.0;
    if (std::abs(r - 1) > eps) ++clipped;

    const double v = values[j], target = batch.returns[j];
    const double plain = (v - target) * (v - target);
    if (settings.clip_value_loss) {
      const double step = v - batch.old_values[j];
      const double v_clipped = batch.old_values[j] + std::clamp(step, -eps, eps);
      const double limited_value = (v_clipped - target) * (v_clipped - target);
      terms.value += std::max(plain, limited_value);
      value_slope[j] = plain >= limited_value ? 2 * (v - target)
                                              : (std::abs(step) < eps ? 2 * (v_clipped - target) : 0.0);
    } else {
      terms.value += plain;
      value_slope[j] = 2 * (v - target);
    }
  }
  terms.surrogate *= inv_m;
  terms.value *= inv_m;
  terms.entropy = actor.entropy();
  terms.total = terms.surrogate + settings.value_loss_coefficient * terms.value -
                settings.entropy_coefficient * terms.entropy;
  terms.kl = GaussianPolicy::klDivergence(batch.old_means, batch.old_log_std, means, actor.logStd()).mean();
  terms.clip_fraction = clipped * inv_m;

  if (actor_gradient) {
    // d rho / d log pi = rho.
    const Eigen::VectorXd weights = inv_m * surrogate_by_ratio.cwiseProduct(ratio);
    const GaussianPolicy::LogProbGradient g = actor.logProbGradient(means, batch.actions, weights);
    const Eigen::VectorXd log_std_gradient =
        g.log_std - settings.entropy_coefficient * Eigen::VectorXd::Ones(actor.actionSize());
    *actor_gradient = actor.backward(actor_tape, g.mean, log_std_gradient);
  }
  if (critic_gradient) {
    const Eigen::MatrixXd output_gradient = (settings.value_loss_coefficient * inv_m) * value_slope.transpose();
    *critic_gradient = critic.backward(critic_tape, output_gradient);
  }
  return terms;
}

}  // namespace pronk
