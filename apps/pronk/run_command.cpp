// `pronk run`: simulate a scenario's episode and report what happened.
#include <cstdio>
#include <memory>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <Eigen/Geometry>

#include "commands.h"
#include "output_paths.h"
#include "pronk/controller_factory.h"
#include "pronk/episode.h"
#include "pronk/file_io.h"
#include "pronk/world.h"
#include "render/episode_video.h"
#include "run_jumps.h"
#include "stop_signal.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Largest foot penetration proxy: the peak vertical foot force over the episode.
double peakFootForce(const Trace& trace) {
  double peak = 0;
  for (const TraceSample& s : trace.samples)
    for (const Eigen::Vector3d& f : s.foot_force) peak = std::max(peak, f.z());
  return peak;
}

// --seed: the named sweep draws its cases from another seed. Only a <random>
// sweep has one; a grid or a variation would silently ignore it.
void reseedSweep(Scenario& scenario, const std::string& name, unsigned long seed) {
  for (SweepSpec& sweep : scenario.sweeps) {
    if (sweep.name != name) continue;
    if (sweep.kind != SweepSpec::Kind::Random) {
      throw InputError(sweep.where, "--seed " + std::to_string(seed) + ": sweep '" + name +
                                        "' is not a <random> sweep and draws nothing from a seed");
    }
    sweep.seed = seed;
    return;
  }
  // An unknown sweep name is reported where the cases are expanded.
}

}  // namespace

