// `pronk run SCENARIO --policy ballistic`: whole jumps to targets through the
// command a user runs, with the results files' schema (docs/results-format.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>
#include <sys/wait.h>

#include "pronk_command.h"

namespace {

using pronk_test::pronk;
using pronk_test::source;
using CommandRun = pronk_test::Outcome;
std::string testScenario(const std::string& name) { return pronk_test::cliScenario(name); }

std::string outDir(const std::string& name) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

// The jumps of a run's results.json (its "run" object aside).
nlohmann::json results(const std::string& dir) {
  std::ifstream in(dir + "/results.json");
  nlohmann::json j;
  if (in) in >> j;
  return j.is_object() ? j["jumps"] : j;
}

nlohmann::json runOf(const std::string& dir) {
  std::ifstream in(dir + "/results.json");
  nlohmann::json j;
  if (in) in >> j;
  return j.is_object() ? j["run"] : j;
}

// Runs a shipped scenario with the ballistic policy (and its trace), expects
// exit 0 and one jump, and returns that jump's results.json object (null after
// a failed expectation); the output directory in *dir.
nlohmann::json onlyJump(const std::string& scenario, const std::string& out_name, std::string* dir = nullptr,
                        const std::string& params = "") {
  const std::string out = outDir(out_name);
  if (dir) *dir = out;
  const CommandRun r = pronk("run " + source(scenario) + " --policy ballistic --trace --out " + out + params);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = results(out);
  EXPECT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  return j.is_array() && j.size() == 1u ? j[0] : nlohmann::json();
}

// Runs a test scenario with the ballistic policy and extra flags, expects
// `count` jumps and returns the exit status and the jumps' results.json objects.
std::pair<int, nlohmann::json> runTestScenario(const std::string& scenario, const std::string& out_name,
                                               const std::string& params, size_t count) {
  const std::string dir = outDir(out_name);
  const CommandRun r = pronk("run " + testScenario(scenario) + " --policy ballistic --out " + dir + params);
  const nlohmann::json j = results(dir);
  EXPECT_EQ(j.size(), count) << r.output;
  return std::make_pair(r.status, j);
}

TEST(JumpRuns, Go1ForwardLandsWithinItsToleranceAndWritesEveryResult) {
  std::string dir;
  const nlohmann::json jump = onlyJump("scenarios/go1/forward.xml", "jump_forward", &dir);
  ASSERT_FALSE(jump.is_null());
  EXPECT_EQ(jump["status"], "ok");
  EXPECT_FALSE(jump["failed"].get<bool>());
  EXPECT_DOUBLE_EQ(jump["target"]["x"].get<double>(), 0.4);
  // The scenario's tolerance is 5 cm (measured 1.5 cm); the landing point and the error agree.
  const double dx = jump["landing"]["x"].get<double>() - 0.4, dy = jump["landing"]["y"].get<double>();
  EXPECT_NEAR(jump["error_xy"].get<double>(), std::hypot(dx, dy), 1e-9);
  EXPECT_LT(jump["error_xy"].get<double>(), 0.05);
  EXPECT_LT(jump["error_yaw_deg"].get<double>(), 5.0);
  EXPECT_TRUE(jump["ended_standing"].get<bool>());
  // Every reward term, the events, planned vs detected lift-off within 20 ms.
  EXPECT_EQ(jump["penalties"].size(), 14u) << jump["penalties"].dump();
  const double planned = jump["events"]["planned_lift_off_time"].get<double>();
  const double detected = jump["events"]["lift_off"].get<double>();
  EXPECT_NEAR(detected, planned, 0.02);
  EXPECT_GT(jump["events"]["touchdown"].get<double>(), detected);
  EXPECT_GT(jump["reward"].get<double>(), 0.0);
  // results.csv takes pronk eval's jumps.csv names and units (angles in degrees).
  std::ifstream csv(dir + "/results.csv");
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  EXPECT_EQ(header.rfind("case,target_x,target_y,target_z,target_yaw_deg,landed_x,landed_y,landed_z,landed_yaw_deg,"
                         "error_xy,landed_height,error,error_yaw_deg,",
                         0),
            0u)
      << header;
  // What the run was: the scenario file's fingerprint, when and where, the simulation and contact settings.
  const nlohmann::json run = runOf(dir);
  EXPECT_EQ(run["scenario_fingerprint"].get<std::string>().size(), 16u) << run.dump();
  EXPECT_TRUE(std::regex_match(run["started_utc"].get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << run.dump();
  EXPECT_TRUE(run["host"].is_string());
  EXPECT_DOUBLE_EQ(run["simulation"]["step_s"].get<double>(), 2e-4) << run.dump();
  EXPECT_EQ(run["simulation"]["contact"]["model"], "stiction");
  EXPECT_EQ(jump["trace"], "jump-000.csv");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/jump-000.csv"));
}

// A robot pronk ships no platform for, from its files alone (issue 22.2): the
// Go1 with the A1's 0.2 m legs, standing as the A1 does. The environment sets
// no stance, gains or ranges; it takes the platform's stance and gains, and
// scales the paper's length ranges by the legs (ActionMapping.RangesScale...).
// Measured 0.6 cm; with the Go1's stance and ranges set instead, 6.4 cm
// (docs/results.md, "A robot from data").
TEST(JumpRuns, ARobotWithAnotherStanceAndLegLengthsJumpsFromItsDataAlone) {
  const std::string out = outDir("a1_sized_forward");
  const CommandRun r = pronk("run " + testScenario("a1_sized_forward.xml") + " --policy ballistic --out " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json run = runOf(out);
  EXPECT_EQ(run["parameters"]["stance"], "0 0.8 -1.5") << run.dump();
  EXPECT_EQ(run["parameters"]["kp"], "100") << run.dump();
  EXPECT_EQ(run["parameters"]["action_max"], "") << run.dump();
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  EXPECT_EQ(j[0]["status"], "ok") << r.output;
  EXPECT_LT(j[0]["error_xy"].get<double>(), 0.05) << r.output;
  EXPECT_TRUE(j[0]["ended_standing"].get<bool>()) << r.output;
}

// Robots brought as the README's "Another robot" says, with a platform file and
// nothing else (tests/robots/): the vendor's Go1 and Aliengo URDFs (the
// Aliengo's thighs are continuous joints, with no position limits; its reward
// used to be NaN) and big_go1, 1.5 times the Go1's legs and 3 times its mass.
// Each lands its forward jump (0.4 m, big_go1 0.6 m) on its feet with the
// plugin's defaults: measured 1.8, 3.7 and 3.7 cm.
TEST(JumpRuns, RobotsBroughtWithAPlatformFileAloneLandTheirForwardJump) {
  for (const std::string robot : {"vendor_go1", "vendor_aliengo", "big_go1"}) {
    if (robot.rfind("vendor_", 0) == 0 && !std::filesystem::exists(source("../shared/thirdparty/unitree"))) {
      std::printf("skipping %s: ../shared/thirdparty is absent\n", robot.c_str());
      continue;
    }
    const std::string out = outDir("robot_" + robot);
    const CommandRun r =
        pronk("run " + source("tests/robots/" + robot + "/flat_200.xml") + " --policy ballistic --out " + out);
    EXPECT_EQ(r.status, 0) << robot << "\n" << r.output;
    const nlohmann::json run = runOf(out);
    EXPECT_EQ(run["parameters"]["momentum_gain"], "10") << run.dump();
    EXPECT_EQ(run["parameters"]["action_max"], "") << run.dump();
    const nlohmann::json j = results(out);
    ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
    EXPECT_EQ(j[0]["status"], "ok") << robot;
    EXPECT_TRUE(std::isfinite(j[0]["reward"].get<double>())) << robot;
    EXPECT_LT(j[0]["error_xy"].get<double>(), 0.05) << robot;
    EXPECT_TRUE(j[0]["ended_standing"].get<bool>()) << robot;
  }
}

// The paper's controller is one include away (scenarios/parts/paper_controller.xml):
// its backward jump leaves the ground with the whole body pitching, as the
// paper's kinematic thrust does, and lands further off than pronk's.
TEST(JumpRuns, ThePapersControllerIsOneIncludeAway) {
  const std::string paper_dir = outDir("mixed_paper"), pronk_dir = outDir("mixed_pronk");
  const CommandRun paper = pronk("run " + source("scenarios/go1/mixed_paper.xml") + " --policy ballistic --out " + paper_dir);
  const CommandRun ours = pronk("run " + source("scenarios/go1/mixed.xml") + " --policy ballistic --out " + pronk_dir);
  EXPECT_NE(paper.status, 1) << paper.output;
  EXPECT_EQ(ours.status, 0) << ours.output;
  const nlohmann::json run = runOf(paper_dir);
  EXPECT_EQ(run["parameters"]["feedforward"], "gravity") << run.dump();
  EXPECT_EQ(run["parameters"]["momentum_gain"], "0") << run.dump();
  EXPECT_EQ(run["parameters"]["stance_feet"], "measured") << run.dump();
  const nlohmann::json a = results(paper_dir), b = results(pronk_dir);
  ASSERT_TRUE(a.is_array() && b.is_array() && a.size() == b.size() && a.size() == 7u);
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i]["case"] != "target backward") continue;
    ASSERT_TRUE(a[i]["metrics"].contains("lift_off_body_rate_y")) << a[i].dump();
    EXPECT_GT(std::abs(a[i]["metrics"]["lift_off_body_rate_y"].get<double>()),
              1.25 * std::abs(b[i]["metrics"]["lift_off_body_rate_y"].get<double>()));
  }
}

TEST(JumpRuns, TracesAreWrittenOnlyWhenAsked) {
  const std::string out = outDir("jump_no_trace");
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy ballistic --out " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  EXPECT_EQ(j[0]["trace"], "");
  EXPECT_FALSE(std::filesystem::exists(out + "/jump-000.csv"));
  const CommandRun no_dir = pronk("run " + source("scenarios/go1/forward.xml") + " --policy ballistic --trace");
  EXPECT_NE(no_dir.status, 0);
  EXPECT_NE(no_dir.output.find("--trace: needs --out DIR"), std::string::npos) << no_dir.output;
}

// results.json without the wall-clock figures, the one thing a rerun may change.
nlohmann::json withoutWallTimes(nlohmann::json j) {
  for (nlohmann::json& jump : j) jump.erase("wall_s");
  return j;
}

TEST(JumpRuns, ResultsDoNotDependOnTheNumberOfJobs) {
  // Landed, refused and failed jumps, with per-target step platforms (worlds
  // reused across cases) and a trunk-mass sweep (worlds rebuilt): every number
  // of results.json is the same with one worker thread as with two.
  for (const std::string sweep : {"mix", "mass"}) {
    const std::string one = outDir("jump_jobs_1_" + sweep), two = outDir("jump_jobs_2_" + sweep);
    const std::string run = "run " + testScenario("go1_rollout_mix.xml") + " --policy ballistic --sweep " + sweep;
    const CommandRun r1 = pronk(run + " --jobs 1 --out " + one);
    const CommandRun r2 = pronk(run + " --jobs 2 --out " + two);
    EXPECT_NE(r1.output.find("1 thread(s)"), std::string::npos) << r1.output;
    EXPECT_NE(r2.output.find("2 thread(s)"), std::string::npos) << r2.output;
    const nlohmann::json a = results(one), b = results(two);
    ASSERT_TRUE(a.is_array() && a.size() >= 3u) << r1.output;
    EXPECT_EQ(withoutWallTimes(a), withoutWallTimes(b)) << sweep;
    EXPECT_EQ(r1.status, r2.status);
  }
}

TEST(JumpRuns, Go1DiagonalWithATurnLandsWithinItsTolerance) {
  // The paper's diagonal jump: 0.3 m forward, 0.2 m left, 45 deg of yaw. Its
  // scenario's tolerances (5 cm, 12 deg; measured 3.6 cm, 6.4 deg) make a miss exit 4.
  const nlohmann::json jump = onlyJump("scenarios/go1/diagonal.xml", "jump_diagonal");
  ASSERT_FALSE(jump.is_null());
  EXPECT_EQ(jump["status"], "ok");
  EXPECT_LT(jump["error_xy"].get<double>(), 0.05);
  EXPECT_LT(jump["error_yaw_deg"].get<double>(), 12.0);
  EXPECT_NEAR(jump["landing"]["yaw"].get<double>(), 45.0 * M_PI / 180.0, 12.0 * M_PI / 180.0);  // rad
  EXPECT_TRUE(jump["ended_standing"].get<bool>());
  EXPECT_NEAR(jump["events"]["lift_off"].get<double>(), jump["events"]["planned_lift_off_time"].get<double>(), 0.02);
}

TEST(JumpRuns, Go1LateralJumpLandsOnItsFeet) {
  // 0.3 m to the left. The legs swing across a sideways push and the whole body
  // leaves the ground rolling: with the least-speed elevation (0.68 rad) it rolled
  // onto a thigh. The steeper sideways lift-off (1.35 rad) and the momentum
  // feedback land it rolled 18.5 deg at touchdown; with the file's 2 s episode it
  // comes to rest standing 3.1 cm off (tolerance 10 cm).
  const nlohmann::json jump = onlyJump("scenarios/go1/lateral.xml", "jump_lateral");
  ASSERT_FALSE(jump.is_null());
  EXPECT_EQ(jump["status"], "ok") << jump["failure_reason"];
  EXPECT_LT(jump["error_xy"].get<double>(), 0.10);
  EXPECT_TRUE(jump["ended_standing"].get<bool>());
  EXPECT_NEAR(jump["metrics"]["action_velocity_elevation"].get<double>(), 1.35, 1e-6);
}

TEST(JumpRuns, Go1DownJumpFromAPlatformLandsWithinItsTolerance) {
  // 0.6 m forward and 0.1 m down off a start platform; its tolerance is 8 cm
  // (measured 5.0 cm). The trailing feet must clear the platform's edge.
  std::string dir;
  const nlohmann::json jump = onlyJump("scenarios/go1/down.xml", "jump_down", &dir);
  ASSERT_FALSE(jump.is_null());
  EXPECT_EQ(jump["status"], "ok");
  EXPECT_LT(jump["error_xy"].get<double>(), 0.08);
  EXPECT_NEAR(jump["landing"]["z"].get<double>(), -0.1, 0.02);
  EXPECT_TRUE(jump["ended_standing"].get<bool>());
  // The trace holds each foot's centre: at the start the feet stand on the
  // 0.1 m platform, one foot radius (0.02 m) above its top.
  std::ifstream trace(dir + "/" + jump["trace"].get<std::string>());
  std::string header, first;
  ASSERT_TRUE(std::getline(trace, header) && std::getline(trace, first));
  std::vector<std::string> names, values;
  for (std::stringstream in(header); in.good();) names.emplace_back(), std::getline(in, names.back(), ',');
  for (std::stringstream in(first); in.good();) values.emplace_back(), std::getline(in, values.back(), ',');
  ASSERT_EQ(names.size(), values.size());
  int feet = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i].size() > 7 && names[i].compare(names[i].size() - 7, 7, "_foot_z") == 0) {
      EXPECT_NEAR(std::stod(values[i]), 0.12, 0.005) << names[i];
      ++feet;
    }
  }
  EXPECT_EQ(feet, 4) << header;
}

