// Plugin loading and the factory registry: the host side of the plugin ABI
// (docs/plugin-abi.md). A PluginRegistry loads shared libraries, runs the
// version handshake, checks every factory a plugin declares and registers it by
// kind and name; resolveParams() checks a scenario's parameters against a
// factory's declared schema; ControllerInstance and EnvironmentInstance own
// plugin instances and turn status codes into pronk::Error.
//
// Lifetimes: a PluginLibrary lives as long as its registry; factory pointers and
// instances created from them must not outlive the registry (its destructor
// dlclose()s the libraries). Loading is not thread-safe; const lookups are.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pronk/error.h"
#include "pronk/plugin_abi.h"
#include "pronk/schema.h"
#include "pronk/scenario.h"

namespace pronk {

// One loaded plugin library. The factories it lists are the host's own copies of
// the plugin's descriptors, normalised to this host's struct sizes (fields the
// plugin's ABI version lacks read as zero / NULL), so `f->params[i]` is safe.
// An environment factory's declarations (ABI 1.3; empty for an older plugin).
EnvironmentSchema environmentSchema(const pronk_factory& factory);

class PluginLibrary {
 public:
  ~PluginLibrary();
  PluginLibrary(const PluginLibrary&) = delete;
  PluginLibrary& operator=(const PluginLibrary&) = delete;

  const std::string& path() const { return path_; }  // absolute; "builtin:<origin>" for built-ins
  const std::string& name() const { return name_; }
  const std::string& version() const { return version_; }
  uint32_t abi_version() const { return abi_version_; }  // negotiated, PRONK_ABI_VERSION(major, minor)
  std::vector<const pronk_factory*> factories() const;

  struct Factory;  // opaque: a normalised factory with its parameter and ops copies

 private:
  friend class PluginRegistry;
  PluginLibrary();

  std::string path_, identity_, name_, version_;
  uint32_t abi_version_ = 0;
  void* handle_ = nullptr;  // dlopen handle, null for built-ins
  std::vector<std::unique_ptr<Factory>> factories_;
};

class PluginRegistry {
 public:
  PluginRegistry();
  ~PluginRegistry();
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  // Loads a plugin library: dlopen(RTLD_NOW | RTLD_LOCAL), the handshake, the checks of
  // every factory. Throws Error naming the file (with dlerror()'s text, or the plugin's
  // message) and registers nothing when anything is wrong. A factory name already
  // registered for the same kind is an error naming both libraries. Loading a path that
  // is already loaded (same file, by canonical path or by dlopen handle) returns it again.
  const PluginLibrary& load(const std::string& file);

  // Registers a plugin linked into the host: the same handshake and checks as load(),
  // without dlopen. `origin` names it in messages and in path() ("builtin:<origin>").
  const PluginLibrary& loadBuiltin(const std::string& origin, pronk_plugin_query_fn query);

  // Loads each entry in order: a file is loaded; a directory is scanned (not
  // recursively, sorted by name) for files named *.so. A library whose file name was
  // already loaded from an earlier entry is skipped, so earlier entries shadow later ones
  // (a build tree's plugin before an installed copy). An entry that does not exist is an
  // error: pass searchPath()'s result, which leaves out missing default directories. A
  // library named as an entry that cannot be loaded is an error; one found in a
  // directory is skipped (skipped()), so that it stops only what needs it.
  void loadSearchPath(const std::vector<std::string>& entries);

  // Libraries of a searched directory that could not be loaded, with the reason.
  struct Skipped {
    std::string path;
    std::string reason;
  };
  const std::vector<Skipped>& skipped() const { return skipped_; }
  // "; not loaded: PATH (REASON), ..." for messages about a factory not found; "" when none.
  std::string skippedNote() const;

  // The plugin search path, highest precedence first: `explicit_entries` (from --plugin,
  // files or directories), then each non-empty entry of the colon-separated
  // PRONK_PLUGIN_PATH, then those of defaultDirectories() that exist.
  static std::vector<std::string> searchPath(const std::vector<std::string>& explicit_entries);

  // <directory of /proc/self/exe>/../lib/pronk/plugins, then the install directory
  // (<prefix>/lib/pronk/plugins), whether they exist or not, duplicates removed.
  static std::vector<std::string> defaultDirectories();

  // The registered factory of this kind and name, or nullptr.
  const pronk_factory* find(pronk_factory_kind kind, const std::string& name) const;
  // The library a factory returned by find() or PluginLibrary::factories() came from.
  const PluginLibrary* libraryOf(const pronk_factory* factory) const;
  // Loaded libraries in load order.
  std::vector<const PluginLibrary*> libraries() const;

 private:
  // Runs the handshake with a plugin's entry point and checks and copies its manifest.
  static std::unique_ptr<PluginLibrary> handshake(const std::string& path, pronk_plugin_query_fn query);
  // Registers a checked library unless one of its names is taken.
  const PluginLibrary& add(std::unique_ptr<PluginLibrary> library);

  std::vector<std::unique_ptr<PluginLibrary>> libraries_;
  std::vector<Skipped> skipped_;
};

// "controller" / "environment" / "kind <n>".
std::string factoryKindName(uint32_t kind);

// From here on, a fatal signal or exit() inside a plugin call names the plugin,
// the factory and the call before the process ends (main() calls it once).
void reportPluginCrashes();

// Parameters resolved against a factory's schema: every declared parameter, in
// declaration order, with defaults filled in. Owns its strings; data() stays
// valid as long as the object (copies and moves included) lives.
class ResolvedParams {
 public:
  ResolvedParams();
  ResolvedParams(const ResolvedParams& other);
  ResolvedParams(ResolvedParams&& other) noexcept;
  ResolvedParams& operator=(ResolvedParams other) noexcept;
  ~ResolvedParams();