int runCommand(const CommonOptions& common, const RunOptions& options) {
  Scenario scenario = loadScenario(options.scenario);
  if (options.seed) reseedSweep(scenario, options.sweep, *options.seed);
  if (runsJumps(scenario, options)) return runJumps(common, options, scenario);
  if (!options.policy.empty() || !options.sweep.empty()) {
    throw Error(std::string(options.policy.empty() ? "--sweep" : "--policy") + ": " + options.scenario +
                (scenario.environment ? " runs its controller here (--controller replaces the environment)"
                                      : " has no <environment> for a policy to drive"));
  }
  if (!options.controller.empty()) {
    scenario.platform.controller = ControllerSpec{options.controller, "", {}, {"--controller", 0}};
  }
  scenario.platform.controller.params = withParamOptions(scenario.platform.controller.params, options);
  const double duration = options.duration > 0 ? options.duration : scenario.sim.duration;
  PluginRegistry registry;
  loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
  World world(scenario);
  for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
  if (!scenario.targets.empty() || !scenario.sweeps.empty()) {
    // Said, not silently skipped: targets and sweeps need an environment and a policy.
    std::cerr << "note: " << scenario.targets.size() << " target(s) and " << scenario.sweeps.size()
              << " sweep(s) need an <environment> and --policy; one episode of the controller runs (the first "
                 "target is drawn in videos)\n";
  }
  Trace events;  // controller events are collected here and merged into the episode trace
  auto controller = makeController(scenario.platform, registry, world, &events);

  render::VideoOptions video = videoOptions(scenario, options);
  if (!options.out_dir.empty()) checkOutputDirectory(options.out_dir, "--out");
  if (!video.path.empty()) {  // before spending time on the simulation
    checkWritableFile(video.path, "--video");
    checkNotAnInput(video.path, "--video", {{options.scenario, "SCENARIO"}});
    checkNotAmongFolderFiles(video.path, "--video", options.out_dir,
                             [](const std::string& name) { return name == "results.json" || name == "trace.csv"; });
  }
  EpisodeOptions episode;
  episode.duration = duration;
  episode.record_body_poses = !video.path.empty();
  // A signal ends the episode where it is; its results and its video are
  // written as of then (a second signal ends the filming with a playable
  // video), and the exit status says it stopped.
  int stopped = 0;
  EpisodeResult result;
  {
    const StopOnSignal stop;
    episode.stop = stop.flag();
    result = runEpisode(world, *controller, episode);
    stopped = stop.signal();
  }
  const StopOnSignal stop_filming;
  video.stop = stop_filming.flag();
  result.trace.events.insert(result.trace.events.begin(), events.events.begin(), events.events.end());
  std::stable_sort(result.trace.events.begin(), result.trace.events.end(),
                   [](const TraceEvent& a, const TraceEvent& b) { return a.time < b.time; });

  const TraceSample& first = result.trace.samples.front();
  const TraceSample& last = result.trace.samples.back();
  const double simulated = last.time;
  std::printf("scenario   %s\n", options.scenario.c_str());
  std::printf("robot      %s (%s), %.3f kg, %d joints, %d feet\n", world.robot().name.c_str(),
              scenario.platform.urdf.c_str(), world.totalMass(), world.jointCount(), world.footCount());
  std::printf("controller %s\n", scenario.platform.controller.factory.c_str());
  std::printf("simulated  %.3f s in %.3f s wall (%.1fx real time), %ld integrator steps (%s)\n", simulated,
              result.wall_seconds, simulated / std::max(result.wall_seconds, 1e-9), result.statistics.integrator_steps,
              scenario.sim.integrator.c_str());
  std::printf("\n| %-10s | %-24s | %-24s |\n", "", "start", "end");
  std::printf("|------------|--------------------------|--------------------------|\n");
  auto row = [](const char* name, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    std::printf("| %-10s | %7.4f %7.4f %7.4f  | %7.4f %7.4f %7.4f  |\n", name, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
  };
  row("trunk [m]", first.base_position, last.base_position);
  row("CoM [m]", first.com_position, last.com_position);
  row("CoM v[m/s]", first.com_velocity, last.com_velocity);
  std::printf("\nevents:\n");
  for (const TraceEvent& e : result.trace.events) {
    std::printf("  %7.3f s  %s%s%s\n", e.time, e.name.c_str(), e.detail.empty() ? "" : "  ", e.detail.c_str());
  }
  std::printf("\nstatus: %s\n", result.failure ? ("FAILED (" + result.failure->reason + ": " + result.failure->detail +
                                                   ")").c_str()
                                               : "ok");

  if (!options.out_dir.empty()) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(options.out_dir, ec);
    if (ec) throw Error("--out " + options.out_dir + ": cannot create the directory: " + ec.message());
    nlohmann::json j;
    nlohmann::json settings = nlohmann::json::object();  // the controller's parameters the file and --param set
    for (const ParamSetting& p : scenario.platform.controller.params) settings[p.name] = p.value;
    j["run"] = {{"pronk_version", PRONK_VERSION},
                {"git_commit", buildCommit()},
                {"command", common.command_line},
                {"controller_parameters", settings},
                {"complete", !stopped}};
    if (stopped) j["run"]["stopped_by_signal"] = stopped;
    j["scenario"] = fs::absolute(options.scenario).string();
    j["robot"] = world.robot().name;
    j["controller"] = scenario.platform.controller.factory;
    j["simulated_s"] = simulated;
    j["wall_s"] = result.wall_seconds;
    j["integrator_steps"] = result.statistics.integrator_steps;
    j["failed"] = result.failure.has_value();
    j["failure_reason"] = result.failure ? result.failure->reason : "";
    j["failure_detail"] = result.failure ? result.failure->detail : "";
    j["start"] = {{"trunk", vec(first.base_position)}, {"com", vec(first.com_position)}};
    j["end"] = {{"trunk", vec(last.base_position)}, {"com", vec(last.com_position)}, {"com_velocity", vec(last.com_velocity)}};
    j["peak_foot_force_n"] = peakFootForce(result.trace);
    j["events"] = nlohmann::json::array();
    for (const TraceEvent& e : result.trace.events) j["events"].push_back({{"time", e.time}, {"name", e.name}, {"detail", e.detail}});
    const std::string json_path = (fs::path(options.out_dir) / "results.json").string();
    replaceFileAtomically(json_path, j.dump(2) + "\n", "results file");
    const std::string trace_path = (fs::path(options.out_dir) / "trace.csv").string();
    writeTraceCsv(result.trace, trace_path);
    std::printf("wrote %s and %s\n", json_path.c_str(), trace_path.c_str());
  }
  if (!video.path.empty()) {
    const render::VideoSummary v = render::renderEpisodeVideo(
        result.trace, world.robot(), world.terrain(), markersFor(scenario, world, result.trace.samples.front()), video,
        &std::cerr);
    for (const std::string& w : v.warnings) std::cerr << "warning: " << w << "\n";
    for (const std::string& png : v.stills) std::printf("still %s\n", png.c_str());
    std::printf("video %s: %d frames, %.2f s at %.0f fps (speed %.2f), %.1f MB, rendered in %.1f s\n", v.path.c_str(),
                v.frames, v.duration_s, video.fps, video.speed, v.bytes / 1e6, v.wall_s);
  }
  if (const int signal = stopped ? stopped : stop_filming.signal()) {
    std::fprintf(stderr, "pronk: stopped by signal %d at %.3f s of the episode\n", signal, simulated);
    return 128 + signal;
  }
  return result.failure ? kEpisodeFailed : kOk;
}

