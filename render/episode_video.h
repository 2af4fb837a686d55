// An episode's trace turned into an MP4: frames sampled at the video's rate
// (slow motion with speed < 1), the phase (thrust, flight, landing) named on
// screen with its colour, the time and speed, a timeline bar, the target with
// its yaw, a legend of the markers and, from touchdown on, the landing error;
// a title card between the jumps of a multi-jump video (docs/video.md).
#pragma once

#include <atomic>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "pronk/robot_description.h"
#include "pronk/terrain.h"
#include "pronk/trace.h"
#include "render/scene_renderer.h"

namespace pronk::render {

struct VideoOptions {
  std::string path;
  int width = 1280, height = 720;
  double fps = 30;
  double speed = 1;            // 0.25 = four times slower than real time
  std::string camera = "side"; // side | follow | top | fixed
  Eigen::Vector3d camera_position{0, -2, 0.6}, camera_look_at{0.3, 0, 0.2};  // fixed
  double fovy_deg = 45;
  std::vector<double> stills;  // simulated times (s) to also save as PNG next to the video
  // When it becomes true (a signal handler's flag) no further frame is added:
  // finish() closes a playable video of the frames so far.
  const std::atomic<bool>* stop = nullptr;
};

struct VideoSummary {
  std::string path;
  int frames = 0;
  double duration_s = 0;       // of the video
  unsigned long long bytes = 0;
  double wall_s = 0;
  std::vector<std::string> warnings;
  std::vector<std::string> stills;  // PNG files written
};

// The phase at time t from the trace's lift_off / touchdown events.
struct PhaseSpan {
  std::string name;            // "stance", "thrust", "flight", "landing"; "ground" when no phase is named
  double begin = 0, end = 0;
};
std::vector<PhaseSpan> phasesOf(const Trace& trace);

// The overlay's words at simulated time t of an episode (`last`: its last frame).
struct OverlayText {
  std::string phase;    // the badge: the phase at t
  std::string header;   // "t = 0.512 s   slow motion 0.5x   TITLE"
  std::string target;   // "target (0.30, 0.20, 0.00) m, yaw 45 deg"; "" without a target
  // "landing error 1.9 cm, yaw 10.4 deg" from touchdown to the end (on the last
  // frame when the episode never touches down); "" before, or without a target.
  std::string landing;
};
OverlayText overlayText(const Trace& trace, const std::vector<PhaseSpan>& phases, const SceneMarkers& markers,
                        double t, bool last, double speed, const std::string& title);

// A terrain that replaces the episode's from `time` on: the paper's apex
// platform (EpisodeOptions::apex_platform), drawn from when it appeared.
struct TerrainChange {
  double time = 0;  // s, simulated
  Terrain terrain;
};

// Several episodes one after another in one video (e.g. one jump per target).
// Frames stream to the encoder as they are drawn.
class EpisodeVideo {
 public:
  // Opens the output. Throws Error for an unwritable path, a bad size, fps or speed.
  EpisodeVideo(const VideoOptions& options, std::ostream* progress);
  ~EpisodeVideo();
  EpisodeVideo(const EpisodeVideo&) = delete;
  EpisodeVideo& operator=(const EpisodeVideo&) = delete;

  // Appends the frames of one episode (its trace must hold body poses); `title`
  // is shown beside the time. Stills (VideoOptions::stills) come from the first episode.
  // `change`: the terrain drawn from its time on instead of `terrain`.
  void add(const Trace& trace, const RobotDescription& robot, const Terrain& terrain, const SceneMarkers& markers,
           const std::string& title, const std::optional<TerrainChange>& change = std::nullopt);
  // Flushes the encoder and closes the file.
  VideoSummary finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Renders the trace (which must hold body poses). `progress` gets one line per
// second of work (frames, fps, ETA); nullptr for silence. Throws Error for an
// unwritable path, a bad size or fps.
VideoSummary renderEpisodeVideo(const Trace& trace, const RobotDescription& robot, const Terrain& terrain,
                                const SceneMarkers& markers, const VideoOptions& options, std::ostream* progress,
                                const std::optional<TerrainChange>& change = std::nullopt);

}  // namespace pronk::render
