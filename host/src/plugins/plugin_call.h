// Which plugin call a thread is in, for the report of a crash inside one: a
// plugin is foreign code, and a segfault in it otherwise ends pronk with no
// word of whose it was.
#pragma once

namespace pronk {

// While one lives on a thread, a fatal signal on that thread (SIGSEGV, SIGBUS,
// SIGFPE, SIGILL, SIGABRT) or exit() called from the plugin prints
// "pronk: fatal signal 11 (Segmentation fault) in plugin PATH, FACTORY's compute()"
// before pronk ends (`factory` null: "in plugin PATH's pronk_plugin_query()").
// Three pointers set and restored: cheap enough for a call per control tick.
// The strings must outlive the scope.
class PluginCallScope {
 public:
  PluginCallScope(const char* plugin, const char* factory, const char* call);
  ~PluginCallScope();
  PluginCallScope(const PluginCallScope&) = delete;
  PluginCallScope& operator=(const PluginCallScope&) = delete;

 private:
  const char* previous_[3];
};

}  // namespace pronk