TEST(JumpRuns, MomentumFeedbackCutsTheWholeBodyPitchRateOfABackwardJump) {
  // The legs swinging under a level trunk carry angular momentum: with the paper's
  // kinematic thrust (momentum_gain 0) the whole body leaves the ground pitching at
  // -0.93 rad/s, lands 18.5 deg nose-up and 3.1 cm off; with the Go1 files'
  // momentum_gain 10 at -0.62 rad/s, 10.4 deg, 1.2 cm (docs/results.md).
  const nlohmann::json plain = onlyJump("tests/cli/scenarios/go1_backward_kinematic.xml", "jump_backward_kinematic");
  const nlohmann::json fed = onlyJump("scenarios/go1/backward.xml", "jump_backward_fed");
  ASSERT_FALSE(plain.is_null() || fed.is_null());
  ASSERT_TRUE(plain["metrics"].contains("lift_off_body_rate_y")) << plain["metrics"].dump();
  const double without = plain["metrics"]["lift_off_body_rate_y"].get<double>();
  const double with = fed["metrics"]["lift_off_body_rate_y"].get<double>();
  EXPECT_LT(without, -0.8);
  EXPECT_LT(std::abs(with), 0.8 * std::abs(without)) << with << " vs " << without;
  ASSERT_TRUE(fed["metrics"].contains("touchdown_pitch")) << fed["metrics"].dump();
  EXPECT_LT(std::abs(fed["metrics"]["touchdown_pitch"].get<double>()),
            0.8 * std::abs(plain["metrics"]["touchdown_pitch"].get<double>()));
  EXPECT_EQ(fed["status"], "ok");
  EXPECT_LT(fed["error_xy"].get<double>(), 0.03);
}

