// Off-screen rendering and encoding: pixels where the scene says they should
// be, frame counts, the file read back by libavformat, determinism and errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pronk/controller.h"
#include "pronk/episode.h"
#include "render/episode_video.h"
#include "render/video_encoder.h"

namespace pronk::render {
namespace {

std::string outDir() {
  std::filesystem::create_directories(PRONK_RENDER_OUT_DIR);
  return PRONK_RENDER_OUT_DIR;
}

PlatformSpec go1Platform() {
  PlatformSpec p;
  p.urdf = std::string(PRONK_SOURCE_DIR) + "/assets/robots/go1/go1.urdf";
  p.feet = {"FR_foot", "FL_foot", "RR_foot", "RL_foot"};
  p.stance = {0, 0.75, -1.5};
  return p;
}

struct Episode {
  RobotDescription robot = loadUrdf(go1Platform().urdf);
  Terrain terrain{true, 0, {}};
  Trace trace;
  explicit Episode(double duration) {
    World world(robot, go1Platform(), SimSpec{}, terrain);
    auto controller = makeStandController(world, nullptr);
    EpisodeOptions options;
    options.duration = duration;
    options.record_body_poses = true;
    trace = runEpisode(world, *controller, options).trace;
  }
};

Eigen::Vector3d pixel(const std::vector<uint8_t>& rgba, int width, const Eigen::Vector2d& at) {
  const size_t i = (size_t(std::lround(at.y())) * width + size_t(std::lround(at.x()))) * 4;
  return Eigen::Vector3d(rgba[i], rgba[i + 1], rgba[i + 2]) / 255.0;
}

// From the robot's right, looking at the standing robot and a target 0.8 m ahead.
Camera sideCamera() {
  Camera camera;
  camera.eye = Eigen::Vector3d(0.3, -1.8, 0.5);
  camera.target = Eigen::Vector3d(0.3, 0, 0.2);
  return camera;
}

TEST(Render, PixelsShowSkyGroundRobotAndTarget) {
  Episode e(0.05);
  const int w = 320, h = 240;
  SceneRenderer renderer(w, h, e.robot, e.terrain);
  const Camera camera = sideCamera();
  SceneMarkers markers;
  markers.target = Eigen::Vector3d(0.8, 0, 0);
  const TraceSample& s = e.trace.samples.back();
  std::vector<uint8_t> rgba;
  renderer.render(camera, markers, {s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
  ASSERT_EQ(rgba.size(), size_t(w * h * 4));

  // The sky fills the top row.
  EXPECT_LT((pixel(rgba, w, {w / 2.0, 1}) - kSkyColour).norm(), 0.02);
  // The ground (greyish green, not sky) fills the bottom row.
  const Eigen::Vector3d ground = pixel(rgba, w, {w / 2.0, h - 2.0});
  EXPECT_GT((ground - kSkyColour).norm(), 0.2);
  EXPECT_NEAR(ground.x(), ground.z(), 0.05);
  // The target disc is drawn in its colour where the target projects.
  Eigen::Vector2d at;
  ASSERT_TRUE(project(camera, w, h, *markers.target, at));
  EXPECT_LT((pixel(rgba, w, at) - kTargetColour).norm(), 0.05) << pixel(rgba, w, at).transpose();
  // The trunk (dark grey in the URDF) covers the projection of the trunk centre.
  ASSERT_TRUE(project(camera, w, h, s.base_position, at));
  const Eigen::Vector3d trunk = pixel(rgba, w, at);
  EXPECT_LT(trunk.maxCoeff(), 0.45) << trunk.transpose();
  // And a point of sky just above the trunk is not robot.
  ASSERT_TRUE(project(camera, w, h, s.base_position + Eigen::Vector3d(0, 0, 0.35), at));
  EXPECT_LT((pixel(rgba, w, at) - kSkyColour).norm(), 0.05);
}

TEST(Render, PlannedArcShowsDashedThroughTheRobot) {
  // The CoM arc runs through the trunk: where the trunk hides it, it is drawn
  // dashed on top, so some of its pixels inside the trunk's outline are the
  // arc's colour and some the trunk's; where nothing hides it, it is solid.
  Episode e(0.05);
  const int w = 320, h = 240;
  SceneRenderer renderer(w, h, e.robot, e.terrain);
  const Camera camera = sideCamera();
  const TraceSample& s = e.trace.samples.back();
  SceneMarkers markers;
  // A straight horizontal segment through the trunk centre, 0.2 m long, and on
  // beyond the trunk's front end to 0.5 m ahead of it.
  for (int i = 0; i <= 35; ++i) markers.planned_arc.push_back(s.base_position + Eigen::Vector3d(-0.1 + 0.02 * i, 0, 0));
  std::vector<uint8_t> rgba;
  renderer.render(camera, markers, {s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
  const auto arcPixelsOn = [&](double x0, double x1) {
    int arc = 0, other = 0;
    for (double x = x0; x <= x1 + 1e-9; x += 0.005) {
      Eigen::Vector2d at;
      if (!project(camera, w, h, s.base_position + Eigen::Vector3d(x, 0, 0), at)) continue;
      ((pixel(rgba, w, at) - kArcColour).norm() < 0.1 ? arc : other) += 1;
    }
    return std::pair{arc, other};
  };
  const auto [inside_arc, inside_trunk] = arcPixelsOn(-0.1, 0.1);
  EXPECT_GT(inside_arc, 3);
  EXPECT_GT(inside_trunk, 3);
  const auto [outside_arc, outside_other] = arcPixelsOn(0.35, 0.5);  // in front of the robot, in sight
  EXPECT_GT(outside_arc, 3 * std::max(outside_other, 1)) << outside_arc << " / " << outside_other;
  // Without the arc none of those pixels is the arc's.
  renderer.render(camera, SceneMarkers{}, {s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
  EXPECT_EQ(arcPixelsOn(-0.1, 0.1).first, 0);
}

TEST(Render, TheTrunksFrontEndIsMarkedSoThatTheHeadingReads) {
  // From above, the front sixth of the trunk is in the front colour (lit, so
  // its hue is compared: blue and green well above red), its rear end is not.
  Episode e(0.05);
  const int w = 320, h = 240;
  SceneRenderer renderer(w, h, e.robot, e.terrain);
  const TraceSample& s = e.trace.samples.back();
  Camera camera;
  camera.eye = s.base_position + Eigen::Vector3d(0, -0.01, 1.2);
  camera.target = s.base_position;
  std::vector<uint8_t> rgba;
  renderer.render(camera, SceneMarkers{}, {s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
  const Eigen::Isometry3d& trunk = s.body_poses[0];
  Eigen::Vector2d front, rear;
  ASSERT_TRUE(project(camera, w, h, trunk * Eigen::Vector3d(0.17, 0, 0.06), front));
  ASSERT_TRUE(project(camera, w, h, trunk * Eigen::Vector3d(-0.17, 0, 0.06), rear));
  const Eigen::Vector3d f = pixel(rgba, w, front), r = pixel(rgba, w, rear);
  EXPECT_GT(f.z(), f.x() + 0.25) << f.transpose();
  EXPECT_GT(f.y(), f.x() + 0.2) << f.transpose();
  EXPECT_LT(r.z(), r.x() + 0.15) << r.transpose();
}

// The apex platform of a height test appears mid-flight: the renderer draws
// the terrain it is given from the next frame on (EpisodeVideo hands it the
// change's terrain from the change's time on; that switch is not tested here).
TEST(Render, ATerrainChangeIsDrawnFromTheNextFrameOn) {
  Episode e(0.05);
  const int w = 320, h = 240;
  SceneRenderer renderer(w, h, e.robot, e.terrain);
  const Camera camera = sideCamera();
  const TraceSample& s = e.trace.samples.back();
  ApexPlatform platform;
  platform.x = 0.8;
  platform.floor = -0.5;
  platform.size = 0.4;
  const Terrain later = withApexPlatform(e.terrain, platform, 0.25);
  Eigen::Vector2d at;  // the middle of the platform's face towards the camera
  ASSERT_TRUE(project(camera, w, h, Eigen::Vector3d(0.8, -0.2, 0.1), at));
  std::vector<uint8_t> before, after;
  renderer.render(camera, {}, {s.body_poses, s.foot_position, s.foot_in_contact}, before);
  renderer.setTerrain(later);
  renderer.render(camera, {}, {s.body_poses, s.foot_position, s.foot_in_contact}, after);
  // The grey-green ground there before; the box's brown (red over blue) after.
  const Eigen::Vector3d ground = pixel(before, w, at);
  EXPECT_LT(std::abs(ground.x() - ground.z()), 0.05) << ground.transpose();
  const Eigen::Vector3d box = pixel(after, w, at);
  EXPECT_GT(box.x() - box.z(), 0.1) << box.transpose();
}

TEST(Render, SameTraceGivesIdenticalFrames) {
  Episode e(0.05);
  SceneRenderer renderer(160, 120, e.robot, e.terrain);
  const TraceSample& s = e.trace.samples.back();
  std::vector<uint8_t> a, b;
  renderer.render(Camera{}, {}, {s.body_poses, s.foot_position, s.foot_in_contact}, a);
  renderer.render(Camera{}, {}, {s.body_poses, s.foot_position, s.foot_in_contact}, b);
  EXPECT_EQ(a, b);
}

TEST(Render, VideoHasDurationTimesFpsOverSpeedFramesAndReadsBack) {
  Episode e(0.5);
  VideoOptions options;
  options.path = outDir() + "/stand.mp4";
  options.width = 320;
  options.height = 240;
  options.fps = 30;
  options.speed = 0.5;
  const VideoSummary summary = renderEpisodeVideo(e.trace, e.robot, e.terrain, {}, options, nullptr);
  EXPECT_EQ(summary.frames, 30);  // 0.5 s / 0.5 x 30 fps
  EXPECT_GT(summary.bytes, 0u);
  const VideoInfo info = probeVideo(options.path);
  EXPECT_EQ(info.codec, "h264");
  EXPECT_EQ(info.width, 320);
  EXPECT_EQ(info.height, 240);
  EXPECT_EQ(info.frames, 30);
  EXPECT_NEAR(info.duration_s, 1.0, 0.05);
}

TEST(Render, BadOutputsAreClearErrors) {
  EXPECT_THROW(VideoEncoder("/nonexistent/dir/v.mp4", 320, 240, 30), Error);
  try {
    VideoEncoder("/nonexistent/dir/v.mp4", 320, 240, 30);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/v.mp4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(VideoEncoder(outDir() + "/odd.mp4", 321, 240, 30), Error);
  EXPECT_THROW(VideoEncoder(outDir() + "/zero.mp4", 320, 240, 0), Error);
  EXPECT_FALSE(std::filesystem::exists(outDir() + "/odd.mp4"));
}

TEST(Render, UnreadableMeshIsAWarningAndAPrimitive) {
  RobotDescription robot = loadUrdf(go1Platform().urdf);
  const std::string bogus = outDir() + "/not_a_mesh.obj";
  std::ofstream(bogus) << "this is not a mesh\n";
  robot.bodies[0].visuals.at(0).mesh_path = bogus;
  std::vector<std::string> warnings;
  Terrain terrain(true, 0, {});
  SceneRenderer renderer(64, 48, robot, terrain, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not_a_mesh.obj"), std::string::npos);
}

TEST(Render, AZUpColladaMeshKeepsItsFileFrame) {
  // The vendors' Unitree DAE files declare <up_axis>Z_UP</up_axis>; the URDF places a mesh in
  // its file frame, so the declaration must not turn it. The fixture is a bar 0.6 m long along
  // the file's z (from -0.2 to +0.4 m), put on the trunk: seen from the side it stands upright
  // above the trunk, where the plain robot has sky. Turned, it would point at the camera.
  Episode e(0.05);
  RobotDescription robot = e.robot;
  VisualShape& trunk = robot.bodies[0].visuals.at(0);
  trunk.mesh_path = std::string(PRONK_SOURCE_DIR) + "/tests/fixtures/meshes/zup_bar.dae";
  trunk.mesh_scale = Eigen::Vector3d::Ones();
  trunk.pose_body = Eigen::Isometry3d::Identity();
  std::vector<std::string> warnings;
  const int w = 320, h = 240;
  SceneRenderer renderer(w, h, robot, e.terrain, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const Camera camera = sideCamera();
  const TraceSample& s = e.trace.samples.back();
  std::vector<uint8_t> rgba;
  renderer.render(camera, SceneMarkers{}, {s.body_poses, s.foot_position, s.foot_in_contact}, rgba);
  const Eigen::Isometry3d& pose = s.body_poses.at(0);
  Eigen::Vector2d at;
  for (double z : {0.2, 0.3, 0.35}) {
    ASSERT_TRUE(project(camera, w, h, pose * Eigen::Vector3d(0, 0, z), at));
    EXPECT_GT((pixel(rgba, w, at) - kSkyColour).norm(), 0.2) << "no bar " << z << " m above the trunk";
  }
  // Beside the bar, as high up, there is sky.
  ASSERT_TRUE(project(camera, w, h, pose * Eigen::Vector3d(0.12, 0, 0.3), at));
  EXPECT_LT((pixel(rgba, w, at) - kSkyColour).norm(), 0.05);
}

TEST(Render, PhasesComeFromLiftOffAndTouchdown) {
  Trace t;
  t.samples.resize(2);
  t.samples[1].time = 1.5;
  EXPECT_EQ(phasesOf(t).size(), 1u);
  t.addEvent(0.6, "lift_off");
  t.addEvent(0.9, "touchdown");
  // No controller phases (a replay of a bare trace): standing and pushing are one span.
  auto p = phasesOf(t);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].name, "ground");
  EXPECT_EQ(p[1].name, "flight");
  EXPECT_DOUBLE_EQ(p[1].begin, 0.6);
  EXPECT_EQ(p[2].name, "landing");
  EXPECT_DOUBLE_EQ(p[2].end, 1.5);
  // The jump controller's thrust start, or another controller's first phase after standing.
  Trace jump = t;
  jump.addEvent(0.0, "phase:hold");
  jump.addEvent(0.2, "phase:thrust");
  p = phasesOf(jump);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].name, "stance");
  EXPECT_EQ(p[1].name, "thrust");
  EXPECT_DOUBLE_EQ(p[1].begin, 0.2);
  Trace hop = t;
  hop.addEvent(0.0, "phase:stand");
  hop.addEvent(0.3, "phase:crouch");
  hop.addEvent(0.45, "phase:push");
  p = phasesOf(hop);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[1].name, "thrust");
  EXPECT_DOUBLE_EQ(p[1].begin, 0.3);
}

// The overlay says the speed and the target's yaw, and holds the landing error
// from touchdown to the end (not before; at the end only for a jump that never lands).
TEST(Render, TheOverlayHoldsTheLandingErrorFromTouchdownOn) {
  Trace t;
  t.samples.resize(2);
  t.samples[1].time = 1.5;
  t.addEvent(0.2, "phase:thrust");
  t.addEvent(0.6, "lift_off");
  t.addEvent(0.9, "touchdown");
  SceneMarkers m;
  m.target = Eigen::Vector3d(0.3, 0.2, 0);
  m.target_yaw = M_PI / 4;
  m.landing_error = 0.019;
  m.landing_yaw_error = 10.4 * M_PI / 180;
  const std::vector<PhaseSpan> phases = phasesOf(t);
  const OverlayText flight = overlayText(t, phases, m, 0.7, false, 0.25, "diagonal");
  EXPECT_EQ(flight.phase, "flight");
  EXPECT_EQ(flight.header, "t = 0.700 s   slow motion 0.25x   diagonal");
  EXPECT_EQ(flight.target, "target (0.30, 0.20, 0.00) m, yaw 45 deg");
  EXPECT_EQ(flight.landing, "");
  for (double time : {0.9, 1.2, 1.5}) {
    EXPECT_EQ(overlayText(t, phases, m, time, time == 1.5, 1, "").landing, "landing error 1.9 cm, yaw 10.4 deg");
  }
  EXPECT_EQ(overlayText(t, phases, m, 1.2, false, 1, "").header, "t = 1.200 s");
  Trace airborne = t;
  airborne.events.pop_back();  // no touchdown
  const std::vector<PhaseSpan> up = phasesOf(airborne);
  EXPECT_EQ(overlayText(airborne, up, m, 1.2, false, 1, "").landing, "");
  EXPECT_NE(overlayText(airborne, up, m, 1.5, true, 1, "").landing, "");
}

// A multi-target video: a title card of kCardSeconds between the jumps, none before the first.
TEST(Render, AVideoOfSeveralJumpsHasATitleCardBetweenThem) {
  Episode e(0.2);
  VideoOptions options;
  options.path = outDir() + "/two_jumps.mp4";
  options.width = 320;
  options.height = 240;
  options.fps = 30;
  SceneMarkers markers;
  markers.target = Eigen::Vector3d(0.4, 0, 0);
  EpisodeVideo video(options, nullptr);
  video.add(e.trace, e.robot, e.terrain, markers, "first");
  video.add(e.trace, e.robot, e.terrain, markers, "second");
  const VideoSummary summary = video.finish();
  EXPECT_EQ(summary.frames, 6 + 24 + 6);  // 0.2 s at 30 fps, twice, and a 0.8 s card
  EXPECT_EQ(probeVideo(options.path).frames, summary.frames);
}

// The side view of a lateral jump turns towards the trunk's flank; a forward jump's does not.
TEST(Render, TheSideViewOfASidewaysJumpTurnsTowardsTheFlank) {
  const Eigen::Vector3d start(0, 0, 0);
  auto viewOf = [&](const Eigen::Vector3d& goal, double heading) {
    const Camera c = frameJump("side", start, goal, 0.3, 45, 16.0 / 9, start, heading);
    Eigen::Vector3d d = c.target - c.eye;
    d.z() = 0;
    return d.normalized();
  };
  // Forward: looking straight across the jump (+y), perpendicular to it.
  EXPECT_NEAR(viewOf({0.6, 0, 0}, 0.0).dot(Eigen::Vector3d::UnitX()), 0.0, 1e-12);
  // Lateral (+y) with the trunk along x: still mostly across the jump, turned by the full angle.
  const Eigen::Vector3d lateral = viewOf({0, 0.5, 0}, 0.0);
  EXPECT_NEAR(std::acos(std::abs(lateral.dot(Eigen::Vector3d::UnitX()))) * 180.0 / M_PI, kSideViewTurnDeg, 1e-9);
  // The same lateral jump by a robot facing +y is a forward jump for it: no turn.
  EXPECT_NEAR(viewOf({0, 0.5, 0}, M_PI / 2).dot(Eigen::Vector3d::UnitY()), 0.0, 1e-12);
}

}  // namespace
}  // namespace pronk::render
