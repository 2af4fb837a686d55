// `pronk train` and residual policies through the command a user runs: a
// residual with a zero head jumps exactly as the planner; a 2-iteration run
// writes a policy that `pronk run` takes; a resumed run equals an
// uninterrupted one; the result does not depend on --jobs; bad files give
// file:line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "pronk_command.h"  // tests/cli: running pronk as a user does

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using pronk_test::Outcome;
using pronk_test::pronk;
using pronk_test::source;
std::string here(const std::string& relative) { return std::string(PRONK_TRAINING_TEST_DIR) + "/" + relative; }
const std::string kTinyTraining = here("scenarios/go1_tiny_train.xml");
const std::string kTinyAimTraining = here("scenarios/go1_tiny_aim_train.xml");
const std::string kTinyAimMirrorTraining = here("scenarios/go1_tiny_aim_mirror_train.xml");
const std::string kTinyOversampleTraining = here("scenarios/go1_tiny_oversample_train.xml");
const std::string kTinyEdgesTraining = here("scenarios/go1_tiny_edges_train.xml");

std::string outDir(const std::string& name) {
  const std::string dir = std::string(PRONK_TRAINING_OUT_DIR) + "/" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  json j;
  if (in) in >> j;
  return j;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every value but those under the keys named (at any depth).
json without(json j, const std::vector<std::string>& keys) {
  if (j.is_object()) {
    for (const std::string& k : keys) j.erase(k);
    for (auto& item : j.items()) item.value() = without(item.value(), keys);
  } else if (j.is_array()) {
    for (auto& v : j) v = without(v, keys);
  }
  return j;
}

// A policy file without what differs between equal runs (command, wall time).
json policyContent(const std::string& path) {
  json p = readJson(path);
  EXPECT_TRUE(p.is_object()) << path;
  p.erase("provenance");  // wall time, command line
  p.erase("checksum");    // covers the provenance too
  return p;
}

TEST(ResidualPolicy, WithAZeroHeadJumpsExactlyAsThePlanner) {
  const std::string planner = outDir("residual_planner"), residual = outDir("residual_zero");
  const std::string scenario = source("scenarios/go1/mixed.xml");
  const Outcome a = pronk("run " + scenario + " --policy ballistic --jobs 2 --out " + planner);
  const Outcome b = pronk("run " + scenario + " --policy " + here("policies/zero_residual.json") + " --jobs 2 --out " +
                          residual);
  ASSERT_TRUE(a.status == 0 || a.status == 4) << a.output;
  EXPECT_EQ(b.status, a.status) << b.output;
  const json ja = readJson(planner + "/results.json")["jumps"], jb = readJson(residual + "/results.json")["jumps"];
  ASSERT_TRUE(ja.is_array() && ja.size() == 7u) << a.output;
  // Every number of every jump (actions, landings, metrics, rewards, events) but the wall times.
  EXPECT_EQ(without(ja, {"wall_s"}), without(jb, {"wall_s"}));
  EXPECT_NE(ja[0]["action"], json()) << "the results name the action";
}

// An aim correction with a zero head aims at the target itself: the planner's jumps exactly.
TEST(AimPolicy, WithAZeroHeadJumpsExactlyAsThePlanner) {
  const std::string planner = outDir("aim_planner"), aim = outDir("aim_zero");
  const std::string scenario = source("scenarios/go1/mixed.xml");
  const Outcome a = pronk("run " + scenario + " --policy ballistic --jobs 2 --out " + planner);
  const Outcome b = pronk("run " + scenario + " --policy " + here("policies/zero_aim.json") + " --jobs 2 --out " + aim);
  ASSERT_TRUE(a.status == 0 || a.status == 4) << a.output;
  EXPECT_EQ(b.status, a.status) << b.output;
  const json ja = readJson(planner + "/results.json")["jumps"], jb = readJson(aim + "/results.json")["jumps"];
  ASSERT_TRUE(ja.is_array() && ja.size() == 7u) << a.output;
  EXPECT_EQ(without(ja, {"wall_s"}), without(jb, {"wall_s"}));
}

// The shipped Go1 policy (docs/training.md) loads, says what it is and where it
// came from, and lands the forward jump within the file's tolerance (5 cm, 5 deg;
// measured 2.0 cm, 2.9 deg): the README's main job.
TEST(ShippedPolicy, Go1FlatAimLandsTheForwardJumpWithinItsTolerance) {
  const std::string file = source("assets/policies/go1_flat_aim.json");
  const json policy = readJson(file);
  ASSERT_TRUE(policy.is_object()) << file;
  EXPECT_EQ(policy["prior"], json({{"kind", "prior_action_at_aim"}, {"environment", "jump"}}));
  EXPECT_EQ(policy["provenance"]["robot"], "go1");
  EXPECT_EQ(policy["provenance"]["jumps"], 10240);
  EXPECT_EQ(policy["provenance"]["validation"]["seed"], 1001);
  const std::string dir = outDir("shipped_forward");
  const Outcome r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + file + " --out " + dir);
  EXPECT_EQ(r.status, 0) << r.output;
  const json results = readJson(dir + "/results.json")["jumps"];
  ASSERT_TRUE(results.is_array() && results.size() == 1u) << r.output;
  EXPECT_EQ(results[0]["status"], "ok");
}

