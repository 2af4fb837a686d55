// <platform>: the robot (URDF, feet, initial pose, joint gains) and, optionally,
// its default controller.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "sections.h"

namespace pronk::scenario_file {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

std::vector<std::string> splitWords(std::string_view text) {
  std::vector<std::string> words;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    const size_t start = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i > start) words.emplace_back(text.substr(start, i - start));
  }
  return words;
}

namespace {

// Every child named `name` must carry a distinct attribute `key`.
void rejectDuplicateKeys(const std::vector<const XMLElement*>& kids, const char* name, const char* key,
                         const SourceFile& file) {
  std::map<std::string, int> seen;
  for (const XMLElement* k : kids) {
    if (std::string(k->Name()) != name || !k->Attribute(key)) continue;
    const auto [it, inserted] = seen.emplace(k->Attribute(key), k->GetLineNum());
    if (!inserted) {
      failAt(*k, file, "duplicate " + std::string(key) + " \"" + it->first + "\" (also at line " +
                           std::to_string(it->second) + ")");
    }
  }
}

void readRobot(const XMLElement& e, const SourceFile& file, PlatformSpec& p) {
  ElementReader r(e, file);
  r.requiredText("urdf");
  p.urdf = r.path("urdf", "");
  p.urdf_where = r.where();
  const std::string packages = r.text("package_path", "");
  r.rejectUnknownAttributes();
  r.children({});
  r.requireFile(p.urdf, "URDF file");
  for (const std::string& dir : splitWords(packages)) {
    const std::string resolved = (file.directory / dir).lexically_normal().string();
    r.requireFile(resolved, "package_path directory", true);
    p.package_paths.push_back(resolved);
  }
}

void readFeet(const XMLElement& e, const SourceFile& file, PlatformSpec& p) {
  ElementReader r(e, file);
  p.feet = splitWords(r.requiredText("links"));
  p.feet_where = r.where();
  r.rejectUnknownAttributes();
  r.children({});
  if (p.feet.empty()) r.fail("links must name at least one foot link");
  std::set<std::string> seen;
  for (const std::string& link : p.feet) {
    if (!seen.insert(link).second) r.fail("links names \"" + link + "\" twice");
  }
}

void readInitial(const XMLElement& e, const SourceFile& file, PlatformSpec& p) {
  ElementReader r(e, file);
  p.initial_where = r.where();
  p.stance = r.angles("stance");
  p.base_position = r.vec3("base", p.base_position);
  p.on_ground = r.boolean("on_ground", p.on_ground);
  p.base_yaw = r.angle("yaw", p.base_yaw);
  r.rejectUnknownAttributes();
  const auto kids = r.children({"joint"});
  rejectDuplicateKeys(kids, "joint", "name", file);
  for (const XMLElement* k : kids) {
    ElementReader j(*k, file);
    const std::string name = j.requiredText("name");
    const double position = j.requiredAngle("position");
    j.rejectUnknownAttributes();
    j.children({});
    p.joint_positions[name] = position;
    p.joint_position_where[name] = j.where();
  }
}

void readJoints(const XMLElement& e, const SourceFile& file, JointSettings& joints) {
  ElementReader r(e, file);
  joints.kp = r.number("kp", joints.kp, Range::nonNegative());
  joints.kd = r.number("kd", joints.kd, Range::nonNegative());
  joints.armature = r.number("armature", joints.armature, Range::nonNegative());
  joints.damping = r.number("damping", joints.damping, Range::nonNegative());
  joints.effort_scale = r.number("effort_scale", joints.effort_scale, Range::positive());
  r.rejectUnknownAttributes();
  const auto kids = r.children({"joint"});
  rejectDuplicateKeys(kids, "joint", "name", file);
  for (const XMLElement* k : kids) {
    ElementReader j(*k, file);
    JointSettings::Override o;
    o.joint = j.requiredText("name");
    o.kp = j.optionalNumber("kp", Range::nonNegative());
    o.kd = j.optionalNumber("kd", Range::nonNegative());
    o.effort = j.optionalNumber("effort", Range::positive());
    o.velocity = j.optionalNumber("velocity", Range::positive());
    o.where = j.where();
    j.rejectUnknownAttributes();
    j.children({});
    if (!o.kp && !o.kd && !o.effort && !o.velocity) j.fail("sets none of kp, kd, effort, velocity");
    joints.overrides.push_back(std::move(o));
  }
}

}  // namespace

namespace {

// The plugin attribute: a library name, or a path (resolved, must exist).
std::string readPluginAttribute(ElementReader& r) {
  const std::string plugin = r.text("plugin", "");
  if (plugin.find('/') == std::string::npos) return plugin;
  const std::string path = r.path("plugin", "");
  r.requireFile(path, "plugin file");
  return path;
}

}  // namespace

std::vector<ParamSetting> readParams(ElementReader& r, const SourceFile& file) {
  std::vector<ParamSetting> params;
  const auto kids = r.children({"param"});
  rejectDuplicateKeys(kids, "param", "name", file);
  for (const XMLElement* k : kids) {
    ElementReader pr(*k, file);
    ParamSetting param;
    param.name = pr.requiredText("name");
    const auto value = pr.optionalText("value");
    if (!value) pr.fail("missing attribute value");
    param.value = *value;
    param.where = pr.where();
    pr.rejectUnknownAttributes();
    pr.children({});
    params.push_back(std::move(param));
  }
  return params;
}

ControllerSpec readController(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  ControllerSpec c;
  c.where = r.where();
  c.factory = r.requiredText("name");
  c.plugin = readPluginAttribute(r);
  r.rejectUnknownAttributes();
  c.params = readParams(r, file);
  return c;
}

EnvironmentSpec readEnvironment(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  EnvironmentSpec env;
  env.where = r.where();
  env.factory = r.requiredText("name");
  env.plugin = readPluginAttribute(r);
  env.policy = r.text("policy", "");
  if (!env.policy.empty() && env.policy != "ballistic") {
    env.policy = r.path("policy", "");  // a policy file, relative to this file
    r.requireFile(env.policy, "policy file");
  }
  r.rejectUnknownAttributes();
  env.params = readParams(r, file);
  return env;
}

PlatformSpec readPlatform(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  PlatformSpec p;
  p.where = r.where();
  p.name = r.requiredText("name");
  // The lower bound depends on the URDF's masses: checked in scenario_file.cpp.
  p.trunk_mass_offset = r.number("trunk_mass_offset", p.trunk_mass_offset);
  p.unreported_trunk_mass = r.number("unreported_trunk_mass", p.unreported_trunk_mass);
  r.rejectUnknownAttributes();
  const auto kids = r.children({"robot", "feet", "initial", "joints", "controller"});
  for (const char* name : {"robot", "feet", "initial", "joints", "controller"}) r.rejectRepeated(kids, name);
  for (const char* name : {"robot", "feet"}) {
    const bool present = std::any_of(kids.begin(), kids.end(), [&](const XMLElement* k) {
      return std::string(k->Name()) == name;
    });
    if (!present) r.fail("missing child <" + std::string(name) + ">");
  }
  for (const XMLElement* k : kids) {
    const std::string name = k->Name();
    if (name == "robot") readRobot(*k, file, p);
    else if (name == "feet") readFeet(*k, file, p);
    else if (name == "initial") readInitial(*k, file, p);
    else if (name == "joints") {
      readJoints(*k, file, p.joints);
      p.joints_where = ElementReader(*k, file).where();
    } else if (name == "controller") p.controller = readController(*k, file);
  }
  return p;
}

}  // namespace pronk::scenario_file
