// The scenario's controller, built-in or from a plugin, behind one interface.
#pragma once

#include <memory>

#include "pronk/controller.h"
#include "pronk/plugin_registry.h"
#include "pronk/scenario.h"

namespace pronk {

// Loads the plugins on the search path: the library a scenario's controller
// names by path (if any), then --plugin entries, PRONK_PLUGIN_PATH and the
// install directory.
void loadPlugins(PluginRegistry& registry, const std::vector<std::string>& explicit_paths,
                 const ControllerSpec* controller = nullptr);

// Checks that the platform's controller exists and its parameters fit its
// schema (defaults the platform gives included); throws InputError at the
// offending line.
void checkController(const PlatformSpec& platform, const PluginRegistry& registry);

// A built-in controller (when the name is one and no plugin is named) or a
// plugin controller with its parameters resolved against the factory schema
// and the platform (ABI 1.5 platform defaults).
std::unique_ptr<Controller> makeController(const PlatformSpec& platform, const PluginRegistry& registry,
                                           const World& world, Trace* trace);

// The scenario's environment factory; throws InputError at the element for an
// unknown name or a library other than the one it names.
const pronk_factory& findEnvironment(const EnvironmentSpec& spec, const PluginRegistry& registry);

}  // namespace pronk
