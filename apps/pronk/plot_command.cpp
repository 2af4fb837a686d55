// `pronk plot LOG.csv`: the training curves of a `pronk train` log again (for
// a run still going, or restyled); `pronk train` draws them when it ends.
#include <cstdio>
#include <filesystem>
#include <string>

#include "commands.h"
#include "output_paths.h"
#include "render/plot/training_plots.h"

namespace pronk::cli {
namespace {

struct PlotOptions {
  std::string log;
  std::string out;     // "" = STEM.train_curves.png beside STEM.train_log.csv
  std::string robot;   // for the title
  std::string policy;  // for the title; "" = the log's STEM
};

constexpr const char* kLogSuffix = ".train_log.csv";

// The policy's name of a log STEM.train_log.csv (or of any other CSV, its stem).
std::string stemOf(const std::string& log) {
  const std::string name = std::filesystem::path(log).filename().string();
  const size_t n = std::char_traits<char>::length(kLogSuffix);
  if (name.size() > n && name.compare(name.size() - n, n, kLogSuffix) == 0) return name.substr(0, name.size() - n);
  return std::filesystem::path(log).stem().string();
}

int plotCommand(const PlotOptions& o) {
  namespace fs = std::filesystem;
  const std::string png =
      o.out.empty() ? (fs::path(o.log).parent_path() / (stemOf(o.log) + ".train_curves.png")).string() : o.out;
  const std::string script = (fs::path(png).parent_path() / (fs::path(png).stem().string() + ".gp")).string();
  const std::string flag = o.out.empty() ? "the curves' file" : "--out";
  for (const auto& [path, what] : {std::pair{png, flag}, std::pair{script, flag + "'s plot script"}}) {
    checkOutputFile(path, what);
    checkNotAnInput(path, what, {{o.log, "LOG"}});
  }
  const render::plot::TrainingLog log = render::plot::readTrainingLog(o.log);
  const std::string policy = o.policy.empty() ? stemOf(o.log) : o.policy;
  std::printf("plot %s\n", render::plot::plotTrainingCurves(log, o.robot, policy, png).c_str());
  return kOk;
}

}  // namespace

Subcommand declarePlot(CLI::App& app, const CommonOptions&) {
  auto o = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "Training curves (PNG, through gnuplot) from a pronk train log");
  cmd->add_option("log", o->log, "the STEM.train_log.csv of a pronk train run")->required()->check(kNonEmpty);
  cmd->add_option("--out", o->out, "the PNG to write (default: STEM.train_curves.png beside the log); its gnuplot "
                                   "script goes beside it")
      ->check(kNonEmpty);
  cmd->add_option("--robot", o->robot, "the robot's name, for the title")->check(kNonEmpty);
  cmd->add_option("--policy", o->policy, "the policy's name, for the title (default: the log's STEM)")
      ->check(kNonEmpty);
  return {cmd, [o] { return plotCommand(*o); }};
}

}  // namespace pronk::cli
