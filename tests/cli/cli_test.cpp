// Scenario tests through the `pronk` command: exit codes, printed errors and
// results.json, exactly as a user or a downstream CI sees them.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <sys/stat.h>
#include <sys/wait.h>

#include "pronk_command.h"

namespace {

using pronk_test::cliScenario;
using pronk_test::Outcome;
using pronk_test::pronk;
using pronk_test::source;

nlohmann::json runAndRead(const std::string& scenario, const std::string& name, int expected_status,
                          const std::string& extra = "") {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/" + name;
  std::filesystem::remove_all(dir);
  const Outcome o = pronk("run " + scenario + " --out " + dir + " " + extra);
  EXPECT_EQ(o.status, expected_status) << o.output;
  std::ifstream in(dir + "/results.json");
  EXPECT_TRUE(in.good()) << o.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/trace.csv"));
  nlohmann::json j;
  if (in) in >> j;
  return j;
}

TEST(Cli, ShippedScenariosValidate) {
  const Outcome o = pronk("validate " + source("scenarios/go1/stand.xml") + " " + source("scenarios/aliengo/stand.xml") +
                          " " + source("scenarios/go1/terrain_demo.xml") + " " + source("scenarios/go1/hop.xml") +
                          " " + source("scenarios/platforms/go1.xml") + " " + source("scenarios/platforms/aliengo.xml"));
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("part: go1"), std::string::npos) << o.output;
}

// The development samples of tests/dev/ (lab variants, failure sets, seeded
// samples): kept out of scenarios/, and valid.
TEST(Cli, DevelopmentSamplesValidate) {
  std::string files;
  int count = 0;
  for (const char* robot : {"go1", "aliengo"}) {
    for (const auto& entry : std::filesystem::directory_iterator(source(std::string("tests/dev/") + robot))) {
      if (entry.path().extension() != ".xml") continue;
      files += " " + entry.path().string();
      ++count;
    }
  }
  EXPECT_GE(count, 20);
  const Outcome o = pronk("validate" + files);
  EXPECT_EQ(o.status, 0) << o.output;
  for (const char* robot : {"go1", "aliengo"}) {
    for (const auto& entry : std::filesystem::directory_iterator(source(std::string("scenarios/") + robot))) {
      const std::string name = entry.path().filename().string();
      EXPECT_EQ(name.find("_dev"), std::string::npos) << "a development sample among the user scenarios: " << name;
      EXPECT_NE(name.rfind("dev_", 0), 0u) << "a development sample among the user scenarios: " << name;
    }
  }
}

TEST(Cli, Go1StandsWhereForwardKinematicsPutsIt) {
  const auto j = runAndRead(source("scenarios/go1/stand.xml"), "go1_stand", 0);
  EXPECT_FALSE(j.at("failed").get<bool>());
  // 2 * 0.213 * cos(0.75) + 0.02: the hip-to-foot height plus the foot radius.
  EXPECT_NEAR(j.at("end").at("trunk")[2].get<double>(), 0.3317, 2e-3);
  EXPECT_NEAR(j.at("end").at("trunk")[0].get<double>(), 0.0, 2e-3);
}

TEST(Cli, AliengoStands) {
  const auto j = runAndRead(source("scenarios/aliengo/stand.xml"), "aliengo_stand", 0);
  EXPECT_FALSE(j.at("failed").get<bool>());
  // 2 * 0.25 * cos(0.75) + 0.0265.
  EXPECT_NEAR(j.at("end").at("trunk")[2].get<double>(), 0.3923, 3e-3);
}

TEST(Cli, ScriptedHopLeavesTheGroundAndLands) {
  const auto j = runAndRead(cliScenario("go1_scripted_hop.xml"), "go1_hop", 0);
  EXPECT_FALSE(j.at("failed").get<bool>());
  double lift_off = -1, touchdown = -1;
  for (const auto& e : j.at("events")) {
    if (e.at("name") == "lift_off" && lift_off < 0) lift_off = e.at("time");
    if (e.at("name") == "touchdown" && touchdown < 0) touchdown = e.at("time");
  }
  ASSERT_GT(lift_off, 0.45);   // after the crouch
  ASSERT_GT(touchdown, lift_off + 0.1);
  EXPECT_NEAR(j.at("end").at("trunk")[2].get<double>(), 0.3317, 1e-2);  // standing again
}