TEST(JumpRuns, ForwardJumpsWithASidewaysComponentAndATurnLand) {
  // Forward jumps with a sideways component and a turn the other way: the whole
  // body leaves the ground rolling. With the hips absorbing the roll in the air
  // and holding it through the descent (commit d962587) they landed 2.0, 2.2 and
  // 8.5 cm off; with the momentum feedback of the thrust instead (no absorber)
  // 2.9, 2.9 and 3.1 cm (docs/results.md).
  const std::string dir = outDir("jump_forward_left_turn");
  const CommandRun r = pronk("run " + testScenario("go1_forward_left_turn.xml") + " --policy ballistic --out " + dir);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = results(dir);
  ASSERT_EQ(j.size(), 3u) << r.output;
  for (const nlohmann::json& jump : j) {
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["failure_reason"];
    EXPECT_LT(jump["error_xy"].get<double>(), 0.12) << jump["target"].dump();
  }
}

TEST(JumpRuns, TurningBackwardSidewaysCrouchesKeepTheirThighsOffTheGround) {
  // Deep, turning crouches of backward-sideways jumps (targets of a development
  // sample, seed 777). With the paper's stance feet (each IK target where its foot
  // is now) and no knee clearance, the thrust's first acceleration unloads two
  // diagonal feet, they float with their legs, and a thigh comes down on the
  // ground before lift-off in all three. Anchored feet press back down; the
  // knee clearance makes the planner choose a thrust whose knees stay up
  // (docs/method-planner.md).
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("go1_backward_sideways_turns.xml", name, params, 3u);
  };
  const auto [status, jumps] = run("jump_backward_sideways", "");
  EXPECT_EQ(status, 0);
  for (const nlohmann::json& jump : jumps) {
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["failure_reason"];
    EXPECT_LT(jump["error_xy"].get<double>(), 0.1) << jump["target"].dump();
    ASSERT_TRUE(jump["metrics"].contains("planned_knee_clearance")) << jump["metrics"].dump();
    EXPECT_GE(jump["metrics"]["planned_knee_clearance"].get<double>(), 0.01);
  }
  const auto [paper_status, paper] =
      run("jump_backward_sideways_paper", " --param stance_feet=measured --param knee_clearance=-1"
                                          " --param momentum_moment_gain=0");
  EXPECT_EQ(paper_status, 4);
  for (const nlohmann::json& jump : paper) {
    EXPECT_EQ(jump["status"], "failed") << jump["target"].dump();
    const std::string reason = jump["failure_reason"].get<std::string>();
    EXPECT_NE(reason.find("_thigh' touched the terrain"), std::string::npos) << reason;
    EXPECT_LT(jump["metrics"]["planned_knee_clearance"].get<double>(), 0.01) << jump["target"].dump();
  }
}

TEST(JumpRuns, AJumpAndItsMirrorImageLandMirrored) {
  // The Go1 is left-right symmetric, and so are the planner and the controller: a
  // jump to (x, -y, -yaw) plans the mirrored action (the signs of the lift-off
  // roll, yaw and their rates flip) and lands as the mirror image of the jump to
  // (x, y, yaw), up to what the simulation's order of operations breaks. The
  // Go1 task's landing pose swings the legs further than levelled feet and
  // carries those differences into the landed yaw: 0.014 rad apart measured
  // (0.002 with landing_pose_levelling 1), within 0.02.
  const std::string dir = outDir("jump_mirror_pairs");
  const CommandRun r = pronk("run " + testScenario("go1_mirror_pairs.xml") + " --policy ballistic --out " + dir);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = results(dir);
  ASSERT_EQ(j.size(), 4u) << r.output;
  for (int pair = 0; pair < 2; ++pair) {
    const nlohmann::json& a = j[2 * pair];
    const nlohmann::json& b = j[2 * pair + 1];
    ASSERT_EQ(a["status"], "ok") << a["case"];
    ASSERT_EQ(b["status"], "ok") << b["case"];
    for (const char* flipped : {"action_liftoff_roll_rate", "action_liftoff_yaw", "action_liftoff_yaw_rate"}) {
      EXPECT_NEAR(a["metrics"][flipped].get<double>(), -b["metrics"][flipped].get<double>(), 1e-9)
          << a["case"] << " " << flipped;
    }
    EXPECT_NEAR(a["metrics"]["action_liftoff_speed"].get<double>(), b["metrics"]["action_liftoff_speed"].get<double>(),
                1e-9);
    EXPECT_NEAR(a["landing"]["x"].get<double>(), b["landing"]["x"].get<double>(), 0.005) << a["case"];
    EXPECT_NEAR(a["landing"]["y"].get<double>(), -b["landing"]["y"].get<double>(), 0.005) << a["case"];
    EXPECT_NEAR(a["landing"]["yaw"].get<double>(), -b["landing"]["yaw"].get<double>(), 0.02) << a["case"];
  }
}

TEST(JumpRuns, RolledLandingsLoadEveryFootAndStayOnTheirFeet) {
  // Turning jumps whose trunk lands rolled about 0.5 rad (targets of a development
  // sample, seed 777; 3 s episodes). The landing stops the CoM over the low side's
  // feet; the high side's feet touch with no load and flicker in and out of
  // contact. Left out of the body wrench, they stay unloaded, and the robot
  // balances on two feet until a thigh touches the ground, in all three. Shared
  // by every foot once all have touched down, the wrench loads them. The forward
  // one lands 22.9 cm off and is still moving at 3 s: the bound is on failures
  // and a quarter metre; two of the three end standing.
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("go1_rolled_landings.xml", name, params, 3u);
  };
  const auto [status, jumps] = run("jump_rolled_landings", "");
  EXPECT_NE(status, 1);
  int standing = 0;
  for (const nlohmann::json& jump : jumps) {
    EXPECT_NE(jump["status"], "failed") << jump["target"].dump() << " " << jump["failure_reason"];
    standing += jump["ended_standing"].get<bool>() ? 1 : 0;
    EXPECT_LT(jump["error_xy"].get<double>(), 0.25) << jump["target"].dump();
    EXPECT_GT(std::abs(jump["metrics"]["touchdown_roll"].get<double>()), 0.3) << jump["target"].dump();
  }
  EXPECT_GE(standing, 2);
}

TEST(JumpRuns, LandingsWhoseLegsFollowTheSinkStayOnTheGround) {
  // Hard landings of a development sample (seed 783): with the legs' reference at
  // the standing height from touchdown on, the compressed legs threw the robot
  // back up and no foot was on the ground at the end of the 1.5 s episode. The
  // landing's 10 rad/s vertical stop, which the legs follow down, keeps every one
  // on its feet (docs/method.md).
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("go1_bouncing_landings.xml", name, params, 3u).second;
  };
  for (const nlohmann::json& jump : run("jump_bouncing_landings", "")) {
    EXPECT_NE(jump["status"], "failed") << jump["target"].dump() << " " << jump["failure_reason"];
  }
}

