// Sweeps and target lists expanded into episode cases (docs/scenario-format.md,
// <sweeps>).
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "pronk/error.h"
#include "pronk/scenario.h"

namespace pronk {
namespace {

bool isTargetVariable(const std::string& v) { return v.rfind("target.", 0) == 0; }

void setTarget(TargetSpec& t, const std::string& variable, double value) {
  if (variable == "target.x") t.x = value;
  else if (variable == "target.y") t.y = value;
  else if (variable == "target.z") t.z = value;
  else if (variable == "target.yaw") t.yaw = value;
  else if (variable == "target.roll") t.roll = value;
  else if (variable == "target.pitch") t.pitch = value;
}

// SplitMix64: the same numbers on every platform and standard library, unlike
// std::uniform_real_distribution.
struct PortableRandom {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * ((next() >> 11) * 0x1.0p-53); }
};

// Each case: one value per axis.
std::vector<std::vector<double>> axisValues(const SweepSpec& sweep) {
  std::vector<std::vector<double>> cases;
  switch (sweep.kind) {
    case SweepSpec::Kind::Grid: {
      cases.push_back({});
      for (const SweepAxis& axis : sweep.axes) {
        std::vector<std::vector<double>> next;
        for (const auto& c : cases) {
          for (double v : axis.values) {
            next.push_back(c);
            next.back().push_back(v);
          }
        }
        cases = std::move(next);
      }
      break;
    }
    case SweepSpec::Kind::Random: {
      PortableRandom random{sweep.seed};
      for (int i = 0; i < sweep.count; ++i) {
        std::vector<double> c;
        for (const SweepAxis& axis : sweep.axes) c.push_back(random.uniform(axis.min, axis.max));
        cases.push_back(std::move(c));
      }
      break;
    }
    case SweepSpec::Kind::Vary:
      for (double v : sweep.axes.front().values) cases.push_back({v});
      break;
  }
  return cases;
}

}  // namespace

std::vector<EpisodeCase> targetCases(const Scenario& scenario) {
  std::vector<EpisodeCase> cases;
  for (const TargetSpec& t : scenario.targets) cases.push_back({"target " + t.name, t, {}});
  if (cases.empty()) {
    TargetSpec start;
    start.name = "start";
    cases.push_back({"start pose", start, {}});
  }
  return cases;
}