TEST(Cli, RunWritesAVideoOfTheHop) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/hop_video";
  std::filesystem::remove_all(dir);
  const Outcome o = pronk("run " + source("scenarios/go1/hop.xml") + " --video " + dir +
                          "/hop.mp4 --size 320x240 --fps 20 --still 0.7");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/hop_t0.700.png")) << o.output;
  // 2.0 s at half speed and 20 fps.
  EXPECT_NE(o.output.find("80 frames"), std::string::npos) << o.output;
  EXPECT_GT(std::filesystem::file_size(dir + "/hop.mp4"), 1000u);
  EXPECT_EQ(pronk("run " + source("scenarios/go1/hop.xml") + " --video " + dir + "/x.mp4 --size 321x240").status, 3);
  // A regular file where a directory should be: the flag is refused before the simulation.
  const Outcome bad = pronk("run " + source("scenarios/go1/hop.xml") + " --video " + dir + "/hop.mp4/x.mp4");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find(dir + "/hop.mp4/x.mp4"), std::string::npos) << bad.output;
  EXPECT_EQ(bad.output.find("simulated"), std::string::npos) << bad.output;
}

// A jump scenario filmed by simulating it: its targets with --policy (or the
// file's <environment policy>); without one the error says what to give.
TEST(Cli, RenderSimulatesAJumpScenarioWithAPolicy) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/render_jump";
  std::filesystem::remove_all(dir);
  const Outcome o = pronk("render " + source("scenarios/go1/forward.xml") + " --policy ballistic -o " + dir +
                          "/forward.mp4 --size 320x240 --fps 10");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("1 landed"), std::string::npos) << o.output;
  EXPECT_GT(std::filesystem::file_size(dir + "/forward.mp4"), 1000u);
  const Outcome none = pronk("render " + source("scenarios/go1/forward.xml") + " -o " + dir + "/x.mp4");
  EXPECT_EQ(none.status, 3) << none.output;
  EXPECT_NE(none.output.find("give --policy ballistic or --policy FILE"), std::string::npos) << none.output;
}

TEST(Cli, RenderReplaysARecordedTraceWithoutSimulating) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/replay";
  std::filesystem::remove_all(dir);
  ASSERT_EQ(pronk("run " + source("scenarios/go1/hop.xml") + " --out " + dir).status, 0);
  const Outcome o = pronk("render " + source("scenarios/go1/hop.xml") + " -o " + dir + "/replay.mp4 --trace " + dir +
                          "/trace.csv --size 320x240 --fps 10");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("no simulation"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("40 frames"), std::string::npos) << o.output;  // 2 s at half speed, 10 fps
  // A damaged trace is an input error naming the file and line.
  std::ifstream in(dir + "/trace.csv");
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::ofstream(dir + "/bad.csv") << header << "\n" << row << "\n" << "0.1,abc\n";
  const Outcome bad = pronk("render " + source("scenarios/go1/hop.xml") + " -o " + dir + "/y.mp4 --trace " + dir +
                            "/bad.csv");
  EXPECT_EQ(bad.status, 3) << bad.output;
  EXPECT_NE(bad.output.find(dir + "/bad.csv:3:"), std::string::npos) << bad.output;
}

// A jump's trace replays with what its run's video showed: the phases its
// controller named and the markers its environment reported, from results.json
// beside the trace; a damaged results.json is named, not ignored.
TEST(Cli, RenderOfAJumpTraceTakesItsEventsAndMarkersFromItsResults) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/replay_jump";
  std::filesystem::remove_all(dir);
  const std::string scenario = source("scenarios/go1/forward.xml");
  ASSERT_EQ(pronk("run " + scenario + " --policy ballistic --trace --out " + dir).status, 0);
  const std::string render = "render " + scenario + " -o " + dir + "/replay.mp4 --size 320x240 --fps 10 --trace ";
  const Outcome o = pronk(render + dir + "/jump-000.csv");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("its jump's events and markers from results.json beside it"), std::string::npos) << o.output;
  // Elsewhere, without its results: the contacts alone.
  std::filesystem::create_directories(dir + "/alone");
  std::filesystem::copy_file(dir + "/jump-000.csv", dir + "/alone/jump-000.csv");
  const Outcome alone = pronk(render + dir + "/alone/jump-000.csv");
  ASSERT_EQ(alone.status, 0) << alone.output;
  EXPECT_NE(alone.output.find("phases from the foot contacts alone"), std::string::npos) << alone.output;
  std::ofstream(dir + "/results.json") << "{\"jumps\": [{\"trace\": \"jump-000.csv\"}]}";
  const Outcome damaged = pronk(render + dir + "/jump-000.csv");
  EXPECT_EQ(damaged.status, 3) << damaged.output;
  EXPECT_NE(damaged.output.find(dir + "/results.json"), std::string::npos) << damaged.output;
}