  const pronk_param_value* data() const;
  int32_t size() const;
  // The value of a parameter, or nullptr when the factory declares no such name.
  const std::string* find(const std::string& name) const;

  // Appends a name and value (used by resolveParams).
  void add(const std::string& name, const std::string& value);

 private:
  struct Storage;
  std::unique_ptr<Storage> storage_;
};

// Why `text` is not a valid value for `decl` ("" when it is): a number that does not
// parse, an integer with a fraction, a value outside [min, max] (with the unit), a
// vector of the wrong length.
std::string checkParamValue(const pronk_param_decl& decl, const std::string& text);

// A platform property a parameter may default to (ABI 1.5,
// pronk_param_decl::platform_default), as text, with where the platform gives it.
struct PlatformValue {
  std::string text;
  SourceLocation where;
};
// The properties this host knows ("stance", "kp", "kd"), in that order.
const std::vector<std::string>& platformPropertyNames();
// The parameter type each property has (PRONK_PARAM_VECTOR for "stance", REAL else).
uint32_t platformPropertyType(const std::string& name);
// The platform's value of a property; nullopt when the platform does not give it
// (a stance given joint by joint instead of per leg).
std::optional<PlatformValue> platformValue(const PlatformSpec& platform, const std::string& name);

// Checks scenario settings against a factory's declared parameters and fills in the
// defaults: the platform's value for a parameter that declares a platform_default
// (when `platform` is given and has it), else the declared default. Throws
// InputError at the setting's location for an unknown name (listing the known ones),
// a value checkParamValue() rejects, or a name set twice; at the platform's for a
// platform value the parameter does not accept; at `owner` for a required parameter
// that is missing.
ResolvedParams resolveParams(const pronk_factory& factory, const std::vector<ParamSetting>& settings,
                             const SourceLocation& owner, const PlatformSpec* platform = nullptr);

// A controller instance: create() in the constructor, destroy() in the destructor.
// `host` must outlive the instance. Failures throw Error naming the factory, the
// library (`origin`, usually PluginLibrary::path()) and the plugin's message.
class ControllerInstance {
 public:
  ControllerInstance(const pronk_factory& factory, const std::string& origin, const pronk_host_api& host,
                     const ResolvedParams& params);
  ~ControllerInstance();
  ControllerInstance(const ControllerInstance&) = delete;
  ControllerInstance& operator=(const ControllerInstance&) = delete;

  void reset(const pronk_robot_state& state);
  // Writes joint_count torques, N m.
  void compute(const pronk_robot_state& state, double* torque);
  const pronk_factory& factory() const { return factory_; }

 private:
  std::string describe() const;
  const pronk_factory& factory_;
  std::string origin_;
  void* instance_ = nullptr;
};

// An environment instance (one action per episode), same conventions as
// ControllerInstance.
class EnvironmentInstance {
 public:
  EnvironmentInstance(const pronk_factory& factory, const std::string& origin, const pronk_host_api& host,
                      const ResolvedParams& params);
  ~EnvironmentInstance();
  EnvironmentInstance(const EnvironmentInstance&) = delete;
  EnvironmentInstance& operator=(const EnvironmentInstance&) = delete;

  // Starts an episode; returns the observation (observation_size numbers).
  // `state` must stay valid until act() for retask().
  std::vector<double> reset(const std::vector<double>& task, uint64_t seed, const pronk_robot_state& state);
  // Starts the episode again with another task, from the last reset's state and
  // seed (before act(): nothing has moved); returns its observation. An aim
  // correction gives the environment the aim as its task, so that the task's
  // own frame (the jump environment's jump plane) is the aim's.
  std::vector<double> retask(const std::vector<double>& task);
  // The episode's action; its length must be the factory's action_size. Returns
  // the environment's reason when it rejects the action (PRONK_REJECTED: the
  // episode must not run), std::nullopt when the action was taken.
  std::optional<std::string> act(const std::vector<double>& action);
  // The environment's own analytic policy (ABI 1.1 prior_action), if it has one.
  bool hasPriorAction() const;
  // Its action for an observation; throws Error when there is none or it fails.
  std::vector<double> priorAction(const std::vector<double>& observation);
  // The same with the environment's verdict (ABI 1.4): `infeasible` holds its
  // reason when it expects act() to refuse the action (its best try).
  struct PriorAction {
    std::vector<double> action;
    std::optional<std::string> infeasible;
  };
  PriorAction prior(const std::vector<double>& observation);
  // One control tick; returns true when the environment ends the episode early.
  bool step(const pronk_robot_state& state, double* torque);
  // The episode's reward.
  double finish(const pronk_robot_state& state);
  const pronk_factory& factory() const { return factory_; }

 private:
  std::string describe() const;
  const pronk_factory& factory_;
  std::string origin_;
  void* instance_ = nullptr;
  uint64_t reset_seed_ = 0;
  const pronk_robot_state* reset_state_ = nullptr;  // the last reset's, until act()
};

}  // namespace pronk