TEST(JumpRuns, ALandingPoseThatSwingsTheLegsFurtherKeepsDownJumpsOffTheirThighs) {
  // Backward down-jumps of a development sample (seeds 782, 783 of heights_dev.xml):
  // with the landing pose levelling the feet under the tilted trunk
  // (landing_pose_levelling 1), the trunk turns against the legs' swing in the
  // air, lands rolled and a rear thigh hits the lower ground in two of the three.
  // The default pose swings the legs half again as far (1.5), and each lands on
  // its feet within 5 cm (docs/method.md).
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("go1_backward_down_jumps.xml", name, params, 3u).second;
  };
  for (const nlohmann::json& jump : run("jump_backward_down", "")) {
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["failure_reason"];
    EXPECT_TRUE(jump["ended_standing"].get<bool>()) << jump["target"].dump();
    EXPECT_LT(jump["error_xy"].get<double>(), 0.05) << jump["target"].dump();
  }
  int thighs = 0;
  for (const nlohmann::json& jump : run("jump_backward_down_levelled", " --param landing_pose_levelling=1")) {
    const std::string reason = jump["failure_reason"].is_string() ? jump["failure_reason"].get<std::string>() : "";
    thighs += jump["status"] == "failed" && reason.find("_thigh' touched the terrain") != std::string::npos ? 1 : 0;
  }
  EXPECT_GE(thighs, 2);
}

TEST(JumpRuns, TheAliengosBackwardJumpsLeaveOnTimeWhenTheLastFeetDoNotCarryTheWeight) {
  // Three backward jumps of the Aliengo's development sample: when the feet still
  // down after the thrust plan's end carried the robot's weight, one or two of
  // them stayed pressed down, the robot left the ground 50-150 ms late turning
  // about them and fell on a rear leg. Held by PD alone every foot is up within
  // a few ms of the planned lift-off and each lands standing within 6 cm
  // (measured 3.5, 1.4 and 5.0 cm; docs/method.md), on the landing they were
  // measured with (no heading term, the stance pose at touchdown).
  const std::string landing = " --param landing_yaw_gain=0 --param landing_yaw_damping=0.4 --param landing_extension=0";
  auto late = [](const nlohmann::json& jump) {
    const nlohmann::json& e = jump["events"];
    if (!e["lift_off"].is_number() || !e["planned_lift_off_time"].is_number()) return std::nan("");
    return e["lift_off"].get<double>() - e["planned_lift_off_time"].get<double>();
  };
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("aliengo_backward_late_lift_offs.xml", name, params, 3u).second;
  };
  for (const nlohmann::json& jump : run("jump_aliengo_backward", landing)) {
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["failure_reason"];
    EXPECT_LT(late(jump), 0.01) << jump["target"].dump();
    EXPECT_TRUE(jump["ended_standing"].get<bool>()) << jump["target"].dump();
    EXPECT_LT(jump["error_xy"].get<double>(), 0.06) << jump["target"].dump();
  }
}

TEST(JumpRuns, AGroundMomentGivesATwistItsYawMomentum) {
  // Turning the trunk over planted feet does not turn the whole body (the legs
  // counter-rotate); a moment about the vertical in the feet's wrench does. With
  // the trunk-turn feedback on roll and pitch only (the Go1 task's share 0), the
  // 60 deg twist leaves the ground with a whole-body yaw rate nearer the plan's
  // lift-off yaw rate with the ground moment (the Go1 task's gain 50) than without,
  // and lands nearer its yaw (measured: 0.19 vs 0.30 rad/s short, 3.0 vs 5.1 deg).
  struct Twist {
    double rate_error = std::nan(""), yaw_error = std::nan("");
  };
  auto twist = [](const std::string& name, const std::string& params) {
    const std::string dir = outDir(name);
    const CommandRun r = pronk("run " + source("scenarios/go1/twist.xml") + " --policy ballistic --out " + dir + params);
    EXPECT_EQ(r.status, 0) << r.output;
    const nlohmann::json j = results(dir);
    EXPECT_EQ(j.size(), 1u) << r.output;
    Twist t;
    if (j.size() != 1u) return t;
    t.rate_error = std::abs(j[0]["metrics"]["lift_off_body_rate_z"].get<double>() -
                            j[0]["metrics"]["action_liftoff_yaw_rate"].get<double>());
    t.yaw_error = j[0]["error_yaw_deg"].get<double>();
    return t;
  };
  // Both on the landing they were measured with (no heading term): the Go1 task's
  // turns either trunk to its planned heading on its feet.
  const std::string landing = " --param landing_yaw_gain=0 --param landing_yaw_damping=0.4";
  const Twist with = twist("jump_twist_ground_moment", landing);
  const Twist without = twist("jump_twist_no_ground_moment", landing + " --param momentum_moment_gain=0");
  EXPECT_LT(with.rate_error, 0.8 * without.rate_error) << with.rate_error << " vs " << without.rate_error;
  EXPECT_LT(with.yaw_error, 0.75 * without.yaw_error) << with.yaw_error << " vs " << without.yaw_error;
}

TEST(JumpRuns, TheLandingTurnsTheTrunkToThePlannedHeading) {
  // After touchdown the trunk keeps turning at its flight yaw rate while the
  // lightly loaded rear feet slide: DIAG's 45 deg lands 9 deg past with a
  // damping of the turn alone, the 60 deg twist 2.8 deg short. The landing's
  // moment about the vertical towards the plan's touchdown heading
  // (landing_yaw_gain 10 N m/rad/kg, landing_yaw_damping 1.5 N m s/rad/kg, the
  // Go1 task's) turns the trunk back, or on, on its feet: both land within
  // 0.3 deg (measured 0.17 and 0.23), and as near the target (docs/method.md,
  // "A landing that holds the planned heading").
  const std::string heading = " --param landing_yaw_gain=10 --param landing_yaw_damping=1.5";
  const std::string damping = " --param landing_yaw_gain=0 --param landing_yaw_damping=0.4";
  for (const std::string scenario : {"diagonal.xml", "twist.xml"}) {
    const nlohmann::json held = onlyJump("scenarios/go1/" + scenario, "jump_heading_" + scenario, nullptr, heading);
    const nlohmann::json free = onlyJump("scenarios/go1/" + scenario, "jump_no_heading_" + scenario, nullptr, damping);
    ASSERT_FALSE(held.is_null() || free.is_null()) << scenario;
    EXPECT_EQ(held["status"], "ok") << scenario << " " << held["failure_reason"];
    EXPECT_TRUE(held["ended_standing"].get<bool>()) << scenario;
    EXPECT_LT(held["error_yaw_deg"].get<double>(), 1.0) << scenario;
    EXPECT_GT(free["error_yaw_deg"].get<double>(), 2.0) << scenario;
    EXPECT_LT(held["error_xy"].get<double>(), free["error_xy"].get<double>() + 0.01) << scenario;
  }
}

TEST(JumpRuns, LegsThatTouchDownLongerStopTheAliengosDownJumpsAboveItsThighs) {
  // Down-jumps of 0.2-0.4 m of a development sample (region3d.xml seeds 7, 9 and
  // 11): the Aliengo touches down fast and its knee motors stay saturated
  // at 44 N m through the stop. From the stance pose at touchdown a thigh comes
  // down to the lower ground before the fall is stopped; with the legs longer at
  // touchdown (the landing extension derived for the Aliengo, 0.111 m; measured
  // 6.9, 4.5 and 6.7 cm off at 0.11 m, 7.1, 7.5 and 10.4 cm at 0.05 m) each lands
  // on its feet within 0.12 m (docs/method.md).
  auto run = [](const std::string& name, const std::string& params) {
    return runTestScenario("aliengo_down_jumps.xml", name, params, 3u).second;
  };
  for (const nlohmann::json& jump : run("jump_aliengo_down_extended", "")) {
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["failure_reason"];
    EXPECT_LT(jump["error_xy"].get<double>(), 0.12) << jump["target"].dump();
  }
  // From the stance pose at touchdown, at least two of the three come down on a thigh.
  int on_a_thigh = 0;
  for (const nlohmann::json& jump : run("jump_aliengo_down_stance", " --param landing_extension=0")) {
    if (jump["status"] == "failed" &&
        jump["failure_reason"].get<std::string>().find("_thigh' touched the terrain") != std::string::npos) {
      ++on_a_thigh;
    }
  }
  EXPECT_GE(on_a_thigh, 2);
}

