// The version handshake with a plugin's entry point, and the checks of what it
// declares: every struct's size, every factory's name, kind, operations and
// parameter schema. What passes is copied into host-sized structs, so the rest
// of the host reads fields the plugin's ABI version lacks as zero / NULL.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <dlfcn.h>
#include <set>

#include "plugin_call.h"
#include "pronk/plugin_registry.h"
#include "pronk/schema.h"

namespace pronk {

struct PluginLibrary::Factory {
  pronk_factory factory{};
  std::vector<pronk_param_decl> params;
  std::vector<pronk_metric_decl> metrics;  // 1.3
  std::vector<pronk_marker_decl> markers;  // 1.3
  std::vector<const char*> task_names;     // 1.3
  std::vector<double> task_mirror;         // 1.5
  pronk_controller_ops controller{};
  pronk_environment_ops environment{};
};

namespace {

// Size of the part of a struct that ABI 1.0 defines: a plugin's struct_size may
// not be smaller. (Fields appended by later minors lie beyond it.)
#define PRONK_END_OF(type, field) (offsetof(type, field) + sizeof(type::field))
constexpr size_t kFactorySize_1_0 = PRONK_END_OF(pronk_factory, environment);
constexpr size_t kParamDeclSize_1_0 = PRONK_END_OF(pronk_param_decl, description);
constexpr size_t kControllerOpsSize_1_0 = PRONK_END_OF(pronk_controller_ops, destroy);
constexpr size_t kEnvironmentOpsSize_1_0 = PRONK_END_OF(pronk_environment_ops, destroy);
constexpr size_t kMetricDeclSize_1_3 = PRONK_END_OF(pronk_metric_decl, pairs_with);
constexpr size_t kMarkerDeclSize_1_3 = PRONK_END_OF(pronk_marker_decl, metrics);
#undef PRONK_END_OF

constexpr uint32_t kMaxStructSize = 1u << 16;  // anything bigger is a corrupt size field
constexpr int32_t kMaxFactories = 1024;
constexpr int32_t kMaxParams = 256;
constexpr uint32_t kMaxVectorSize = 4096;
constexpr size_t kMaxNameLength = 128;
// Far beyond any robot or network, small enough that the host's buffers of
// these sizes (per episode, per jump) cost nothing: a corrupt field is refused,
// not allocated.
constexpr int32_t kMaxJoints = 1024;
constexpr int32_t kMaxObservationSize = 1 << 16;
constexpr int32_t kMaxActionSize = 4096;

std::string versionText(uint32_t v) {
  return std::to_string(PRONK_ABI_VERSION_MAJOR(v)) + "." + std::to_string(PRONK_ABI_VERSION_MINOR(v));
}

uint32_t sizeField(const void* p) {
  uint32_t size = 0;
  std::memcpy(&size, p, sizeof size);
  return size;
}

// A copy of a size-prefixed struct at host size: the plugin's fields that fit,
// zero beyond.
template <class T>
T readSized(const void* p) {
  T out{};
  std::memcpy(&out, p, std::min<size_t>(sizeField(p), sizeof(T)));
  out.struct_size = sizeof(T);
  return out;
}

bool validName(const char* name) {
  if (!name || !*name) return false;
  const size_t n = std::strlen(name);
  if (n > kMaxNameLength) return false;
  return std::all_of(name, name + n, [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

std::string quoted(const char* s) { return s ? "'" + std::string(s) + "'" : "NULL"; }

class Checker {
 public:
  explicit Checker(const std::string& path) : path_(path) {}
  [[noreturn]] void fail(const std::string& what) const { throw Error("plugin '" + path_ + "': " + what); }
  void checkSize(const void* p, size_t minimum, const std::string& what) const {
    const uint32_t size = sizeField(p);
    if (size < minimum || size > kMaxStructSize) {
      fail(what + " has struct_size " + std::to_string(size) + "; ABI 1.0 needs at least " + std::to_string(minimum));
    }
  }

 private:
  const std::string& path_;
};

std::vector<pronk_param_decl> readParams(const Checker& check, const pronk_factory& f, const std::string& who) {
  std::vector<pronk_param_decl> out;
  if (f.param_count < 0 || f.param_count > kMaxParams) {
    check.fail(who + " declares " + std::to_string(f.param_count) + " parameters");
  }
  if (f.param_count == 0) return out;
  if (!f.params) check.fail(who + " declares " + std::to_string(f.param_count) + " parameters but params is NULL");
  const auto* base = reinterpret_cast<const unsigned char*>(f.params);
  const uint32_t stride = sizeField(base);
  std::set<std::string> names;
  for (int32_t i = 0; i < f.param_count; ++i) {
    const unsigned char* raw = base + static_cast<size_t>(i) * stride;
    const std::string at = who + ", parameter #" + std::to_string(i);
    check.checkSize(raw, kParamDeclSize_1_0, at);
    if (sizeField(raw) != stride) {
      check.fail(at + " has struct_size " + std::to_string(sizeField(raw)) + ", the first has " + std::to_string(stride) +
                 " (all entries of the array must have the same)");
    }
    const pronk_param_decl d = readSized<pronk_param_decl>(raw);
    if (!validName(d.name)) check.fail(at + " is named " + quoted(d.name) + ", not [a-z0-9_]+");
    const std::string param = who + ", parameter '" + d.name + "'";
    if (!names.insert(d.name).second) check.fail(param + " is declared twice");
    if (d.type < PRONK_PARAM_REAL || d.type > PRONK_PARAM_VECTOR) {
      check.fail(param + " has unknown type " + std::to_string(d.type));
    }
    if (std::isnan(d.min_value) || std::isnan(d.max_value)) check.fail(param + " has a NaN bound");
    if (d.type == PRONK_PARAM_VECTOR && d.vector_size > kMaxVectorSize) {
      check.fail(param + " declares a vector of " + std::to_string(d.vector_size) + " numbers");
    }
    if (d.platform_default) {  // 1.5
      const std::vector<std::string>& known = platformPropertyNames();
      if (std::find(known.begin(), known.end(), d.platform_default) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        check.fail(param + " defaults to the platform's " + quoted(d.platform_default) + ", not one of " + list);
      }
      if (d.type != platformPropertyType(d.platform_default)) {
        check.fail(param + " defaults to the platform's '" + d.platform_default + "' but is not of its type");
      }
    }
    if (!d.required) {
      if (!d.default_value) check.fail(param + " is neither required nor has a default value");
      const std::string why = checkParamValue(d, d.default_value);
      if (!why.empty()) check.fail(param + " has an invalid default: " + why);
    }
    out.push_back(d);
  }
  return out;
}

// A size-prefixed array (stride: the first entry's struct_size), each entry
// checked against `minimum` and copied at host size.
template <class T>
std::vector<T> readArray(const Checker& check, const void* array, int32_t count, size_t minimum, int32_t limit,
                         const std::string& what) {
  std::vector<T> out;
  if (count < 0 || count > limit) check.fail(what + ": " + std::to_string(count) + " entries");
  if (count == 0) return out;
  if (!array) check.fail(what + ": " + std::to_string(count) + " entries but the array is NULL");
  const auto* base = static_cast<const unsigned char*>(array);
  const uint32_t stride = sizeField(base);
  for (int32_t i = 0; i < count; ++i) {
    const unsigned char* raw = base + static_cast<size_t>(i) * stride;
    const std::string at = what + " #" + std::to_string(i);
    const uint32_t size = sizeField(raw);
    if (size < minimum || size > kMaxStructSize) {
      check.fail(at + " has struct_size " + std::to_string(size) + "; ABI 1.3 needs at least " + std::to_string(minimum));
    }
    if (size != stride) check.fail(at + " has struct_size " + std::to_string(size) + ", the first has " + std::to_string(stride));
    out.push_back(readSized<T>(raw));
  }
  return out;
}

// ABI 1.3: the environment's declared metrics, task names and markers.
void readDeclarations(const Checker& check, PluginLibrary::Factory& out, const std::string& who) {
  pronk_factory& f = out.factory;
  out.metrics = readArray<pronk_metric_decl>(check, f.metrics, f.metric_count, kMetricDeclSize_1_3, kMaxParams * 4,
                                             who + ", metric");
  std::set<std::string> names;
  for (const pronk_metric_decl& m : out.metrics) {
    if (!validName(m.name)) check.fail(who + " declares a metric named " + quoted(m.name) + ", not [a-z0-9_]+");
    if (!names.insert(m.name).second) check.fail(who + " declares metric '" + std::string(m.name) + "' twice");
    if (m.kind > PRONK_METRIC_TIME) {
      check.fail(who + ", metric '" + m.name + "' has unknown kind " + std::to_string(m.kind));
    }
  }
  for (const pronk_metric_decl& m : out.metrics) {
    if (!m.pairs_with) continue;
    const std::string with = m.pairs_with;
    const auto& events = hostContactEvents();
    if (!names.count(with) && std::find(events.begin(), events.end(), with) == events.end()) {
      check.fail(who + ", metric '" + m.name + "' pairs with '" + with + "', neither a declared metric nor a host event");
    }
  }
  out.markers = readArray<pronk_marker_decl>(check, f.markers, f.marker_count, kMarkerDeclSize_1_3, 64, who + ", marker");
  for (const pronk_marker_decl& m : out.markers) {
    if (m.kind != PRONK_MARKER_POINT && m.kind != PRONK_MARKER_ARC) {
      check.fail(who + " declares a marker of unknown kind " + std::to_string(m.kind));
    }
    const int needed = m.kind == PRONK_MARKER_POINT ? 3 : 7;
    for (int i = 0; i < needed; ++i) {
      if (!m.metrics[i] || !names.count(m.metrics[i])) {
        check.fail(who + ", marker " + quoted(m.label) + ": metrics[" + std::to_string(i) + "] " + quoted(m.metrics[i]) +
                   " is not a declared metric");
      }
    }
  }
  if (f.task_size < 0 || f.task_size > 4096) check.fail(who + " declares " + std::to_string(f.task_size) + " task names");
  if (f.task_size > 0 && !f.task_names) check.fail(who + " declares " + std::to_string(f.task_size) + " task names but none");
  for (int32_t i = 0; i < f.task_size; ++i) {
    if (!validName(f.task_names[i])) check.fail(who + ", task name #" + std::to_string(i) + " " + quoted(f.task_names[i]) + " is not [a-z0-9_]+");
    out.task_names.push_back(f.task_names[i]);
  }
  if (f.task_mirror) {  // 1.5
    if (f.task_size <= 0) check.fail(who + " declares a task mirror but no task names (task_size)");
    for (int32_t i = 0; i < f.task_size; ++i) {
      if (f.task_mirror[i] != 1.0 && f.task_mirror[i] != -1.0) {
        check.fail(who + ", task_mirror[" + std::to_string(i) + "] is " + std::to_string(f.task_mirror[i]) +
                   ", not +1 or -1");
      }
      out.task_mirror.push_back(f.task_mirror[i]);
    }
  }
  f.metrics = out.metrics.empty() ? nullptr : out.metrics.data();
  f.markers = out.markers.empty() ? nullptr : out.markers.data();
  f.task_names = out.task_names.empty() ? nullptr : out.task_names.data();
  f.task_mirror = out.task_mirror.empty() ? nullptr : out.task_mirror.data();
}

std::unique_ptr<PluginLibrary::Factory> readFactory(const Checker& check, const pronk_factory* raw, int32_t index,
                                                    uint32_t abi_version) {
  const std::string slot = "factory #" + std::to_string(index);
  if (!raw) check.fail(slot + " is NULL");
  check.checkSize(raw, kFactorySize_1_0, slot);
  auto out = std::make_unique<PluginLibrary::Factory>();
  pronk_factory& f = out->factory;
  f = readSized<pronk_factory>(raw);
  if (PRONK_ABI_VERSION_MINOR(abi_version) < 3) {
    // Fields of 1.3 are not the plugin's to fill at an older minor.
    f.metric_count = f.task_size = f.marker_count = 0;
    f.metrics = nullptr;
    f.task_names = nullptr;
    f.markers = nullptr;
  }
  if (PRONK_ABI_VERSION_MINOR(abi_version) < 5) f.task_mirror = nullptr;  // 1.5's
  if (!validName(f.name)) check.fail(slot + " is named " + quoted(f.name) + ", not [a-z0-9_]+");
  if (f.kind != PRONK_FACTORY_CONTROLLER && f.kind != PRONK_FACTORY_ENVIRONMENT) {
    check.fail(slot + " ('" + f.name + "') has unknown kind " + std::to_string(f.kind));
  }
  const std::string who = factoryKindName(f.kind) + " '" + f.name + "'";
  if (!f.create) check.fail(who + " has no create()");
  if (f.joint_count < 0 || f.joint_count > kMaxJoints) {
    check.fail(who + " declares " + std::to_string(f.joint_count) + " joints (at most " + std::to_string(kMaxJoints) +
               ")");
  }
  if (!std::isfinite(f.control_period) || f.control_period < 0) {
    check.fail(who + " declares control period " + std::to_string(f.control_period) + " s");
  }
  out->params = readParams(check, f, who);
  f.params = out->params.empty() ? nullptr : out->params.data();

  if (f.kind == PRONK_FACTORY_CONTROLLER) {
    if (!f.controller) check.fail(who + " has no controller operations");
    check.checkSize(f.controller, kControllerOpsSize_1_0, who + "'s controller operations");
    out->controller = readSized<pronk_controller_ops>(f.controller);
    if (!out->controller.compute) check.fail(who + " has no compute()");
    if (!out->controller.destroy) check.fail(who + " has no destroy()");
    f.controller = &out->controller;
    f.environment = nullptr;
  } else {
    if (!f.environment) check.fail(who + " has no environment operations");
    check.checkSize(f.environment, kEnvironmentOpsSize_1_0, who + "'s environment operations");
    out->environment = readSized<pronk_environment_ops>(f.environment);
    const pronk_environment_ops& e = out->environment;
    if (!e.reset || !e.act || !e.step || !e.finish || !e.destroy) {
      check.fail(who + " lacks one of reset(), act(), step(), finish(), destroy()");
    }
    if (f.observation_size <= 0 || f.action_size <= 0 || f.observation_size > kMaxObservationSize ||
        f.action_size > kMaxActionSize) {
      check.fail(who + " declares observation size " + std::to_string(f.observation_size) + " and action size " +
                 std::to_string(f.action_size) + "; an environment needs both > 0, at most " +
                 std::to_string(kMaxObservationSize) + " and " + std::to_string(kMaxActionSize));
    }
    f.environment = &out->environment;
    f.controller = nullptr;
    readDeclarations(check, *out, who);
  }
  return out;
}

}  // namespace

EnvironmentSchema environmentSchema(const pronk_factory& f) {
  EnvironmentSchema schema;
  auto text = [](const char* s) { return std::string(s ? s : ""); };
  for (int32_t i = 0; i < f.metric_count; ++i) {
    const pronk_metric_decl& d = f.metrics[i];  // the host's copy: host stride
    MetricSpec m;
    m.name = d.name;
    m.kind = d.kind == PRONK_METRIC_PENALTY ? MetricSpec::Kind::Penalty
             : d.kind == PRONK_METRIC_TIME  ? MetricSpec::Kind::Time
                                            : MetricSpec::Kind::Value;
    m.unit = text(d.unit);
    m.description = text(d.description);
    m.column = text(d.column);
    m.pairs_with = text(d.pairs_with);
    schema.metrics.push_back(std::move(m));
  }
  for (int32_t i = 0; i < f.task_size; ++i) schema.task_names.push_back(f.task_names[i]);
  if (f.task_mirror) schema.task_mirror.assign(f.task_mirror, f.task_mirror + f.task_size);
  for (int32_t i = 0; i < f.marker_count; ++i) {
    const pronk_marker_decl& d = f.markers[i];
    MarkerSpec m;
    m.kind = d.kind == PRONK_MARKER_ARC ? MarkerSpec::Kind::Arc : MarkerSpec::Kind::Point;
    m.label = text(d.label);
    for (int k = 0; k < (d.kind == PRONK_MARKER_ARC ? 7 : 3); ++k) m.metrics.push_back(d.metrics[k]);
    schema.markers.push_back(std::move(m));
  }
  return schema;
}

PluginLibrary::PluginLibrary() = default;

PluginLibrary::~PluginLibrary() {
  factories_.clear();
  if (handle_) dlclose(handle_);
}

std::vector<const pronk_factory*> PluginLibrary::factories() const {
  std::vector<const pronk_factory*> out;
  out.reserve(factories_.size());
  for (const auto& f : factories_) out.push_back(&f->factory);
  return out;
}

std::unique_ptr<PluginLibrary> PluginRegistry::handshake(const std::string& path, pronk_plugin_query_fn query) {
  const Checker check(path);
  const uint32_t host = PRONK_ABI_VERSION(PRONK_ABI_MAJOR, PRONK_ABI_MINOR);
  pronk_plugin_manifest manifest{};
  manifest.struct_size = sizeof manifest;
  char message[1024] = "";
  pronk_status status = PRONK_OK;
  {
    const PluginCallScope call(path.c_str(), nullptr, "pronk_plugin_query");
    status = query(host, &manifest, message, sizeof message);
  }
  message[sizeof message - 1] = '\0';
  const std::string said = message[0] ? message : "no message";
  if (status == PRONK_ERROR_VERSION) {
    std::string what = "rejected this host's ABI version " + versionText(host) + ": " + said;
    if (manifest.abi_version) what += " (the plugin speaks ABI " + versionText(manifest.abi_version) + ")";
    check.fail(what);
  }
  if (status != PRONK_OK) {
    check.fail(std::string(PRONK_PLUGIN_ENTRY_NAME) + " failed (status " + std::to_string(status) + "): " + said);
  }
  if (PRONK_ABI_VERSION_MAJOR(manifest.abi_version) != PRONK_ABI_MAJOR ||
      PRONK_ABI_VERSION_MINOR(manifest.abi_version) > PRONK_ABI_MINOR) {
    check.fail("answered ABI version " + versionText(manifest.abi_version) + " to this host's " + versionText(host) +
               "; it must answer " + std::to_string(PRONK_ABI_MAJOR) + ".n with n <= " + std::to_string(PRONK_ABI_MINOR));
  }
  if (!manifest.plugin_name || !*manifest.plugin_name) check.fail("the manifest has no plugin name");
  if (manifest.factory_count < 0 || manifest.factory_count > kMaxFactories) {
    check.fail("the manifest declares " + std::to_string(manifest.factory_count) + " factories");
  }
  if (manifest.factory_count > 0 && !manifest.factories) check.fail("the manifest's factory array is NULL");

  auto library = std::unique_ptr<PluginLibrary>(new PluginLibrary());
  library->path_ = path;
  library->name_ = manifest.plugin_name;
  library->version_ = manifest.plugin_version ? manifest.plugin_version : "";
  library->abi_version_ = manifest.abi_version;
  for (int32_t i = 0; i < manifest.factory_count; ++i) {
    auto f = readFactory(check, manifest.factories[i], i, manifest.abi_version);
    for (const auto& other : library->factories_) {
      if (other->factory.kind == f->factory.kind && std::strcmp(other->factory.name, f->factory.name) == 0) {
        check.fail("declares " + factoryKindName(f->factory.kind) + " '" + f->factory.name + "' twice");
      }
    }
    library->factories_.push_back(std::move(f));
  }
  return library;
}

}  // namespace pronk
