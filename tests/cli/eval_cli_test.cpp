// `pronk eval`: every set of a file through the command a user runs; the
// summary, the per-jump CSV and the figures; an earlier evaluation is never
// overwritten; --resume runs only what is left and ends where a whole run ends.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pronk_command.h"

namespace {

namespace fs = std::filesystem;
using pronk_test::pronk;

const std::string kSmall = pronk_test::cliScenario("go1_eval_small.xml");

std::string outDir(const std::string& name) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/" + name;
  fs::remove_all(dir);
  return dir;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json summary(const std::string& dir) {
  const std::string text = readFile(dir + "/summary.json");
  return text.empty() ? nlohmann::json() : nlohmann::json::parse(text);
}

std::vector<std::string> lines(const std::string& path) {
  std::vector<std::string> out;
  std::istringstream in(readFile(path));
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A jumps.csv line without its wall_s field (the 18th), which no two runs share.
std::string withoutWallTime(const std::string& line) {
  size_t start = 0;
  for (int field = 0; field < 17; ++field) start = line.find(',', start) + 1;
  return line.substr(0, start) + line.substr(line.find(',', start) + 1);
}

TEST(PronkEval, RunsEverySetAndWritesItsSummaryJumpsAndFigures) {
  const std::string out = outDir("eval_all");
  const pronk_test::Outcome r = pronk("eval " + kSmall + " --policy ballistic --jobs 2 --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json s = summary(out);
  ASSERT_TRUE(s.contains("sets")) << r.output;
  ASSERT_EQ(s["sets"].size(), 2u);
  const nlohmann::json& targets = s["sets"][0];
  const nlohmann::json& ahead = s["sets"][1];
  EXPECT_EQ(targets["set"], "go1_eval_small-targets");
  EXPECT_EQ(ahead["set"], "go1_eval_small-ahead");
  EXPECT_EQ(targets["summary"]["jumps"], 2);
  EXPECT_EQ(ahead["summary"]["jumps"], 12);
  EXPECT_TRUE(ahead["complete"].get<bool>());
  // Short jumps ahead: the planner lands every one within 0.2 m.
  EXPECT_EQ(ahead["summary"]["within_radius_share"].get<double>(), 1.0) << ahead.dump(2);
  EXPECT_LT(ahead["summary"]["error_m"]["median"].get<double>(), 0.05);
  EXPECT_EQ(ahead["plots"], nlohmann::json::array({"go1_eval_small-ahead/distance.png"}));
  EXPECT_TRUE(fs::file_size(out + "/go1_eval_small-ahead/distance.png") > 1000);
  EXPECT_TRUE(fs::exists(out + "/go1_eval_small-ahead/distance.gp"));
  EXPECT_EQ(lines(out + "/go1_eval_small-ahead/jumps.csv").size(), 13u);
  EXPECT_EQ(lines(out + "/go1_eval_small-ahead/jumps.jsonl").size(), 12u);
  EXPECT_NE(r.output.find("| go1_eval_small-ahead | 12 | 100.0 % |"), std::string::npos) << r.output;
}

TEST(PronkEval, NeverOverwritesAnEarlierEvaluation) {
  const std::string out = outDir("eval_twice");
  ASSERT_EQ(pronk("eval " + kSmall + " --sweep targets --policy ballistic --out " + out).status, 0);
  const std::string before = readFile(out + "/go1_eval_small-targets/jumps.jsonl");
  const pronk_test::Outcome again = pronk("eval " + kSmall + " --sweep targets --policy ballistic --out " + out);
  EXPECT_EQ(again.status, 3) << again.output;
  EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
  EXPECT_EQ(readFile(out + "/go1_eval_small-targets/jumps.jsonl"), before);
  // A resume with another policy is refused by the set's manifest, and the
  // finished evaluation's summary is left as it was.
  const std::string summary = readFile(out + "/summary.json");
  const pronk_test::Outcome other = pronk("eval " + kSmall + " --sweep targets --resume --out " + out + " --policy " +
                                          pronk_test::source("assets/policies/go1_flat_aim.json"));
  EXPECT_EQ(other.status, 3) << other.output;
  EXPECT_NE(other.output.find("set.json: written for policy \"ballistic\""), std::string::npos) << other.output;
  EXPECT_EQ(readFile(out + "/go1_eval_small-targets/jumps.jsonl"), before);
  EXPECT_EQ(readFile(out + "/summary.json"), summary);
}

TEST(PronkEval, AResumedRunDoesOnlyWhatIsLeftAndEndsAsAWholeRun) {
  const std::string whole = outDir("eval_whole"), cut = outDir("eval_cut");
  ASSERT_EQ(pronk("eval " + kSmall + " --sweep ahead --no-plots --policy ballistic --out " + whole).status, 0);
  // The state an interrupted run leaves: five finished jumps and a torn line.
  ASSERT_EQ(pronk("eval " + kSmall + " --sweep ahead --no-plots --policy ballistic --out " + cut).status, 0);
  const std::vector<std::string> log = lines(cut + "/go1_eval_small-ahead/jumps.jsonl");
  {
    std::ofstream rewrite(cut + "/go1_eval_small-ahead/jumps.jsonl", std::ios::trunc);
    for (int i = 0; i < 5; ++i) rewrite << log[i] << "\n";
    rewrite << log[5].substr(0, 40);
  }
  fs::remove(cut + "/summary.json");
  fs::remove(cut + "/go1_eval_small-ahead/jumps.csv");
  const pronk_test::Outcome resumed =
      pronk("eval " + kSmall + " --sweep ahead --no-plots --policy ballistic --resume --out " + cut);
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("12 jump(s), 5 done before (--resume)"), std::string::npos) << resumed.output;
  const std::vector<std::string> a = lines(whole + "/go1_eval_small-ahead/jumps.csv");
  const std::vector<std::string> b = lines(cut + "/go1_eval_small-ahead/jumps.csv");
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 1; i < a.size(); ++i) EXPECT_EQ(withoutWallTime(a[i]), withoutWallTime(b[i])) << i;
  EXPECT_EQ(summary(whole)["sets"][0]["summary"]["error_m"], summary(cut)["sets"][0]["summary"]["error_m"]);
}

TEST(PronkEval, FiguresThatCannotBeDrawnLoseNoResult) {
  // No gnuplot on the PATH: the set's jumps and summary are kept, the reason
  // is named, the exit status is 3; --resume draws the figures once it is back.
  const std::string out = outDir("eval_no_gnuplot");
  std::string output;
  FILE* pipe = popen(("PATH=/nonexistent " + std::string(PRONK_EXE) + " eval " + kSmall +
                      " --sweep ahead --policy ballistic --out " + out + " 2>&1; echo \"exit $?\"")
                         .c_str(),
                     "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  pclose(pipe);
  EXPECT_NE(output.find("exit 3"), std::string::npos) << output;
  EXPECT_NE(output.find("no figures"), std::string::npos) << output;
  EXPECT_NE(output.find("gnuplot"), std::string::npos) << output;
  const nlohmann::json s = summary(out);
  ASSERT_TRUE(s.contains("sets")) << output;
  EXPECT_EQ(s["sets"][0]["summary"]["jumps"], 12);
  EXPECT_TRUE(s["sets"][0].contains("plot_error"));
  EXPECT_EQ(lines(out + "/go1_eval_small-ahead/jumps.csv").size(), 13u);
  const pronk_test::Outcome again = pronk("eval " + kSmall + " --sweep ahead --policy ballistic --resume --out " + out);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("12 done before (--resume)"), std::string::npos) << again.output;
  EXPECT_TRUE(fs::exists(out + "/go1_eval_small-ahead/distance.png"));
}

TEST(PronkEval, BadInputIsNamedBeforeAnyJumpRuns) {
  const std::string out = outDir("eval_bad");
  const pronk_test::Outcome sweep = pronk("eval " + kSmall + " --sweep nowhere --policy ballistic --out " + out);
  EXPECT_EQ(sweep.status, 3) << sweep.output;
  EXPECT_NE(sweep.output.find(kSmall), std::string::npos) << sweep.output;
  EXPECT_FALSE(fs::exists(out));
  const pronk_test::Outcome radius = pronk("eval " + kSmall + " --radius nan --out " + out);
  EXPECT_EQ(radius.status, 2) << radius.output;
  EXPECT_NE(radius.output.find("--radius"), std::string::npos) << radius.output;
}

}  // namespace

