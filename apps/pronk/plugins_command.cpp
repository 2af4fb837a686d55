// `pronk plugins`: the plugin search path, the libraries found, their factories and parameters.
#include <cmath>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>

#include "commands.h"
#include "pronk/controller_factory.h"

namespace pronk::cli {
namespace {

int pluginsCommand(const CommonOptions& common);

// The range a number (or each number of a vector) is checked against, as the
// host checks it: "in [lo, hi]", one-sided when the other bound is infinite,
// "" when the plugin declares none (min > max) or the parameter is text.
std::string rangeOf(const pronk_param_decl& p) {
  const bool numeric = p.type == PRONK_PARAM_REAL || p.type == PRONK_PARAM_INT || p.type == PRONK_PARAM_VECTOR;
  if (!numeric || p.min_value > p.max_value) return "";
  const bool low = std::isfinite(p.min_value), high = std::isfinite(p.max_value);
  if (low && high) return fmt::format("in [{:g}, {:g}]", p.min_value, p.max_value);
  if (low) return fmt::format(">= {:g}", p.min_value);
  if (high) return fmt::format("<= {:g}", p.max_value);
  return "";
}

}  // namespace

Subcommand declarePlugins(CLI::App& app, const CommonOptions& common) {
  CLI::App* sub = app.add_subcommand("plugins", "list loadable plugins, their ABI versions and factories");
  return {sub, [&common] { return pluginsCommand(common); }};
}

namespace {


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
      if (env) {
        const EnvironmentSchema schema = environmentSchema(*f);
        int penalties = 0, times = 0;
        for (const MetricSpec& m : schema.metrics) {
          penalties += m.kind == MetricSpec::Kind::Penalty;
          times += m.kind == MetricSpec::Kind::Time;
        }
        std::printf("              declares %zu metrics (%d reward cost terms, %d times), %zu task numbers, %zu video "
                    "markers (ABI 1.3)\n",
                    schema.metrics.size(), penalties, times, schema.task_names.size(), schema.markers.size());
      }
      for (int32_t i = 0; i < f->param_count; ++i) {
        const pronk_param_decl& p = f->params[i];
        const std::string unit = p.unit && *p.unit ? fmt::format("[{}] ", p.unit) : "";
        // A platform default (ABI 1.5) shows as the platform's; an empty one as "".
        const std::string default_text =
            p.platform_default ? fmt::format("platform's {}", p.platform_default)
            : !p.default_value ? std::string("(required)")
            : *p.default_value ? std::string(p.default_value)
                               : std::string("\"\"");
        fmt::print("              param {:<22} default {:<17} {:<18} {}{}\n", p.name, default_text, rangeOf(p), unit,
                   p.description ? p.description : "");
      }
    }
  }
  std::printf("\nbuilt-in controllers:");
  for (const std::string& n : builtinControllerNames()) std::printf(" %s", n.c_str());
  std::printf("\n");
  // Listed, and the status says so: a broken library is skipped by the commands that do not need it.
  for (const PluginRegistry::Skipped& s : registry.skipped()) {
    std::fprintf(stderr, "pronk: not loaded: %s: %s\n", s.path.c_str(), s.reason.c_str());
  }
  return registry.skipped().empty() ? kOk : kInputError;
}

}  // namespace
}  // namespace pronk::cli
