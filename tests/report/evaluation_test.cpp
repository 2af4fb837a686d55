// Evaluation records: the summary counted as the paper counts, the jump log
// that a resumed run reads back (a torn last line dropped, a broken one named
// by its line), and a set directory that refuses to mix runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "pronk/evaluation.h"
#include "pronk/error.h"

namespace {

namespace fs = std::filesystem;
using pronk::JumpRow;

JumpRow row(size_t index, const std::string& status, double tx, double lx, double ly = 0) {
  JumpRow r;
  r.index = index;
  r.label = "case " + std::to_string(index);
  r.status = status;
  r.target_x = tx;
  if (status == "ok" || status == "missed") {
    r.landed_x = lx;
    r.landed_y = ly;
    r.error_xy = r.error = std::hypot(lx - tx, ly);
    r.error_yaw_deg = 2.0 * index;
    r.standing = true;
  }
  return r;
}

std::string tempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pronk_evaluation_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

TEST(SetSummary, CountsSharesOverEveryJumpAndErrorsOverTheLandedOnes) {
  // Landed errors 0.1, 0.3, 0.05 (one missed its tolerance: it landed); one
  // failure, one refusal.
  const std::vector<JumpRow> rows = {row(0, "ok", 0.5, 0.6), row(1, "missed", 1.0, 0.7), row(2, "ok", 0.2, 0.2, 0.05),
                                     row(3, "failed", 1.1, 0), row(4, "rejected", 1.2, 0)};
  const pronk::SetSummary s = pronk::summarize(rows, 0.2);
  EXPECT_EQ(s.jumps, 5u);
  EXPECT_EQ(s.landed, 3u);
  EXPECT_EQ(s.within, 2u);
  EXPECT_DOUBLE_EQ(s.withinShare(), 0.4);  // a failure or a refusal is not within
  EXPECT_EQ(s.failed, 1u);
  EXPECT_EQ(s.rejected, 1u);
  EXPECT_EQ(s.missed, 1u);
  EXPECT_NEAR(s.mean, (0.1 + 0.3 + 0.05) / 3, 1e-12);
  EXPECT_NEAR(s.median, 0.1, 1e-12);
  EXPECT_NEAR(s.max, 0.3, 1e-12);
  // Signed errors along x: +0.1, -0.3, 0 (the paper's e_x, mean and sample std).
  EXPECT_NEAR(s.error_x_mean, -0.2 / 3, 1e-12);
  const double m = -0.2 / 3;
  EXPECT_NEAR(s.error_x_std, std::sqrt(((0.1 - m) * (0.1 - m) + (-0.3 - m) * (-0.3 - m) + m * m) / 2), 1e-12);
  EXPECT_NEAR(s.error_y_mean, 0.05 / 3, 1e-12);
  EXPECT_NEAR(s.yaw_mean_deg, (0 + 2 + 4) / 3.0, 1e-12);
  EXPECT_NEAR(s.yaw_max_deg, 4.0, 1e-12);
  EXPECT_EQ(s.standing, 3u);
}

TEST(SetSummary, OfNoLandedJumpHasNoErrorsAndNoShareOfNothing) {
  const pronk::SetSummary none = pronk::summarize({}, 0.2);
  EXPECT_TRUE(std::isnan(none.withinShare()));
  const pronk::SetSummary failed = pronk::summarize({row(0, "failed", 1, 0)}, 0.2);
  EXPECT_DOUBLE_EQ(failed.withinShare(), 0.0);
  EXPECT_TRUE(std::isnan(failed.mean));
  const nlohmann::json j = pronk::toJson(failed);
  EXPECT_TRUE(j["error_m"]["mean"].is_null());
  EXPECT_EQ(j["failed"], 1);
}

TEST(JumpRow, RoundTripsThroughJsonWithNaNAsNull) {
  JumpRow r = row(7, "ok", 0.4, 0.41, -0.02);
  r.reason = "a \"quoted\" reason";
  r.assignments = {{"joints.damping", 0.3}};
  const nlohmann::json j = pronk::toJson(r);
  const JumpRow back = pronk::jumpRowFromJson(nlohmann::json::parse(j.dump()), "here");
  EXPECT_EQ(back.index, 7u);
  EXPECT_EQ(back.reason, r.reason);
  EXPECT_DOUBLE_EQ(back.error_xy, r.error_xy);
  ASSERT_EQ(back.assignments.size(), 1u);
  EXPECT_EQ(back.assignments[0].first, "joints.damping");
  const JumpRow refused = pronk::jumpRowFromJson(pronk::toJson(row(1, "rejected", 1, 0)), "here");
  EXPECT_TRUE(std::isnan(refused.landed_x));
  EXPECT_TRUE(pronk::toJson(refused)["landed"]["x"].is_null());
  try {
    pronk::jumpRowFromJson({{"index", 1}}, "log.jsonl:3");
    FAIL() << "a record without its fields was accepted";
  } catch (const pronk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("log.jsonl:3"), std::string::npos) << e.what();
  }
}

