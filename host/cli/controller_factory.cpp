#include "controller_factory.h"

#include <algorithm>

namespace pronk::cli {
namespace {

bool isBuiltin(const ControllerSpec& spec) {
  const auto& names = builtinControllerNames();
  return spec.plugin.empty() && std::find(names.begin(), names.end(), spec.factory) != names.end();
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
                                     known);
  }
  return *factory;
}

}  // namespace

void loadPlugins(PluginRegistry& registry, const std::vector<std::string>& explicit_paths) {
  registry.loadSearchPath(PluginRegistry::searchPath(explicit_paths));
}

void checkController(const ControllerSpec& spec, const PluginRegistry& registry) {
  if (isBuiltin(spec)) {
    if (!spec.params.empty()) {
      throw InputError(spec.params.front().where,
                       "the built-in controller '" + spec.factory + "' takes no parameters (its gains come from <joints>)");
    }
    return;
  }
  resolveParams(findFactory(spec, registry), spec.params, spec.where);
}

std::unique_ptr<Controller> makeController(const ControllerSpec& spec, const PluginRegistry& registry,
                                           const World& world, Trace* trace) {
  checkController(spec, registry);
  if (isBuiltin(spec)) return makeBuiltinController(spec.factory, world, trace);
  const pronk_factory& factory = findFactory(spec, registry);
  const ResolvedParams params = resolveParams(factory, spec.params, spec.where);
  return std::make_unique<PluginController>(factory, params.data(), params.size(), world, trace);
}

}  // namespace pronk::cli
