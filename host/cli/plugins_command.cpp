// `pronk plugins` and `pronk validate`.
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "controller_factory.h"
#include "pronk/world.h"

namespace pronk::cli {

int pluginsCommand(const CommonOptions& common) {
  PluginRegistry registry;
  const auto path = PluginRegistry::searchPath(common.plugin_paths);
  std::printf("search path:\n");
  for (const std::string& p : path) std::printf("  %s\n", p.c_str());
  loadPlugins(registry, common.plugin_paths);
  if (registry.libraries().empty()) std::printf("no plugins found\n");
  for (const auto& lib : registry.libraries()) {
    const uint32_t v = lib->abi_version();
    std::printf("\n%s %s (ABI %u.%u)\n  %s\n", lib->name().c_str(), lib->version().c_str(), PRONK_ABI_VERSION_MAJOR(v),
                PRONK_ABI_VERSION_MINOR(v), lib->path().c_str());
    for (const pronk_factory* f : lib->factories()) {
      const bool env = f->kind == PRONK_FACTORY_ENVIRONMENT;
      std::printf("  %-11s %-14s %s\n", env ? "environment" : "controller", f->name,
                  f->description ? f->description : "");
      std::printf("              joints %s, control period %s", f->joint_count ? std::to_string(f->joint_count).c_str() : "any",
                  f->control_period > 0 ? (std::to_string(f->control_period) + " s").c_str() : "any");
      if (env) std::printf(", observation %d, action %d", f->observation_size, f->action_size);
      std::printf("\n");
      for (int32_t i = 0; i < f->param_count; ++i) {
        const pronk_param_decl& p = f->params[i];
        std::printf("              param %-22s default %-12s %s%s%s\n", p.name, p.default_value ? p.default_value : "(required)",
                    p.unit && *p.unit ? "[" : "", p.unit && *p.unit ? (std::string(p.unit) + "] ").c_str() : "",
                    p.description ? p.description : "");
      }
    }
  }
  std::printf("\nbuilt-in controllers:");
  for (const std::string& n : builtinControllerNames()) std::printf(" %s", n.c_str());
  std::printf("\n");
  return kOk;
}

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
        resolveParams(env, scenario.environment->params, scenario.environment->where);
        environment = std::string(", environment ") + env.name;
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

}  // namespace pronk::cli
