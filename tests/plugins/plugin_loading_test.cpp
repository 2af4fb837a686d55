// Loading plugin libraries: the handshake, the checks of what a plugin declares,
// duplicate names, and the real guided_jump plugin.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "fake_robot.h"
#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

using ::testing::HasSubstr;

// Runs `load` expecting an Error; returns its message.
template <class F>
std::string errorOf(F&& load) {
  try {
    load();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return "";
}

const pronk_param_decl* paramOf(const pronk_factory& f, const char* name) {
  for (int32_t i = 0; i < f.param_count; ++i) {
    if (std::strcmp(f.params[i].name, name) == 0) return &f.params[i];
  }
  return nullptr;
}

TEST(PluginLoading, GuidedJumpPluginListsItsTwoFactories) {
  PluginRegistry registry;
  const PluginLibrary& lib = registry.load(PRONK_GUIDED_JUMP_PLUGIN);
  EXPECT_EQ(lib.name(), "pronk_guided_jump");
  EXPECT_EQ(lib.version(), PRONK_PROJECT_VERSION);
  EXPECT_EQ(lib.abi_version(), PRONK_ABI_VERSION(PRONK_ABI_MAJOR, PRONK_ABI_MINOR));
  ASSERT_EQ(lib.factories().size(), 2u);

  const pronk_factory* controller = registry.find(PRONK_FACTORY_CONTROLLER, "guided_jump");
  ASSERT_NE(controller, nullptr);
  EXPECT_EQ(controller->joint_count, 0);
  EXPECT_DOUBLE_EQ(controller->control_period, 0.001);
  ASSERT_NE(controller->controller, nullptr);
  EXPECT_EQ(registry.libraryOf(controller), &lib);
  const pronk_param_decl* kp = paramOf(*controller, "kp");
  ASSERT_NE(kp, nullptr);
  EXPECT_EQ(kp->type, static_cast<uint32_t>(PRONK_PARAM_REAL));
  EXPECT_STREQ(kp->default_value, "100");
  EXPECT_STREQ(kp->unit, "N m/rad");
  EXPECT_DOUBLE_EQ(kp->min_value, 0);
  EXPECT_DOUBLE_EQ(kp->max_value, 1000);
  ASSERT_NE(paramOf(*controller, "kd"), nullptr);
  EXPECT_STREQ(paramOf(*controller, "kd")->default_value, "2");
  const pronk_param_decl* stance = paramOf(*controller, "stance");
  ASSERT_NE(stance, nullptr);
  EXPECT_EQ(stance->type, static_cast<uint32_t>(PRONK_PARAM_VECTOR));
  EXPECT_EQ(stance->vector_size, 3u);
  EXPECT_STREQ(stance->default_value, "0 0.75 -1.5");
  const pronk_param_decl* motor = paramOf(*controller, "motor");
  ASSERT_NE(motor, nullptr);
  EXPECT_EQ(motor->type, static_cast<uint32_t>(PRONK_PARAM_STRING));
  EXPECT_STREQ(motor->default_value, "effort");

  const pronk_factory* env = registry.find(PRONK_FACTORY_ENVIRONMENT, "jump");
  ASSERT_NE(env, nullptr);
  EXPECT_EQ(env->observation_size, 6);
  EXPECT_EQ(env->action_size, 13);
  ASSERT_NE(env->environment, nullptr);
  EXPECT_NE(paramOf(*env, "duration"), nullptr);
  EXPECT_NE(paramOf(*env, "kp"), nullptr);

  // Kinds are separate name spaces.
  EXPECT_EQ(registry.find(PRONK_FACTORY_ENVIRONMENT, "guided_jump"), nullptr);
  EXPECT_EQ(registry.find(PRONK_FACTORY_CONTROLLER, "jump"), nullptr);
}

TEST(PluginLoading, GuidedJumpExportsOnlyTheEntryPoint) {
  const std::string command = std::string("nm -D --defined-only '") + PRONK_GUIDED_JUMP_PLUGIN + "' 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) GTEST_SKIP() << "cannot run nm";
  std::vector<std::string> symbols;
  char line[512];
  while (std::fgets(line, sizeof line, pipe.get())) {
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const size_t space = s.rfind(' ');
    if (space != std::string::npos) symbols.push_back(s.substr(space + 1));
  }
  if (symbols.empty()) GTEST_SKIP() << "nm printed nothing (not installed?)";
  for (const std::string& s : symbols) {
    EXPECT_EQ(s, PRONK_PLUGIN_ENTRY_NAME) << "exported symbol " << s;
  }
}

TEST(PluginLoading, MissingFileQuotesDlerror) {
  PluginRegistry registry;
  const std::string msg = errorOf([&] { registry.load("/nonexistent/libnothing.so"); });
  EXPECT_THAT(msg, HasSubstr("/nonexistent/libnothing.so"));
  EXPECT_THAT(msg, HasSubstr("cannot open shared object file"));
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoading, WrongMajorIsRejectedNamingBothVersions) {
  PluginRegistry registry;
  const std::string msg = errorOf([&] { registry.load(PRONK_FIXTURE_WRONG_MAJOR); });
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_WRONG_MAJOR));
  EXPECT_THAT(msg, HasSubstr("rejected this host's ABI version 1." + std::to_string(PRONK_ABI_MINOR)));
  EXPECT_THAT(msg, HasSubstr("fixture_wrong_major speaks ABI 2.x"));  // the plugin's own message
  EXPECT_THAT(msg, HasSubstr("the plugin speaks ABI 2.0"));
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoading, MissingEntryPointNamesTheSymbol) {
  PluginRegistry registry;
  const std::string msg = errorOf([&] { registry.load(PRONK_FIXTURE_NO_ENTRY); });
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_NO_ENTRY));
  EXPECT_THAT(msg, HasSubstr("pronk_plugin_query"));
  EXPECT_THAT(msg, HasSubstr("undefined symbol"));  // dlerror()'s text
}

