// `pronk render`: an episode's video without the report.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "stop_signal.h"
#include "output_paths.h"
#include "pronk/controller_factory.h"
#include "pronk/episode.h"
#include "run_jumps.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

// What `pronk run --trace --out DIR` wrote about a trace's jump in
// DIR/results.json: the events (phases), the metrics (the declared markers),
// the target and the landing errors.
struct RecordedJump {
  std::vector<TraceEvent> events;
  std::vector<TraceMetric> metrics;
  std::optional<TargetSpec> target;  // none for a controller's episode
  std::optional<double> error_xy, error_yaw;
};

std::vector<TraceEvent> eventsOf(const nlohmann::json& log) {
  std::vector<TraceEvent> events;
  for (const nlohmann::json& e : log) {
    events.push_back({e.at("time").get<double>(), e.at("name").get<std::string>(), e.value("detail", std::string())});
  }
  return events;
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

// The jump of the results.json beside `trace_path` whose "trace" names that
// file (a jump run's), or the episode of a controller run's results.json beside
// its trace.csv; nullopt when there is no results.json or no such jump. A
// results.json that is not one pronk writes is an error naming it.
std::optional<RecordedJump> recordedJump(const std::string& trace_path) {
  namespace fs = std::filesystem;
  const fs::path results = fs::path(trace_path).parent_path() / "results.json";
  if (!fs::is_regular_file(results)) return std::nullopt;
  nlohmann::json doc;
  try {
    std::ifstream in(results);
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError({results.string(), 0}, std::string("not a results file: ") + e.what());
  }
  const std::string name = fs::path(trace_path).filename().string();
  if (doc.is_object() && !doc.contains("jumps") && doc.contains("events")) {  // a controller's episode
    if (name != "trace.csv") return std::nullopt;
    try {
      return RecordedJump{eventsOf(doc.at("events")), {}, std::nullopt, std::nullopt, std::nullopt};
    } catch (const nlohmann::json::exception& e) {
      throw InputError({results.string(), 0}, std::string("its events: ") + e.what());
    }
  }
  const nlohmann::json* jumps = doc.is_object() && doc.contains("jumps") ? &doc["jumps"] : &doc;
  if (!jumps->is_array()) throw InputError({results.string(), 0}, "not a results file: no jumps and no events");
  for (const nlohmann::json& j : *jumps) {
    if (!j.is_object() || !j.contains("trace") || j["trace"] != name) continue;
    try {
      RecordedJump r;
      r.events = eventsOf(j.at("event_log"));
      for (const auto& [metric, value] : j.at("metrics").items()) {
        if (value.is_number()) r.metrics.push_back({metric, value.get<double>()});
      }
      const nlohmann::json& t = j.at("target");
      TargetSpec& target = r.target.emplace();
      target.name = t.value("name", std::string());
      target.x = t.at("x").get<double>();
      target.y = t.at("y").get<double>();
      target.z = t.at("z").get<double>();
      target.yaw = t.at("yaw").get<double>();
      r.error_xy = number(j, "error_xy");
      r.error_yaw = number(j, "error_yaw_deg") * M_PI / 180.0;
      return r;
    } catch (const nlohmann::json::exception& e) {
      throw InputError({results.string(), 0}, "the jump of " + name + ": " + e.what());
    }
  }
  return std::nullopt;
}

// A recorded trace made renderable: body and foot positions from forward
// kinematics of the recorded base pose and joint positions; the events and
// metrics of its jump from results.json beside it, else contact events from
// the recorded flags.
Trace replay(const World& world, const std::string& path, const std::optional<RecordedJump>& jump) {
  Trace trace = readTraceCsv(path);
  if (trace.joint_names != world.jointNames() || trace.foot_links != world.footLinks()) {
    throw InputError({path, 1}, "the trace's joints or feet do not match the scenario's robot");
  }
  for (TraceSample& s : trace.samples) {
    s.body_poses = world.bodyPosesAt(s.base_position, s.base_quaternion, s.q, &s.foot_position);
  }
  if (jump) {
    trace.events = jump->events;
    trace.metrics = jump->metrics;
  } else {
    addContactEvents(trace);
  }
  return trace;
}

}  // namespace