TEST(Cli, NonFootContactFailsTheRunWithStatus4) {
  const auto j = runAndRead(cliScenario("go1_fall.xml"), "go1_fall", 4);
  EXPECT_TRUE(j.at("failed").get<bool>());
  EXPECT_EQ(j.at("failure_reason"), "non_foot_contact");
  EXPECT_NE(j.at("failure_detail").get<std::string>().find("trunk"), std::string::npos);
}

TEST(Cli, PluginControllerRunsFromAScenario) {
  const auto j = runAndRead(cliScenario("go1_guided_hold.xml"), "go1_guided_hold", 0);
  EXPECT_FALSE(j.at("failed").get<bool>());
  EXPECT_EQ(j.at("controller"), "guided_jump");
  EXPECT_NEAR(j.at("end").at("trunk")[2].get<double>(), 0.3317, 3e-3);
}

TEST(Cli, BadPluginParameterNamesFileAndLine) {
  const Outcome o = pronk("validate " + cliScenario("go1_bad_param.xml"));
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(cliScenario("go1_bad_param.xml") + ":6:"), std::string::npos) << o.output;
}

TEST(Cli, BrokenScenarioIsAnInputError) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/broken.xml";
  std::ofstream(path) << "<scenario version=\"1\" name=\"b\">\n  <sim step=\"abc\"/>\n</scenario>\n";
  const Outcome o = pronk("run " + path);
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(path + ":2:"), std::string::npos) << o.output;
}

TEST(Cli, ControllerFromTheWrongPluginIsAnInputError) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/wrong_plugin.xml";
  std::ofstream(path) << "<scenario version=\"1\" name=\"w\">\n  <include file=\"" << source("scenarios/platforms/go1.xml")
                      << "\"/>\n  <controller name=\"guided_jump\" plugin=\"someone_else\"/>\n</scenario>\n";
  const Outcome o = pronk("validate " + path);
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(path + ":3:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("someone_else"), std::string::npos) << o.output;
}

TEST(Cli, UsageErrorsExitWith2) {
  EXPECT_EQ(pronk("run").status, 2);
  EXPECT_EQ(pronk("frobnicate").status, 2);
  // A mistyped command is named, with the one it is nearest.
  const Outcome typo = pronk("evl x.xml");
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.output.find("'evl' is not a command; did you mean 'pronk eval'?"), std::string::npos) << typo.output;
  EXPECT_EQ(pronk("run " + source("scenarios/go1/stand.xml") + " --duration -1").status, 2);
  EXPECT_EQ(pronk("--help").status, 0);
}

TEST(Cli, HelpShowsOneValueNamePerOptionAndTheSameJobsEverywhere) {
  for (const char* command : {"run", "render", "train", "eval", "check", "bench", "validate", "plot"}) {
    const Outcome o = pronk(std::string(command) + " --help");
    ASSERT_EQ(o.status, 0) << command << o.output;
    // CLI11's type and validator names run together ("TEXT:TEXT", "INT:INT in [...]")
    // and a negated flag's default ("--no-plots{false}") are not shown.
    EXPECT_FALSE(std::regex_search(o.output, std::regex(R"([A-Z]+:[A-Z{])"))) << command << o.output;
    EXPECT_EQ(o.output.find("{false}"), std::string::npos) << command << o.output;
    if (std::string(command) != "validate" && std::string(command) != "plot" && std::string(command) != "render") {
      EXPECT_NE(o.output.find("-j,--jobs INT in [1 - 1024]"), std::string::npos) << command << o.output;
    }
  }
  EXPECT_EQ(pronk("eval x.xml --jobs 0").status, 2);
}