TEST(JumpLog, AResumedLogHoldsEveryAppendedRowAndDropsATornLastLine) {
  const std::string dir = tempDir("log");
  const std::string path = dir + "/jumps.jsonl";
  {
    pronk::JumpLog log(path, false);
    log.append(row(0, "ok", 0.3, 0.31));
    log.append(row(2, "failed", 1.0, 0));
  }
  {  // a kill in the middle of the third line
    std::ofstream out(path, std::ios::app);
    out << "{\"index\": 1, \"case\": \"cas";
  }
  {
    pronk::JumpLog log(path, true);
    ASSERT_EQ(log.rows().size(), 2u);
    EXPECT_EQ(log.rows()[1].index, 2u);
    log.append(row(1, "ok", 0.5, 0.5));
  }
  pronk::JumpLog again(path, true);
  ASSERT_EQ(again.rows().size(), 3u);
  EXPECT_EQ(again.rows()[2].index, 1u);
  EXPECT_EQ(again.rows()[2].status, "ok");
}

TEST(JumpLog, RefusesToOverwriteAndNamesABrokenLine) {
  const std::string dir = tempDir("broken");
  const std::string path = dir + "/jumps.jsonl";
  { pronk::JumpLog log(path, false); log.append(row(0, "ok", 0.3, 0.31)); }
  EXPECT_THROW(pronk::JumpLog(path, false), pronk::Error);  // an earlier run's log is never truncated
  {
    std::ofstream out(path, std::ios::app);
    out << "not json\n" << pronk::toJson(row(1, "ok", 0.3, 0.3)).dump() << "\n";
  }
  try {
    pronk::JumpLog log(path, true);
    FAIL() << "a broken line was accepted";
  } catch (const pronk::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2"), std::string::npos) << e.what();
  }
}

TEST(EvaluationSetDir, ResumesOnlyTheSameRunAndListsWhatIsLeft) {
  const std::string base = tempDir("setdir");
  const std::string dir = base + "/set";
  const nlohmann::json manifest = {{"policy", "a.json"}, {"cases", 4}};
  {
    pronk::EvaluationSetDir set(dir, manifest, false);
    set.log().append(row(0, "ok", 0.3, 0.3));
    set.log().append(row(2, "ok", 0.3, 0.3));
    EXPECT_EQ(set.remaining(4), (std::vector<size_t>{1, 3}));
  }
  EXPECT_THROW(pronk::EvaluationSetDir(dir, manifest, false), pronk::Error);
  pronk::EvaluationSetDir resumed(dir, manifest, true);
  EXPECT_EQ(resumed.remaining(4), (std::vector<size_t>{1, 3}));
  try {
    pronk::EvaluationSetDir other(dir, {{"policy", "b.json"}, {"cases", 4}}, true);
    FAIL() << "a resume with another policy was accepted";
  } catch (const pronk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("set.json: written for policy \"a.json\""), std::string::npos) << e.what();
  }
}

TEST(JumpsCsv, HasAHeaderAndOneLinePerRowWithTheSweepVariablesAndRfc4180Text) {
  const std::string dir = tempDir("csv");
  JumpRow a = row(0, "ok", 0.3, 0.31), b = row(1, "rejected", 1.0, 0);
  a.assignments = {{"joints.damping", 0.25}};
  b.reason = "no \"plan\", none";
  b.label = "x = 1, y = 0";
  pronk::writeJumpsCsv({a, b}, dir + "/jumps.csv");
  std::ifstream in(dir + "/jumps.csv");
  std::string header, first, second, extra;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_FALSE(std::getline(in, extra));
  EXPECT_NE(header.find(",joints.damping,reason"), std::string::npos) << header;
  // As many columns named as a row holds (the first row quotes no comma).
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(first.begin(), first.end(), ','))
      << header << "\n" << first;
  EXPECT_NE(header.find(",error_xy,landed_height,error,error_yaw_deg,"), std::string::npos) << header;
  EXPECT_NE(first.find(",0.25,"), std::string::npos) << first;
  EXPECT_NE(second.find("rejected"), std::string::npos) << second;
  // RFC 4180: text quoted, a quote doubled, the comma kept inside the quotes.
  EXPECT_NE(second.find(",\"x = 1, y = 0\","), std::string::npos) << second;
  EXPECT_NE(second.find(",\"no \"\"plan\"\", none\""), std::string::npos) << second;
}

}  // namespace
