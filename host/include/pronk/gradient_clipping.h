// Gradient-norm clipping, as PyTorch's clip_grad_norm_: a gradient longer than
// max_norm is scaled to length max_norm, so one outlying batch cannot throw
// the parameters far.
#pragma once

#include <Eigen/Core>

namespace pronk {

// Scales gradient by max_norm / (norm + 1e-6) when that is below 1 (the 1e-6
// is PyTorch's). Returns the Euclidean norm before clipping.
double clipGradientNorm(Eigen::VectorXd& gradient, double max_norm);

}  // namespace pronk
