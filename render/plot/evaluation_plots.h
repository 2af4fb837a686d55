// The paper's evaluation figures for one set of jumps, chosen by what the set
// varies: the feasible-region map (landing error over flat (x, y) targets, log
// colour scale, the 0.2 m contour), landed against target distance (forward
// and backward), height maps (the highest up-jump and the lowest down-jump
// landed per (x, y)), and the yaw error of in-place twists (polar).
#pragma once

#include <string>
#include <vector>

#include "pronk/evaluation.h"

namespace pronk::render::plot {

// What every plot's title names.
struct PlotContext {
  std::string robot;   // the platform's name
  std::string policy;  // "ballistic" or the policy file's name
  std::string set;     // "eval_flat / eval"
  double radius = 0.2; // m, the accuracy threshold (contour, shares)
};

// Which figures suit `rows` (names without extension): "region_map",
// "distance", "heights", "twist_yaw"; none for a set too small to show a trend.
std::vector<std::string> figuresFor(const std::vector<JumpRow>& rows);

// Writes DIR/NAME.png and DIR/NAME.gp for each figure of figuresFor(rows) and
// returns the PNG paths. Throws pronk::Error (gnuplot's message) on failure.
std::vector<std::string> plotEvaluationSet(const std::vector<JumpRow>& rows, const PlotContext& context,
                                           const std::string& dir);

}  // namespace pronk::render::plot