TEST(ResidualPolicy, OverAnotherEnvironmentIsAnErrorNamingTheFile) {
  const std::string file = here("policies/residual_of_another_environment.json");
  const Outcome r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + file);
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find(file + ": a residual over environment 'walk''s prior_action; this scenario's environment "
                                 "is 'jump'"),
            std::string::npos)
      << r.output;
}

TEST(PronkTrain, TwoIterationsWriteAPolicyThatPronkRunTakes) {
  const std::string dir = outDir("train_smoke");
  const Outcome t = pronk("train " + kTinyTraining + " --out " + dir + "/policy.json --jobs 2");
  ASSERT_EQ(t.status, 0) << t.output;
  EXPECT_NE(t.output.find("iter    2/2  jumps      16  reward "), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("trained 2 iteration(s), 16 jumps"), std::string::npos) << t.output;
  // The mean penalties: their sum per jump and the largest three by name.
  const size_t second = t.output.find("iter    2/2");
  ASSERT_NE(second, std::string::npos) << t.output;
  EXPECT_NE(t.output.substr(second, t.output.find('\n', second) - second).find("  penalties "), std::string::npos)
      << t.output;

  const json policy = readJson(dir + "/policy.json");
  EXPECT_EQ(policy["version"], 3);
  EXPECT_EQ(policy["checksum"].get<std::string>().rfind("sha256:", 0), 0u);
  EXPECT_EQ(policy["prior"], json({{"kind", "prior_action"}, {"environment", "jump"}}));
  EXPECT_EQ(policy["layers"].size(), 3u);  // [32, 32] hidden
  EXPECT_EQ(policy["layers"][0]["weights"].size(), 32u);
  EXPECT_EQ(policy["provenance"]["jumps"], 16);
  EXPECT_EQ(policy["provenance"]["iterations"], 2);
  EXPECT_EQ(policy["provenance"]["seed"], 3);
  EXPECT_EQ(policy["provenance"]["robot"], "go1");
  EXPECT_EQ(policy["provenance"]["environment"], "jump");
  EXPECT_TRUE(policy["provenance"]["git_commit"].is_string()) << policy["provenance"].dump();
  EXPECT_EQ(policy["provenance"]["pronk_version"], PRONK_PROJECT_VERSION);
  EXPECT_EQ(policy["provenance"]["validation"]["iteration"], 2);
  EXPECT_EQ(policy["provenance"]["validation"]["count"], 3);

  // policy.train_log.csv: the header and rows 0 (the start's validation), 1 and 2.
  std::istringstream log(readText(dir + "/policy.train_log.csv"));
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(log, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << readText(dir + "/policy.train_log.csv");
  EXPECT_EQ(lines[0].rfind("iteration,iterations,jumps,batch_jumps,", 0), 0u);
  EXPECT_EQ(lines[1].rfind("0,2,0,", 0), 0u);
  EXPECT_EQ(lines[3].rfind("2,2,16,8,", 0), 0u);
  EXPECT_TRUE(std::filesystem::exists(dir + "/policy.train_curves.png")) << t.output;
  // A second run into the same folder keeps its own log; pronk plot names a log's
  // curves and their title after its policy.
  const std::string first_log = readText(dir + "/policy.train_log.csv");
  ASSERT_EQ(pronk("train " + kTinyTraining + " --iterations 1 --out " + dir + "/other.json --jobs 2").status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/other.train_log.csv"));
  EXPECT_EQ(readText(dir + "/policy.train_log.csv"), first_log);
  std::filesystem::remove(dir + "/policy.train_curves.png");
  const Outcome plot = pronk("plot " + dir + "/policy.train_log.csv");
  ASSERT_EQ(plot.status, 0) << plot.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/policy.train_curves.png")) << plot.output;
  EXPECT_NE(readText(dir + "/policy.train_curves.gp").find("policy"), std::string::npos);
  // Every penalty the jump environment declares has its column, after their sum.
  EXPECT_NE(lines[0].find(",eta_s,penalty_sum_mean,"), std::string::npos) << lines[0];
  for (const char* p : {"penalty_touchdown_bounce", "penalty_lift_off_orientation", "penalty_torque_saturation"}) {
    EXPECT_NE(lines[0].find(p), std::string::npos) << p;
  }
  EXPECT_EQ(std::count(lines[0].begin(), lines[0].end(), ','), std::count(lines[3].begin(), lines[3].end(), ','));
  EXPECT_EQ(lines[3].find(",nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan"), std::string::npos) << lines[3];
  const json checkpoint = readJson(dir + "/policy.checkpoint.json");
  EXPECT_EQ(checkpoint["format"], "pronk-train-checkpoint");
  EXPECT_EQ(checkpoint["iteration"], 2);

  const std::string run = outDir("train_smoke_run");
  const Outcome r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + dir + "/policy.json --out " + run);
  EXPECT_TRUE(r.status == 0 || r.status == 4) << r.output;  // a trained policy may miss; it must run
  const json results = readJson(run + "/results.json")["jumps"];
  ASSERT_TRUE(results.is_array() && results.size() == 1u) << r.output;
}

TEST(PronkTrain, ResumedRunEqualsAnUninterruptedOne) {
  const std::string whole = outDir("train_whole"), split = outDir("train_split");
  const Outcome a = pronk("train " + kTinyTraining + " --iterations 4 --jobs 2 --out " + whole + "/p.json");
  ASSERT_EQ(a.status, 0) << a.output;
  const Outcome b = pronk("train " + kTinyTraining + " --iterations 2 --jobs 2 --out " + split + "/p.json");
  ASSERT_EQ(b.status, 0) << b.output;
  const json halfway = policyContent(split + "/p.json");
  const Outcome c = pronk("train " + kTinyTraining + " --iterations 4 --jobs 2 --out " + split + "/p.json --resume " +
                          split + "/p.checkpoint.json");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("iter    4/4  jumps      32"), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find("iter    2/"), std::string::npos) << "the resumed run redid an iteration\n" << c.output;
  EXPECT_NE(halfway, policyContent(split + "/p.json"));  // it went on learning
  EXPECT_EQ(policyContent(whole + "/p.json"), policyContent(split + "/p.json"));
  // Everything a further resume needs, too: networks, Adam moments, std, streams.
  const json ca = readJson(whole + "/p.checkpoint.json"), cb = readJson(split + "/p.checkpoint.json");
  EXPECT_EQ(ca["ppo"], cb["ppo"]);
  EXPECT_EQ(ca["target_rng"], cb["target_rng"]);
  EXPECT_EQ(ca["noise_rng"], cb["noise_rng"]);
  EXPECT_EQ(ca["jumps"], 32);
  EXPECT_EQ(cb["jumps"], 32);
}

