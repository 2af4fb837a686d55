// `pronk run`: simulate a scenario's episode and report what happened.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <Eigen/Geometry>

#include "commands.h"
#include "controller_factory.h"
#include "pronk/episode.h"
#include "pronk/world.h"
#include "render/episode_video.h"

namespace pronk::cli {
namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Largest foot penetration proxy: the peak vertical foot force over the episode.
// Video settings: the scenario's <render> block, then the flags.
render::VideoOptions videoOptions(const Scenario& scenario, const RunOptions& options) {
  render::VideoOptions v;
  if (scenario.render) {
    const RenderSpec& r = *scenario.render;
    v.width = r.width;
    v.height = r.height;
    v.fps = r.fps;
    v.speed = r.speed;
    v.path = r.output;
    v.camera = r.camera.mode;
    v.camera_position = Eigen::Vector3d(r.camera.position[0], r.camera.position[1], r.camera.position[2]);
    v.camera_look_at = Eigen::Vector3d(r.camera.look_at[0], r.camera.look_at[1], r.camera.look_at[2]);
    v.fovy_deg = r.camera.fovy_deg;
  }
  if (!options.video.empty()) v.path = options.video;
  if (options.speed > 0) v.speed = options.speed;
  if (options.fps > 0) v.fps = options.fps;
  if (!options.camera.empty()) v.camera = options.camera;
  v.stills = options.stills;
  if (!v.stills.empty() && v.path.empty()) throw Error("--still needs a video (--video FILE or a <render output>)");
  if (!options.size.empty()) {
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(options.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w <= 0 || h <= 0 || w % 2 || h % 2 ||
        w > 7680 || h > 4320) {
      throw Error("--size " + options.size + ": expected WIDTHxHEIGHT, both even, at most 7680x4320");
    }
    v.width = w;
    v.height = h;
  }
  return v;
}

// Fails now, naming the file, if the video cannot be written later.
void checkWritable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw Error(path + ": cannot create the video's directory: " + ec.message());
  const bool existed = fs::exists(path, ec);
  std::ofstream probe(path, std::ios::app);
  if (!probe) throw Error(path + ": cannot write the video file");
  probe.close();
  if (!existed) fs::remove(path, ec);
}

// The scenario's first target in the world, for the video's marker.
render::SceneMarkers markersFor(const Scenario& scenario, const World& world, const TraceSample& start) {
  render::SceneMarkers m;
  if (scenario.targets.empty()) return m;
  const TargetSpec& t = scenario.targets.front();
  const double yaw = scenario.platform.base_yaw;
  const Eigen::Vector2d offset = Eigen::Rotation2Dd(yaw) * Eigen::Vector2d(t.x, t.y);
  const auto ground = world.terrain().topAt(start.base_position.x(), start.base_position.y());
  m.target = Eigen::Vector3d(start.base_position.x() + offset.x(), start.base_position.y() + offset.y(),
                             (ground ? ground->height : 0.0) + t.z);
  m.target_yaw = yaw + t.yaw;
  return m;
}

double peakFootForce(const Trace& trace) {
  double peak = 0;
  for (const TraceSample& s : trace.samples)
    for (const Eigen::Vector3d& f : s.foot_force) peak = std::max(peak, f.z());
  return peak;
}

}  // namespace

int runCommand(const CommonOptions& common, const RunOptions& options) {
  Scenario scenario = loadScenario(options.scenario);
  if (!options.controller.empty()) {
    scenario.platform.controller = ControllerSpec{options.controller, "", {}, {"--controller", 0}};
  }
  const double duration = options.duration > 0 ? options.duration : scenario.sim.duration;
  PluginRegistry registry;
  loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
  World world(scenario);
  for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
  Trace events;  // controller events are collected here and merged into the episode trace
  auto controller = makeController(scenario.platform.controller, registry, world, &events);

  const render::VideoOptions video = videoOptions(scenario, options);
  if (!video.path.empty()) checkWritable(video.path);  // before spending time on the simulation
  EpisodeOptions episode;
  episode.duration = duration;
  episode.record_body_poses = !video.path.empty();
  EpisodeResult result = runEpisode(world, *controller, episode);
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
    std::ofstream out(json_path);
    if (!(out << j.dump(2) << "\n")) throw Error(json_path + ": cannot write");
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
  return result.failure ? kEpisodeFailed : kOk;
}

}  // namespace pronk::cli
