#include "urdf_root_mass.h"

#include <tinyxml2.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

namespace pronk::scenario_file {

std::optional<RootBody> urdfRootBody(const std::string& urdf_path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(urdf_path, ec)) return std::nullopt;  // the URDF reader says why
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(urdf_path.c_str()) != tinyxml2::XML_SUCCESS) return std::nullopt;
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::strcmp(robot->Name(), "robot") != 0) return std::nullopt;

  std::map<std::string, double> link_mass;
  for (const auto* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    const char* name = link->Attribute("name");
    if (!name) return std::nullopt;
    double mass = 0;
    if (const auto* inertial = link->FirstChildElement("inertial")) {
      if (const auto* m = inertial->FirstChildElement("mass")) m->QueryDoubleAttribute("value", &mass);
    }
    link_mass[name] = mass;
  }

  std::multimap<std::string, std::string> fixed_children;  // parent -> child
  std::set<std::string> children;
  for (const auto* joint = robot->FirstChildElement("joint"); joint; joint = joint->NextSiblingElement("joint")) {
    const auto* parent = joint->FirstChildElement("parent");
    const auto* child = joint->FirstChildElement("child");
    const char* type = joint->Attribute("type");
    if (!parent || !child || !type || !parent->Attribute("link") || !child->Attribute("link")) return std::nullopt;
    children.insert(child->Attribute("link"));
    if (std::strcmp(type, "fixed") == 0) fixed_children.emplace(parent->Attribute("link"), child->Attribute("link"));
  }

  std::vector<std::string> roots;
  for (const auto& [name, mass] : link_mass) {
    if (!children.count(name)) roots.push_back(name);
  }
  if (roots.size() != 1) return std::nullopt;

  RootBody body{roots.front(), 0};
  std::vector<std::string> pending{roots.front()};
  std::set<std::string> visited;
  while (!pending.empty()) {
    const std::string link = pending.back();
    pending.pop_back();
    if (!visited.insert(link).second) continue;
    body.mass += link_mass.count(link) ? link_mass[link] : 0;
    const auto [first, last] = fixed_children.equal_range(link);
    for (auto it = first; it != last; ++it) pending.push_back(it->second);
  }
  return body;
}

}  // namespace pronk::scenario_file
