// clipGradientNorm.
#include "pronk/gradient_clipping.h"

namespace pronk {

double clipGradientNorm(Eigen::VectorXd& gradient, double max_norm) {
  const double norm = gradient.norm();
  const double scale = max_norm / (norm + 1e-6);
  if (scale < 1) gradient *= scale;
  return norm;
}

}  // namespace pronk
