// The house's arrows point down only (docs/architecture.md): apps -> render ->
// host libraries -> plugin/sdk. Each rule reads the quoted #include lines of
// the tree, so a new file that breaks one fails here with its name and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kSource = PRONK_SOURCE_DIR;

struct Include {
  std::string file;  // relative to the source tree
  int line = 0;
  std::string header;
};

// Every `#include "..."` of the C and C++ files under `folder`.
std::vector<Include> includesUnder(const std::string& folder) {
  static const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<Include> out;
  for (const auto& entry : fs::recursive_directory_iterator(kSource / folder)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp" && ext != ".c")) continue;
    std::ifstream in(entry.path());
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
      std::smatch m;
      if (std::regex_search(text, m, quoted)) {
        out.push_back({fs::relative(entry.path(), kSource).string(), line, m[1]});
      }
    }
  }
  return out;
}

std::string where(const Include& i) { return i.file + ":" + std::to_string(i.line) + ": \"" + i.header + "\""; }

TEST(IncludeRules, HostLibrariesIncludeNeitherRenderNorApps) {
  const std::vector<Include> includes = includesUnder("host");
  ASSERT_FALSE(includes.empty());
  for (const Include& i : includes) {
    // A host file includes pronk's public headers or its own module's files.
    const bool public_header = i.header.rfind("pronk/", 0) == 0;
    const bool own_file = fs::exists(kSource / fs::path(i.file).parent_path() / i.header);
    EXPECT_TRUE(public_header || own_file) << where(i);
    EXPECT_NE(i.header.rfind("render/", 0), 0u) << where(i);
    EXPECT_FALSE(fs::exists(kSource / "apps" / "pronk" / i.header) && !public_header && !own_file) << where(i);
  }
}

TEST(IncludeRules, PluginsSeeOnlyThePluginAbiHeader) {
  const std::vector<Include> includes = includesUnder("plugin");
  ASSERT_FALSE(includes.empty());
  for (const Include& i : includes) {
    if (i.header.rfind("pronk/", 0) == 0) {
      EXPECT_EQ(i.header, "pronk/plugin_abi.h") << where(i);
      continue;
    }
    // Otherwise a file of the plugin itself, by a path from the plugin's folder
    // or from the including file's.
    const fs::path dir = fs::path(i.file).parent_path();
    bool inside = false;
    for (fs::path base = dir; !base.empty() && base != "plugin"; base = base.parent_path()) {
      inside = inside || fs::exists(kSource / base / i.header);
    }
    EXPECT_TRUE(inside) << where(i);
  }
}

TEST(IncludeRules, TheJumpPluginsLayersPointDown) {
  // plugin/guided_jump: abi/ (the C callbacks, the host view, the declaration
  // tables) -> environment/ (the RL environment) -> control/ (the phase machine
  // and its phases) -> method/ (the paper's pipeline). No layer includes one
  // above it.
  const std::string root = "plugin/guided_jump/";
  const std::vector<std::string> layers = {"abi", "environment", "control", "method"};
  for (size_t layer = 1; layer < layers.size(); ++layer) {
    const std::vector<Include> includes = includesUnder(root + layers[layer]);
    ASSERT_FALSE(includes.empty()) << layers[layer];
    for (const Include& i : includes) {
      for (size_t above = 0; above < layer; ++above) {
        EXPECT_NE(i.header.rfind(layers[above] + "/", 0), 0u) << where(i);
      }
    }
  }
}

TEST(IncludeRules, RenderReadsTracesAndModelsNotTheSimulation) {
  // Video is made from traces: the renderer needs trace/ and model/ (robot
  // description, terrain) and the scenario's plain structs, never a World;
  // plots read an evaluation's rows (report/'s evaluation.h, no simulation types).
  const std::set<std::string> allowed = {"pronk/trace.h",    "pronk/robot_description.h", "pronk/terrain.h",
                                         "pronk/scenario.h", "pronk/error.h",             "pronk/schema.h",
                                         "pronk/file_io.h",  "pronk/evaluation.h"};
  for (const Include& i : includesUnder("render")) {
    if (i.header.rfind("pronk/", 0) == 0) EXPECT_TRUE(allowed.count(i.header)) << where(i);
  }
}

TEST(IncludeRules, OnlyTheAppsIncludeRender) {
  for (const std::string folder : {"host", "plugin"}) {
    for (const Include& i : includesUnder(folder)) EXPECT_NE(i.header.rfind("render/", 0), 0u) << where(i);
  }
}

}  // namespace