// A signal during the last iteration's validation leaves that iteration done
// and its row unvalidated; resuming runs the validation into that row, so the
// policy's provenance carries the end's figures, not an earlier iteration's.
TEST(PronkTrain, AValidationCutShortIsRunOnResuming) {
  const std::string dir = outDir("train_validation_cut");
  ASSERT_EQ(pronk("train " + kTinyTraining + " --jobs 2 --out " + dir + "/p.json").status, 0);
  const json finished = readJson(dir + "/p.json")["provenance"]["validation"];
  ASSERT_EQ(finished["iteration"], 2) << finished.dump();
  // The checkpoint as the signal leaves it: iteration 2 done, its row not validated.
  json checkpoint = readJson(dir + "/p.checkpoint.json");
  const std::vector<std::string> columns = checkpoint["log_columns"].get<std::vector<std::string>>();
  const size_t validated = static_cast<size_t>(std::find(columns.begin(), columns.end(), "validated") - columns.begin());
  ASSERT_LT(validated, columns.size());
  checkpoint["log"].back()[validated] = 0;
  std::ofstream(dir + "/p.checkpoint.json") << checkpoint.dump(1) << "\n";

  const Outcome resumed = pronk("train " + kTinyTraining + " --jobs 2 --out " + dir + "/p.json --resume " + dir +
                                "/p.checkpoint.json");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  const json validation = readJson(dir + "/p.json")["provenance"]["validation"];
  EXPECT_EQ(validation["iteration"], 2) << validation.dump();
  EXPECT_EQ(validation, finished);  // the same policy, the same fixed targets
  EXPECT_EQ(readJson(dir + "/p.checkpoint.json")["log"].back()[validated], 1);
}