TEST(JumpRuns, AToeThatBrushesTheGroundAfterLiftOffDoesNotStartTheLanding) {
  // Three flat planner jumps of the Aliengo's development sample whose thrust
  // leaves a toe that touches the ground again a millisecond after lift-off.
  // Taken for the touchdown, that brush started the landing in mid-air and its
  // stop pulled the flight back: 21.5, 30.1 and 38.6 cm off. The landing now
  // waits for a contact with the CoM no longer rising; each lands within the
  // paper's 0.2 m (measured 5.6, 15.4 and 10.6 cm at commit d037524; docs/method.md,
  // "A touchdown is a contact with the CoM no longer rising").
  // The planner's thrust, scaled to the Aliengo's legs, leaves the brush in two
  // of them (6.1 and 10.2 cm off); the third lands 17.1 cm off without one.
  const std::string dir = outDir("jump_aliengo_scuffs");
  const CommandRun r = pronk("run " + testScenario("aliengo_scuffs.xml") + " --policy ballistic --out " + dir);
  const nlohmann::json jumps = results(dir);
  ASSERT_EQ(jumps.size(), 3u) << r.output;
  int brushes = 0;
  for (const nlohmann::json& jump : jumps) {
    double lift_off = -1, brush = -1, descend = -1, landing = -1;
    for (const nlohmann::json& e : jump["event_log"]) {
      const std::string name = e["name"];
      const double t = e["time"];
      if (name == "lift_off" && lift_off < 0) lift_off = t;
      if (name == "touchdown" && brush < 0) brush = t;
      if (name == "phase:descend" && descend < 0) descend = t;
      if (name == "phase:landing" && landing < 0) landing = t;
    }
    // The brush is still there (the host reports it), but the controller flies on.
    EXPECT_GT(lift_off, 0) << jump["target"].dump();
    if (brush - lift_off <= 0.005) {
      ++brushes;
      EXPECT_GT(descend, brush) << jump["target"].dump();
    }
    EXPECT_GT(landing, descend) << jump["target"].dump();
    EXPECT_EQ(jump["status"], "ok") << jump["target"].dump() << " " << jump["error_xy"];
  }
  EXPECT_GE(brushes, 2);
  // The console's touchdown column sets the plan's touchdown beside the controller's
  // (events.touchdown_time), not beside the brush.
  for (const nlohmann::json& jump : jumps) {
    char pair[32];
    std::snprintf(pair, sizeof pair, "%5.3f/%5.3f", jump["events"]["planned_touchdown_time"].get<double>(),
                  jump["events"]["touchdown_time"].get<double>());
    EXPECT_NE(r.output.find(pair), std::string::npos) << pair << "\n" << r.output;
  }
  EXPECT_NE(r.output.find("touchdown s: planned_touchdown_time / touchdown_time"), std::string::npos) << r.output;
}

// Runs a one-target test scenario with the ballistic policy, expects its jump
// to be rejected before anything was simulated (exit 4) and returns the jump's
// failure reason ("" after a failed expectation); the run's output in *output.
std::string rejectedReason(const std::string& scenario, const std::string& out_name, std::string* output = nullptr) {
  const std::string dir = outDir(out_name);
  const CommandRun r = pronk("run " + testScenario(scenario) + " --policy ballistic --out " + dir);
  if (output) *output = r.output;
  EXPECT_EQ(r.status, 4) << r.output;  // an episode did not succeed
  const nlohmann::json j = results(dir);
  EXPECT_EQ(j.size(), 1u) << r.output;
  if (j.size() != 1u) return "";
  EXPECT_EQ(j[0]["status"], "rejected");
  EXPECT_EQ(j[0]["simulated_s"].get<double>(), 0.0);  // nothing was simulated
  EXPECT_EQ(j[0]["trace"], "");
  EXPECT_DOUBLE_EQ(j[0]["reward"].get<double>(), 0.0);
  return j[0]["failure_reason"].get<std::string>();
}

TEST(JumpRuns, JumpBeyondTheMotorsIsRejectedWithThePredictedTorque) {
  // A Go1 with a fifth of its effort limits: the planner's torque prediction
  // finds no push the motors can give, and the forward jump is refused for that
  // reason, naming the joint, before it runs (with a quarter the planner finds a
  // slower push that fits).
  std::string output;
  const std::string reason = rejectedReason("go1_weak_motors.xml", "jump_weak_motors", &output);
  EXPECT_EQ(reason.rfind("torque: ", 0), 0u) << reason;
  EXPECT_NE(reason.find(" would need "), std::string::npos) << reason;
  EXPECT_NE(output.find("simulated nothing"), std::string::npos) << output;
}

TEST(JumpRuns, ImpossibleUpJumpIsRejectedBeforeAnythingRunsWithThePlannersReason) {
  const std::string reason = rejectedReason("go1_impossible_up.xml", "jump_impossible_up");
  EXPECT_EQ(reason.rfind("action_range: ", 0), 0u) << reason;
  EXPECT_NE(reason.find("exceeds k_max x the Bezier speed cap"), std::string::npos) << reason;
}

// Onto a 0.3 m box whose edge lies 11 cm and 2 cm ahead of the front feet: the
// planner finds no push that keeps the hips and legs above the edge, so each jump
// is refused before it runs (the 2 cm one naming the edge); neither strikes it.
TEST(JumpRuns, ABoxJustAheadOfTheFeetIsRefusedNotStruck) {
  std::string reason = rejectedReason("go1_box_2cm.xml", "jump_box_2cm");
  EXPECT_EQ(reason.rfind("terrain: the thrust carries the hips over the edge 0.2", 0), 0u) << reason;
  EXPECT_NE(reason.find("(top 0.3 m)"), std::string::npos) << reason;
  reason = rejectedReason("go1_box_11cm.xml", "jump_box_11cm");
  EXPECT_FALSE(reason.empty());
}

TEST(JumpRuns, AWallThatCannotBeClearedIsRefusedNamingItsEdge) {
  const std::string reason = rejectedReason("go1_wall.xml", "jump_wall");
  EXPECT_EQ(reason.rfind("terrain: the flight passes the edge 0.45", 0), 0u) << reason;  // the face nearer the start
  EXPECT_NE(reason.find("(top 1.2 m)"), std::string::npos) << reason;
  EXPECT_NE(reason.find("too low for the tucked legs"), std::string::npos) << reason;
}

// Down and sideways off a 0.4 m box from 3 cm behind its edge
// (go1_off_box_sideways.xml). Turning 45 deg on the way down, the trailing legs
// swing off the box for the landing, and the jump lands, whether the planner or
// the Go1 policy's aim asked for it. Turning 90 deg to a nearer spot, they would
// come down on the box: the planner finds no plan, and its best try is refused
// for the planner's reason, naming the box the robot stands on. Straight down
// the policy lands.
TEST(JumpRuns, OffABoxSidewaysWhatCannotClearTheEdgeIsRefusedNotFlown) {
  for (const std::string policy : {std::string("ballistic"), source("assets/policies/go1_omni.json")}) {
    const std::string dir = outDir(policy == "ballistic" ? "off_box_sideways_planner" : "off_box_sideways_policy");
    const CommandRun r = pronk("run " + testScenario("go1_off_box_sideways.xml") + " --policy " + policy +
                               " --jobs 2 --out " + dir);
    const nlohmann::json j = results(dir);
    ASSERT_EQ(j.size(), 5u) << r.output;
    EXPECT_EQ(j[3]["status"], "ok") << policy << ": " << j[3].dump().substr(0, 600);
    const nlohmann::json& turning = j[4];
    EXPECT_EQ(turning["status"], "rejected") << policy << ": " << turning.dump().substr(0, 600);
    EXPECT_EQ(turning["simulated_s"].get<double>(), 0.0);
    const std::string reason = turning["failure_reason"].get<std::string>();
    EXPECT_EQ(reason.rfind("terrain: ", 0), 0u) << reason;
    EXPECT_NE(reason.find("(top 0 m)"), std::string::npos) << reason;  // the box the robot stands on
    if (policy != "ballistic") {
      for (int i : {0, 2}) EXPECT_EQ(j[i]["status"], "ok") << j[i].dump().substr(0, 600);
    }
  }
}

