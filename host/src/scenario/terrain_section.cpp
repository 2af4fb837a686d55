// <terrain>: the ground plane and static boxes; <targets>: where to jump.
#include <array>
#include <limits>
#include <string_view>
#include <map>

#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

// Fails when `name` was already used by an earlier element of the same list.
void rejectDuplicateName(std::map<std::string, int>& seen, const std::string& name, const ElementReader& r) {
  const auto [it, inserted] = seen.emplace(name, r.where().line);
  if (!inserted) {
    r.fail("duplicate name \"" + name + "\" (also at line " + std::to_string(it->second) + ")");
  }
}

}  // namespace

void readTerrain(const XMLElement& e, const SourceFile& file, Scenario& scenario) {
  ElementReader r(e, file);
  scenario.ground = r.boolean("ground", scenario.ground);
  scenario.ground_height = r.number("ground_height", scenario.ground_height);
  static constexpr std::array<std::string_view, 4> kStepPlatforms{"false", "true", "edge", "apex"};
  const std::string platforms = r.choice("step_platforms", "false", kStepPlatforms);
  scenario.step_platforms = platforms == "apex"    ? StepPlatforms::apex
                            : platforms == "false" ? StepPlatforms::none
                                                   : StepPlatforms::edge;
  r.rejectUnknownAttributes();
  std::map<std::string, int> names;
  for (const XMLElement* k : r.children({"box"})) {
    ElementReader b(*k, file);
    TerrainBox box;
    box.where = b.where();
    box.name = b.requiredText("name");
    rejectDuplicateName(names, box.name, b);
    box.size = b.vec3("size", box.size, Range::positive());
    box.position = b.vec3("pos", box.position);
    box.yaw = b.angle("yaw", box.yaw);
    box.mu = b.optionalNumber("mu", Range::nonNegative());
    b.rejectUnknownAttributes();
    b.children({});
    scenario.terrain.push_back(std::move(box));
  }
}

std::vector<TargetSpec> readTargets(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  r.rejectUnknownAttributes();
  std::vector<TargetSpec> targets;
  std::map<std::string, int> names;
  const Range tilt = Range::open(-kMaxTiltRad, kMaxTiltRad);
  for (const XMLElement* k : r.children({"target"})) {
    ElementReader t(*k, file);
    TargetSpec target;
    target.where = t.where();
    target.name = t.requiredText("name");
    rejectDuplicateName(names, target.name, t);
    target.x = t.number("x", target.x);
    target.y = t.number("y", target.y);
    target.z = t.number("z", target.z);
    target.yaw = t.angle("yaw", target.yaw);
    target.roll = t.angle("roll", target.roll, tilt);
    target.pitch = t.angle("pitch", target.pitch, tilt);
    target.tolerance_xy = t.optionalNumber("tolerance_xy", Range::positive());
    target.tolerance_yaw = t.optionalAngle("tolerance_yaw", Range::positive());
    t.rejectUnknownAttributes();
    t.children({});
    targets.push_back(std::move(target));
  }
  return targets;
}

}  // namespace pronk::scenario_file