// The aim correction with hindsight relabelling: the policy file says what it
// is, its checkpoint carries the hindsight pairs (the newest 12 of the jumps
// that ended standing), and a resumed run equals an uninterrupted one.
TEST(PronkTrain, AimCorrectionWithHindsightResumesBitForBit) {
  const std::string whole = outDir("train_aim_whole"), split = outDir("train_aim_split");
  const Outcome a = pronk("train " + kTinyAimTraining + " --iterations 4 --jobs 2 --out " + whole + "/p.json");
  ASSERT_EQ(a.status, 0) << a.output;
  const Outcome b = pronk("train " + kTinyAimTraining + " --iterations 2 --jobs 2 --out " + split + "/p.json");
  ASSERT_EQ(b.status, 0) << b.output;
  const Outcome c = pronk("train " + kTinyAimTraining + " --iterations 4 --jobs 1 --out " + split + "/p.json --resume " +
                          split + "/p.checkpoint.json");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_EQ(policyContent(whole + "/p.json"), policyContent(split + "/p.json"));
  const json ca = readJson(whole + "/p.checkpoint.json"), cb = readJson(split + "/p.checkpoint.json");
  EXPECT_EQ(ca["ppo"], cb["ppo"]);
  EXPECT_EQ(ca["hindsight"], cb["hindsight"]);

  const json policy = readJson(whole + "/p.json");
  EXPECT_EQ(policy["prior"], json({{"kind", "prior_action_at_aim"}, {"environment", "jump"}}));
  EXPECT_EQ(policy["layers"].back()["bias"].size(), 6u) << "an aim correction outputs an offset of the 6 observations";
  EXPECT_EQ(policy["provenance"]["guidance"]["aim"], true);
  EXPECT_EQ(policy["provenance"]["guidance"]["hindsight"], true);
  const json& pairs = ca["hindsight"]["observations"];
  ASSERT_TRUE(pairs.is_array());
  EXPECT_GT(pairs.size(), 0u) << "no jump of 32 ended standing";
  EXPECT_LE(pairs.size(), 12u);
  EXPECT_EQ(ca["hindsight"]["actions"].size(), pairs.size());
  EXPECT_NE(policy["layers"].back()["bias"], json(std::vector<double>(6, 0.0))) << "the hindsight fit changed nothing";
  // The log has the hindsight columns, and PPO's actor stood still: the std is the file's.
  const std::string log = readText(whole + "/p.train_log.csv");
  EXPECT_NE(log.find(",hindsight_pairs,hindsight_added,hindsight_loss,"), std::string::npos);
  EXPECT_NE(policy["action_log_std"], json()) << policy.dump().substr(0, 400);

  // pronk run takes it.
  const std::string run = outDir("train_aim_run");
  const Outcome r = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + whole + "/p.json --out " + run);
  EXPECT_TRUE(r.status == 0 || r.status == 4) << r.output;
  const json results = readJson(run + "/results.json")["jumps"];
  ASSERT_TRUE(results.is_array() && results.size() == 1u) << r.output;
}