TEST(Cli, MissingPluginPathIsAnInputError) {
  const Outcome o = pronk("--plugin /nonexistent/libnothing.so plugins");
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find("/nonexistent/libnothing.so"), std::string::npos) << o.output;
}

TEST(Cli, PluginsListsTheGuidedJumpFactories) {
  const Outcome o = pronk("plugins");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("guided_jump"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("jump"), std::string::npos);
  EXPECT_NE(o.output.find("ABI 1.6"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("declares 62 metrics (14 reward cost terms, 7 times), 6 task numbers, 2 video markers"),
            std::string::npos)
      << o.output;
  // Each parameter with its default, the range the host checks and its unit (docs/plugin-abi.md).
  EXPECT_TRUE(std::regex_search(o.output, std::regex(R"(param kp +default platform's kp +in \[0, 1000\] +\[N m/rad\])")))
      << o.output;
  EXPECT_TRUE(std::regex_search(o.output, std::regex(R"(param stance +default platform's stance )"))) << o.output;
  EXPECT_TRUE(std::regex_search(o.output, std::regex(R"(param workspace_z +default "" )"))) << o.output;
  EXPECT_TRUE(std::regex_search(o.output, std::regex(R"(param duration +default 1.5 +in \[0.01, 60\] +\[s\])")))
      << o.output;
}

TEST(Cli, TheManPageListsEveryCommandAndOptionAndRendersCleanly) {
  const Outcome o = pronk("man");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(o.output.rfind(".\\\" pronk(1)", 0), 0u) << o.output.substr(0, 200);
  EXPECT_NE(o.output.find(".TH PRONK 1"), std::string::npos);
  for (const char* command : {"plugins", "validate", "run", "render", "bench", "train", "eval", "check", "plot"}) {
    EXPECT_NE(o.output.find(std::string(".SS \\fBpronk ") + command + "\\fR"), std::string::npos) << command;
  }
  for (const char* option : {"\\fB\\-\\-seed\\fR \\fIUINT\\fR", "\\fB\\-\\-camera\\fR \\fI{side,follow,top,fixed}\\fR",
                             "\\fB\\-\\-resume\\fR", "\\fB\\-\\-junit\\fR"}) {
    EXPECT_NE(o.output.find(option), std::string::npos) << option;
  }
  // groff, where the machine has it, renders the page without a warning.
  if (std::system("command -v groff >/dev/null 2>&1") == 0) {
    const Outcome g = pronk("man | groff -man -Tutf8 -ww -z");
    EXPECT_EQ(g.status, 0);
    EXPECT_EQ(g.output, "") << g.output;
  }
}

TEST(Cli, TheBashCompletionCompletesCommandsOptionsAndChoices) {
  // The generated script, sourced into bash, asked as bash asks it on TAB.
  auto complete = [](const std::string& words, int cword) {
    const std::string script = std::string(PRONK_CLI_OUT_DIR) + "/pronk.bash";
    std::filesystem::create_directories(PRONK_CLI_OUT_DIR);
    EXPECT_EQ(pronk("completion bash > " + script).status, 0);
    return pronk_test::shell("bash -c 'source " + script + "; COMP_WORDS=(" + words +
                             "); COMP_CWORD=" + std::to_string(cword) + "; _pronk; echo \"${COMPREPLY[*]}\"'");
  };
  EXPECT_EQ(complete("pronk ru", 1).output, "run\n");
  EXPECT_EQ(complete("pronk run --se", 2).output, "--seed\n");
  EXPECT_EQ(complete("pronk run a.xml --camera f", 4).output, "follow fixed\n");
  EXPECT_EQ(complete("pronk eval a.xml --res", 3).output, "--resume\n");
  EXPECT_EQ(complete("pronk run a.xml --jobs ", 4).output, "\n");  // a number: nothing to offer
}

TEST(Cli, BenchRolloutPrintsEachLeverAndTheSpeedUp) {
  // A smoke run on a two-case sweep (the figures come from the region sweep,
  // docs/performance.md): every row and the last line's exact form.
  const Outcome o = pronk("bench --rollout --repeats 1 --jobs 2 --scenario " + cliScenario("go1_sweep.xml"));
  EXPECT_EQ(o.status, 0) << o.output;
  for (const char* row : {"one world per case, full episodes, traces", "+ the controller's exact leg IK",
                          "+ worlds reused", "+ episodes end at rest", "+ no trace (the engine, 1 thread)",
                          "the engine, 2 threads"}) {
    EXPECT_NE(o.output.find(row), std::string::npos) << row << "\n" << o.output;
  }
  const std::regex last(R"re(rollout speed-up: [0-9]+\.[0-9]{2}x \(2 threads\) over one world per case with full episodes and traces\n$)re");
  EXPECT_TRUE(std::regex_search(o.output, last)) << o.output;
}

TEST(Cli, BenchRunsTheConvergedReferenceThroughTheLanding) {
  // The reference's impact takes more steps in one control period than the
  // default step budget allows; cut short, it made every error column wrong
  // (51 mm instead of 1.6). The default setting lands within 5 mm of it.
  const Outcome o = pronk("bench --repeats 1");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(o.output.find("step_budget"), std::string::npos) << o.output;
  // The jump table's default row: | setting | wall/sim | x realtime | steps/sim s |
  // steps/wall s | trunk xy (mm) | CoM at td (mm) | t_lo | t_td | status |
  const std::string jump = o.output.substr(o.output.find("Jump with landing"));
  const size_t start = jump.find("| default:");
  ASSERT_NE(start, std::string::npos) << o.output;
  std::vector<std::string> cells;
  std::stringstream line(jump.substr(start + 1, jump.find('\n', start) - start - 1));
  for (std::string cell; std::getline(line, cell, '|');) cells.push_back(cell);
  ASSERT_EQ(cells.size(), 10u) << o.output;
  EXPECT_LT(std::stod(cells[5]), 5.0) << "trunk xy, mm\n" << o.output;
  EXPECT_LT(std::stod(cells[6]), 5.0) << "CoM at touchdown, mm\n" << o.output;
  EXPECT_NE(cells[9].find("ok"), std::string::npos) << o.output;
}

TEST(Cli, PipesDevicesAndEmptyDocumentsAreRefusedNotWaitedOn) {
  // A FIFO given as a scenario or a policy would block a reader forever, and
  // /dev/zero would fill the memory: both are refused by name, at once.
  const std::string fifo = std::string(PRONK_CLI_OUT_DIR) + "/fifo.xml";
  std::filesystem::create_directories(PRONK_CLI_OUT_DIR);
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Outcome scenario = pronk("validate " + fifo);
  EXPECT_EQ(scenario.status, 3) << scenario.output;
  EXPECT_NE(scenario.output.find("not a regular file"), std::string::npos) << scenario.output;
  for (const std::string& policy : {fifo, std::string("/dev/zero")}) {
    const Outcome o = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + policy);
    EXPECT_EQ(o.status, 3) << o.output;
    EXPECT_NE(o.output.find(policy + ": the policy file is not a regular file"), std::string::npos) << o.output;
  }
  std::filesystem::remove(fifo);
  // Only the XML declaration: no root element, with the file and line.
  const std::string declaration = std::string(PRONK_CLI_OUT_DIR) + "/declaration_only.xml";
  std::ofstream(declaration) << "<?xml version=\"1.0\"?>\n";
  const Outcome empty = pronk("validate " + declaration);
  EXPECT_EQ(empty.status, 3) << empty.output;
  EXPECT_NE(empty.output.find(declaration + ":1: no root element"), std::string::npos) << empty.output;
}