namespace {

// `pronk check`: each <expect> bound is one result, a miss names its line and
// makes the exit status 4, and the JUnit report has one test case per bound.
// Each jump's row without its wall time, the one figure that differs between runs.
std::vector<nlohmann::json> rowsWithoutWallTime(const std::string& jsonl) {
  std::vector<nlohmann::json> rows;
  for (const std::string& line : lines(jsonl)) {
    nlohmann::json row = nlohmann::json::parse(line);
    row.erase("wall_s");
    rows.push_back(row);
  }
  return rows;
}

TEST(PronkEval, MpiRanksShareTheJumpsAndGiveWhatOneProcessGives) {
#ifndef PRONK_MPIEXEC
  GTEST_SKIP() << "built without MPI (PRONK_WITH_MPI off)";
#else
  // Two ranks of one thread each against one process of two threads: the same
  // rows to the last bit, in the same order (a jump's seed is its case index).
  const std::string ranks = outDir("eval_mpi_ranks"), threads = outDir("eval_mpi_threads");
  const std::string args = " eval " + kSmall + " --policy ballistic --no-plots";
  const pronk_test::Outcome m = pronk_test::shell(pronk_test::mpirunTwo() + args + " --jobs 1 --out " + ranks);
  ASSERT_EQ(m.status, 0) << m.output;
  EXPECT_NE(m.output.find("2 ranks"), std::string::npos) << m.output;
  const pronk_test::Outcome t = pronk(args.substr(1) + " --jobs 2 --out " + threads);
  ASSERT_EQ(t.status, 0) << t.output;
  for (const char* set : {"go1_eval_small-targets", "go1_eval_small-ahead"}) {
    const auto a = rowsWithoutWallTime(ranks + "/" + set + "/jumps.jsonl");
    const auto b = rowsWithoutWallTime(threads + "/" + set + "/jumps.jsonl");
    ASSERT_FALSE(a.empty()) << set;
    EXPECT_EQ(a, b) << set;
  }
  nlohmann::json a = summary(ranks)["sets"], b = summary(threads)["sets"];
  ASSERT_EQ(a.size(), 2u);
  for (nlohmann::json* sets : {&a, &b})
    for (nlohmann::json& set : *sets) set["summary"].erase("episode_wall_s");
  EXPECT_EQ(a, b);
  // An error rank 0 finds in --out ends every rank, with its message, once.
  const pronk_test::Outcome again = pronk_test::shell(pronk_test::mpirunTwo() + args + " --out " + ranks);
  EXPECT_EQ(again.status, 3) << again.output;
  const std::string message = "holds an earlier evaluation (summary.json)";
  const size_t first = again.output.find(message);
  ASSERT_NE(first, std::string::npos) << again.output;
  EXPECT_EQ(again.output.find(message, first + 1), std::string::npos) << again.output;
#endif
}

TEST(PronkEval, UnderMpirunOnlyEvalRuns) {
#ifndef PRONK_MPIEXEC
  GTEST_SKIP() << "built without MPI (PRONK_WITH_MPI off)";
#else
  // Every rank would run the whole jump and write the same files.
  const pronk_test::Outcome o = pronk_test::shell(pronk_test::mpirunTwo() + " run " +
                                                  pronk_test::source("scenarios/go1/forward.xml") + " --policy ballistic");
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("pronk run runs in one process; under mpirun only pronk eval and pronk train"), std::string::npos) << o.output;
#endif
}