int renderCommand(const CommonOptions& common, const RenderOptions& options) {
  Scenario scenario = loadScenario(options.scenario);
  // A scenario with an <environment> jumps: its targets, with its policy or --policy,
  // as `pronk run --video` films them.
  if (options.trace.empty() && runsJumps(scenario, options)) return runJumps(common, options, scenario);
  if (!options.policy.empty()) {
    throw Error("--policy: " + options.scenario +
                (!options.trace.empty() ? " is filmed from --trace here, which records what a policy did"
                 : scenario.environment ? " runs its controller here (--controller replaces the environment)"
                                        : " has no <environment> for a policy to drive"));
  }
  if (!options.controller.empty()) {
    scenario.platform.controller = ControllerSpec{options.controller, "", {}, {"--controller", 0}};
  }
  render::VideoOptions video = videoOptions(scenario, options);
  checkWritableFile(video.path, "-o");
  // A signal ends the simulation where it is, and what was simulated is filmed;
  // a signal while filming closes a playable video of the frames so far. The
  // exit status says it stopped.
  int stopped = 0;
  checkNotAnInput(video.path, "-o", {{options.scenario, "SCENARIO"}, {options.trace, "--trace"}});
  World world(scenario);
  for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
  Trace trace;
  render::SceneMarkers markers;
  std::optional<Terrain> terrain;
  std::optional<render::TerrainChange> apex;
  if (!options.trace.empty()) {
    const std::optional<RecordedJump> jump = recordedJump(options.trace);
    trace = replay(world, options.trace, jump);
    std::cerr << "render: " << trace.samples.size() << " samples from " << options.trace
              << (!jump           ? " (no results.json naming it beside it: phases from the foot contacts alone)"
                  : jump->target ? ", its jump's events and markers from results.json beside it"
                                 : ", its events from results.json beside it")
              << " (no simulation)\n";
    if (jump && jump->target) {
      // The jump's own terrain (a step platform for a target with a height) and
      // the markers its run's video drew.
      const Scenario s = applyCase(scenario, EpisodeCase{"", *jump->target, {}}, world.footprint());
      terrain.emplace(s.ground, s.ground_height, s.terrain);
      apex = apexTerrainChange(s, *terrain, trace);
      std::optional<EnvironmentSchema> schema;
      if (scenario.environment) {
        PluginRegistry registry;
        loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
        schema = environmentSchema(findEnvironment(*scenario.environment, registry));
      }
      const Eigen::Vector3d gravity(scenario.sim.gravity[0], scenario.sim.gravity[1], scenario.sim.gravity[2]);
      markers = jumpMarkers(trace, *jump->target, jump->error_xy, jump->error_yaw, *terrain, gravity,
                            schema ? &*schema : nullptr);
    } else {
      markers = markersFor(scenario, world, trace.samples.front());
    }
  } else {
    PluginRegistry registry;
    loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
    auto controller = makeController(scenario.platform, registry, world, nullptr);
    EpisodeOptions episode;
    episode.duration = options.duration > 0 ? options.duration : scenario.sim.duration;
    episode.record_body_poses = true;
    const StopOnSignal stop;
    episode.stop = stop.flag();
    trace = runEpisode(world, *controller, episode).trace;
    stopped = stop.signal();
    markers = markersFor(scenario, world, trace.samples.front());
  }
  const StopOnSignal stop_filming;
  video.stop = stop_filming.flag();
  const render::VideoSummary v = render::renderEpisodeVideo(trace, world.robot(), terrain ? *terrain : world.terrain(),
                                                            markers, video, &std::cerr, apex);
  for (const std::string& w : v.warnings) std::cerr << "warning: " << w << "\n";
  for (const std::string& png : v.stills) std::printf("still %s\n", png.c_str());
  std::printf("video %s: %d frames, %.2f s at %.0f fps (speed %.2f), %.1f MB, rendered in %.1f s\n", v.path.c_str(),
              v.frames, v.duration_s, video.fps, video.speed, v.bytes / 1e6, v.wall_s);
  if (const int signal = stopped ? stopped : stop_filming.signal()) {
    std::fprintf(stderr, "pronk: stopped by signal %d; the video holds what was %s\n", signal,
                 stopped ? "simulated" : "filmed");
    return 128 + signal;
  }
  return kOk;
}

Subcommand declareRender(CLI::App& app, const CommonOptions& common) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "film a scenario's episode off-screen, from a recorded trace or by "
                                                  "simulating it");
  sub->add_option("scenario", o->scenario, "scenario file")->required();
  sub->add_option("-o,--output", o->video, "MP4 file to write")->required()->check(kNonEmpty);
  sub->add_option("--trace", o->trace, "trace.csv of an earlier `pronk run --out` (no simulation)")
      ->check(CLI::ExistingFile);
  sub->add_option("--controller", o->controller, "controller to use instead of the scenario's")->check(kNonEmpty);
  sub->add_option("--policy", o->policy,
                  "a jump scenario's policy: 'ballistic' (the environment's analytic planner) or a policy file "
                  "(default: the scenario's <environment policy>)")
      ->check(kNonEmpty);
  sub->add_option("--duration", o->duration, "episode length in s")->check(finiteIn(0, kMaxEpisodeSeconds, true));
  sub->add_option("--speed", o->speed, "playback speed, e.g. 0.25 (default: the scenario's <render speed>, else 1)")->check(finiteIn(0.01, 100));
  sub->add_option("--fps", o->fps, "frames per second (default: the scenario's <render fps>, else 30)")->check(finiteIn(1.0, 240.0));
  sub->add_option("--size", o->size, "WIDTHxHEIGHT, both even (default: the scenario's <render>, else 1280x720)")->check(kNonEmpty);
  sub->add_option("--still", o->stills, "also save the frame at this simulated time as a PNG (repeatable)")
      ->check(finiteIn(0, kMaxEpisodeSeconds));
  sub->add_option("--camera", o->camera, "camera (default: the scenario's <render><camera mode>, else side)")->check(CLI::IsMember({"side", "follow", "top", "fixed"}));

  return {sub, [&common, o] { return renderCommand(common, *o); }};
}

}  // namespace pronk::cli