TEST(Cli, NanEmptyAndHugeFlagValuesAreUsageErrors) {
  // CLI11's ranges let NaN through and an empty value read as "unset": each is
  // now refused against its flag (exit 2), never a silent default.
  const std::string run = "run " + source("scenarios/go1/forward.xml") + " --policy ballistic ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--fps nan --video x.mp4", "--fps: 'nan' is not a finite number"},
      {"--duration nan", "--duration: 'nan' is not a finite number"},
      {"--duration 1e308", "--duration: 1e308 is not in (0, 3600]"},
      {"--still nan --video x.mp4", "--still: 'nan' is not a finite number"},
      {"--speed inf --video x.mp4", "--speed: 'inf' is not a finite number"},
      {"--size ''", "--size: an empty value"},
      {"--out ''", "--out: an empty value"},
      {"--sweep ''", "--sweep: an empty value"},
      // Whole numbers in decimal only, and a playback speed that makes a video of sane length.
      {"--jobs 0x2", "--jobs: '0x2' is not a decimal whole number"},
      {"--jobs ' 2'", "--jobs: ' 2' is not a decimal whole number"},
      {"--sweep region --seed 0x10", "--seed: '0x10' is not a decimal whole number"},
      {"--speed 1e-9 --video x.mp4", "--speed: 1e-9 is not in [0.01, 100]"},
      {"--duration ' 1.5'", "--duration: ' 1.5' is not a decimal number"},
      {"--duration 0x1p0", "--duration: '0x1p0' is not a decimal number"},
  };
  for (const auto& [flags, message] : cases) {
    const Outcome o = pronk(run + flags);
    EXPECT_EQ(o.status, 2) << flags << "\n" << o.output;
    EXPECT_NE(o.output.find(message), std::string::npos) << flags << "\n" << o.output;
  }
  // An empty --video is a bare --video, which needs --out for the scenario's name.
  const Outcome video = pronk(run + "--video ''");
  EXPECT_EQ(video.status, 3) << video.output;
  EXPECT_NE(video.output.find("--video without a file name"), std::string::npos) << video.output;
}

