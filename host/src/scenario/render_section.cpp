// <render>: video size, frame rate, playback speed, output file and <camera>.
#include <filesystem>

#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

constexpr double kRadToDeg = 57.295779513082320876798;
constexpr double kPi = 3.14159265358979323846;

CameraSpec readCamera(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  CameraSpec c;
  c.where = r.where();
  c.mode = r.choice("mode", c.mode, kCameraModes);
  const bool placed = r.has("pos") || r.has("look_at");
  c.position = r.vec3("pos", c.position);
  c.look_at = r.vec3("look_at", c.look_at);
  c.fovy_deg = r.angle("fovy", c.fovy_deg / kRadToDeg, Range::open(0, kPi)) * kRadToDeg;
  r.rejectUnknownAttributes();
  r.children({});
  if (placed && c.mode != "fixed") r.fail("pos and look_at place a fixed camera; mode is \"" + c.mode + "\"");
  return c;
}

int evenSize(ElementReader& r, const char* name, int fallback) {
  const int v = static_cast<int>(r.integer(name, fallback, 2, 16384));
  if (v % 2 != 0) r.fail(std::string(name) + " must be even (video encoders need it; got " + std::to_string(v) + ")");
  return v;
}

}  // namespace

RenderSpec readRender(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  RenderSpec s;
  s.where = r.where();
  s.width = evenSize(r, "width", s.width);
  s.height = evenSize(r, "height", s.height);
  s.fps = r.number("fps", s.fps, Range::positive());
  s.speed = r.number("speed", s.speed, Range::positive());
  // Only a suggested file name: the command line decides whether a video is
  // written and where (under --out), so a scenario cannot write a file anywhere.
  s.output = r.text("output", s.output);
  if (r.has("output")) {
    const std::filesystem::path name(s.output);
    bool climbs = false;
    for (const auto& part : name) climbs = climbs || part == "..";
    if (s.output.empty() || name.is_absolute() || climbs) {
      r.fail("output=\"" + s.output + "\" must be a relative file name without '..': the video goes under the "
             "command's --out directory, and only when the command asks for a video");
    }
  }
  r.rejectUnknownAttributes();
  const auto kids = r.children({"camera"});
  r.rejectRepeated(kids, "camera");
  s.camera.where = s.where;
  for (const XMLElement* k : kids) s.camera = readCamera(*k, file);
  return s;
}

}  // namespace pronk::scenario_file