// Training on real boxes: each case places its box's edge, and a target
// without room for one between the stances is drawn again, so that no case of
// the batch or the validation set fails to be set up.
TEST(PronkTrain, OnRealBoxesEveryCaseHasRoomForItsEdge) {
  const std::string dir = outDir("train_edges");
  const Outcome o = pronk("train " + kTinyEdgesTraining + " --jobs 2 --out " + dir + "/p.json");
  ASSERT_EQ(o.status, 0) << o.output;
  std::istringstream log(readText(dir + "/p.train_log.csv"));
  std::string header, row, last;
  std::getline(log, header);
  while (std::getline(log, row)) last = row;
  auto column = [](const std::string& line, const std::string& name, const std::string& names) {
    std::vector<std::string> keys, values;
    std::string cell;
    for (std::istringstream k(names); std::getline(k, cell, ',');) keys.push_back(cell);
    for (std::istringstream v(line); std::getline(v, cell, ',');) values.push_back(cell);
    const auto at = std::find(keys.begin(), keys.end(), name);
    return at == keys.end() || values.size() <= static_cast<size_t>(at - keys.begin())
               ? std::string("?")
               : values[at - keys.begin()];
  };
  EXPECT_EQ(column(last, "batch_jumps", header), "8") << last;
  EXPECT_EQ(column(last, "batch_setup_errors", header), "0") << last;
  EXPECT_EQ(column(last, "validation_jumps", header), "3") << last;
}

// Mirror guidance: each hindsight pair enters with its mirror image (y, yaw and
// roll, of the task and of the aim offset, negated), so pairs come in couples.
TEST(PronkTrain, MirrorGuidanceAddsTheMirrorImageOfEveryHindsightPair) {
  const std::string dir = outDir("train_aim_mirror");
  const Outcome o = pronk("train " + kTinyAimMirrorTraining + " --iterations 1 --jobs 2 --out " + dir + "/p.json");
  ASSERT_EQ(o.status, 0) << o.output;
  const json c = readJson(dir + "/p.checkpoint.json");
  const json& obs = c["hindsight"]["observations"];
  const json& act = c["hindsight"]["actions"];
  ASSERT_TRUE(obs.is_array() && act.is_array());
  ASSERT_GT(obs.size(), 0u) << "no jump of 8 ended standing";
  ASSERT_EQ(obs.size() % 2, 0u);
  const std::array<double, 6> signs = {1, -1, 1, -1, -1, 1};
  for (size_t k = 0; k < obs.size(); k += 2) {
    for (size_t i = 0; i < 6; ++i) {
      EXPECT_EQ(obs[k + 1][i].get<double>(), signs[i] * obs[k][i].get<double>()) << "pair " << k << ", task " << i;
      EXPECT_EQ(act[k + 1][i].get<double>(), signs[i] * act[k][i].get<double>()) << "pair " << k << ", aim " << i;
    }
  }
  EXPECT_EQ(readJson(dir + "/p.json")["provenance"]["guidance"]["mirror"], true);
}

