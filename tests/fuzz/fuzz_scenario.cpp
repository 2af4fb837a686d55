// libFuzzer target: the bytes as a scenario file -> pronk::loadScenario (or
// loadScenarioPart for a <scenario_part>, as `pronk validate` does), then each
// case of the targets and of every sweep applied, as validate does, for sweeps
// of at most kMaxCases cases (a legal sweep may hold 100 000). The reader takes a path and follows <include file> and
// <platform urdf> relative to it, so the input is written to a file in a
// per-process sandbox whose links make the paths of the project's scenarios
// (scenarios/*/) and test fixtures (tests/scenario/broken/) resolve. A
// pronk::Error is the expected refusal; any other exception escapes and
// counts as a finding.
#include <stdlib.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "pronk/error.h"
#include "pronk/scenario.h"

namespace {

namespace fs = std::filesystem;

constexpr double kMaxCases = 1000;
// A Go1-sized footprint for the step platforms (no robot is loaded here).
const pronk::Footprint kFootprint{{{0.2, -0.12, -0.3}, {0.2, 0.12, -0.3}, {-0.2, -0.12, -0.3}, {-0.2, 0.12, -0.3}}};

fs::path g_sandbox;
std::string g_input;

void removeSandbox() {
  std::error_code ec;
  fs::remove_all(g_sandbox, ec);  // removes the links, not what they point at
}

void link(const fs::path& target, const fs::path& at) {
  fs::create_directories(at.parent_path());
  fs::create_symlink(target, at);
}

// SANDBOX/t/s/b/input.xml is the input. From there "../platforms/go1.xml",
// "../parts/jump.xml" and "../../assets/..." (a shipped scenario's paths), "parts/platform.xml",
// "../data/tiny_robot.urdf" and "../../../scenarios/..." (a fixture's) all
// reach the project's files.
void makeSandbox() {
  const fs::path source = PRONK_SOURCE_DIR;
  std::string dir = (fs::temp_directory_path() / "pronk-fuzz-scenario.XXXXXX").string();
  if (!mkdtemp(dir.data())) {
    std::perror("fuzz_scenario: mkdtemp");
    std::abort();
  }
  g_sandbox = dir;
  std::atexit(removeSandbox);
  const fs::path s = g_sandbox / "t" / "s";
  link(source / "scenarios", g_sandbox / "scenarios");
  link(source / "assets", g_sandbox / "assets");
  link(source / "assets", g_sandbox / "t" / "assets");
  for (const char* d : {"platforms", "parts", "go1", "aliengo", "eval", "train"}) link(source / "scenarios" / d, s / d);
  link(source / "tests" / "scenario" / "data", s / "data");
  link(source / "tests" / "scenario" / "broken" / "parts", s / "b" / "parts");
  link(source / "scenarios" / "go1" / "jump_environment.xml", s / "b" / "jump_environment.xml");
  g_input = (s / "b" / "input.xml").string();
}

// The cases sweepCases would return, without making them.
double caseCount(const pronk::Scenario& scenario, const pronk::SweepSpec& sweep) {
  double n = 1;
  switch (sweep.kind) {
    case pronk::SweepSpec::Kind::Grid:
      for (const pronk::SweepAxis& axis : sweep.axes) n *= static_cast<double>(axis.values.size());
      break;
    case pronk::SweepSpec::Kind::Random: n = sweep.count; break;
    case pronk::SweepSpec::Kind::Vary: n = sweep.axes.empty() ? 0 : static_cast<double>(sweep.axes.front().values.size()); break;
  }
  return n * static_cast<double>(std::max<std::size_t>(1, scenario.targets.size()));  // a sweep may run every target
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  makeSandbox();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(g_input, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
      std::perror("fuzz_scenario: cannot write the input file");
      std::abort();
    }
  }
  try {
    if (pronk::isScenarioPart(g_input)) {
      pronk::loadScenarioPart(g_input);
    } else {
      const pronk::Scenario scenario = pronk::loadScenario(g_input);
      for (const pronk::EpisodeCase& c : pronk::targetCases(scenario)) pronk::applyCase(scenario, c, kFootprint);
      for (const pronk::SweepSpec& sweep : scenario.sweeps) {
        if (caseCount(scenario, sweep) > kMaxCases) continue;
        for (const pronk::EpisodeCase& c : pronk::sweepCases(scenario, sweep.name)) pronk::applyCase(scenario, c, kFootprint);
      }
    }
  } catch (const pronk::Error&) {
  }
  return 0;
}