TEST(Cli, FlagsThatMeanNothingAloneAndHalfGivenParametersAreUsageErrors) {
  const std::string run = "run " + source("scenarios/go1/forward.xml") + " --policy ballistic ";
  for (const std::string& alone : {"--size 320x240", "--video-per-jump", "--fps 20", "--still 0.5", "--camera top"}) {
    const Outcome o = pronk(run + alone);
    EXPECT_EQ(o.status, 2) << alone << "\n" << o.output;
    EXPECT_NE(o.output.find("requires --video"), std::string::npos) << alone << "\n" << o.output;
  }
  const Outcome empty = pronk(run + "--param motor=");
  EXPECT_EQ(empty.status, 2) << empty.output;
  EXPECT_NE(empty.output.find("'motor=': expected NAME=VALUE, both given"), std::string::npos) << empty.output;
  const Outcome twice = pronk(run + "--param motor=dc --param motor=ideal");
  EXPECT_EQ(twice.status, 2) << twice.output;
  EXPECT_NE(twice.output.find("--param motor is given twice"), std::string::npos) << twice.output;
}

TEST(Cli, APolicyTrainedOnAnotherRobotIsFlownWithAWarningNamingBoth) {
  const Outcome o = pronk("run " + source("scenarios/aliengo/forward.xml") + " --policy " +
                          source("assets/policies/go1_omni.json"));
  EXPECT_NE(o.output.find("go1_omni.json was trained on the go1; this scenario's robot is the aliengo"),
            std::string::npos)
      << o.output;
  const Outcome own = pronk("run " + source("scenarios/aliengo/forward.xml") + " --policy " +
                            source("assets/policies/aliengo_omni.json"));
  EXPECT_EQ(own.output.find("was trained on the"), std::string::npos) << own.output;
}

TEST(Cli, ATraceWithANonFiniteNumberIsRefusedAtItsLine) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/trace_nan";
  std::filesystem::remove_all(dir);
  ASSERT_EQ(pronk("run " + source("scenarios/go1/stand.xml") + " --duration 0.05 --out " + dir).status, 0);
  std::ifstream in(dir + "/trace.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_GT(lines.size(), 3u);
  lines[2] = lines[2].substr(0, lines[2].find(',')) + ",nan" + lines[2].substr(lines[2].find(',', lines[2].find(',') + 1));
  std::ofstream out(dir + "/trace.csv");
  for (const std::string& line : lines) out << line << "\n";
  out.close();
  const Outcome o = pronk("render " + source("scenarios/go1/stand.xml") + " --trace " + dir + "/trace.csv -o " + dir +
                          "/v.mp4");
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(dir + "/trace.csv:3: column 'base_x': 'nan' is not a finite number"), std::string::npos)
      << o.output;
}

