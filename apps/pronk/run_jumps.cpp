// `pronk run SCENARIO --policy ...`: one episode of the scenario's environment
// per target (or per sweep case) through the rollout engine; the sinks print
// the table, write the results files and traces, and film the video.
#include "run_jumps.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>
#include <ctime>
#include <unistd.h>
#include <Eigen/Geometry>

#include "output_paths.h"
#include "progress.h"
#include "stop_signal.h"
#include "pronk/controller_factory.h"
#include "pronk/evaluation.h"
#include "pronk/report.h"
#include "render/declared_markers.h"
#include "render/episode_video.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

// When the run started, as ISO 8601 in UTC, and the machine it ran on: what a
// results file needs to be told apart from another run of the same command.
std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string hostName() {
  char name[256] = "";
  if (gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

namespace fs = std::filesystem;

// The files a jump run writes into --out: a new run replaces them as one set.
bool isRunFile(const fs::path& p) {
  const std::string name = p.filename().string();
  return name == "results.json" || name == "results.csv" ||
         (name.rfind("jump-", 0) == 0 && p.extension() == ".csv");
}

constexpr double kResultsEvery = 10.0;  // s between rewrites of the results files during a run

// --duration sets the episode length, which the environment's `duration`
// parameter owns in a jump run (resolveParams refuses it, naming the flag, for
// an environment without one or a value out of its range).
std::vector<ParamSetting> withDurationOption(std::vector<ParamSetting> params, const RunOptions& options) {
  if (options.duration <= 0) return params;
  char value[32];
  std::snprintf(value, sizeof value, "%.17g", options.duration);
  setParam(params, {"duration", value, SourceLocation{"--duration", 0}});
  return params;
}

}  // namespace

std::vector<ParamSetting> withParamOptions(std::vector<ParamSetting> params, const RunOptions& options) {
  std::vector<std::string> given;
  for (const std::string& option : options.params) {
    const size_t eq = option.find('=');  // the flag's check: a name, '=', a value
    const std::string name = option.substr(0, eq);
    if (std::find(given.begin(), given.end(), name) != given.end()) {
      throw UsageError("--param " + name + " is given twice: give each parameter once");
    }
    given.push_back(name);
    setParam(params, {name, option.substr(eq + 1), SourceLocation{"--param", 0}});
  }
  return params;
}

bool runsJumps(const Scenario& scenario, const RunOptions& options) {
  return scenario.environment && options.controller.empty();
}

int jobsOf(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

int runJumps(const CommonOptions& common, const RunOptions& options, const Scenario& scenario) {
  const EnvironmentSpec& spec = *scenario.environment;
  const std::string policy_name = options.policy.empty() ? spec.policy : options.policy;
  if (policy_name.empty()) {
    throw InputError(spec.where, "<environment>: no policy: give --policy ballistic or --policy FILE (or the "
                                 "element's policy attribute)");
  }
  PluginRegistry registry;
  ControllerSpec as_controller{spec.factory, spec.plugin, spec.params, spec.where};
  loadPlugins(registry, common.plugin_paths, &as_controller);
  RolloutSetup setup =
      environmentSetup(scenario, registry, withDurationOption(withParamOptions({}, options), options), policy_name);

  const std::vector<EpisodeCase> cases = options.sweep.empty() ? targetCases(scenario) : sweepCases(scenario, options.sweep);
  const render::VideoOptions video = videoOptions(scenario, options);
  if (!video.path.empty()) {
    checkWritableFile(video.path, "--video");
    checkNotAnInput(video.path, "--video", {{options.scenario, "SCENARIO"}, {policy_name, "--policy"}});
    checkNotAmongFolderFiles(video.path, "--video", options.out_dir,
                             [](const std::string& name) { return isRunFile(name); });
  }
  if (!options.out_dir.empty()) {
    checkOutputDirectory(options.out_dir, "--out");
    std::error_code ec;
    fs::create_directories(options.out_dir, ec);
    if (ec) throw Error("--out " + options.out_dir + ": cannot create the directory: " + ec.message());
    // An earlier run's results and traces go, so that none is left beside this run's.
    for (const auto& entry : fs::directory_iterator(options.out_dir, ec)) {
      if (entry.is_regular_file() && isRunFile(entry.path())) fs::remove(entry.path(), ec);
    }
  }
  if (options.trace && options.out_dir.empty()) throw Error("--trace: needs --out DIR for the trace files");

  // What this run was, for results.json: a motor=dc run must not read like a default one.
  nlohmann::json provenance = {{"pronk_version", PRONK_VERSION},
                               {"git_commit", buildCommit()},
                               {"command", common.command_line},
                               {"scenario", fs::absolute(options.scenario).lexically_normal().string()},
                               {"environment", setup.factory->name},
                               {"plugin", setup.origin},
                               {"policy", policy_name == "ballistic" ? policy_name
                                                                   : fs::absolute(policy_name).lexically_normal().string()},
                               {"policy_fingerprint", policy_name == "ballistic" ? "" : fileFingerprint(policy_name)},
                               {"sweep", options.sweep.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.sweep)},
                               {"seed", nullptr},
                               {"cases", cases.size()}};
  for (const SweepSpec& sweep : scenario.sweeps)
    if (sweep.name == options.sweep && sweep.kind == SweepSpec::Kind::Random) provenance["seed"] = sweep.seed;
  provenance["scenario_fingerprint"] = fileFingerprint(options.scenario);
  provenance["started_utc"] = utcNow();
  provenance["host"] = hostName();
  const SimSpec& sim = scenario.sim;
  const ContactSpec& c = sim.contact;
  provenance["simulation"] = {{"control_rate_hz", sim.control_rate},
                              {"integrator", sim.integrator},
                              {"step_s", sim.step},
                              {"accuracy", sim.accuracy},
                              {"flight_max_step_s", sim.flight_max_step},
                              {"gravity", {sim.gravity[0], sim.gravity[1], sim.gravity[2]}},
                              {"contact",
                               {{"model", c.model},
                                {"stiffness", c.stiffness},
                                {"dissipation", c.dissipation},
                                {"mu_static", c.mu_static},
                                {"mu_dynamic", c.mu_dynamic},
                                {"tangential_stiffness", c.tangential_stiffness},
                                {"tangential_damping", c.tangential_damping},
                                {"implicit", c.implicit}}}};
  nlohmann::json parameters = nlohmann::json::object();  // every declared parameter, as the environment got it
  for (int32_t i = 0; i < setup.params.size(); ++i) parameters[setup.params.data()[i].name] = setup.params.data()[i].value;
  provenance["parameters"] = parameters;

  RolloutOptions rollout;
  rollout.threads = std::min<int>(jobsOf(options.jobs), static_cast<int>(std::max<size_t>(cases.size(), 1)));
  rollout.record_samples = options.trace || !video.path.empty();
  rollout.record_body_poses = !video.path.empty();
  if (options.full_episodes) rollout.end_at_rest = 0;
  // A signal (StopOnSignal): the running jumps finish, then the summary and the
  // files of every finished jump are written (exit 128 + the signal).
  const StopOnSignal stop;
  rollout.stop = stop.flag();
  const std::string factory_name = setup.factory->name, origin = setup.origin;
  const EnvironmentSchema schema = setup.schema;
  for (const std::string& w : setup.warnings) std::cerr << "warning: " << w << "\n";
  RolloutPool pool(std::move(setup), rollout);
  for (const std::string& w : pool.robot().warnings) std::cerr << "warning: " << w << "\n";

  std::printf("scenario    %s\n", options.scenario.c_str());
  std::printf("environment %s (%s), policy %s, %zu jump(s)%s, %d thread(s)\n", factory_name.c_str(), origin.c_str(),
              policy_name.c_str(), cases.size(), options.sweep.empty() ? "" : (", sweep " + options.sweep).c_str(),
              pool.threads());
  // Parameters set on the command line, said before the table: a motor=dc run
  // must not read like a default one.
  if (!options.params.empty()) {
    std::string set;
    for (const std::string& p : options.params) set += (set.empty() ? "" : " ") + p;
    std::printf("parameters  %s (--param, over the scenario's)\n", set.c_str());
  }
  printJumpTableHeader(stdout, schema);
  std::fflush(stdout);

  std::unique_ptr<render::EpisodeVideo> movie;
  JumpStatistics stats;
  JumpResultsFiles files(schema);
  provenance["jobs"] = pool.threads();
  provenance["end_at_rest_s"] = rollout.end_at_rest;
  provenance["complete"] = false;  // until every case has run and every file is written
  files.setRun(provenance);
  // The first trace or video write that fails (a full disk, a file-size limit):
  // the run goes on without traces and video, and its results are written.
  std::string write_failure;
  Progress progress("jump", cases.size());
  const Eigen::Vector3d gravity(scenario.sim.gravity[0], scenario.sim.gravity[1], scenario.sim.gravity[2]);
  const auto start = std::chrono::steady_clock::now();
  auto last_write = start;
  pool.run(cases, [&](EpisodeRecord& r) {
    const JumpOutcome outcome = judgeJump(r);
    printJumpRow(stdout, r, outcome, schema);
    std::fflush(stdout);
    stats.add(r, outcome);
    const Trace& trace = r.result.episode.trace;
    std::string trace_file;
    if (options.trace && !trace.samples.empty() && write_failure.empty()) {
      char name[32];
      std::snprintf(name, sizeof name, "jump-%03zu.csv", r.index);
      try {
        writeTraceCsv(trace, (fs::path(options.out_dir) / name).string());
        trace_file = name;
      } catch (const Error& e) {
        write_failure = e.what();
      }
    }
    files.add(r, outcome, trace_file);
    if (!video.path.empty() && !trace.samples.empty() && write_failure.empty()) {
      try {
        const Scenario s = applyCase(scenario, r.episode, pool.footprint());  // it ran, so it applies
        const Terrain terrain(s.ground, s.ground_height, s.terrain);
        const render::SceneMarkers markers = jumpMarkers(trace, r.episode.target, outcome.landing.error_xy,
                                                        outcome.landing.error_yaw, terrain, gravity, &schema);
        const std::optional<render::TerrainChange> apex = apexTerrainChange(s, terrain, trace);
        if (options.video_per_jump) {
          render::VideoOptions one = video;
          char suffix[32];
          std::snprintf(suffix, sizeof suffix, "-%03zu", r.index);
          one.path = (fs::path(video.path).parent_path() / (fs::path(video.path).stem().string() + suffix +
                                                             fs::path(video.path).extension().string()))
                         .string();
          const render::VideoSummary v =
              render::renderEpisodeVideo(trace, pool.robot(), terrain, markers, one, &std::cerr, apex);
          std::printf("video %s: %d frames, %.2f s\n", v.path.c_str(), v.frames, v.duration_s);
        } else {
          if (!movie) movie = std::make_unique<render::EpisodeVideo>(video, &std::cerr);
          movie->add(trace, pool.robot(), terrain, markers, r.episode.label, apex);
        }
      } catch (const Error& e) {
        write_failure = e.what();
        movie.reset();  // its partial file goes with it
      }
    }
    r.result.episode.trace.samples = {};  // keep memory bounded over long sweeps
    progress.done(stats.jumps);
    // Finished jumps reach the results files as the run goes: a kill loses at
    // most the last few seconds.
    const auto now = std::chrono::steady_clock::now();
    if (!options.out_dir.empty() && std::chrono::duration<double>(now - last_write).count() > kResultsEvery) {
      files.write(options.out_dir);
      last_write = now;
    }
  });
  if (stop.signal()) {
    std::fprintf(stderr, "pronk: stopped by signal %d after %zu of %zu jump(s); writing what finished\n",
                 stop.signal(), stats.jumps, cases.size());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printJumpSummary(stdout, stats, wall);

  std::optional<render::VideoSummary> film;
  if (movie) {
    try {
      film = movie->finish();
    } catch (const Error& e) {
      if (write_failure.empty()) write_failure = e.what();
    }
  }
  provenance["complete"] = !stop.signal() && write_failure.empty() && stats.jumps == cases.size();
  if (stop.signal()) provenance["stopped_by_signal"] = stop.signal();
  if (!write_failure.empty()) provenance["write_failure"] = write_failure;
  files.setRun(provenance);
  if (!options.out_dir.empty()) {
    files.write(options.out_dir);
    std::printf("wrote %s, %s%s\n", (fs::path(options.out_dir) / "results.json").c_str(),
                (fs::path(options.out_dir) / "results.csv").c_str(), options.trace ? " and a trace per jump" : "");
  }
  if (film) {
    const render::VideoSummary& v = *film;
    for (const std::string& w : v.warnings) std::cerr << "warning: " << w << "\n";
    for (const std::string& png : v.stills) std::printf("still %s\n", png.c_str());
    std::printf("video %s: %d frames, %.2f s at %.0f fps (speed %.2f), %.1f MB, rendered in %.1f s\n", v.path.c_str(),
                v.frames, v.duration_s, video.fps, video.speed, v.bytes / 1e6, v.wall_s);
  }
  if (!write_failure.empty()) {
    std::fprintf(stderr, "pronk: %s; the run went on without %s, and %s\n", write_failure.c_str(),
                 options.trace && video.path.empty() ? "traces" : "traces and video",
                 options.out_dir.empty() ? "no results were asked for (--out)" : "every finished jump's results are written");
    return kInputError;
  }
  if (stop.signal()) return 128 + stop.signal();
  return stats.failed + stats.rejected + stats.missed > 0 ? kEpisodeFailed : kOk;
}

}  // namespace pronk::cli
