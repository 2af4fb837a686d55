// `pronk bench`: how fast the simulation runs and how far its answer is from a
// converged reference of the same model, measured side by side in one run.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <iostream>

#include "bench_rollout.h"
#include "commands.h"
#include "pronk/controller.h"
#include "pronk/episode.h"
#include "pronk/scenario.h"
#include "pronk/world.h"
#include "render/episode_video.h"

#include <filesystem>

namespace pronk::cli {
namespace {

// The converged reference: an error-controlled high-order integrator at a
// tolerance where halving it no longer moves the landing (docs/physics.md).
SimSpec referenceSettings(SimSpec sim) {
  sim.integrator = "runge_kutta_merson";
  sim.accuracy = 1e-7;
  return sim;
}

struct Measurement {
  std::string label;
  double wall_per_sim = 0;        // median wall seconds per simulated second
  double steps_per_sim = 0;       // integrator steps per simulated second
  double steps_per_wall = 0;
  Eigen::Vector3d final_trunk = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_touchdown = Eigen::Vector3d::Constant(NAN);
  double t_lift_off = NAN, t_touchdown = NAN;
  std::string status = "ok";
};

Measurement measure(const Scenario& scenario, const SimSpec& sim, const std::string& controller_name,
                    double duration, int repeats, const std::string& label) {
  Measurement m;
  m.label = label;
  std::vector<double> walls;
  for (int r = 0; r < repeats; ++r) {
    Scenario with_settings = scenario;
    with_settings.sim = sim;
    World world(with_settings);
    auto controller = makeBuiltinController(controller_name, world, nullptr);
    EpisodeOptions options;
    options.duration = duration;
    const EpisodeResult result = runEpisode(world, *controller, options);
    walls.push_back(result.wall_seconds / duration);
    if (r > 0) continue;
    m.steps_per_sim = result.statistics.integrator_steps / duration;
    m.final_trunk = result.trace.samples.back().base_position;
    if (const TraceEvent* e = result.trace.findEvent("lift_off")) m.t_lift_off = e->time;
    if (const TraceEvent* e = result.trace.findEvent("touchdown")) {
      m.t_touchdown = e->time;
      // The CoM at the last tick before touchdown: flight is over, landing not begun.
      for (const TraceSample& s : result.trace.samples) {
        if (s.time < e->time - 1e-9) m.com_touchdown = s.com_position;
      }
    }
    if (result.failure) m.status = result.failure->reason + " at " + std::to_string(result.failure->time) + " s";
  }
  std::sort(walls.begin(), walls.end());
  m.wall_per_sim = walls[walls.size() / 2];
  m.steps_per_wall = m.steps_per_sim / m.wall_per_sim;
  return m;
}

std::string describe(const SimSpec& sim) {
  char buffer[128];
  if (sim.integrator == "semi_explicit_euler" || sim.integrator == "explicit_euler") {
    std::snprintf(buffer, sizeof buffer, "%s h %.0e%s", sim.integrator.c_str(), sim.step,
                  sim.contact.implicit ? " implicit" : "");
  } else {
    std::snprintf(buffer, sizeof buffer, "%s acc %.0e", sim.integrator.c_str(), sim.accuracy);
  }
  return buffer;
}

void printHeader() {
  std::printf("| %-34s | %9s | %9s | %11s | %11s | %13s | %14s | %8s | %8s | %s |\n", "setting", "wall/sim", "x realtime",
              "steps/sim s", "steps/wall s", "trunk xy (mm)", "CoM at td (mm)", "t_lo (s)", "t_td (s)", "status");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(36, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(13, '-').c_str(), std::string(13, '-').c_str(),
              std::string(15, '-').c_str(), std::string(16, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(8, '-').c_str());
}

void printRow(const Measurement& m, const Measurement* reference) {
  std::string trunk = "-", com = "-";
  if (reference) {
    char b[64];
    std::snprintf(b, sizeof b, "%.2f", 1e3 * (m.final_trunk - reference->final_trunk).head<2>().norm());
    trunk = b;
    if (std::isfinite(m.com_touchdown.x()) && std::isfinite(reference->com_touchdown.x())) {
      std::snprintf(b, sizeof b, "%.2f", 1e3 * (m.com_touchdown - reference->com_touchdown).norm());
      com = b;
    }
  }
  std::printf("| %-34s | %9.3f | %9.1fx | %11.0f | %11.0f | %13s | %14s | %8.3f | %8.3f | %s |\n", m.label.c_str(),
              m.wall_per_sim, 1.0 / m.wall_per_sim, m.steps_per_sim, m.steps_per_wall, trunk.c_str(), com.c_str(),
              m.t_lift_off, m.t_touchdown, m.status.c_str());
  std::fflush(stdout);
}

}  // namespace

// Simulating a 2 s hop with body poses recorded, then rendering and encoding it
// at 1280x720, 30 fps, real-time playback: frames per second end to end and
// the whole job's wall time against the simulated time.
int videoBench(const BenchOptions& options) {
  const std::string path = options.scenario.empty() ? dataDirectory() + "/scenarios/go1/hop.xml" : options.scenario;
  Scenario scenario = loadScenario(path);
  scenario.platform.controller = ControllerSpec{"scripted_jump", "", {}, {}};
  const std::string out = (std::filesystem::temp_directory_path() / "pronk-bench-video.mp4").string();
  std::printf("pronk bench --video: %s, 1280x720 H.264 (libx264 veryfast), 30 fps, speed 1, %d run(s)\n\n",
              path.c_str(), options.repeats);
  std::printf("| run | simulated (s) | simulation wall (s) | frames | render+encode wall (s) | fps end to end | "
              "whole job wall / simulated |\n|---|---|---|---|---|---|---|\n");
  for (int r = 0; r < options.repeats; ++r) {
    World world(scenario);
    auto controller = makeBuiltinController("scripted_jump", world, nullptr);
    EpisodeOptions episode;
    episode.duration = 2.0;
    episode.record_body_poses = true;
    const EpisodeResult result = runEpisode(world, *controller, episode);
    render::VideoOptions video;
    video.path = out;
    const render::VideoSummary v =
        render::renderEpisodeVideo(result.trace, world.robot(), world.terrain(), {}, video, nullptr);
    std::printf("| %d | %.3f | %.3f | %d | %.3f | %.1f | %.2f |\n", r + 1, episode.duration, result.wall_seconds,
                v.frames, v.wall_s, v.frames / v.wall_s, (result.wall_seconds + v.wall_s) / episode.duration);
    std::fflush(stdout);
  }
  std::filesystem::remove(out);
  return kOk;
}

int benchCommand(const CommonOptions& common, const BenchOptions& options) {
  if (options.video) return videoBench(options);
  if (options.rollout) return rolloutBench(common, options);
  const std::string path = options.scenario.empty() ? dataDirectory() + "/scenarios/go1/stand.xml" : options.scenario;
  const Scenario scenario = loadScenario(path);
  const SimSpec defaults = scenario.sim;
  const SimSpec reference = referenceSettings(defaults);
  const double jump_duration = 2.0;  // long enough for the landing to settle
  std::printf("pronk bench: %s, robot %s, %d timed run(s) per row, single thread\n", path.c_str(),
              scenario.platform.urdf.c_str(), options.repeats);
  std::printf("Errors are against the reference (%s) of the same model: trunk xy at the end, CoM at the last tick "
              "before touchdown.\n\n",
              describe(reference).c_str());

  std::printf("Standing, %.1f s (built-in controller `stand`):\n\n", 1.5);
  printHeader();
  const Measurement stand_default = measure(scenario, defaults, "stand", 1.5, options.repeats, "default: " + describe(defaults));
  const Measurement stand_reference = measure(scenario, reference, "stand", 1.5, 1, "reference: " + describe(reference));
  printRow(stand_default, &stand_reference);
  printRow(stand_reference, &stand_reference);

  std::printf("\nJump with landing, %.1f s (built-in controller `scripted_jump`):\n\n", jump_duration);
  printHeader();
  const Measurement jump_reference =
      measure(scenario, reference, "scripted_jump", jump_duration, 1, "reference: " + describe(reference));
  const Measurement jump_default =
      measure(scenario, defaults, "scripted_jump", jump_duration, options.repeats, "default: " + describe(defaults));
  printRow(jump_default, &jump_reference);
  printRow(jump_reference, &jump_reference);
  std::printf("\nRatio default/reference speed: stand %.1fx, jump %.1fx\n",
              stand_reference.wall_per_sim / stand_default.wall_per_sim,
              jump_reference.wall_per_sim / jump_default.wall_per_sim);

  // Every error column is measured against the references: one that stopped
  // early makes them meaningless, so the bench says so and fails.
  for (const Measurement* r : {&stand_reference, &jump_reference}) {
    if (r->status != "ok") {
      std::fprintf(stderr, "pronk bench: the reference run (%s) did not finish: %s; its errors are not meaningful\n",
                   r->label.c_str(), r->status.c_str());
      return kEpisodeFailed;
    }
  }

  if (options.sweep) {
    std::printf("\nSweep, jump with landing, %.1f s:\n\n", jump_duration);
    printHeader();
    std::vector<SimSpec> sweep;
    // One row per integrator and step (fixed steps) or accuracy (error-controlled).
    auto add = [&](const char* integrator, std::initializer_list<double> settings, bool implicit_contact) {
      for (double v : settings) {
        SimSpec s = defaults;
        s.integrator = integrator;
        (s.integrator == "semi_explicit_euler" ? s.step : s.accuracy) = v;
        s.contact.implicit = implicit_contact;
        sweep.push_back(s);
      }
    };
    add("semi_explicit_euler", {1e-4, 2e-4, 5e-4, 1e-3}, false);
    add("semi_explicit_euler", {2e-4, 5e-4, 1e-3}, true);
    add("semi_explicit_euler2", {1e-2, 3e-3, 1e-3, 1e-4}, false);
    add("runge_kutta_merson", {1e-3, 1e-5, 1e-6}, false);
    for (const SimSpec& s : sweep) {
      printRow(measure(scenario, s, "scripted_jump", jump_duration, options.repeats, describe(s)), &jump_reference);
    }
  }
  return kOk;
}

Subcommand declareBench(CLI::App& app, const CommonOptions& common) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "simulation speed and accuracy: default settings vs a converged reference");
  sub->add_option("--scenario", o->scenario, "scenario whose robot and settings to measure "
                                                      "(default: scenarios/go1/stand.xml)")
      ->check(kNonEmpty);
  sub->add_option("--repeats", o->repeats, "timed runs per setting (median reported)")
      ->check(CLI::Range(1, 100));
  sub->add_flag("--sweep", o->sweep, "measure the whole table of integrators and steps");
  sub->add_flag("--video", o->video,
                      "measure video instead: simulate the hop and encode 1280x720 H.264 at 30 fps, end to end");

  sub->add_flag("--rollout", o->rollout,
                "measure the rollout engine instead: the Go1 region sweep (40 targets) through one world per case "
                "with full episodes and traces, and through the engine at 1 and N threads");
  sub->add_option("--jobs,-j", o->jobs, "threads of the engine's last row (default: one per core)")
      ->check(CLI::Range(1, 1024));
  return {sub, [&common, o] { return benchCommand(common, *o); }};
}

}  // namespace pronk::cli