TEST(PluginLoading, DuplicateNameInOneLibraryIsRejected) {
  PluginRegistry registry;
  const std::string msg = errorOf([&] { registry.load(PRONK_FIXTURE_DUPLICATE_IN_ONE); });
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_DUPLICATE_IN_ONE));
  EXPECT_THAT(msg, HasSubstr("declares controller 'twin' twice"));
  EXPECT_EQ(registry.find(PRONK_FACTORY_CONTROLLER, "twin"), nullptr);
}

TEST(PluginLoading, DuplicateNameAcrossLibrariesNamesBoth) {
  PluginRegistry registry;
  registry.load(PRONK_FIXTURE_MINIMAL);
  const std::string msg = errorOf([&] { registry.load(PRONK_FIXTURE_DUPLICATE_ACROSS); });
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_DUPLICATE_ACROSS));
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_MINIMAL));
  EXPECT_THAT(msg, HasSubstr("controller 'fixture_hold' is already registered"));
  // The first registration stands; the second library was not kept.
  ASSERT_EQ(registry.libraries().size(), 1u);
  EXPECT_EQ(registry.libraryOf(registry.find(PRONK_FACTORY_CONTROLLER, "fixture_hold"))->name(), "fixture_minimal");
}

TEST(PluginLoading, SamePathTwiceIsANoOp) {
  PluginRegistry registry;
  const PluginLibrary& a = registry.load(PRONK_FIXTURE_MINIMAL);
  const PluginLibrary& b = registry.load(std::string(PRONK_FIXTURE_MINIMAL));
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(registry.libraries().size(), 1u);
}

TEST(PluginLoading, FailingCreateSurfacesThePluginsMessage) {
  PluginRegistry registry;
  const PluginLibrary& lib = registry.load(PRONK_FIXTURE_FAILING_CREATE);
  const pronk_factory* f = registry.find(PRONK_FACTORY_CONTROLLER, "fixture_failing");
  ASSERT_NE(f, nullptr);
  test::FakeRobot robot;
  const std::string msg = errorOf([&] { ControllerInstance c(*f, lib.path(), robot.api(), ResolvedParams()); });
  EXPECT_THAT(msg, HasSubstr("controller 'fixture_failing'"));
  EXPECT_THAT(msg, HasSubstr(PRONK_FIXTURE_FAILING_CREATE));
  EXPECT_THAT(msg, HasSubstr("fixture: this robot has no tail to balance with"));
}

TEST(PluginLoading, HigherMinorPluginNegotiatesDownToTheHosts) {
  PluginRegistry registry;
  const PluginLibrary& lib = registry.load(PRONK_FIXTURE_FUTURE_MINOR);
  EXPECT_EQ(lib.abi_version(), PRONK_ABI_VERSION(PRONK_ABI_MAJOR, PRONK_ABI_MINOR));
  // Its structs are larger than this host's: the host reads the known part and
  // steps through the parameter array by the plugin's struct size.
  const pronk_factory* f = registry.find(PRONK_FACTORY_CONTROLLER, "fixture_future");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->struct_size, sizeof(pronk_factory));
  ASSERT_EQ(f->param_count, 2);
  EXPECT_STREQ(f->params[0].name, "first");
  EXPECT_STREQ(f->params[1].name, "second");
  EXPECT_STREQ(f->params[1].default_value, "3");
  EXPECT_EQ(f->params[1].struct_size, sizeof(pronk_param_decl));
}

