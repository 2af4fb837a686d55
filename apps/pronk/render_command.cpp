// `pronk render`: an episode's video without the report.
#include <cstdio>
#include <memory>
#include <iostream>

#include "commands.h"
#include "pronk/controller_factory.h"
#include "pronk/episode.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

// A recorded trace made renderable: body and foot positions from forward
// kinematics of the recorded base pose and joint positions, contact events
// from the recorded flags.
Trace replay(const World& world, const std::string& path) {
  Trace trace = readTraceCsv(path);
  if (trace.joint_names != world.jointNames() || trace.foot_links != world.footLinks()) {
    throw InputError({path, 1}, "the trace's joints or feet do not match the scenario's robot");
  }
  for (TraceSample& s : trace.samples) {
    s.body_poses = world.bodyPosesAt(s.base_position, s.base_quaternion, s.q, &s.foot_position);
  }
  addContactEvents(trace);
  return trace;
}

}  // namespace

int renderCommand(const CommonOptions& common, const RenderOptions& options) {
  Scenario scenario = loadScenario(options.scenario);
  if (!options.controller.empty()) {
    scenario.platform.controller = ControllerSpec{options.controller, "", {}, {"--controller", 0}};
  }
  const render::VideoOptions video = videoOptions(scenario, options);
  checkWritable(video.path);
  World world(scenario);
  for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
  Trace trace;
  if (!options.trace.empty()) {
    trace = replay(world, options.trace);
    std::cerr << "render: " << trace.samples.size() << " samples from " << options.trace << " (no simulation)\n";
  } else {
    PluginRegistry registry;
    loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
    auto controller = makeController(scenario.platform, registry, world, nullptr);
    EpisodeOptions episode;
    episode.duration = options.duration > 0 ? options.duration : scenario.sim.duration;
    episode.record_body_poses = true;
    trace = runEpisode(world, *controller, episode).trace;
  }
  const render::VideoSummary v =
      render::renderEpisodeVideo(trace, world.robot(), world.terrain(), markersFor(scenario, world, trace.samples.front()),
                                 video, &std::cerr);
  for (const std::string& w : v.warnings) std::cerr << "warning: " << w << "\n";
  for (const std::string& png : v.stills) std::printf("still %s\n", png.c_str());
  std::printf("video %s: %d frames, %.2f s at %.0f fps (speed %.2f), %.1f MB, rendered in %.1f s\n", v.path.c_str(),
              v.frames, v.duration_s, video.fps, video.speed, v.bytes / 1e6, v.wall_s);
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
  sub->add_option("--duration", o->duration, "episode length in s")->check(finiteIn(0, kMaxEpisodeSeconds, true));
  sub->add_option("--speed", o->speed, "playback speed, e.g. 0.25")->check(finiteIn(0, 1e3, true));
  sub->add_option("--fps", o->fps, "frames per second")->check(finiteIn(1.0, 240.0));
  sub->add_option("--size", o->size, "WIDTHxHEIGHT, both even")->check(kNonEmpty);
  sub->add_option("--still", o->stills, "also save the frame at this simulated time as a PNG (repeatable)")
      ->check(finiteIn(0, kMaxEpisodeSeconds));
  sub->add_option("--camera", o->camera, "camera")->check(CLI::IsMember({"side", "follow", "top", "fixed"}));

  return {sub, [&common, o] { return renderCommand(common, *o); }};
}

}  // namespace pronk::cli
