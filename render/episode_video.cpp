#include "render/episode_video.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "pronk/error.h"
#include "render/text_overlay.h"
#include "render/video_encoder.h"

namespace pronk::render {
namespace {

Eigen::Vector3d phaseColour(const std::string& phase) {
  if (phase == "thrust") return {0.95, 0.55, 0.1};
  if (phase == "flight") return {0.2, 0.55, 0.95};
  if (phase == "landing") return {0.2, 0.75, 0.3};
  return {0.55, 0.55, 0.55};
}

// The last sample at or before time t.
const TraceSample& sampleAt(const Trace& trace, double t) {
  size_t lo = 0, hi = trace.samples.size() - 1;
  while (lo < hi) {
    const size_t mid = (lo + hi + 1) / 2;
    if (trace.samples[mid].time <= t + 1e-9) lo = mid;
    else hi = mid - 1;
  }
  return trace.samples[lo];
}

}  // namespace

std::vector<PhaseSpan> phasesOf(const Trace& trace) {
  const double end = trace.samples.empty() ? 0 : trace.samples.back().time;
  const TraceEvent* lift_off = trace.findEvent("lift_off");
  if (!lift_off) return {{"stance", 0, end}};
  const TraceEvent* touchdown = nullptr;
  for (const TraceEvent& e : trace.events)
    if (e.name == "touchdown" && e.time > lift_off->time) {
      touchdown = &e;
      break;
    }
  std::vector<PhaseSpan> spans{{"thrust", 0, lift_off->time}};
  if (!touchdown) {
    spans.push_back({"flight", lift_off->time, end});
  } else {
    spans.push_back({"flight", lift_off->time, touchdown->time});
    spans.push_back({"landing", touchdown->time, end});
  }
  return spans;
}

VideoSummary renderEpisodeVideo(const Trace& trace, const RobotDescription& robot, const Terrain& terrain,
                                const SceneMarkers& markers, const VideoOptions& options, std::ostream* progress) {
  if (trace.samples.empty() || trace.samples.front().body_poses.empty()) {
    throw Error(options.path + ": the trace holds no body poses to render");
  }
  if (!(options.speed > 0) || !std::isfinite(options.speed)) {
    throw Error(options.path + ": playback speed must be positive (0.25 = slow motion)");
  }
  const auto start_wall = std::chrono::steady_clock::now();
  VideoSummary summary;
  summary.path = options.path;
  VideoEncoder encoder(options.path, options.width, options.height, options.fps);
  SceneRenderer renderer(options.width, options.height, robot, terrain, &summary.warnings);
  TextOverlay big(std::max(12, options.height / 20), true), small(std::max(10, options.height / 36));

  const double sim_duration = trace.samples.back().time;
  const int frames = std::max(1, int(std::lround(sim_duration / options.speed * options.fps)));
  const std::vector<PhaseSpan> phases = phasesOf(trace);
  const Eigen::Vector3d start = trace.samples.front().com_position;
  const Eigen::Vector3d goal = markers.target ? *markers.target : trace.samples.back().com_position;
  double apex = 0.3;
  for (const TraceSample& s : trace.samples) apex = std::max(apex, s.base_position.z() - std::min(start.z(), goal.z()));
  const double aspect = double(options.width) / options.height;

  std::vector<uint8_t> rgba;
  auto last_report = start_wall;
  for (int i = 0; i < frames; ++i) {
    const double t = std::min(sim_duration, i / options.fps * options.speed);
    const TraceSample& s = sampleAt(trace, t);
    Camera camera;
    if (options.camera == "fixed") {
      camera.eye = options.camera_position;
      camera.target = options.camera_look_at;
      camera.fovy_deg = options.fovy_deg;
    } else {
      camera = frameJump(options.camera, Eigen::Vector3d(start.x(), start.y(), 0), Eigen::Vector3d(goal.x(), goal.y(), 0),
                         apex, options.fovy_deg, aspect, s.base_position);
    }
    FrameState frame{s.body_poses, s.foot_position, s.foot_in_contact};
    renderer.render(camera, markers, frame, rgba);

    // Overlay: phase badge, time, timeline, and the landing error at the end.
    std::string phase = phases.front().name;
    for (const PhaseSpan& p : phases)
      if (t >= p.begin - 1e-9) phase = p.name;
    const int pad = options.height / 40;
    const int badge_w = big.measure(phase) + 2 * pad;
    fillRect(rgba, options.width, options.height, pad, pad, badge_w, big.lineHeight() + pad, phaseColour(phase), 0.9);
    big.draw(rgba, options.width, options.height, 2 * pad, pad + pad / 3, phase, {1, 1, 1});
    char text[128];
    std::snprintf(text, sizeof text, "t = %.3f s%s", t, options.speed != 1 ? "   (slow motion)" : "");
    small.draw(rgba, options.width, options.height, badge_w + 2 * pad, pad + pad / 2, text, {0.1, 0.1, 0.12});
    if (markers.target) {
      std::snprintf(text, sizeof text, "target (%.2f, %.2f, %.2f) m", markers.target->x(), markers.target->y(),
                    markers.target->z());
      small.draw(rgba, options.width, options.height, badge_w + 2 * pad, pad + pad / 2 + small.lineHeight() + 4, text,
                 {0.6, 0.05, 0.05});
    }
    const int bar_y = options.height - 3 * pad, bar_h = pad, bar_x = 2 * pad, bar_w = options.width - 4 * pad;
    for (const PhaseSpan& p : phases) {
      const int x0 = bar_x + int(bar_w * p.begin / sim_duration), x1 = bar_x + int(bar_w * p.end / sim_duration);
      fillRect(rgba, options.width, options.height, x0, bar_y, std::max(1, x1 - x0), bar_h, phaseColour(p.name), 0.85);
    }
    const int cursor = bar_x + int(bar_w * t / sim_duration);
    fillRect(rgba, options.width, options.height, cursor - 1, bar_y - pad / 2, 3, bar_h + pad, {0.05, 0.05, 0.05});
    if (markers.target && i == frames - 1) {
      const Eigen::Vector3d& end = trace.samples.back().com_position;
      std::snprintf(text, sizeof text, "landing error %.1f cm", 100 * (end - *markers.target).head<2>().norm());
      big.draw(rgba, options.width, options.height, options.width / 2 - big.measure(text) / 2, options.height / 2 -
                                                                                                   big.lineHeight(),
               text, {0.6, 0.05, 0.05});
    }
    encoder.addFrame(rgba);
    for (double still : options.stills) {
      // The frame whose time is nearest the requested one.
      const int wanted = int(std::lround(std::clamp(still, 0.0, sim_duration) / options.speed * options.fps));
      if (std::min(wanted, frames - 1) != i) continue;
      char suffix[64];
      std::snprintf(suffix, sizeof suffix, "_t%.3f.png", t);
      const std::string png = (std::filesystem::path(options.path).replace_extension("").string()) + suffix;
      writePng(png, rgba, options.width, options.height);
      summary.stills.push_back(png);
    }

    const auto now = std::chrono::steady_clock::now();
    if (progress && (std::chrono::duration<double>(now - last_report).count() > 1.0 || i + 1 == frames)) {
      last_report = now;
      const double elapsed = std::chrono::duration<double>(now - start_wall).count();
      const double rate = (i + 1) / std::max(elapsed, 1e-9);
      *progress << "video: frame " << (i + 1) << "/" << frames << ", " << std::lround(rate) << " fps, ETA "
                << std::lround((frames - i - 1) / rate) << " s\n";
    }
  }
  encoder.finish();
  summary.frames = encoder.frames();
  summary.duration_s = frames / options.fps;
  std::error_code ec;
  summary.bytes = std::filesystem::file_size(options.path, ec);
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_wall).count();
  return summary;
}

}  // namespace pronk::render
