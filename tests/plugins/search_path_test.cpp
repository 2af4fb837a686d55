// Where plugins are looked for: --plugin entries, then PRONK_PLUGIN_PATH, then
// the default directories; earlier entries shadow later ones.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>

#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class SearchPath : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* old = std::getenv("PRONK_PLUGIN_PATH")) old_env_ = old;
    root_ = fs::temp_directory_path() / ("pronk_search_path_" + std::to_string(getpid()));
    fs::create_directories(root_);
  }
  void TearDown() override {
    if (old_env_) {
      setenv("PRONK_PLUGIN_PATH", old_env_->c_str(), 1);
    } else {
      unsetenv("PRONK_PLUGIN_PATH");
    }
    if (created_default_) fs::remove_all(*created_default_);
    fs::remove_all(root_);
  }
  std::string dir(const std::string& name) {
    const fs::path p = root_ / name;
    fs::create_directories(p);
    return p.string();
  }
  static void copy(const char* from, const std::string& to) { fs::copy_file(from, to, fs::copy_options::overwrite_existing); }

  fs::path root_;
  std::optional<std::string> old_env_;
  std::optional<fs::path> created_default_;
};

TEST_F(SearchPath, DefaultDirectoriesAreBesideTheExecutableThenTheInstallPrefix) {
  const std::vector<std::string> defaults = PluginRegistry::defaultDirectories();
  ASSERT_GE(defaults.size(), 1u);
  ASSERT_LE(defaults.size(), 2u);
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  EXPECT_EQ(defaults[0].rfind(exe.parent_path().parent_path().string() + "/", 0), 0u) << defaults[0];
  for (const std::string& d : defaults) {
    EXPECT_TRUE(fs::path(d).is_absolute()) << d;
    EXPECT_THAT(d, ::testing::EndsWith("/pronk/plugins"));
  }
}

TEST_F(SearchPath, ExplicitEntriesComeBeforeTheEnvironmentBeforeTheDefaults) {
  // Make the executable-relative default directory exist for this test.
  const fs::path wanted = PluginRegistry::defaultDirectories().front();
  if (!fs::exists(wanted)) {
    fs::path top = wanted;
    while (!fs::exists(top.parent_path())) top = top.parent_path();
    fs::create_directories(wanted);
    created_default_ = top;
  }
  const std::string beside_exe = PluginRegistry::defaultDirectories().front();
  const std::string a = dir("a"), b = dir("b"), c = dir("c");
  setenv("PRONK_PLUGIN_PATH", (":" + b + "::" + c + ":").c_str(), 1);

  const std::vector<std::string> path = PluginRegistry::searchPath({a, "/explicit/file.so"});
  ASSERT_GE(path.size(), 5u);
  EXPECT_EQ(path[0], a);
  EXPECT_EQ(path[1], "/explicit/file.so");
  EXPECT_EQ(path[2], b);  // empty PRONK_PLUGIN_PATH entries are skipped
  EXPECT_EQ(path[3], c);
  EXPECT_EQ(path[4], beside_exe);
  for (size_t i = 5; i < path.size(); ++i) EXPECT_TRUE(fs::is_directory(path[i])) << path[i];
}

TEST_F(SearchPath, MissingDefaultDirectoriesAreLeftOut) {
  unsetenv("PRONK_PLUGIN_PATH");
  const std::vector<std::string> path = PluginRegistry::searchPath({});
  for (const std::string& p : path) EXPECT_TRUE(fs::is_directory(p)) << p;
}

TEST_F(SearchPath, DirectoriesAreScannedSortedForSharedObjectsAndEarlierEntriesShadowLater) {
  const std::string first = dir("first"), second = dir("second");
  copy(PRONK_FIXTURE_MINIMAL, first + "/libfixture.so");
  copy(PRONK_FIXTURE_MINIMAL, second + "/libfixture.so");  // same name: shadowed, not a duplicate
  copy(PRONK_FIXTURE_FAILING_CREATE, second + "/b_failing.so");
  copy(PRONK_FIXTURE_FUTURE_MINOR, second + "/a_future.so");
  copy(PRONK_FIXTURE_WRONG_MAJOR, second + "/c_wrong_major.so.1");  // not *.so: ignored
  std::ofstream(second + "/notes.txt") << "not a plugin\n";

  PluginRegistry registry;
  setenv("PRONK_PLUGIN_PATH", second.c_str(), 1);
  registry.loadSearchPath(PluginRegistry::searchPath({first}));

  std::vector<std::string> loaded;
  for (const PluginLibrary* lib : registry.libraries()) {
    if (lib->path().rfind(root_.string(), 0) == 0) loaded.push_back(lib->path());  // not an installed pronk's
  }
  EXPECT_THAT(loaded, ::testing::ElementsAre(first + "/libfixture.so", second + "/a_future.so", second + "/b_failing.so"));
}

TEST_F(SearchPath, AFileEntryIsLoaded) {
  PluginRegistry registry;
  registry.loadSearchPath({PRONK_FIXTURE_MINIMAL});
  EXPECT_NE(registry.find(PRONK_FACTORY_CONTROLLER, "fixture_hold"), nullptr);
}

TEST_F(SearchPath, MissingExplicitEntryIsAnError) {
  PluginRegistry registry;
  try {
    registry.loadSearchPath({"/nonexistent/plugins"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'/nonexistent/plugins' does not exist"));
  }
}

}  // namespace
}  // namespace pronk