TEST(JumpRuns, PluginWarningsGoToEachJumpsEventsAndOnlyTheFirstTenToStderr) {
  const std::string dir = outDir("many_infeasible");
  const CommandRun r = pronk("run " + testScenario("go1_many_infeasible.xml") + " --policy ballistic --jobs 2 --out " +
                             dir);
  EXPECT_EQ(r.status, 4) << r.output;
  size_t printed = 0;
  for (size_t at = r.output.find("plugin warning: "); at != std::string::npos;
       at = r.output.find("plugin warning: ", at + 1)) {
    ++printed;
  }
  EXPECT_EQ(printed, 10u) << r.output;
  EXPECT_NE(r.output.find("plugin: further info and warning lines are not printed"), std::string::npos) << r.output;
  const nlohmann::json jumps = results(dir);
  ASSERT_TRUE(jumps.is_array() && jumps.size() == 14u) << r.output;
  const auto warnings = [](const nlohmann::json& jump) {
    int n = 0;
    for (const nlohmann::json& e : jump["event_log"]) {
      n += e["name"] == "plugin_warning" && e["detail"].get<std::string>().find("no feasible jump") != std::string::npos;
    }
    return n;
  };
  for (const nlohmann::json& jump : jumps) {
    EXPECT_EQ(jump["status"], "rejected");
    EXPECT_EQ(warnings(jump), 1) << jump["event_log"].dump();
  }
  // An aim correction asks the planner for its aim first, then falls back to the
  // target: the warning is the episode's, said once.
  const std::string aimed = outDir("many_infeasible_aim");
  pronk("run " + testScenario("go1_many_infeasible.xml") + " --policy " +
        source("tests/training/policies/aim_offset_3cm.json") + " --jobs 2 --out " + aimed);
  const nlohmann::json aimed_jumps = results(aimed);
  ASSERT_TRUE(aimed_jumps.is_array() && aimed_jumps.size() == 14u);
  for (const nlohmann::json& jump : aimed_jumps) EXPECT_EQ(warnings(jump), 1) << jump["event_log"].dump();
}

TEST(JumpRuns, SweepCasesAreSeededAndReproducible) {
  const std::string a = outDir("jump_sweep_a"), b = outDir("jump_sweep_b");
  const CommandRun ra = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --out " + a);
  const CommandRun rb = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --out " + b);
  const nlohmann::json ja = results(a), jb = results(b);
  ASSERT_EQ(ja.size(), 2u) << ra.output;
  ASSERT_EQ(jb.size(), 2u) << rb.output;
  for (size_t i = 0; i < 2; ++i) {
    const double x = ja[i]["target"]["x"].get<double>();
    EXPECT_GE(x, 0.1);
    EXPECT_LE(x, 0.4);
    EXPECT_EQ(ja[i]["target"], jb[i]["target"]);
    // The same case simulates the same way.
    EXPECT_EQ(ja[i]["landing"], jb[i]["landing"]);
  }
  EXPECT_NE(ja[0]["target"]["x"], ja[1]["target"]["x"]);
  const CommandRun bad = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep nope");
  EXPECT_EQ(bad.status, 3) << bad.output;
  EXPECT_NE(bad.output.find("no sweep named 'nope'; known: ahead"), std::string::npos) << bad.output;
}

TEST(JumpRuns, SeedOverridesARandomSweepsSeedAndOnlyThat) {
  // --seed 7 is the file's own seed: the same cases; another seed draws others.
  const std::string same = outDir("jump_seed_same"), other = outDir("jump_seed_other"), file = outDir("jump_seed_file");
  pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --out " + file);
  const CommandRun rs = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --seed 7 --out " + same);
  const CommandRun ro = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --seed 8 --out " + other);
  const nlohmann::json jf = results(file), js = results(same), jo = results(other);
  ASSERT_EQ(js.size(), 2u) << rs.output;
  ASSERT_EQ(jo.size(), 2u) << ro.output;
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(jf[i]["target"], js[i]["target"]);
    EXPECT_NE(jf[i]["target"], jo[i]["target"]);
    EXPECT_GE(jo[i]["target"]["x"].get<double>(), 0.1);
    EXPECT_LE(jo[i]["target"]["x"].get<double>(), 0.4);
  }
  // Without --sweep there is nothing to reseed (usage, 2); a sweep without a seed is named at its line (3).
  const CommandRun alone = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --seed 8");
  EXPECT_EQ(alone.status, 2) << alone.output;
  EXPECT_NE(alone.output.find("--sweep"), std::string::npos) << alone.output;
  const CommandRun vary = pronk("run " + testScenario("go1_rollout_mix.xml") + " --policy ballistic --sweep mass --seed 8");
  EXPECT_EQ(vary.status, 3) << vary.output;
  EXPECT_NE(vary.output.find("go1_rollout_mix.xml:19: --seed 8: sweep 'mass' is not a <random> sweep"), std::string::npos)
      << vary.output;
}

TEST(JumpRuns, ResultsSayWhatTheRunWasAndTheTableKeepsOneRowPerJump) {
  // A motor=dc run must not read like a default one: results.json carries the
  // version, the command, the resolved parameters, the policy and the seed.
  const std::string dir = outDir("jump_provenance");
  const CommandRun r = pronk("run " + testScenario("go1_sweep.xml") + " --policy ballistic --sweep ahead --seed 9 "
                             "--param motor=dc --out " + dir);
  const nlohmann::json run = runOf(dir);
  ASSERT_TRUE(run.is_object()) << r.output;
  EXPECT_EQ(run["pronk_version"], PRONK_PROJECT_VERSION);
  EXPECT_TRUE(run["git_commit"].is_string());
  EXPECT_NE(run["command"].get<std::string>().find("--param motor=dc"), std::string::npos) << run.dump(1);
  EXPECT_EQ(run["parameters"]["motor"], "dc");
  EXPECT_EQ(run["parameters"]["kp"], "100");  // a default, resolved
  EXPECT_EQ(run["policy"], "ballistic");
  EXPECT_EQ(run["sweep"], "ahead");
  EXPECT_EQ(run["seed"], 9);
  EXPECT_EQ(run["environment"], "jump");
  // The console table, over landed, refused and failed jumps (the mix sweep): a
  // legend for the paired columns, one markdown row per jump with as many cells
  // as the header, a reason in the refused and failed rows, and no nan anywhere.
  const CommandRun mix = pronk("run " + testScenario("go1_rollout_mix.xml") + " --policy ballistic --sweep mix");
  EXPECT_NE(mix.output.find("| rejected |"), std::string::npos) << mix.output;
  EXPECT_NE(mix.output.find("| failed   |"), std::string::npos) << mix.output;
  EXPECT_NE(mix.output.find("|     -     -     -      - |      - |"), std::string::npos) << mix.output;
  EXPECT_NE(r.output.find("paired columns, planned / detected: lift-off s: planned_lift_off_time / lift_off"),
            std::string::npos) << r.output;
  EXPECT_FALSE(std::regex_search(mix.output, std::regex(R"(\bnan\b)"))) << mix.output;
  std::istringstream lines(mix.output);
  size_t header_cells = 0, rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("|", 0) != 0) continue;
    const size_t cells = std::count(line.begin(), line.end(), '|');
    if (!header_cells) header_cells = cells;
    EXPECT_EQ(cells, header_cells) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2u + 6u) << mix.output;  // header, rule, six jumps
}

