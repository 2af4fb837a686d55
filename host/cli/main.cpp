// pronk: run quadruped jump scenarios on the Simbody host.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.h"
#include "pronk/error.h"

int main(int argc, char** argv) {
  using namespace pronk::cli;
  CLI::App app{"pronk: learned, precise, omnidirectional jumps of legged robots in simulation"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 internal error, 2 usage error, 3 bad input (scenario, URDF, plugin),\n"
      "4 an episode failed (non-foot contact, divergence, controller error).");
  CommonOptions common;
  app.add_option("--plugin", common.plugin_paths,
                 "plugin library or directory, searched before PRONK_PLUGIN_PATH and the install directory "
                 "(repeatable)");

  auto* plugins = app.add_subcommand("plugins", "list loadable plugins, their ABI versions and factories");

  std::vector<std::string> validate_files;
  auto* validate = app.add_subcommand("validate", "check scenario files (and their URDFs and controllers)");
  validate->add_option("files", validate_files, "scenario files")->required()->check(CLI::ExistingFile);

  RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "simulate a scenario and print what happened");
  run_cmd->add_option("scenario", run.scenario, "scenario file")->required()->check(CLI::ExistingFile);
  run_cmd->add_option("--out", run.out_dir, "directory for results.json and the trace CSV");
  run_cmd->add_option("--controller", run.controller, "controller to use instead of the scenario's (e.g. stand)");
  run_cmd->add_option("--duration", run.duration,
                      "episode length in s (default: the scenario's <sim duration>, or in a jump run its "
                      "<environment>'s duration parameter)")
      ->check(CLI::PositiveNumber);
  run_cmd->add_option("--video", run.video, "write an H.264 MP4 of the episode (off-screen, OSMesa)");
  run_cmd->add_option("--speed", run.speed, "video playback speed, e.g. 0.25 for slow motion")
      ->check(CLI::PositiveNumber);
  run_cmd->add_option("--fps", run.fps, "video frames per second")->check(CLI::Range(1.0, 240.0));
  run_cmd->add_option("--size", run.size, "video size WIDTHxHEIGHT, both even (default 1280x720)");
  run_cmd->add_option("--still", run.stills, "also save the video frame at this simulated time (s) as a PNG "
                                             "(repeatable)")
      ->check(CLI::NonNegativeNumber);
  run_cmd->add_option("--camera", run.camera, "video camera")->check(CLI::IsMember({"side", "follow", "top", "fixed"}));
  run_cmd->add_option("--policy", run.policy,
                      "jump to the scenario's targets with this policy: 'ballistic' (the environment's analytic "
                      "planner) or a policy file (default: the scenario's <environment policy>)");
  run_cmd->add_option("--sweep", run.sweep, "run the cases of this <sweeps> entry instead of the targets");
  run_cmd->add_flag("--video-per-jump", run.video_per_jump, "one video file per jump (NAME-000.mp4 ...) instead of one");
  run_cmd->add_option("--param", run.params,
                      "NAME=VALUE: set a parameter of the scenario's <environment> in a jump run, of its controller "
                      "otherwise, over the file's (repeatable; e.g. --param motor=dc)")
      ->check([](const std::string& s) {
        return s.find('=') == std::string::npos || s.front() == '=' ? std::string("expected NAME=VALUE") : std::string();
      });

  RenderOptions render;
  auto* render_cmd = app.add_subcommand("render", "film a scenario's episode off-screen, from a recorded trace or by "
                                                  "simulating it");
  render_cmd->add_option("scenario", render.scenario, "scenario file")->required()->check(CLI::ExistingFile);
  render_cmd->add_option("-o,--output", render.video, "MP4 file to write")->required();
  render_cmd->add_option("--trace", render.trace, "trace.csv of an earlier `pronk run --out` (no simulation)")
      ->check(CLI::ExistingFile);
  render_cmd->add_option("--controller", render.controller, "controller to use instead of the scenario's");
  render_cmd->add_option("--duration", render.duration, "episode length in s")->check(CLI::PositiveNumber);
  render_cmd->add_option("--speed", render.speed, "playback speed, e.g. 0.25")->check(CLI::PositiveNumber);
  render_cmd->add_option("--fps", render.fps, "frames per second")->check(CLI::Range(1.0, 240.0));
  render_cmd->add_option("--size", render.size, "WIDTHxHEIGHT, both even");
  render_cmd->add_option("--still", render.stills, "also save the frame at this simulated time as a PNG (repeatable)")
      ->check(CLI::NonNegativeNumber);
  render_cmd->add_option("--camera", render.camera, "camera")->check(CLI::IsMember({"side", "follow", "top", "fixed"}));

  BenchOptions bench;
  auto* bench_cmd = app.add_subcommand("bench", "simulation speed and accuracy: default settings vs a converged reference");
  bench_cmd->add_option("--scenario", bench.scenario, "scenario whose robot and settings to measure "
                                                      "(default: scenarios/go1/stand.xml)")
      ->check(CLI::ExistingFile);
  bench_cmd->add_option("--repeats", bench.repeats, "timed runs per setting (median reported)")
      ->check(CLI::Range(1, 100));
  bench_cmd->add_flag("--sweep", bench.sweep, "measure the whole table of integrators and steps");
  bench_cmd->add_flag("--video", bench.video,
                      "measure video instead: simulate the hop and encode 1280x720 H.264 at 30 fps, end to end");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsageError;
  }
  try {
    if (*plugins) return pluginsCommand(common);
    if (*validate) return validateCommand(common, validate_files);
    if (*run_cmd) return runCommand(common, run);
    if (*render_cmd) return renderCommand(common, render);
    if (*bench_cmd) return benchCommand(common, bench);
  } catch (const pronk::Error& e) {
    std::cerr << "pronk: " << e.what() << "\n";
    return kInputError;
  } catch (const std::exception& e) {
    std::cerr << "pronk: internal error: " << e.what() << "\n";
    return kInternalError;
  }
  return kUsageError;
}