TEST(PluginLoading, AnswerAboveTheHostsMinorIsRejected) {
  PluginRegistry registry;
  const std::string msg = errorOf([&] { registry.load(PRONK_FIXTURE_MINOR_ABOVE_HOST); });
  EXPECT_THAT(msg, HasSubstr("answered ABI version 1.9 to this host's 1." + std::to_string(PRONK_ABI_MINOR)));
}

TEST(PluginLoading, BuiltinPluginGoesThroughTheSameChecks) {
  PluginRegistry registry;
  const PluginLibrary& builtin = registry.loadBuiltin("test", [](uint32_t host, pronk_plugin_manifest* m, char*, size_t) {
    m->abi_version = host;
    m->plugin_name = "builtin_test";
    m->plugin_version = "1";
    m->factory_count = 0;
    return PRONK_OK;
  });
  EXPECT_EQ(builtin.path(), "builtin:test");
  EXPECT_EQ(builtin.name(), "builtin_test");
  const std::string msg = errorOf([&] {
    registry.loadBuiltin("nameless", [](uint32_t host, pronk_plugin_manifest* m, char*, size_t) {
      m->abi_version = host;
      return PRONK_OK;
    });
  });
  EXPECT_THAT(msg, HasSubstr("builtin:nameless"));
  EXPECT_THAT(msg, HasSubstr("no plugin name"));
}

// Factory descriptors a plugin can get wrong, each checked at load time.
pronk_status noCreate(const pronk_host_api*, const pronk_param_value*, int32_t, void**, char*, size_t) {
  return PRONK_ERROR_FAILED;
}
pronk_status noCompute(void*, const pronk_robot_state*, double*, char*, size_t) { return PRONK_ERROR_FAILED; }
void noDestroy(void*) {}
const pronk_controller_ops kOps = {sizeof(pronk_controller_ops), nullptr, noCompute, noDestroy};
const pronk_controller_ops kOpsWithoutCompute = {sizeof(pronk_controller_ops), nullptr, nullptr, noDestroy};
const pronk_param_decl kBadDefault[] = {
    {sizeof(pronk_param_decl), "gain", PRONK_PARAM_REAL, 0, 0.0, 1.0, 0, "7", "", ""}};
// ABI 1.5: a platform default the host does not know, and one of the wrong type.
const pronk_param_decl kUnknownPlatformDefault[] = {
    {sizeof(pronk_param_decl), "gain", PRONK_PARAM_REAL, 0, 0.0, 1.0, 0, "1", "", "", "mass"}};
const pronk_param_decl kMistypedPlatformDefault[] = {
    {sizeof(pronk_param_decl), "pose", PRONK_PARAM_REAL, 0, -1.0, 1.0, 0, "0", "", "", "stance"}};
// An environment with two task numbers and a mirror that is not +-1.
pronk_status noReset(void*, const double*, int32_t, uint64_t, const pronk_robot_state*, double*, char*, size_t) {
  return PRONK_ERROR_FAILED;
}
pronk_status noAct(void*, const double*, char*, size_t) { return PRONK_ERROR_FAILED; }
pronk_status noStep(void*, const pronk_robot_state*, double*, int32_t*, char*, size_t) { return PRONK_ERROR_FAILED; }
pronk_status noFinish(void*, const pronk_robot_state*, double*, char*, size_t) { return PRONK_ERROR_FAILED; }
const pronk_environment_ops kEnvOps = {sizeof(pronk_environment_ops), noReset, noAct, noStep, noFinish, noDestroy};
const char* const kTwoTasks[] = {"x", "y"};
const double kBadMirror[] = {1.0, 0.5};

pronk_factory controllerNamed(const char* name) {
  return {sizeof(pronk_factory), PRONK_FACTORY_CONTROLLER, name, "", 0, nullptr, 0, 0, 0, 0.0, noCreate, &kOps, nullptr, 0, nullptr, nullptr, 0, 0, nullptr};
}

const pronk_factory* g_factory = nullptr;  // what the test plugin below declares
pronk_status declareOne(uint32_t host, pronk_plugin_manifest* m, char*, size_t) {
  m->abi_version = host;
  m->plugin_name = "bad";
  m->plugin_version = "1";
  m->factory_count = 1;
  m->factories = &g_factory;
  return PRONK_OK;
}

std::string loadError(const pronk_factory& f) {
  g_factory = &f;
  PluginRegistry registry;
  return errorOf([&] { registry.loadBuiltin("bad", declareOne); });
}

