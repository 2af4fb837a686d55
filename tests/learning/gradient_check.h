// Central finite differences, to check hand-written gradients against.
#pragma once

#include <Eigen/Core>

#include <algorithm>

namespace pronk_test {

// d f / d x by (f(x + h e_i) - f(x - h e_i)) / 2h, for each i.
template <class F>
Eigen::VectorXd numericalGradient(F f, Eigen::VectorXd x, double h = 1e-5) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double xi = x[i];
    x[i] = xi + h;
    const double plus = f(x);
    x[i] = xi - h;
    const double minus = f(x);
    x[i] = xi;
    g[i] = (plus - minus) / (2 * h);
  }
  return g;
}

// |a - b| / max(|a|, |b|), over whole vectors: small components are judged
// against the gradient's size, not their own.
inline double relativeError(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale == 0 ? 0 : (a - b).norm() / scale;
}

// A matrix of independent standard normals, reproducible for a seed.
Eigen::MatrixXd randomMatrix(Eigen::Index rows, Eigen::Index cols, unsigned seed);

}  // namespace pronk_test