// Oversampling: the targets that failed or were refused come back in later
// batches (half of each here), kept in the checkpoint so that a resumed run
// draws the same ones.
TEST(PronkTrain, OversamplingDrawsFailedAndRefusedTargetsAgain) {
  const std::string whole = outDir("train_oversample_whole"), split = outDir("train_oversample_split");
  const Outcome a = pronk("train " + kTinyOversampleTraining + " --iterations 3 --jobs 2 --out " + whole + "/p.json");
  ASSERT_EQ(a.status, 0) << a.output;
  const json c = readJson(whole + "/p.checkpoint.json");
  const json& hard = c["hard_targets"];
  ASSERT_TRUE(hard.is_array()) << c.dump().substr(0, 300);
  ASSERT_GT(hard.size(), 0u) << "no target of the far region was refused or failed";
  EXPECT_LE(hard.size(), 8u);
  for (const json& t : hard) {
    ASSERT_EQ(t.size(), 4u);
    EXPECT_GE(t[0].get<double>(), 0.8);
    EXPECT_LE(t[0].get<double>(), 1.8);
  }
  // The log's oversampled column: none in the first batch (nothing failed yet), half of the later ones.
  const std::string log = readText(whole + "/p.train_log.csv");
  std::istringstream lines(log);
  std::string header, row;
  std::getline(lines, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string name; std::getline(h, name, ',');) names.push_back(name);
  const size_t column = std::find(names.begin(), names.end(), "oversampled") - names.begin();
  ASSERT_LT(column, names.size()) << header;
  std::vector<std::string> values;
  while (std::getline(lines, row)) {
    std::stringstream r(row);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(r, cell, ',');) cells.push_back(cell);
    ASSERT_GT(cells.size(), column);
    values.push_back(cells[column]);
  }
  ASSERT_EQ(values.size(), 3u) << log;  // no validation row: <validation count="0">
  EXPECT_EQ(values[0], "0");
  EXPECT_EQ(values[2], "4");
  // Resumed after 2 iterations, the third draws the same targets again.
  ASSERT_EQ(pronk("train " + kTinyOversampleTraining + " --iterations 2 --jobs 1 --out " + split + "/p.json").status, 0);
  const Outcome b = pronk("train " + kTinyOversampleTraining + " --iterations 3 --jobs 2 --out " + split +
                          "/p.json --resume " + split + "/p.checkpoint.json");
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_EQ(readJson(split + "/p.checkpoint.json")["hard_targets"], hard);
  EXPECT_EQ(policyContent(whole + "/p.json"), policyContent(split + "/p.json"));
}

TEST(PronkTrain, DoesNotDependOnTheNumberOfJobs) {
  const std::string one = outDir("train_jobs_1"), two = outDir("train_jobs_2");
  const Outcome a = pronk("train " + kTinyTraining + " --jobs 1 --out " + one + "/p.json");
  const Outcome b = pronk("train " + kTinyTraining + " --jobs 2 --out " + two + "/p.json");
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_EQ(policyContent(one + "/p.json"), policyContent(two + "/p.json"));
  EXPECT_EQ(readJson(one + "/p.checkpoint.json")["ppo"], readJson(two + "/p.checkpoint.json")["ppo"]);
  EXPECT_NE(readJson(one + "/p.json")["layers"].back()["bias"],
            json(std::vector<double>(13, 0.0)))  // it learned something: the head is no longer zero
      << "the residual's head is still zero";
}

