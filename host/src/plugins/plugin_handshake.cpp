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

#include "pronk/plugin_registry.h"

namespace pronk {

struct PluginLibrary::Factory {
  pronk_factory factory{};
  std::vector<pronk_param_decl> params;
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
#undef PRONK_END_OF

constexpr uint32_t kMaxStructSize = 1u << 16;  // anything bigger is a corrupt size field
constexpr int32_t kMaxFactories = 1024;
constexpr int32_t kMaxParams = 256;
constexpr uint32_t kMaxVectorSize = 4096;
constexpr size_t kMaxNameLength = 128;

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
    if (!d.required) {
      if (!d.default_value) check.fail(param + " is neither required nor has a default value");
      const std::string why = checkParamValue(d, d.default_value);
      if (!why.empty()) check.fail(param + " has an invalid default: " + why);
    }
    out.push_back(d);
  }
  return out;
}

std::unique_ptr<PluginLibrary::Factory> readFactory(const Checker& check, const pronk_factory* raw, int32_t index) {
  const std::string slot = "factory #" + std::to_string(index);
  if (!raw) check.fail(slot + " is NULL");
  check.checkSize(raw, kFactorySize_1_0, slot);
  auto out = std::make_unique<PluginLibrary::Factory>();
  pronk_factory& f = out->factory;
  f = readSized<pronk_factory>(raw);
  if (!validName(f.name)) check.fail(slot + " is named " + quoted(f.name) + ", not [a-z0-9_]+");
  if (f.kind != PRONK_FACTORY_CONTROLLER && f.kind != PRONK_FACTORY_ENVIRONMENT) {
    check.fail(slot + " ('" + f.name + "') has unknown kind " + std::to_string(f.kind));
  }
  const std::string who = factoryKindName(f.kind) + " '" + f.name + "'";
  if (!f.create) check.fail(who + " has no create()");
  if (f.joint_count < 0) check.fail(who + " declares " + std::to_string(f.joint_count) + " joints");
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
    if (f.observation_size <= 0 || f.action_size <= 0) {
      check.fail(who + " declares observation size " + std::to_string(f.observation_size) + " and action size " +
                 std::to_string(f.action_size) + "; an environment needs both > 0");
    }
    f.environment = &out->environment;
    f.controller = nullptr;
  }
  return out;
}

}  // namespace

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
  const pronk_status status = query(host, &manifest, message, sizeof message);
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
    auto f = readFactory(check, manifest.factories[i], i);
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