TEST(PluginLoading, FactoryDeclarationsAreChecked) {
  EXPECT_THAT(loadError(controllerNamed("Bad-Name")), HasSubstr("named 'Bad-Name', not [a-z0-9_]+"));
  EXPECT_THAT(loadError(controllerNamed("")), HasSubstr("not [a-z0-9_]+"));

  pronk_factory small = controllerNamed("small");
  small.struct_size = 8;
  EXPECT_THAT(loadError(small), HasSubstr("struct_size 8"));

  pronk_factory kindless = controllerNamed("kindless");
  kindless.kind = 7;
  EXPECT_THAT(loadError(kindless), HasSubstr("unknown kind 7"));

  pronk_factory no_compute = controllerNamed("no_compute");
  no_compute.controller = &kOpsWithoutCompute;
  EXPECT_THAT(loadError(no_compute), HasSubstr("controller 'no_compute' has no compute()"));

  pronk_factory env = controllerNamed("env");
  env.kind = PRONK_FACTORY_ENVIRONMENT;
  EXPECT_THAT(loadError(env), HasSubstr("environment 'env' has no environment operations"));

  pronk_factory bad_default = controllerNamed("bad_default");
  bad_default.param_count = 1;
  bad_default.params = kBadDefault;
  EXPECT_THAT(loadError(bad_default), HasSubstr("parameter 'gain' has an invalid default: 7 is out of range [0, 1]"));

  pronk_factory unknown_platform = controllerNamed("unknown_platform");
  unknown_platform.param_count = 1;
  unknown_platform.params = kUnknownPlatformDefault;
  EXPECT_THAT(loadError(unknown_platform), HasSubstr("defaults to the platform's 'mass', not one of stance, kp, kd"));
  pronk_factory mistyped_platform = controllerNamed("mistyped_platform");
  mistyped_platform.param_count = 1;
  mistyped_platform.params = kMistypedPlatformDefault;
  EXPECT_THAT(loadError(mistyped_platform), HasSubstr("defaults to the platform's 'stance' but is not of its type"));

  pronk_factory mirror = controllerNamed("mirror");
  mirror.kind = PRONK_FACTORY_ENVIRONMENT;
  mirror.controller = nullptr;
  mirror.environment = &kEnvOps;
  mirror.observation_size = 2;
  mirror.action_size = 1;
  mirror.task_names = kTwoTasks;
  mirror.task_size = 2;
  mirror.task_mirror = kBadMirror;
  EXPECT_THAT(loadError(mirror), HasSubstr("environment 'mirror', task_mirror[1] is 0.500000, not +1 or -1"));
}

}  // namespace
}  // namespace pronk

namespace pronk {
namespace {

TEST(PluginLoading, TheDocumentedExamplePluginLoadsAndDamps) {
  PluginRegistry registry;
  const PluginLibrary& lib = registry.load(PRONK_FIXTURE_DAMPER);
  const pronk_factory* f = registry.find(PRONK_FACTORY_CONTROLLER, "damper");
  ASSERT_NE(f, nullptr);
  test::FakeRobot robot;
  ControllerInstance c(*f, lib.path(), robot.api(), resolveParams(*f, {{"c", "4", {}}}, {}));
  for (int j = 0; j < robot.jointCount(); ++j) robot.qd()[j] = 0.5 * j;
  std::vector<double> tau(robot.jointCount());
  c.compute(robot.state(), tau.data());
  for (int j = 0; j < robot.jointCount(); ++j) EXPECT_DOUBLE_EQ(tau[j], -4 * 0.5 * j);
}

}  // namespace
TEST(PluginLoading, AnAbi12EnvironmentLoadsWithoutDeclarations) {
  // Its factory's struct_size ends before the 1.3 fields, which hold garbage:
  // the host reads none of them and the environment has an empty schema.
  PluginRegistry registry;
  const PluginLibrary& lib = registry.load(PRONK_FIXTURE_ABI_1_2);
  EXPECT_EQ(lib.abi_version(), PRONK_ABI_VERSION(1, 2));
  const pronk_factory* f = registry.find(PRONK_FACTORY_ENVIRONMENT, "fixture_env_1_2");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->metric_count, 0);
  EXPECT_EQ(f->marker_count, 0);
  EXPECT_EQ(f->task_size, 0);
  const EnvironmentSchema schema = environmentSchema(*f);
  EXPECT_TRUE(schema.metrics.empty());
  EXPECT_TRUE(schema.markers.empty());
  EXPECT_TRUE(schema.task_names.empty());
}

}  // namespace pronk