TEST(PronkCheck, AMissNamesItsLineAndFailsTheRunWithAJUnitCasePerBound) {
  const std::string out = outDir("check_small");
  fs::create_directories(out);
  const std::string file = pronk_test::cliScenario("go1_check_small.xml");
  const pronk_test::Outcome r = pronk("check " + file + " --policy ballistic --junit " + out + "/report.xml");
  EXPECT_EQ(r.status, 4) << r.output;
  EXPECT_NE(r.output.find("ok   " + file + ":11: target forward: max_error <= 5.0 cm"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("MISS " + file + ":13: target left: max_error <= 0.1 cm: worst"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("6 expectation(s): 5 held, 1 missed"), std::string::npos) << r.output;
  const std::string junit = readFile(out + "/report.xml");
  EXPECT_NE(junit.find("<testsuites name=\"pronk check\" tests=\"6\" failures=\"1\">"), std::string::npos) << junit;
  size_t cases = 0, failures = 0;
  for (size_t at = junit.find("<testcase "); at != std::string::npos; at = junit.find("<testcase ", at + 1)) ++cases;
  for (size_t at = junit.find("<failure "); at != std::string::npos; at = junit.find("<failure ", at + 1)) ++failures;
  EXPECT_EQ(cases, 6u);
  EXPECT_EQ(failures, 1u);
}

TEST(PronkCheck, ExitsZeroWhenEveryBoundHolds) {
  const pronk_test::Outcome r = pronk("check " + pronk_test::cliScenario("go1_check_pass.xml") + " --policy ballistic");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2 expectation(s): 2 held, 0 missed"), std::string::npos) << r.output;
}

TEST(PronkCheck, AFileWithoutExpectationsIsAnError) {
  const pronk_test::Outcome r = pronk("check " + kSmall + " --policy ballistic");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("no <expectations>"), std::string::npos) << r.output;
}

}  // namespace