TEST(JumpRuns, PolicyNeedsAnEnvironment) {
  const CommandRun r = pronk("run " + source("scenarios/go1/stand.xml") + " --policy ballistic");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("has no <environment>"), std::string::npos) << r.output;
  const CommandRun none = pronk("run " + source("scenarios/go1/forward.xml"));
  EXPECT_EQ(none.status, 3) << none.output;
  EXPECT_NE(none.output.find("--policy ballistic"), std::string::npos) << none.output;
}

}  // namespace

namespace {

TEST(JumpRuns, PolicyFileDrivesTheEnvironment) {
  const std::string dir = outDir("jump_policy_file");
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " +
                             std::string(PRONK_CLI_TEST_DIR) + "/policies/mid_range.json --out " + dir);
  EXPECT_TRUE(r.status == 0 || r.status == 4) << r.output;  // it jumps somewhere; the fixture is not trained
  const nlohmann::json j = results(dir);
  ASSERT_EQ(j.size(), 1u) << r.output;
  const std::vector<double> action = j[0]["action"].get<std::vector<double>>();
  ASSERT_EQ(action.size(), 13u);
  EXPECT_DOUBLE_EQ(action[0], -2.5);  // the network's output reached the environment unchanged
  for (size_t i = 1; i < 13; ++i) EXPECT_DOUBLE_EQ(action[i], 0.0);
  // raw -2.5 of +-5 is a quarter of the way into T_th's range [0.4, 1.0] s
  EXPECT_NEAR(j[0]["metrics"]["action_thrust_duration"].get<double>(), 0.55, 1e-9);
}

TEST(JumpRuns, PolicyFileOfTheWrongShapeIsABadInput) {
  const std::string file = std::string(PRONK_CLI_TEST_DIR) + "/policies/wrong_size.json";
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + file);
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find(file + ": the policy maps 5 numbers to 13"), std::string::npos) << r.output;
  const CommandRun missing = pronk("run " + source("scenarios/go1/forward.xml") + " --policy /nonexistent/p.json");
  EXPECT_EQ(missing.status, 3) << missing.output;
  EXPECT_NE(missing.output.find("/nonexistent/p.json"), std::string::npos) << missing.output;
}

}  // namespace

namespace {

TEST(JumpRuns, AShippedPolicyWithOneWeightChangedIsRefusedByItsChecksum) {
  std::ifstream in(source("assets/policies/go1_flat_aim.json"));
  std::stringstream text;
  text << in.rdbuf();
  std::string changed = text.str();
  const std::size_t row = changed.find("\"weights\": [\n        [");
  ASSERT_NE(row, std::string::npos);
  const std::size_t digit = changed.find_first_of("123456789", row + 24);
  changed[digit] = changed[digit] == '9' ? '8' : static_cast<char>(changed[digit] + 1);
  const std::string dir = outDir("changed_policy");
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/changed.json";
  std::ofstream(file) << changed;
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + file + " --out " + dir + "/out");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find(file + ":"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(": checksum: sha256:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the file was changed after it was written"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/results.json"));
}

TEST(JumpRuns, ControllerFlagRunsAControllerInsteadOfTheEnvironment) {
  // forward.xml has an <environment> and no <controller>: --controller still runs one.
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --controller stand --duration 0.2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("controller stand"), std::string::npos) << r.output;
}

// The largest amount (N m) by which a jump trace's torques leave the Go1's DC
// motor range at the traced joint speeds (effort 23.7, 23.7, 35.55 N m; no-load
// speed 30.1, 30.1, 20.06 rad/s: the URDF's limits).
double worstExcessOverGo1DcMotors(const std::string& trace_path) {
  std::ifstream trace(trace_path);
  std::string line;
  std::getline(trace, line);
  std::vector<std::string> names;
  for (std::stringstream in(line); in.good();) names.emplace_back(), std::getline(in, names.back(), ',');
  struct Joint {
    size_t tau, qd;
    double effort, speed;
  };
  std::vector<Joint> joints;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i].rfind("tau_", 0) != 0) continue;
    const std::string joint = names[i].substr(4);
    const bool calf = joint.find("calf") != std::string::npos;
    for (size_t k = 0; k < names.size(); ++k) {
      if (names[k] == "qd_" + joint) joints.push_back({i, k, calf ? 35.55 : 23.7, calf ? 20.06 : 30.1});
    }
  }
  EXPECT_EQ(joints.size(), 12u) << line;
  double worst = 0.0;
  while (std::getline(trace, line)) {
    std::vector<double> v;
    for (std::stringstream in(line); in.good();) {
      std::string cell;
      std::getline(in, cell, ',');
      v.push_back(cell.empty() ? 0.0 : std::stod(cell));
    }
    for (const Joint& j : joints) {
      const double w = v[j.qd] / j.speed, tau = v[j.tau];
      const double upper = std::clamp(j.effort * (1.0 - w), 0.0, j.effort);
      const double lower = std::clamp(j.effort * (-1.0 - w), -j.effort, 0.0);
      worst = std::max({worst, tau - upper, lower - tau});
    }
  }
  return worst;
}

TEST(JumpRuns, DcMotorKeepsEveryTorqueOnItsTorqueSpeedLine) {
  // The diagonal jump with the effort box (diagonal.xml) drives a joint beyond
  // what a DC motor delivers at its speed; with `motor` dc every torque of the
  // run stays inside the torque-speed line, and the jump still lands within the
  // file's 5 cm and 12 deg (measured 3.6 cm, 6.5 deg; docs/results.md).
  std::string box_dir, dc_dir;
  const nlohmann::json box = onlyJump("scenarios/go1/diagonal.xml", "jump_diagonal_effort_box", &box_dir);
  const nlohmann::json dc = onlyJump("tests/dev/go1/diagonal_dc_motor.xml", "jump_diagonal_dc_motor", &dc_dir);
  ASSERT_FALSE(box.is_null() || dc.is_null());
  EXPECT_GT(worstExcessOverGo1DcMotors(box_dir + "/" + box["trace"].get<std::string>()), 1.0);
  EXPECT_LT(worstExcessOverGo1DcMotors(dc_dir + "/" + dc["trace"].get<std::string>()), 1e-4);
  EXPECT_EQ(dc["status"], "ok");
  EXPECT_LT(dc["error_xy"].get<double>(), 0.05);
}

