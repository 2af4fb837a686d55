// The guided_jump controller jumping, through the `pronk` command: a vertical jump
// in place and a forward jump, from scenario files with an `action` parameter.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "pronk_command.h"
#include <vector>

namespace {

std::string jumpScenario(const std::string& name) { return pronk_test::cliScenario(name); }

nlohmann::json runJump(const std::string& scenario, const std::string& name) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/" + name;
  std::filesystem::remove_all(dir);
  const pronk_test::Outcome o = pronk_test::pronk("run " + jumpScenario(scenario) + " --out " + dir);
  EXPECT_EQ(o.status, 0) << o.output;
  std::ifstream in(dir + "/results.json");
  EXPECT_TRUE(in.good()) << o.output;
  nlohmann::json j;
  if (in) in >> j;
  return j;
}

// Time of the first event `name` at or after `after`; -1 when there is none.
double eventTime(const nlohmann::json& j, const std::string& name, double after = -1.0) {
  for (const auto& e : j.at("events")) {
    if (e.at("name") == name && e.at("time").get<double>() >= after) return e.at("time").get<double>();
  }
  return -1.0;
}

struct JumpTimes {
  double thrust = -1, lift_off = -1, flight = -1, touchdown = -1, landing = -1;
};

// The phases in their order: thrust, lift_off, touchdown, landing.
JumpTimes checkJumpEvents(const nlohmann::json& j) {
  JumpTimes t;
  t.thrust = eventTime(j, "phase:thrust");
  EXPECT_NEAR(t.thrust, 0.2, 2e-3) << j.at("events").dump(1);  // start_delay
  t.lift_off = eventTime(j, "lift_off", t.thrust);
  t.flight = eventTime(j, "phase:flight", t.thrust);
  t.touchdown = eventTime(j, "touchdown", t.lift_off);
  t.landing = eventTime(j, "phase:landing", t.lift_off);
  EXPECT_GT(t.lift_off, t.thrust) << j.at("events").dump(1);
  EXPECT_GE(t.flight, t.lift_off) << j.at("events").dump(1);
  EXPECT_GT(t.touchdown, t.lift_off) << j.at("events").dump(1);
  EXPECT_GE(t.landing, t.touchdown) << j.at("events").dump(1);
  EXPECT_LT(t.landing, t.touchdown + 0.0025) << j.at("events").dump(1);  // the next control tick
  return t;
}

TEST(GuidedJumpCli, VerticalJumpLiftsOffAndLandsInPlace) {
  const auto j = runJump("go1_guided_jump_vertical.xml", "go1_guided_jump_vertical");
  ASSERT_TRUE(j.contains("events"));
  EXPECT_FALSE(j.at("failed").get<bool>()) << j.dump(1);
  const JumpTimes t = checkJumpEvents(j);
  // Plan: thrust 0.2 .. 0.65 s, lift-off at 1.6 m/s up (measured: lift-off 0.652 s,
  // touchdown 1.027 s, end trunk (-0.039, 0.000, 0.330) m).
  EXPECT_GT(t.lift_off, 0.60);
  EXPECT_LT(t.lift_off, 0.72);
  EXPECT_GT(t.touchdown - t.lift_off, 0.25);  // 1.6 m/s up: ~0.33 s ballistic
  const auto& end = j.at("end").at("trunk");
  EXPECT_NEAR(end[0].get<double>(), 0.0, 0.1);
  EXPECT_NEAR(end[1].get<double>(), 0.0, 0.05);
  EXPECT_NEAR(end[2].get<double>(), 0.33, 0.03);  // standing again
}

TEST(GuidedJumpCli, ForwardJumpLandsAhead) {
  const auto j = runJump("go1_guided_jump_forward.xml", "go1_guided_jump_forward");
  ASSERT_TRUE(j.contains("events"));
  EXPECT_FALSE(j.at("failed").get<bool>()) << j.dump(1);
  const JumpTimes t = checkJumpEvents(j);
  // Measured: lift-off 0.652 s, touchdown 1.044 s, end trunk (0.312, 0.001, 0.330) m.
  EXPECT_GT(t.lift_off, 0.60);
  EXPECT_LT(t.lift_off, 0.72);
  EXPECT_GT(t.touchdown - t.lift_off, 0.25);
  const auto& end = j.at("end").at("trunk");
  EXPECT_GT(end[0].get<double>(), 0.15);
  EXPECT_LT(end[0].get<double>(), 0.5);
  EXPECT_NEAR(end[1].get<double>(), 0.0, 0.05);
  EXPECT_NEAR(end[2].get<double>(), 0.33, 0.03);
}

TEST(GuidedJumpCli, ActionOfTheWrongLengthIsRefused) {
  const pronk_test::Outcome o = pronk_test::pronk("run " + jumpScenario("go1_guided_jump_bad_action.xml"));
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("'action' needs 13 numbers"), std::string::npos) << o.output;
}

}  // namespace
