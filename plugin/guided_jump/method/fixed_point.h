// A scalar fixed point x = f(x) by the secant method on g(x) = f(x) - x, with
// a plain (or half-damped) step where the secant step misbehaves. The planner's
// rule (docs/method-planner.md) depends on its own lift-off point only through
// one number, the lift-off offset along the jump plane; this solves for it in
// about a third of the rounds of plain iteration.
#pragma once

#include <algorithm>
#include <cmath>

namespace pronk::jump {

struct FixedPoint1D {
  double x = 0.0;           // the last point f was evaluated at (the solution when converged)
  double fx = 0.0;          // f(x)
  int evaluations = 0;      // calls of f
  int fallbacks = 0;        // steps that were not secant steps for want of a usable secant
  bool converged = false;   // |f(x) - x| <= tolerance
};

// Solves x = f(x) for an f that maps [lo, hi] into itself, from x0 (clamped
// into [lo, hi]). The first step is a plain one (x <- f(x)); each later step is
// the secant step of g through the last two points, taken when the secant's
// slope g' = f' - 1 is negative (the fixed point lies the way the plain step
// goes, as for any contraction) and the step is at most 100 plain steps long.
// Otherwise, and after a secant step that did not shrink |g|, the step is a
// plain one, halved when g changed its sign (an oscillation). Iterates are
// clamped into [lo, hi]. Returns at the first x with |f(x) - x| <= tolerance,
// at a non-finite f(x), or after max_evaluations calls of f; the last call of
// f is always at the returned x.
template <typename F>
FixedPoint1D solveFixedPoint1D(F&& f, double x0, double lo, double hi, double tolerance, int max_evaluations) {
  constexpr double kMaxStretch = 100.0;
  FixedPoint1D r;
  double x = std::clamp(x0, lo, hi);
  double x_prev = 0.0, g_prev = 0.0;
  bool have_prev = false, secant_step = false;
  for (;;) {
    const double fx = f(x);
    ++r.evaluations;
    r.x = x;
    r.fx = fx;
    if (!std::isfinite(fx)) return r;
    const double g = fx - x;
    if (std::abs(g) <= tolerance) {
      r.converged = true;
      return r;
    }
    if (r.evaluations >= max_evaluations) return r;
    double next = fx;  // the plain step
    bool took_secant = false;
    if (have_prev) {
      if (secant_step && !(std::abs(g) < std::abs(g_prev))) {
        ++r.fallbacks;
        if (g * g_prev < 0.0) next = x + 0.5 * g;
      } else {
        const double slope = (g - g_prev) / (x - x_prev);
        if (slope < 0.0) {  // false for NaN (x == x_prev) too
          const double step = -g / slope;
          const double longest = kMaxStretch * std::abs(g);
          next = x + std::clamp(step, -longest, longest);
          took_secant = true;
        } else {
          ++r.fallbacks;
        }
      }
    }
    x_prev = x;
    g_prev = g;
    have_prev = true;
    secant_step = took_secant;
    x = std::clamp(next, lo, hi);
  }
}

}  // namespace pronk::jump