// An episode whose duration (0.75 s) ends in the flight (lift-off near 0.65 s,
// touchdown near 0.85 s) is not cut off in the air: it runs on until the
// landing has its gains back, 0.3 s after the touchdown, and the jump lands.
// One that ends before the lift-off ends there (DurationFlagSetsTheEpisodeLength).
TEST(JumpRuns, AFlightInTheAirAtTheDurationIsNotCutOff) {
  const std::string out = outDir("jump_short_duration");
  const CommandRun r =
      pronk("run " + source("scenarios/go1/forward.xml") + " --policy ballistic --param duration=0.75 --out " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  EXPECT_EQ(j[0]["status"], "ok") << j[0].dump().substr(0, 600);
  ASSERT_TRUE(j[0]["events"]["lift_off"].is_number()) << j[0]["events"].dump();
  ASSERT_TRUE(j[0]["events"]["touchdown"].is_number()) << j[0]["events"].dump();
  EXPECT_LT(j[0]["events"]["lift_off"].get<double>(), 0.75);
  const double touchdown = j[0]["events"]["touchdown"].get<double>();
  EXPECT_GT(touchdown, 0.75);
  EXPECT_NEAR(j[0]["simulated_s"].get<double>(), touchdown + 0.3, 2e-3);
}

TEST(JumpRuns, ParamFlagSetsAnEnvironmentParameter) {
  // The up-jump runs with the effort box (up.xml). With --param motor=dc its
  // calves would turn near their 20 rad/s no-load speed; even the planner's
  // lowest, longest pushes leave the lift-off more than the torque check's
  // 0.1 m/s short, so the planner finds no plan, the jump is refused before it
  // runs for the planner's reason, and the safety filter's predicted shortfall
  // is reported.
  const std::string out = outDir("jump_param_dc_motor");
  const CommandRun r = pronk("run " + source("scenarios/go1/up.xml") + " --policy ballistic --param motor=dc --out " + out);
  EXPECT_EQ(r.status, 4) << r.output;  // no jump landed
  EXPECT_NE(r.output.find("parameters  motor=dc (--param, over the scenario's)"), std::string::npos) << r.output;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  EXPECT_EQ(j[0]["status"], "rejected");
  const std::string reason = j[0]["failure_reason"].get<std::string>();
  EXPECT_EQ(reason.rfind("torque: ", 0), 0u) << reason;
  EXPECT_NE(reason.find("slower than planned (allowed 0.1)"), std::string::npos) << reason;
  ASSERT_TRUE(j[0]["metrics"].contains("predicted_speed_shortfall")) << j[0]["metrics"].dump();
  EXPECT_GT(j[0]["metrics"]["predicted_speed_shortfall"].get<double>(), 0.1);
  // The same jump with the effort box is predicted to lose nothing.
  const std::string box_out = outDir("jump_param_effort_box");
  pronk("run " + source("scenarios/go1/up.xml") + " --policy ballistic --out " + box_out);
  const nlohmann::json box = results(box_out);
  ASSERT_TRUE(box.is_array() && box.size() == 1u);
  EXPECT_EQ(box[0]["metrics"]["predicted_speed_shortfall"].get<double>(), 0.0);
  // Bad settings are reported against the flag.
  const CommandRun unknown = pronk("run " + source("scenarios/go1/up.xml") + " --policy ballistic --param motr=dc");
  EXPECT_EQ(unknown.status, 3) << unknown.output;
  EXPECT_NE(unknown.output.find("--param: unknown parameter 'motr'"), std::string::npos) << unknown.output;
  const CommandRun malformed = pronk("run " + source("scenarios/go1/up.xml") + " --policy ballistic --param motor");
  EXPECT_EQ(malformed.status, 2) << malformed.output;
  EXPECT_NE(malformed.output.find("--param: 'motor': expected NAME=VALUE"), std::string::npos) << malformed.output;
}

TEST(JumpRuns, DurationFlagSetsTheEpisodeLength) {
  // In a jump run the environment's `duration` parameter owns the episode
  // length; --duration overrides it (here 0.4 s: the thrust, no lift-off yet,
  // so the jump misses the file's 5 cm tolerance: exit 4).
  const std::string out = outDir("jump_duration_flag");
  const CommandRun r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy ballistic --duration 0.4 --out " + out);
  EXPECT_EQ(r.status, 4) << r.output;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 1u) << r.output;
  EXPECT_NEAR(j[0]["simulated_s"].get<double>(), 0.4, 2e-3);
  EXPECT_TRUE(j[0]["events"]["lift_off"].is_null()) << j[0]["events"].dump();
  // A value the environment refuses is reported against the flag, not the file.
  const CommandRun bad = pronk("run " + source("scenarios/go1/forward.xml") + " --policy ballistic --duration 100");
  EXPECT_EQ(bad.status, 3) << bad.output;
  EXPECT_NE(bad.output.find("--duration: parameter 'duration' of environment 'jump': 100 is out of range"),
            std::string::npos)
      << bad.output;
}

TEST(JumpRuns, ACaseWithNoRoomForItsEdgeIsRefusedByValidateAndAloneInARun) {
  const std::string file = testScenario("go1_case_without_room.xml");
  const CommandRun v = pronk("validate " + file);
  EXPECT_EQ(v.status, 3) << v.output;
  EXPECT_NE(v.output.find("go1_case_without_room.xml:9: target straight_up: target z = 0.2"), std::string::npos)
      << v.output;
  const std::string out = outDir("jump_case_without_room");
  const CommandRun r = pronk("run " + file + " --policy ballistic --out " + out);
  EXPECT_EQ(r.status, 4) << r.output;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array() && j.size() == 2u) << r.output;
  EXPECT_EQ(j[0]["status"], "ok");
  // Refused as an infeasible jump is, with its reason, not counted as a failure.
  EXPECT_EQ(j[1]["status"], "rejected");
  EXPECT_EQ(j[1]["failure_reason"].get<std::string>().rfind("terrain: ", 0), 0u) << j[1]["failure_reason"];
  EXPECT_NE(j[1]["failure_reason"].get<std::string>().find("needs a platform edge"), std::string::npos);
  EXPECT_NE(r.output.find("1 rejected before running, 0 failed"), std::string::npos) << r.output;
}

TEST(JumpRuns, AnInterruptedSweepKeepsEveryFinishedJump) {
  // SIGINT two seconds into the 40-target region sweep on one thread: the
  // running jump finishes, the summary and the files of every finished jump
  // are written, the exit status is 130; an earlier run's files are gone.
  const std::string out = outDir("jump_interrupted");
  std::filesystem::create_directories(out);
  std::ofstream(out + "/jump-999.csv") << "stale\n";
  const std::string command = "sh -c '" + std::string(PRONK_EXE) + " run " + source("scenarios/go1/region.xml") +
                              " --policy ballistic --sweep region --jobs 1 --out " + out +
                              " > " + out + "/log.txt 2>&1 & pid=$!; sleep 2; kill -INT $pid; wait $pid; echo $?'";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char text[64] = "";
  ASSERT_NE(fgets(text, sizeof text, pipe), nullptr);
  pclose(pipe);
  EXPECT_EQ(std::atoi(text), 130) << text;
  const nlohmann::json j = results(out);
  ASSERT_TRUE(j.is_array()) << out;
  EXPECT_GT(j.size(), 0u);
  EXPECT_LT(j.size(), 40u);
  for (size_t i = 0; i < j.size(); ++i) EXPECT_EQ(j[i]["case"], "region #" + std::to_string(i));
  std::ifstream csv(out + "/results.csv");
  size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, j.size() + 1);  // the header and one row per finished jump
  EXPECT_FALSE(std::filesystem::exists(out + "/jump-999.csv"));
  EXPECT_FALSE(std::filesystem::exists(out + "/results.json.partial"));
}

}  // namespace

namespace {

// Issue 19: the shipped policy of a robot runs every jump scenario of that
// robot (each target once; a file with only sweeps runs its start pose): no
// file, robot or policy error, every jump judged.
TEST(JumpRuns, TheShippedOmniPoliciesRunEveryJumpScenarioOfTheirRobot) {
  for (const std::string robot : {"go1", "aliengo"}) {
    const std::string policy = source("assets/policies/" + robot + "_omni.json");
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(source("scenarios/" + robot))) {
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      if (entry.path().extension() != ".xml" || text.str().find("jump_environment.xml") == std::string::npos) continue;
      ++files;
      const std::string out = outDir("shipped_" + robot + "_" + entry.path().stem().string());
      const CommandRun r = pronk("run " + entry.path().string() + " --policy " + policy + " --jobs 2 --out " + out);
      EXPECT_TRUE(r.status == 0 || r.status == 4) << entry.path() << "\n" << r.output;  // 4: a jump failed or missed
      const nlohmann::json jumps = results(out);
      ASSERT_TRUE(jumps.is_array() && !jumps.empty()) << entry.path() << "\n" << r.output;
      for (const nlohmann::json& j : jumps) {
        const std::string reason = j["failure_reason"].get<std::string>();
        EXPECT_EQ(reason.rfind("error:", 0), std::string::npos) << entry.path() << ": " << reason;
        EXPECT_EQ(reason.rfind("setup:", 0), std::string::npos) << entry.path() << ": " << reason;
      }
    }
    EXPECT_GE(files, 8) << robot;
  }
}

}  // namespace