Subcommand declareRun(CLI::App& app, const CommonOptions& common) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "simulate a scenario and print what happened");
  sub->add_option("scenario", o->scenario, "scenario file")->required();
  sub->add_option("--out", o->out_dir, "directory for results.json and the trace CSV")->check(kNonEmpty);
  sub->add_option("--controller", o->controller, "controller to use instead of the scenario's (e.g. stand)")->check(kNonEmpty);
  sub->add_option("--duration", o->duration,
                      "episode length in s (default: the scenario's <sim duration>, or in a jump run its "
                      "<environment>'s duration parameter)")
      ->check(finiteIn(0, kMaxEpisodeSeconds, true));
  sub->add_option("--video", o->video,
                  "write an H.264 MP4 of the episode (off-screen, OSMesa) to FILE; without FILE, under --out with the "
                  "name the scenario's <render output> suggests")
      ->expected(0, 1)
      ->check(kNonEmpty);
  sub->add_option("--speed", o->speed, "video playback speed, e.g. 0.25 for slow motion (default: the scenario's <render speed>, else 1)")
      ->check(finiteIn(0.01, 100));
  sub->add_option("--fps", o->fps, "video frames per second (default: the scenario's <render fps>, else 30)")->check(finiteIn(1.0, 240.0));
  sub->add_option("--size", o->size, "video size WIDTHxHEIGHT, both even (default: the scenario's <render>, else 1280x720)")->check(kNonEmpty);
  sub->add_option("--still", o->stills, "also save the video frame at this simulated time (s) as a PNG "
                                             "(repeatable)")
      ->check(finiteIn(0, kMaxEpisodeSeconds));
  sub->add_option("--camera", o->camera, "video camera (default: the scenario's <render><camera mode>, else side)")->check(CLI::IsMember({"side", "follow", "top", "fixed"}));
  sub->add_option("--policy", o->policy,
                      "jump to the scenario's targets with this policy: 'ballistic' (the environment's analytic "
                      "planner) or a policy file (default: the scenario's <environment policy>)")->check(kNonEmpty);
  sub->add_option("--sweep", o->sweep, "run the cases of this <sweeps> entry instead of the targets")->check(kNonEmpty);
  sub->add_option("--seed", o->seed, "draw the --sweep's random cases from this seed instead of the file's "
                                     "(a <random> sweep; 0 ... 4294967295)")
      ->check(CLI::Range(0ul, 4294967295ul))
      ->needs("--sweep");
  sub->add_flag("--video-per-jump", o->video_per_jump, "one video file per jump (NAME-000.mp4 ...) instead of one");
  sub->add_option("--param", o->params,
                      "NAME=VALUE: set a parameter of the scenario's <environment> in a jump run, of its controller "
                      "otherwise, over the file's (repeatable; e.g. --param motor=dc)")
      ->check([](const std::string& s) {
        const size_t eq = s.find('=');
        return eq == std::string::npos || eq == 0 || eq + 1 == s.size()
                   ? "'" + s + "': expected NAME=VALUE, both given"
                   : std::string();
      });
  // Flags that mean nothing alone are refused rather than ignored.
  sub->get_option("--video-per-jump")->needs("--video");
  sub->get_option("--size")->needs("--video");
  sub->get_option("--fps")->needs("--video");
  sub->get_option("--speed")->needs("--video");
  sub->get_option("--camera")->needs("--video");
  sub->get_option("--still")->needs("--video");

  sub->add_option("--jobs,-j", o->jobs, "worker threads of a jump run, one World each (default: one per core); "
                                     "results do not depend on it")
      ->check(CLI::Range(1, 1024));
  sub->add_flag("--full-episodes", o->full_episodes,
                "a jump run simulates every episode to the environment's end instead of stopping once the robot "
                "has been at rest for 0.2 s after landing");
  sub->add_flag("--trace", o->trace, "a jump run also writes each jump's trace (jump-NNN.csv, a sample per tick) "
                                     "into --out");
  return {sub, [&common, o, sub] {
            o->video_requested = sub->count("--video") > 0;
            return runCommand(common, *o);
          }};
}

}  // namespace pronk::cli
