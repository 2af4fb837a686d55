#include "render/episode_video.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

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

constexpr double kCardSeconds = 0.8;  // of video: the title card before each target but the first
const Eigen::Vector3d kTextColour{0.1, 0.1, 0.12};
const Eigen::Vector3d kErrorColour{0.6, 0.05, 0.05};

// printf into a string (short texts of the overlay).
template <class... Args>
std::string printed(const char* format, Args... args) {
  char text[160];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

// "slow motion 0.25x", "2x", "" at real time.
std::string speedText(double speed) {
  if (speed == 1) return "";
  char text[48];
  std::snprintf(text, sizeof text, speed < 1 ? "slow motion %gx" : "%gx speed", speed);
  return text;
}

// "target (0.40, 0.00, 0.00) m, yaw 45 deg" in the world frame, "" without a target.
std::string targetText(const SceneMarkers& markers) {
  if (!markers.target) return "";
  char text[96];
  std::snprintf(text, sizeof text, "target (%.2f, %.2f, %.2f) m, yaw %.0f deg", markers.target->x(),
                markers.target->y(), markers.target->z(), markers.target_yaw * 180.0 / M_PI);
  return text;
}

// A legend of what the scene's markers mean, right-aligned above `bottom`.
void drawLegend(std::vector<uint8_t>& rgba, int width, int height, TextOverlay& small, const SceneMarkers& markers,
                int bottom, int pad) {
  struct Entry {
    std::string label;
    Eigen::Vector3d colour;
    bool line;  // a line swatch (the arc), else a square (a point)
  };
  std::vector<Entry> entries;
  if (markers.target) entries.push_back({"target", kTargetColour, false});
  if (!markers.planned_arc.empty()) entries.push_back({markers.arc_label, kArcColour, true});
  if (markers.predicted_landing) entries.push_back({markers.landing_label, kArcColour, false});
  if (entries.empty()) return;
  entries.push_back({"robot's front", kFrontColour, false});
  int text_w = 0;
  for (const Entry& e : entries) text_w = std::max(text_w, small.measure(e.label));
  const int line_h = small.lineHeight() + pad / 3, swatch = small.lineHeight() * 2 / 3;
  const int box_w = text_w + swatch + 3 * pad, box_h = int(entries.size()) * line_h + pad;
  const int x = width - pad - box_w, y = bottom - box_h;
  fillRect(rgba, width, height, x, y, box_w, box_h, {1, 1, 1}, 0.6);
  for (size_t i = 0; i < entries.size(); ++i) {
    const int row = y + pad / 2 + int(i) * line_h, mid = row + small.lineHeight() / 2;
    if (entries[i].line) {
      fillRect(rgba, width, height, x + pad, mid - 1, swatch, 3, entries[i].colour);
    } else {
      fillRect(rgba, width, height, x + pad, mid - swatch / 2, swatch, swatch, entries[i].colour);
    }
    small.draw(rgba, width, height, x + 2 * pad + swatch, row, entries[i].label, kTextColour);
  }
}

// The trunk's yaw of a (w, x, y, z) quaternion, rad.
double headingOf(const Eigen::Vector4d& q) {
  return std::atan2(2.0 * (q(0) * q(3) + q(1) * q(2)), 1.0 - 2.0 * (q(2) * q(2) + q(3) * q(3)));
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
  // The thrust starts at the controller's phase:thrust; a controller that names
  // other phases (the host's hop: stand, crouch, push) at its first one after
  // standing. A trace without phase events (a replay without its jump's record)
  // cannot tell standing from pushing: before lift-off it is "ground".
  const TraceEvent* thrust = trace.findEvent("phase:thrust");
  bool named = false;
  for (const TraceEvent& e : trace.events) {
    if (e.name.rfind("phase:", 0) != 0) continue;
    named = true;
    if (!thrust && e.name != "phase:stand" && e.name != "phase:hold" && e.time < lift_off->time) thrust = &e;
  }
  std::vector<PhaseSpan> spans;
  if (!named) {
    spans.push_back({"ground", 0, lift_off->time});
  } else {
    const double thrust_start = thrust && thrust->time < lift_off->time ? thrust->time : 0.0;
    if (thrust_start > 0) spans.push_back({"stance", 0, thrust_start});
    spans.push_back({"thrust", thrust_start, lift_off->time});
  }
  if (!touchdown) {
    spans.push_back({"flight", lift_off->time, end});
  } else {
    spans.push_back({"flight", lift_off->time, touchdown->time});
    spans.push_back({"landing", touchdown->time, end});
  }
  return spans;
}

OverlayText overlayText(const Trace& trace, const std::vector<PhaseSpan>& phases, const SceneMarkers& markers,
                        double t, bool last, double speed, const std::string& title) {
  OverlayText words;
  words.phase = phases.empty() ? "" : phases.front().name;
  double landed_from = INFINITY;  // no touchdown: the last frame only
  for (const PhaseSpan& p : phases) {
    if (t >= p.begin - 1e-9) words.phase = p.name;
    if (p.name == "landing") landed_from = p.begin;
  }
  const std::string pace = speedText(speed);
  words.header = printed("t = %.3f s", t) + (pace.empty() ? "" : "   " + pace) + (title.empty() ? "" : "   " + title);
  words.target = targetText(markers);
  std::optional<double> error = markers.landing_error;
  if (!error && markers.target && !trace.samples.empty()) {
    error = (trace.samples.back().com_position - *markers.target).head<2>().norm();
  }
  if (markers.target && error && (t >= landed_from - 1e-9 || last)) {
    words.landing = printed("landing error %.1f cm", 100 * *error);
    if (markers.landing_yaw_error) words.landing += printed(", yaw %.1f deg", *markers.landing_yaw_error * 180.0 / M_PI);
  }
  return words;
}

struct EpisodeVideo::Impl {
  VideoOptions options;
  std::ostream* progress;
  VideoEncoder encoder;
  TextOverlay big, medium, small;
  VideoSummary summary;
  std::chrono::steady_clock::time_point start_wall = std::chrono::steady_clock::now();
  int episodes = 0;
  Impl(const VideoOptions& o, std::ostream* p)
      : options(o),
        progress(p),
        encoder(o.path, o.width, o.height, o.fps),
        big(std::max(12, o.height / 20), true),
        medium(std::max(11, o.height / 28), true),
        small(std::max(10, o.height / 36)) {
    summary.path = o.path;
  }
};

EpisodeVideo::EpisodeVideo(const VideoOptions& options, std::ostream* progress) {
  if (!(options.speed > 0) || !std::isfinite(options.speed)) {
    throw Error(options.path + ": playback speed must be positive (0.25 = slow motion)");
  }
  impl_ = std::make_unique<Impl>(options, progress);
}

EpisodeVideo::~EpisodeVideo() = default;

void EpisodeVideo::add(const Trace& trace, const RobotDescription& robot, const Terrain& terrain,
                       const SceneMarkers& markers, const std::string& title,
                       const std::optional<TerrainChange>& change) {
  const VideoOptions& options = impl_->options;
  if (trace.samples.empty() || trace.samples.front().body_poses.empty()) {
    throw Error(options.path + ": the trace holds no body poses to render");
  }
  VideoEncoder& encoder = impl_->encoder;
  TextOverlay& big = impl_->big;
  TextOverlay& small = impl_->small;
  VideoSummary& summary = impl_->summary;
  const auto start_wall = std::chrono::steady_clock::now();
  const bool first_episode = impl_->episodes++ == 0;
  SceneRenderer renderer(options.width, options.height, robot, terrain, &summary.warnings);

  const double sim_duration = trace.samples.back().time;
  const int frames = std::max(1, int(std::lround(sim_duration / options.speed * options.fps)));
  const std::vector<PhaseSpan> phases = phasesOf(trace);
  const Eigen::Vector3d start = trace.samples.front().com_position;
  const Eigen::Vector3d goal = markers.target ? *markers.target : trace.samples.back().com_position;
  double apex = 0.3;
  for (const TraceSample& s : trace.samples) apex = std::max(apex, s.base_position.z() - std::min(start.z(), goal.z()));
  const double aspect = double(options.width) / options.height;

  const std::string target = targetText(markers);
  const int pad = options.height / 40;

  std::vector<uint8_t> rgba;
  auto last_report = start_wall;
  auto cameraAt = [&](const TraceSample& s) {
    if (options.camera == "fixed") {
      Camera camera;
      camera.eye = options.camera_position;
      camera.target = options.camera_look_at;
      camera.fovy_deg = options.fovy_deg;
      return camera;
    }
    // An up-jump's goal keeps its height, so the view rises with the robot onto
    // the platform; level and down-jumps are framed from the ground plane.
    return frameJump(options.camera, Eigen::Vector3d(start.x(), start.y(), 0),
                     Eigen::Vector3d(goal.x(), goal.y(), std::max(0.0, goal.z())), apex, options.fovy_deg, aspect,
                     s.base_position, headingOf(trace.samples.front().base_quaternion));
  };

  // Between targets: a title card over the next jump's first frame.
  if (!first_episode) {
    const TraceSample& s = trace.samples.front();
    renderer.render(cameraAt(s), markers, FrameState{s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
    fillRect(rgba, options.width, options.height, 0, 0, options.width, options.height, {0.08, 0.09, 0.11}, 0.72);
    const std::string heading = title.empty() ? "next jump" : title;
    big.draw(rgba, options.width, options.height, options.width / 2 - big.measure(heading) / 2,
             options.height / 2 - big.lineHeight(), heading, {1, 1, 1});
    small.draw(rgba, options.width, options.height, options.width / 2 - small.measure(target) / 2,
               options.height / 2 + pad, target, {1, 0.75, 0.7});
    const int card_frames = std::max(1, int(std::lround(kCardSeconds * options.fps)));
    for (int k = 0; k < card_frames; ++k) encoder.addFrame(rgba);
  }

  for (int i = 0; i < frames; ++i) {
    if (options.stop && options.stop->load()) break;
    const double t = std::min(sim_duration, i / options.fps * options.speed);
    const TraceSample& s = sampleAt(trace, t);
    FrameState frame{s.body_poses, s.foot_position, s.foot_in_contact};
    renderer.setTerrain(change && t >= change->time ? change->terrain : terrain);
    renderer.render(cameraAt(s), markers, frame, rgba);

    // Overlay: phase badge, time, speed and title, the target, the timeline,
    // the legend, and from touchdown on the landing error.
    const OverlayText words = overlayText(trace, phases, markers, t, i == frames - 1, options.speed, title);
    const std::string& phase = words.phase;
    const int badge_w = big.measure(phase) + 2 * pad;
    fillRect(rgba, options.width, options.height, pad, pad, badge_w, big.lineHeight() + pad, phaseColour(phase), 0.9);
    big.draw(rgba, options.width, options.height, 2 * pad, pad + pad / 3, phase, {1, 1, 1});
    small.draw(rgba, options.width, options.height, badge_w + 2 * pad, pad + pad / 2, words.header, kTextColour);
    if (!words.target.empty()) {
      small.draw(rgba, options.width, options.height, badge_w + 2 * pad, pad + pad / 2 + small.lineHeight() + 4,
                 words.target, kErrorColour);
    }
    const int bar_y = options.height - 3 * pad, bar_h = pad, bar_x = 2 * pad, bar_w = options.width - 4 * pad;
    for (const PhaseSpan& p : phases) {
      const int x0 = bar_x + int(bar_w * p.begin / sim_duration), x1 = bar_x + int(bar_w * p.end / sim_duration);
      fillRect(rgba, options.width, options.height, x0, bar_y, std::max(1, x1 - x0), bar_h, phaseColour(p.name), 0.85);
    }
    const int cursor = bar_x + int(bar_w * t / sim_duration);
    fillRect(rgba, options.width, options.height, cursor - 1, bar_y - pad / 2, 3, bar_h + pad, {0.05, 0.05, 0.05});
    drawLegend(rgba, options.width, options.height, small, markers, bar_y - pad, pad);
    if (!words.landing.empty()) {
      // Below the header, right-aligned: clear of the text and, in the side and
      // follow views, of the robot.
      TextOverlay& medium = impl_->medium;
      const int w = medium.measure(words.landing) + 2 * pad, x = options.width - pad - w;
      const int y = 2 * pad + big.lineHeight() + pad;
      fillRect(rgba, options.width, options.height, x, y, w, medium.lineHeight() + pad, {1, 1, 1}, 0.75);
      medium.draw(rgba, options.width, options.height, x + pad, y + pad / 3, words.landing, kErrorColour);
    }
    encoder.addFrame(rgba);
    for (double still : options.stills) {
      if (!first_episode) break;  // still times are those of the first episode
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
    if (impl_->progress && (std::chrono::duration<double>(now - last_report).count() > 1.0 || i + 1 == frames)) {
      last_report = now;
      const double elapsed = std::chrono::duration<double>(now - start_wall).count();
      const double rate = (i + 1) / std::max(elapsed, 1e-9);
      *impl_->progress << "video: " << (title.empty() ? "" : title + ": ") << "frame " << (i + 1) << "/" << frames
                       << ", " << std::lround(rate) << " fps, ETA " << std::lround((frames - i - 1) / rate) << " s\n";
    }
  }
}

VideoSummary EpisodeVideo::finish() {
  VideoEncoder& encoder = impl_->encoder;
  VideoSummary& summary = impl_->summary;
  encoder.finish();
  summary.frames = encoder.frames();
  summary.duration_s = summary.frames / impl_->options.fps;
  std::error_code ec;
  summary.bytes = std::filesystem::file_size(impl_->options.path, ec);
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - impl_->start_wall).count();
  return summary;
}

VideoSummary renderEpisodeVideo(const Trace& trace, const RobotDescription& robot, const Terrain& terrain,
                                const SceneMarkers& markers, const VideoOptions& options, std::ostream* progress,
                                const std::optional<TerrainChange>& change) {
  if (trace.samples.empty() || trace.samples.front().body_poses.empty()) {
    throw Error(options.path + ": the trace holds no body poses to render");
  }
  EpisodeVideo video(options, progress);
  video.add(trace, robot, terrain, markers, "", change);
  return video.finish();
}

}  // namespace pronk::render
