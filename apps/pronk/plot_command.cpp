// `pronk plot LOG.csv`: the training curves of a `pronk train` log again (for
// a run still going, or restyled); `pronk train` draws them when it ends.
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "render/plot/training_plots.h"

namespace pronk::cli {
namespace {

struct PlotOptions {
  std::string log;
  std::string out;     // "" = train_curves.png beside the log
  std::string robot;   // for the title
  std::string policy;  // for the title; "" = the log's folder name
};

int plotCommand(const PlotOptions& o) {
  namespace fs = std::filesystem;
  const render::plot::TrainingLog log = render::plot::readTrainingLog(o.log);
  const std::string png = o.out.empty() ? (fs::path(o.log).parent_path() / "train_curves.png").string() : o.out;
  const std::string policy =
      o.policy.empty() ? fs::absolute(o.log).parent_path().filename().string() : o.policy;
  std::printf("plot %s\n", render::plot::plotTrainingCurves(log, o.robot, policy, png).c_str());
  return kOk;
}

}  // namespace

Subcommand declarePlot(CLI::App& app, const CommonOptions&) {
  auto o = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "Training curves (PNG, through gnuplot) from a pronk train log");
  cmd->add_option("log", o->log, "train_log.csv of a pronk train run")->required()->check(kNonEmpty);
  cmd->add_option("--out", o->out, "the PNG to write (default: train_curves.png beside the log); its gnuplot "
                                   "script goes beside it")
      ->check(kNonEmpty);
  cmd->add_option("--robot", o->robot, "the robot's name, for the title")->check(kNonEmpty);
  cmd->add_option("--policy", o->policy, "the policy's name, for the title (default: the log's folder)")
      ->check(kNonEmpty);
  return {cmd, [o] { return plotCommand(*o); }};
}

}  // namespace pronk::cli