TEST(PronkTrain, MpiRanksRollOutAndGiveWhatOneProcessGives) {
#ifndef PRONK_MPIEXEC
  GTEST_SKIP() << "built without MPI (PRONK_WITH_MPI off)";
#else
  // Two ranks of one thread (rank 0 learns, both roll out) against one process
  // of two threads, with the aim correction, hindsight and oversampling (each
  // case's draw and the failed targets cross over): the same learner, buffer,
  // streams and log, to the last bit, also across a resume.
  const std::string ranks = outDir("train_mpi_ranks"), threads = outDir("train_mpi_threads");
  const std::string mpirun = pronk_test::mpirunTwo();
  const std::string file = " train " + kTinyOversampleTraining;
  Outcome m = pronk_test::shell(mpirun + file + " --jobs 1 --iterations 1 --out " + ranks + "/p.json");
  ASSERT_EQ(m.status, 0) << m.output;
  EXPECT_NE(m.output.find("2 ranks of 1 thread(s) each"), std::string::npos) << m.output;
  m = pronk_test::shell(mpirun + file + " --jobs 1 --out " + ranks + "/p.json --resume " + ranks + "/p.checkpoint.json");
  ASSERT_EQ(m.status, 0) << m.output;
  const Outcome t = pronk(file.substr(1) + " --jobs 2 --out " + threads + "/p.json");
  ASSERT_EQ(t.status, 0) << t.output;
  EXPECT_EQ(policyContent(ranks + "/p.json"), policyContent(threads + "/p.json"));
  const json a = readJson(ranks + "/p.checkpoint.json"), b = readJson(threads + "/p.checkpoint.json");
  for (const char* key : {"ppo", "hindsight", "hard_targets", "target_rng", "noise_rng", "jumps", "iteration"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }
  // The log, but for its timings and the first run's planned iterations (--iterations 1).
  ASSERT_EQ(a["log"].size(), b["log"].size());
  const json& columns = a["log_columns"];
  for (size_t r = 0; r < a["log"].size(); ++r) {
    for (size_t c = 0; c < columns.size(); ++c) {
      const std::string name = columns[c].get<std::string>();
      if (name == "iterations" || (name.size() > 2 && name.substr(name.size() - 2) == "_s")) continue;
      EXPECT_EQ(a["log"][r][c], b["log"][r][c]) << "row " << r << ", " << name;
    }
  }
#endif
}

TEST(PronkTrain, BadFilesAndOptionsAreErrorsThatSayWhere) {
  const std::string dir = outDir("train_errors");
  const std::string broken = source("tests/scenario/broken/training_yaw_range_reversed.xml");
  Outcome r = pronk("train " + broken + " --out " + dir + "/p.json");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find(broken + ":6: <region>: yaw: max (-90) must be >= min (90)"), std::string::npos) << r.output;

  r = pronk("train " + source("scenarios/go1/forward.xml") + " --out " + dir + "/p.json");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("no <training> element: nothing to train"), std::string::npos) << r.output;

  r = pronk("train " + kTinyTraining + " --jumps 1 --out " + dir + "/p.json");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("--jumps 1: must be >= the <ppo> minibatches (2)"), std::string::npos) << r.output;

  // A checkpoint continues only the run it was made by.
  r = pronk("train " + kTinyTraining + " --iterations 1 --jobs 2 --out " + dir + "/p.json");
  ASSERT_EQ(r.status, 0) << r.output;
  r = pronk("train " + kTinyTraining + " --iterations 2 --seed 4 --out " + dir + "/p.json --resume " + dir +
            "/p.checkpoint.json");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find(dir + "/p.checkpoint.json: settings.seed: 3, but this run has 4"), std::string::npos)
      << r.output;

  // A checkpoint from before <region flat_share> existed has no such setting:
  // its share was 0, and a run without one continues it.
  json old = readJson(dir + "/p.checkpoint.json");
  ASSERT_TRUE(old["settings"].contains("flat_share"));
  old["settings"].erase("flat_share");
  std::ofstream(dir + "/old.checkpoint.json") << old.dump();
  r = pronk("train " + kTinyTraining + " --iterations 2 --out " + dir + "/old.json --resume " + dir +
            "/old.checkpoint.json");
  EXPECT_EQ(r.status, 0) << r.output;
}

}  // namespace
