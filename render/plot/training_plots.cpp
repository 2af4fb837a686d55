// Training curves (render/plot/training_plots.h).
#include "render/plot/training_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "pronk/error.h"
#include "pronk/file_io.h"
#include "render/plot/gnuplot.h"

namespace pronk::render::plot {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

// The paper's run (4096 jumps per iteration), in millions of jumps: where its
// reward reached 50/80/90/95 % of its final value (complete_policy_reward.csv)
// and its 2000-iteration end; and its forward-only run's exploring mean landing
// error at iterations 0 and 306. Said in the figure's text: on an axis with
// them, pronk's few thousand jumps would take a fifth of the width.
constexpr const char* kPaperRun =
    "the paper's run: 50/80/90/95 % of its final reward after 0.57/1.47/2.21/3.69 M jumps, its end at 8.19 M;\n"
    "its forward-only run's exploring mean error: 87 cm at the start, 18 cm after 1.25 M jumps";

}  // namespace

std::vector<double> TrainingLog::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) throw InputError({path, 1}, "the training log has no column \"" + name + "\"");
  const size_t c = static_cast<size_t>(it - columns.begin());
  std::vector<double> out;
  for (const auto& row : rows) out.push_back(row[c]);
  return out;
}

TrainingLog readTrainingLog(const std::string& path) {
  TrainingLog log;
  log.path = path;
  std::istringstream in(readInputFile(path, "training log"));
  std::string line;
  if (!std::getline(in, line) || line.empty()) throw InputError({path, 1}, "an empty file: no training log header");
  log.columns = splitCsv(line);
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitCsv(line);
    if (cells.size() != log.columns.size()) {
      throw InputError({path, number}, std::to_string(cells.size()) + " cells, the header has " +
                                           std::to_string(log.columns.size()));
    }
    std::vector<double> row;
    for (size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].empty() || cells[c] == "nan") {
        row.push_back(NAN);
        continue;
      }
      size_t used = 0;
      double v = NAN;
      try {
        v = std::stod(cells[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != cells[c].size()) {
        throw InputError({path, number}, log.columns[c] + ": \"" + cells[c] + "\" is not a number");
      }
      row.push_back(v);
    }
    log.rows.push_back(std::move(row));
  }
  if (log.rows.empty()) throw InputError({path, 1}, "no iteration: the training log has only its header");
  return log;
}

std::string plotTrainingCurves(const TrainingLog& log, const std::string& robot, const std::string& policy,
                               const std::string& png) {
  const std::vector<double> jumps = log.column("jumps"), reward = log.column("reward_mean"),
                            batch_mean = log.column("batch_error_mean_m"), batch_within = log.column("batch_within_0.2m"),
                            val_median = log.column("validation_error_median_m"),
                            val_mean = log.column("validation_error_mean_m"),
                            val_within = log.column("validation_within_0.2m");
  // Iteration 0 has simulated no training jump: on the log axis it is the
  // horizontal line of where the policy started (the prior's validation).
  std::vector<std::vector<double>> train, validation;
  double start_mean = NAN, start_within = NAN, last_jumps = 0;
  for (size_t i = 0; i < jumps.size(); ++i) {
    last_jumps = std::max(last_jumps, jumps[i]);
    if (jumps[i] <= 0) {
      if (std::isfinite(val_mean[i])) start_mean = val_mean[i], start_within = val_within[i];
      continue;
    }
    train.push_back({jumps[i], reward[i], 100 * batch_mean[i], 100 * batch_within[i]});
    if (std::isfinite(val_mean[i])) {
      validation.push_back({jumps[i], 100 * val_median[i], 100 * val_mean[i], 100 * val_within[i]});
    }
  }
  if (train.empty()) throw InputError({log.path, 0}, "no trained iteration to plot (only iteration 0)");

  GnuplotScript g(png, 1100, 1100);
  g.line("set grid lc rgb \"gray80\"");
  g.line("set tics out nomirror");
  g.line("set xrange [0:" + std::to_string(1.02 * last_jumps) + "]");
  g.data("train", train);
  if (!validation.empty()) g.data("validation", validation);
  char jumps_text[64];
  std::snprintf(jumps_text, sizeof jumps_text, "%.0f", last_jumps);
  g.line("set multiplot layout 3,1 title " +
         quoted((robot.empty() ? "" : robot + ", ") + "policy " + policy + ": training curves over " + jumps_text +
                " simulated jumps (" + fs::path(log.path).filename().string() + ")\n" + kPaperRun));
  // Each panel's key under it, across: the curves keep the whole width.
  g.line("set key below horizontal maxrows 2 width 2");
  g.line("set lmargin 12");
  g.line("set rmargin 4");
  g.line("set title \"batch reward (exploring jumps)\"");
  g.line("set ylabel \"reward mean\"");
  g.line("set xlabel \"\"");
  g.line("plot $train using 1:2 with linespoints pt 7 ps 0.6 lw 1.5 lc rgb \"#2b83ba\" title \"pronk: batch mean\"");
  g.line("set title \"landing error\"");
  g.line("set ylabel \"error [cm]\"");
  g.line("set yrange [0:*]");
  std::string errors = "plot $train using 1:3 with lines lw 1 lc rgb \"#abd9e9\" title \"pronk: batch mean\"";
  if (!validation.empty()) {
    errors += ", \\\n     $validation using 1:3 with linespoints pt 7 ps 0.7 lw 2 lc rgb \"#d7191c\" title "
              "\"pronk: validation mean\", \\\n     $validation using 1:2 with linespoints pt 5 ps 0.7 lw 1.5 lc rgb "
              "\"#fdae61\" title \"pronk: validation median\"";
  }
  if (std::isfinite(start_mean)) {
    char v[64];
    std::snprintf(v, sizeof v, "%.3f", 100 * start_mean);
    errors += ", \\\n     " + std::string(v) + " with lines dt 2 lw 1.5 lc rgb \"black\" title \"iteration 0 (the prior): validation mean\"";
  }
  g.line(errors);
  g.line("set title \"share of the jumps within 0.2 m\"");
  g.line("set ylabel \"within 0.2 m [%]\"");
  g.line("set xlabel \"simulated jumps\"");
  g.line("set yrange [0:100]");
  std::string shares = "plot $train using 1:4 with lines lw 1 lc rgb \"#abd9e9\" title \"pronk: batch\"";
  if (!validation.empty()) {
    shares += ", \\\n     $validation using 1:4 with linespoints pt 7 ps 0.7 lw 2 lc rgb \"#d7191c\" title \"pronk: validation\"";
  }
  if (std::isfinite(start_within)) {
    char v[64];
    std::snprintf(v, sizeof v, "%.3f", 100 * start_within);
    shares += ", \\\n     " + std::string(v) + " with lines dt 2 lw 1.5 lc rgb \"black\" title \"iteration 0 (the prior)\"";
  }
  shares += ", \\\n     85.1 with lines dt 4 lw 1.5 lc rgb \"gray30\" title \"paper's final policy (8192 targets)\"";
  g.line(shares);
  g.line("unset multiplot");
  const std::string script = (fs::path(png).parent_path() / (fs::path(png).stem().string() + ".gp")).string();
  render(g, script);
  return png;
}

}  // namespace pronk::render::plot
