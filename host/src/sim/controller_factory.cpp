#include "pronk/controller_factory.h"

#include <algorithm>
#include <filesystem>

namespace pronk {
namespace {

bool isBuiltin(const ControllerSpec& spec) {
  const auto& names = builtinControllerNames();
  return spec.plugin.empty() && std::find(names.begin(), names.end(), spec.factory) != names.end();
}

// When the scenario names the library a factory must come from (its plugin
// name, or a path compared by file name), the factory found must be from it.
void checkLibrary(const pronk_factory& factory, const char* kind, const std::string& plugin,
                  const SourceLocation& where, const PluginRegistry& registry) {
  if (plugin.empty()) return;
  const PluginLibrary* library = registry.libraryOf(&factory);
  const bool by_path = plugin.find('/') != std::string::npos;
  const std::string wanted = by_path ? std::filesystem::path(plugin).filename().string() : plugin;
  const std::string have = by_path ? std::filesystem::path(library->path()).filename().string() : library->name();
  if (wanted != have) {
    throw InputError(where, std::string(kind) + " '" + factory.name + "' comes from " + library->path() +
                                " (plugin '" + library->name() + "'), not from plugin '" + plugin + "'");
  }
}

const pronk_factory& findFactory(const ControllerSpec& spec, const PluginRegistry& registry) {
  const pronk_factory* factory = registry.find(PRONK_FACTORY_CONTROLLER, spec.factory);
  if (!factory) {
    std::string known;
    for (const std::string& n : builtinControllerNames()) known += (known.empty() ? "" : ", ") + n;
    for (const auto& lib : registry.libraries())
      for (const pronk_factory* f : lib->factories())
        if (f->kind == PRONK_FACTORY_CONTROLLER) known += std::string(", ") + f->name;
    throw InputError(spec.where, "no controller named '" + spec.factory + "' (built-in or in a loaded plugin); known: " +
                                     known + registry.skippedNote());
  }
  checkLibrary(*factory, "controller", spec.plugin, spec.where, registry);
  return *factory;
}

}  // namespace

const pronk_factory& findEnvironment(const EnvironmentSpec& spec, const PluginRegistry& registry) {
  const pronk_factory* factory = registry.find(PRONK_FACTORY_ENVIRONMENT, spec.factory);
  if (!factory) {
    std::string known;
    for (const auto& lib : registry.libraries())
      for (const pronk_factory* f : lib->factories())
        if (f->kind == PRONK_FACTORY_ENVIRONMENT) known += (known.empty() ? "" : ", ") + std::string(f->name);
    throw InputError(spec.where, "no environment named '" + spec.factory + "' in the loaded plugins" +
                                     (known.empty() ? std::string(" (none has one)") : "; known: " + known) +
                                     registry.skippedNote());
  }
  checkLibrary(*factory, "environment", spec.plugin, spec.where, registry);
  return *factory;
}

void loadPlugins(PluginRegistry& registry, const std::vector<std::string>& explicit_paths,
                 const ControllerSpec* controller) {
  std::vector<std::string> entries;
  if (controller && controller->plugin.find('/') != std::string::npos) entries.push_back(controller->plugin);
  entries.insert(entries.end(), explicit_paths.begin(), explicit_paths.end());
  registry.loadSearchPath(PluginRegistry::searchPath(entries));
}

void checkController(const PlatformSpec& platform, const PluginRegistry& registry) {
  const ControllerSpec& spec = platform.controller;
  if (isBuiltin(spec)) {
    if (!spec.params.empty()) {
      throw InputError(spec.params.front().where,
                       "the built-in controller '" + spec.factory + "' takes no parameters (its gains come from <joints>)");
    }
    return;
  }
  resolveParams(findFactory(spec, registry), spec.params, spec.where, &platform);
}

std::unique_ptr<Controller> makeController(const PlatformSpec& platform, const PluginRegistry& registry,
                                           const World& world, Trace* trace) {
  checkController(platform, registry);
  const ControllerSpec& spec = platform.controller;
  if (isBuiltin(spec)) return makeBuiltinController(spec.factory, world, trace);
  const pronk_factory& factory = findFactory(spec, registry);
  const ResolvedParams params = resolveParams(factory, spec.params, spec.where, &platform);
  return std::make_unique<PluginController>(factory, registry.libraryOf(&factory)->path(), params, world, trace);
}

}  // namespace pronk