TEST(Cli, AModelTooStiffToSimulateFailsOnItsStepBudget) {
  // dissipation 1e9 once took about 5 minutes for a 1.5 s hop; the step budget
  // ends it within its first 10 ms, as a failure with its reason.
  const std::string file = std::string(PRONK_CLI_OUT_DIR) + "/stiff_contact.xml";
  std::ofstream(file) << "<scenario version=\"1\" name=\"stiff\" angle=\"rad\">\n"
                      << "  <include file=\"" << source("scenarios/platforms/go1.xml") << "\"/>\n"
                      << "  <controller name=\"scripted_jump\"/>\n"
                      << "  <sim duration=\"1.5\"><contact dissipation=\"1e9\"/></sim>\n</scenario>\n";
  const Outcome o = pronk("run " + file);
  EXPECT_EQ(o.status, 4) << o.output;
  EXPECT_NE(o.output.find("step_budget: the integrator needed more than"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("steps in the first 0.01 s (max_steps_per_second 500000)"), std::string::npos) << o.output;
}

TEST(Cli, AScenarioNeverWritesAVideoByItselfNorOutsideOut) {
  // A scenario from someone else must not overwrite the user's files: an
  // absolute or climbing output is refused at its line; a plain name is only a
  // suggestion, used by a bare --video under --out.
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/render_output";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  auto scenario = [&](const std::string& output) {
    const std::string file = dir + "/scene.xml";
    std::ofstream(file) << "<scenario version=\"1\" name=\"scene\" angle=\"rad\">\n"
                        << "  <include file=\"" << source("scenarios/platforms/go1.xml") << "\"/>\n"
                        << "  <controller name=\"stand\"/>\n  <sim duration=\"0.1\"/>\n"
                        << "  <render output=\"" << output << "\"/>\n</scenario>\n";
    return file;
  };
  for (const std::string bad : {std::string("/tmp/victim.txt"), std::string("../victim.mp4"), std::string("a/../../b.mp4")}) {
    const Outcome o = pronk("validate " + scenario(bad));
    EXPECT_EQ(o.status, 3) << bad << "\n" << o.output;
    EXPECT_NE(o.output.find("scene.xml:5: <render>: output=\"" + bad + "\" must be a relative file name"),
              std::string::npos)
        << o.output;
  }
  const std::string file = scenario("suggested.mp4");
  const Outcome plain = pronk("run " + file + " --out " + dir + "/plain");
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/plain/suggested.mp4"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/suggested.mp4"));
  const Outcome asked = pronk("run " + file + " --out " + dir + "/asked --video");
  EXPECT_EQ(asked.status, 0) << asked.output;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/asked/suggested.mp4")) << asked.output;
  const Outcome no_out = pronk("run " + file + " --video");
  EXPECT_EQ(no_out.status, 3) << no_out.output;
  EXPECT_NE(no_out.output.find("--video without a file name"), std::string::npos) << no_out.output;
}

TEST(Cli, VersionMissingScenarioAndPluginAfterTheSubcommand) {
  const Outcome version = pronk("--version");
  EXPECT_EQ(version.status, 0) << version.output;
  EXPECT_NE(version.output.find("pronk " PRONK_PROJECT_VERSION ", plugin ABI 1.6, commit "), std::string::npos)
      << version.output;
  // The commit is the source tree's as it was built, not as it was configured.
  if (FILE* git = popen(("git -C " + source("") + " rev-parse --short=12 HEAD 2>/dev/null").c_str(), "r")) {
    char head[64] = {0};
    const bool read = std::fgets(head, sizeof head, git) != nullptr;
    if (pclose(git) == 0 && read) {
      std::string commit(head);
      while (!commit.empty() && std::isspace(static_cast<unsigned char>(commit.back()))) commit.pop_back();
      EXPECT_NE(version.output.find(", commit " + commit), std::string::npos) << version.output;
    }
  }
  // A missing scenario is bad input (exit 3) named by the loader, for every command that reads one.
  for (const std::string command : {"run", "validate", "render -o x.mp4"}) {
    const Outcome o = pronk(command + " /nonexistent/scene.xml");
    EXPECT_EQ(o.status, 3) << command << "\n" << o.output;
    EXPECT_NE(o.output.find("/nonexistent/scene.xml: scenario file not found"), std::string::npos) << o.output;
  }
  // --plugin after the subcommand, as docs/plugin-abi.md writes it.
  const Outcome after = pronk("plugins --plugin /nonexistent/libnothing.so");
  EXPECT_EQ(after.status, 3) << after.output;
  EXPECT_NE(after.output.find("/nonexistent/libnothing.so"), std::string::npos) << after.output;
}