std::vector<EpisodeCase> sweepCases(const Scenario& scenario, const std::string& name) {
  const SweepSpec* sweep = nullptr;
  std::string known;
  for (const SweepSpec& s : scenario.sweeps) {
    if (s.name == name) sweep = &s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  if (!sweep) {
    throw InputError(SourceLocation{scenario.file, 0},
                     "no sweep named '" + name + "'" + (known.empty() ? " (the scenario has none)" : "; known: " + known));
  }
  bool sets_target = false;
  for (const SweepAxis& axis : sweep->axes) sets_target = sets_target || isTargetVariable(axis.variable);
  std::vector<EpisodeCase> out;
  const std::vector<std::vector<double>> values = axisValues(*sweep);
  for (size_t i = 0; i < values.size(); ++i) {
    EpisodeCase c;
    c.label = sweep->name + " #" + std::to_string(i);
    c.target.name = c.label;
    c.target.where = sweep->where;
    for (size_t a = 0; a < sweep->axes.size(); ++a) {
      const std::string& variable = sweep->axes[a].variable;
      if (isTargetVariable(variable)) setTarget(c.target, variable, values[i][a]);
      else c.assignments.emplace_back(variable, values[i][a]);
    }
    if (sets_target) {
      out.push_back(std::move(c));
      continue;
    }
    for (const EpisodeCase& t : targetCases(scenario)) {
      EpisodeCase each = c;
      each.label = c.label + ", " + t.label;
      each.target = t.target;
      out.push_back(std::move(each));
    }
  }
  return out;
}

namespace {

constexpr double kPlatformWidth = 1.2;     // m across the jump direction
constexpr double kPlatformBeyond = 0.6;    // m past an up target
constexpr double kPlatformBehind = 0.8;    // m behind a down target's start
constexpr double kApexFloorDrop = 0.5;       // m: the paper's ground under its take-off platform
constexpr double kDefaultEdge = 0.5;         // terrain.edge: the middle of the room between the stances

// The case's up or down platform (Scenario::step_platforms), its edge at
// `edge` (0 ... 1) of the room between the start's and the landing's footprints.
void addStepPlatform(Scenario& s, const EpisodeCase& episode, const Footprint& footprint, double edge) {
  const TargetSpec& t = episode.target;
  if (std::abs(t.z) < 1e-9) return;
  const SourceLocation where = t.where.file.empty() ? SourceLocation{s.file, 0} : t.where;
  const double distance = std::hypot(t.x, t.y);
  if (footprint.points.empty()) throw Error("applyCase: a step platform needs the robot's footprint");
  // Along the jump direction u (in the start's heading frame), from the start:
  // the start's foremost foot and the landing's rearmost one.
  const double ux = distance > 0 ? t.x / distance : 1.0, uy = distance > 0 ? t.y / distance : 0.0;
  const double c = std::cos(t.yaw), sn = std::sin(t.yaw);
  double start_front = -1e300, landing_rear = 1e300;
  for (const Vec3& f : footprint.points) {
    start_front = std::max(start_front, f[0] * ux + f[1] * uy);
    landing_rear = std::min(landing_rear, (t.x + c * f[0] - sn * f[1]) * ux + (t.y + sn * f[0] + c * f[1]) * uy);
  }
  const double lo = start_front + kStepEdgeClearance, hi = landing_rear - kStepEdgeClearance;
  if (!(distance > 0) || hi < lo) {
    throw NoRoomForEdge(where, fmt::format("{}: target z = {:.3g} m needs a platform edge between the start and "
                                           "the target, but its feet and knees at the target stand {:.3f} m too near "
                                           "the start's for one (each at least {:.2f} m from the edge; terrain "
                                           "step_platforms)",
                                           episode.label, t.z, std::max(0.0, lo - hi), kStepEdgeClearance));
  }
  const PlatformSpec& p = s.platform;
  const double azimuth = p.base_yaw + std::atan2(t.y, t.x);
  const double at = lo + edge * (hi - lo);
  const double height = std::abs(t.z);
  // Along the jump direction, from the start: where the box begins and ends.
  const double from = t.z > 0 ? at : -kPlatformBehind;
  const double to = t.z > 0 ? distance + kPlatformBeyond : at;
  const double middle = (from + to) / 2.0;
  TerrainBox box;
  box.name = t.z > 0 ? "landing_platform" : "start_platform";
  box.size = {to - from, kPlatformWidth, height};
  box.position = {p.base_position[0] + middle * std::cos(azimuth), p.base_position[1] + middle * std::sin(azimuth),
                  s.ground_height + height / 2.0};
  box.yaw = azimuth;
  box.where = where;
  s.terrain.push_back(box);
  if (t.z < 0 && !p.on_ground) s.platform.base_position[2] += height;
}

// The case's apex platform (Scenario::step_platforms == apex): placed at the
// target in the start's heading frame; the robot takes off from the surface it
// stands on, so the target's height is relative to the ground plane.
void setApexPlatform(Scenario& s, const EpisodeCase& episode) {
  const TargetSpec& t = episode.target;
  if (std::abs(t.z) < 1e-9) return;
  const PlatformSpec& p = s.platform;
  const double c = std::cos(p.base_yaw), si = std::sin(p.base_yaw);
  ApexPlatform a;
  a.x = p.base_position[0] + c * t.x - si * t.y;
  a.y = p.base_position[1] + si * t.x + c * t.y;
  a.yaw = p.base_yaw + t.yaw;
  a.top = s.ground_height + t.z;
  a.floor = s.ground_height - kApexFloorDrop;
  s.apex_platform = a;
}

}  // namespace

Scenario applyCase(const Scenario& scenario, const EpisodeCase& episode, const Footprint& footprint) {
  // Everything but the lists of cases: a case needs none of them, and their
  // copy for each of N cases made N cases take N^2.
  Scenario s;
  s.file = scenario.file;
  s.name = scenario.name;
  s.version = scenario.version;
  s.platform = scenario.platform;
  s.sim = scenario.sim;
  s.terrain = scenario.terrain;
  s.ground_height = scenario.ground_height;
  s.ground = scenario.ground;
  s.step_platforms = scenario.step_platforms;
  s.apex_platform = scenario.apex_platform;
  s.environment = scenario.environment;
  s.render = scenario.render;
  double edge = kDefaultEdge;
  for (const auto& [variable, value] : episode.assignments) {
    if (variable == "terrain.edge") edge = value;
  }
  if (s.step_platforms == StepPlatforms::edge) addStepPlatform(s, episode, footprint, edge);
  if (s.step_platforms == StepPlatforms::apex) setApexPlatform(s, episode);
  for (const auto& [variable, value] : episode.assignments) {
    if (variable == "platform.trunk_mass_offset") s.platform.trunk_mass_offset = value;
    else if (variable == "platform.unreported_trunk_mass") s.platform.unreported_trunk_mass = value;
    else if (variable == "joints.damping") s.platform.joints.damping = value;
    else if (variable == "joints.kp") s.platform.joints.kp = value;
    else if (variable == "joints.kd") s.platform.joints.kd = value;
    else if (variable == "contact.mu_static") s.sim.contact.mu_static = value;
    else if (variable == "terrain.edge") continue;  // placed the platform above
    else throw Error("sweep variable '" + variable + "' cannot be applied");
  }
  return s;
}

}  // namespace pronk
