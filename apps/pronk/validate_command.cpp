// `pronk validate`: scenario files (and the parts they include) checked with
// their URDFs, controllers and environments, without simulating.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "pronk/controller.h"
#include "pronk/controller_factory.h"
#include "pronk/world.h"

namespace pronk::cli {
namespace {

// The scenario's (or part's) environment: its factory, its parameters against
// the factory's declarations, and, on a robot, what only the environment can
// judge (a motor model's name, action ranges, planner settings): an instance
// created as a run would create it, its refusal reported at the parameter's line.
// Returns the environment's name.
std::string checkEnvironment(const Scenario& scenario, const PluginRegistry& registry, const World* world) {
  const pronk_factory& env = findEnvironment(*scenario.environment, registry);
  const ResolvedParams params = resolveParams(env, scenario.environment->params, scenario.environment->where,
                                              scenario.platform.urdf.empty() ? nullptr : &scenario.platform);
  if (!world) return env.name;
  try {
    checkFactoryFitsWorld(env, PRONK_FACTORY_ENVIRONMENT, registry.libraryOf(&env)->path(), *world);
    const HostApi host(*world, nullptr);
    EnvironmentInstance instance(env, registry.libraryOf(&env)->path(), *host.api(), params);
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    const std::string message = e.what();
    SourceLocation where = scenario.environment->where;
    for (const ParamSetting& p : scenario.environment->params) {
      if (message.find("'" + p.name + "'") != std::string::npos) where = p.where;
    }
    throw InputError(where, message);
  }
  return env.name;
}

// A file meant to be included: what it holds, its robot if it has one, its
// controller's and environment's parameters (on its own robot, or against the
// declarations alone when it has none: the including file's validate judges
// the rest on its robot).
void validatePart(const CommonOptions& common, const std::string& file) {
  const Scenario part = loadScenarioPart(file);
  std::optional<World> world;
  std::string robot = "no platform";
  if (!part.platform.urdf.empty()) {
    world.emplace(part);
    robot = world->robot().name + ", " + std::to_string(world->jointCount()) + " joints, " +
            std::to_string(world->footCount()) + " feet";
  }
  std::string environment;
  const bool plugin_controller = !part.platform.controller.factory.empty();
  if (plugin_controller || part.environment) {
    PluginRegistry registry;
    loadPlugins(registry, common.plugin_paths, &part.platform.controller);
    if (plugin_controller) checkController(part.platform, registry);
    if (part.environment) {
      environment = ", environment " + checkEnvironment(part, registry, world ? &*world : nullptr);
      if (!world) environment += " (parameters checked against its declarations)";
    }
  }
  std::printf("ok  %s (part: %s%s)\n", file.c_str(), robot.c_str(), environment.c_str());
}

int validateCommand(const CommonOptions& common, const std::vector<std::string>& files) {
  int failures = 0;
  for (const std::string& file : files) {
    try {
      if (isScenarioPart(file)) {
        validatePart(common, file);
        continue;
      }
      const Scenario scenario = loadScenario(file);
      PluginRegistry registry;
      loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
      World world(scenario);  // reads the URDF, checks the feet, legs and joint names
      for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
      if (!scenario.platform.controller.factory.empty()) checkController(scenario.platform, registry);
      std::string environment;
      if (scenario.environment) environment = ", environment " + checkEnvironment(scenario, registry, &world);
      // Every case a run would set up (a step platform needs room for its edge):
      // a target or a grid case a run would refuse, validate refuses, at its line;
      // a random sweep's draws that a run would refuse alone are counted in a warning.
      const Footprint footprint = world.footprint();
      for (const EpisodeCase& c : targetCases(scenario)) applyCase(scenario, c, footprint);
      for (const SweepSpec& sweep : scenario.sweeps) {
        size_t refused = 0;
        std::string first;
        for (const EpisodeCase& c : sweepCases(scenario, sweep.name)) {
          try {
            applyCase(scenario, c, footprint);
          } catch (const NoRoomForEdge& e) {
            if (sweep.kind != SweepSpec::Kind::Random) throw;
            if (refused++ == 0) first = e.what();
          }
        }
        if (refused > 0) {
          std::cerr << "warning: " << file << ": sweep '" << sweep.name << "': " << refused
                    << " of its cases have no room for a platform edge and will be refused alone; the first: " << first << "\n";
        }
      }
      std::printf("ok  %s (%s, %d joints, %d feet, %zu targets%s)\n", file.c_str(), world.robot().name.c_str(),
                  world.jointCount(), world.footCount(), scenario.targets.size(), environment.c_str());
    } catch (const Error& e) {
      std::cerr << e.what() << "\n";
      ++failures;
    }
  }
  return failures ? kInputError : kOk;
}

}  // namespace

Subcommand declareValidate(CLI::App& app, const CommonOptions& common) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* sub = app.add_subcommand("validate", "check scenario files (and their URDFs and controllers)");
  sub->add_option("files", *files, "scenario files")->required();
  return {sub, [&common, files] { return validateCommand(common, *files); }};
}

}  // namespace pronk::cli
