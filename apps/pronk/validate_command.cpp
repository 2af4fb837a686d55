// `pronk validate`: scenario files (and the parts they include) checked with
// their URDFs, controllers and environments, without simulating.
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.h"
#include "pronk/controller.h"
#include "pronk/controller_factory.h"
#include "pronk/world.h"

namespace pronk::cli {
namespace {

int validateCommand(const CommonOptions& common, const std::vector<std::string>& files) {
  int failures = 0;
  for (const std::string& file : files) {
    try {
      if (isScenarioPart(file)) {
        // A file meant to be included: check what it holds, and its robot if it has one.
        const Scenario part = loadScenarioPart(file);
        std::string robot = "no platform";
        if (!part.platform.urdf.empty()) {
          World world(part);
          robot = world.robot().name + ", " + std::to_string(world.jointCount()) + " joints, " +
                  std::to_string(world.footCount()) + " feet";
        }
        std::printf("ok  %s (part: %s)\n", file.c_str(), robot.c_str());
        continue;
      }
      const Scenario scenario = loadScenario(file);
      PluginRegistry registry;
      loadPlugins(registry, common.plugin_paths, &scenario.platform.controller);
      World world(scenario);  // reads the URDF, checks the feet, legs and joint names
      for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
      if (!scenario.platform.controller.factory.empty()) checkController(scenario.platform.controller, registry);
      std::string environment;
      if (scenario.environment) {
        const pronk_factory& env = findEnvironment(*scenario.environment, registry);
        const ResolvedParams params = resolveParams(env, scenario.environment->params, scenario.environment->where);
        // What only the environment can judge (a motor model's name, action
        // ranges, planner settings): create an instance on this robot, as a run
        // would, and report its refusal at the parameter's line.
        try {
          checkFactoryFitsWorld(env, PRONK_FACTORY_ENVIRONMENT, registry.libraryOf(&env)->path(), world);
          const HostApi host(world, nullptr);
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
        environment = std::string(", environment ") + env.name;
      }
      // Every case a run would set up (a step platform needs room for its edge):
      // what a run would refuse, validate refuses, at the target's or sweep's line.
      std::vector<EpisodeCase> cases = targetCases(scenario);
      for (const SweepSpec& sweep : scenario.sweeps) {
        const std::vector<EpisodeCase> more = sweepCases(scenario, sweep.name);
        cases.insert(cases.end(), more.begin(), more.end());
      }
      for (const EpisodeCase& c : cases) applyCase(scenario, c);
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
