// Training curves from `pronk train`'s train_log.csv: the batch's reward, the
// landing error and the share within 0.2 m (validation and batch) against
// simulated jumps on a log axis, beside the paper's run at its own marks
// (4096 jumps per iteration; ../shared/reference/training-evidence.md).
#pragma once

#include <string>
#include <vector>

namespace pronk::render::plot {

// A train_log.csv: its header and numeric rows ("nan" and empty cells are NaN).
struct TrainingLog {
  std::string path;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  // The column's values; throws pronk::Error naming the file when it lacks it.
  std::vector<double> column(const std::string& name) const;
};

// Throws pronk::InputError naming the file (and line) for a file that is not
// such a log: no header, a row of another length, a cell that is no number.
TrainingLog readTrainingLog(const std::string& path);

// Writes `png` and its script beside it (NAME.gp); returns the PNG's path.
// `robot` and `policy` go into the title.
std::string plotTrainingCurves(const TrainingLog& log, const std::string& robot, const std::string& policy,
                               const std::string& png);

}  // namespace pronk::render::plot