TEST(Cli, ValidateRefusesWhatARunWouldWithTheParameterLine) {
  // A motor model's name is the environment's to judge: validate creates the
  // environment on the robot, as a run would, and names the <param>'s line.
  // Hexadecimal numbers, which strtod reads, are refused like attributes.
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/validate_params";
  std::filesystem::create_directories(dir);
  auto scenario = [&](const std::string& name, const std::string& value) {
    const std::string file = dir + "/" + name + ".xml";
    std::ofstream(file) << "<scenario version=\"1\" name=\"p\" angle=\"rad\">\n"
                        << "  <include file=\"" << source("scenarios/platforms/go1.xml") << "\"/>\n"
                        << "  <environment name=\"jump\" plugin=\"pronk_guided_jump\">\n"
                        << "    <param name=\"" << name << "\" value=\"" << value << "\"/>\n"
                        << "  </environment>\n  <sim/>\n</scenario>\n";
    return file;
  };
  const Outcome motor = pronk("validate " + scenario("motor", "bogus"));
  EXPECT_EQ(motor.status, 3) << motor.output;
  EXPECT_NE(motor.output.find("motor.xml:4: "), std::string::npos) << motor.output;
  EXPECT_NE(motor.output.find("'bogus' is neither dc nor effort"), std::string::npos) << motor.output;
  const Outcome hex = pronk("validate " + scenario("duration", "0x1.8p0"));
  EXPECT_EQ(hex.status, 3) << hex.output;
  EXPECT_NE(hex.output.find("duration.xml:4: "), std::string::npos) << hex.output;
  EXPECT_EQ(pronk("validate " + scenario("duration", "1.5")).status, 0);
}

TEST(Cli, ValidateOfAnIncludedPartChecksItsParameters) {
  // A part file's <param>s: against the plugin's declarations when the part has
  // no robot (an unknown name, a number outside its declared range); on its own
  // robot, as the environment would judge them in a run.
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/validate_part_params";
  std::filesystem::create_directories(dir);
  auto part = [&](const std::string& file_name, const std::string& name, const std::string& value, bool robot) {
    const std::string file = dir + "/" + file_name + ".xml";
    std::ofstream out(file);
    out << "<scenario_part version=\"1\" angle=\"rad\">\n";
    if (robot) out << "  <include file=\"" << source("scenarios/platforms/go1.xml") << "\"/>\n";
    out << "  <environment name=\"jump\" plugin=\"pronk_guided_jump\">\n"
        << "    <param name=\"" << name << "\" value=\"" << value << "\"/>\n"
        << "  </environment>\n</scenario_part>\n";
    return file;
  };
  const Outcome unknown = pronk("validate " + part("unknown", "no_such_parameter", "3", false));
  EXPECT_EQ(unknown.status, 3) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown.xml:3: "), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("no_such_parameter"), std::string::npos) << unknown.output;
  const Outcome range = pronk("validate " + part("range", "kp", "-3", false));
  EXPECT_EQ(range.status, 3) << range.output;
  EXPECT_NE(range.output.find("range.xml:3: "), std::string::npos) << range.output;
  const Outcome fine = pronk("validate " + part("fine", "kp", "50", false));
  EXPECT_EQ(fine.status, 0) << fine.output;
  EXPECT_NE(fine.output.find("parameters checked against its declarations"), std::string::npos) << fine.output;
  const Outcome motor = pronk("validate " + part("motor_on_robot", "motor", "bogus", true));
  EXPECT_EQ(motor.status, 3) << motor.output;
  EXPECT_NE(motor.output.find("motor_on_robot.xml:4: "), std::string::npos) << motor.output;
  EXPECT_NE(motor.output.find("'bogus' is neither dc nor effort"), std::string::npos) << motor.output;
  // The shipped environment parts pass.
  EXPECT_EQ(pronk("validate " + source("scenarios/go1/jump_environment.xml")).status, 0);
}

}  // namespace
