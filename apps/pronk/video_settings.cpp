// Video settings shared by `pronk run --video` and `pronk render`.
#include "video_settings.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "pronk/episode.h"
#include "pronk/landing.h"
#include "render/declared_markers.h"

namespace pronk::cli {

// Video settings: the scenario's <render> block, then the flags.
render::VideoOptions videoOptions(const Scenario& scenario, const RunOptions& options) {
  render::VideoOptions v;
  if (scenario.render) {
    const RenderSpec& r = *scenario.render;
    v.width = r.width;
    v.height = r.height;
    v.fps = r.fps;
    v.speed = r.speed;
    v.camera = r.camera.mode;
    v.camera_position = Eigen::Vector3d(r.camera.position[0], r.camera.position[1], r.camera.position[2]);
    v.camera_look_at = Eigen::Vector3d(r.camera.look_at[0], r.camera.look_at[1], r.camera.look_at[2]);
    v.fovy_deg = r.camera.fovy_deg;
  }
  if (!options.video.empty()) {
    v.path = options.video;
  } else if (options.video_requested) {
    // Bare --video: the scenario's suggested name (or its own name), under --out.
    if (options.out_dir.empty()) {
      throw Error("--video without a file name writes the scenario's video under --out DIR: give --out, or "
                  "--video FILE");
    }
    const std::string name = scenario.render && !scenario.render->output.empty() ? scenario.render->output
                                                                                  : scenario.name + ".mp4";
    v.path = (std::filesystem::path(options.out_dir) / name).string();
  }
  if (options.speed > 0) v.speed = options.speed;
  if (options.fps > 0) v.fps = options.fps;
  if (!options.camera.empty()) v.camera = options.camera;
  v.stills = options.stills;
  if (!v.stills.empty() && v.path.empty()) throw Error("--still needs a video (--video [FILE])");
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

render::SceneMarkers jumpMarkers(const Trace& trace, const TargetSpec& t, std::optional<double> error_xy,
                                 std::optional<double> error_yaw, const Terrain& terrain,
                                 const Eigen::Vector3d& gravity, const EnvironmentSchema* schema) {
  render::SceneMarkers m;
  const TraceSample& s0 = trace.samples.front();
  const double yaw0 = yawOf(s0.base_quaternion);
  const Eigen::AngleAxisd heading(yaw0, Eigen::Vector3d::UnitZ());
  const auto ground = terrain.topAt(s0.base_position.x(), s0.base_position.y());
  const double surface = ground ? ground->height : 0.0;
  // The target marks where the trunk should come to rest, on the landing surface.
  const Eigen::Vector3d trunk_ground(s0.base_position.x(), s0.base_position.y(), surface);
  m.target = trunk_ground + heading * Eigen::Vector3d(t.x, t.y, t.z);
  m.target_yaw = yaw0 + t.yaw;
  if (error_xy && std::isfinite(*error_xy)) m.landing_error = error_xy;
  if (error_yaw && std::isfinite(*error_yaw)) m.landing_yaw_error = error_yaw;
  if (schema) render::addDeclaredMarkers(m, trace, *schema, terrain, gravity);
  return m;
}

std::optional<render::TerrainChange> apexTerrainChange(const Scenario& s, const Terrain& terrain, const Trace& trace) {
  const std::optional<ApexPlatformEvent> e = apexPlatformEvent(trace);
  if (!s.apex_platform || !e) return std::nullopt;
  return render::TerrainChange{e->time, withApexPlatform(terrain, *s.apex_platform, e->top)};
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

}  // namespace pronk::cli
