// Reports of jump runs, from the rollout engine's records: each jump judged
// from its trace (landing, status), the statistics as the paper counts them,
// the console table and the results files (docs/results-format.md).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pronk/landing.h"
#include "pronk/rollout.h"

namespace pronk {

// One jump as the report sees it.
struct JumpOutcome {
  Landing landing;
  std::string status;  // ok | missed | rejected | failed
  std::string reason;  // why, for every status but ok
  bool ran = false;    // something was simulated (not rejected, not a setup error)
};

// A target without tolerance_xy is missed beyond this horizontal error: the
// paper's success radius (a landing more than 0.2 m off is not a landing on it).
constexpr double kDefaultMissRadius = 0.2;  // m

JumpOutcome judgeJump(const EpisodeRecord& record);

// Counts and errors over a run's jumps; landed = ok + missed. Times to rest are
// the host's (the trace's "at_rest" event, pronk/episode.h).
struct JumpStatistics {
  size_t jumps = 0, ran = 0;
  int standing = 0, failed = 0, rejected = 0, missed = 0;
  std::vector<double> errors, yaw_errors_deg, rest_times;  // landed jumps
  double wall_s = 0, simulated_s = 0;                      // summed over the episodes
  void add(const EpisodeRecord& record, const JumpOutcome& outcome);
  size_t landed() const { return errors.size(); }
};

// The console table (markdown), one row per jump, and the summary under it.
// Beyond the host's columns (target, landing, errors, status, reward, reason),
// one per metric the environment declares with a column (pronk/schema.h); a
// column that pairs two values says which is which in the legend above the
// table. What does not exist (a rejected jump's landing) is "-", never nan.
void printJumpTableHeader(std::FILE* out, const EnvironmentSchema& schema);
void printJumpRow(std::FILE* out, const EpisodeRecord& record, const JumpOutcome& outcome,
                  const EnvironmentSchema& schema);
// `wall_clock_s` > 0: the run's own wall time, for the jumps/s of the whole
// run (threads overlap, so the episodes' summed wall time overstates it).
void printJumpSummary(std::FILE* out, const JumpStatistics& stats, double wall_clock_s);

// results.json and results.csv of a run's jumps (docs/results-format.md): the
// metrics filed by their declared kinds, the CSV's metric columns those the
// environment declares.
class JumpResultsFiles {
 public:
  explicit JumpResultsFiles(EnvironmentSchema schema) : schema_(std::move(schema)) {}
  // `trace_file`: the jump's trace CSV beside the results ("" = none written).
  void add(const EpisodeRecord& record, const JumpOutcome& outcome, const std::string& trace_file);
  // What the run was (pronk's version and commit, scenario, resolved
  // parameters, policy, seeds ...): results.json's "run" object.
  void setRun(nlohmann::json run) { run_ = std::move(run); }
  // Writes DIR/results.json and DIR/results.csv, each replaced as a whole
  // (written beside, then renamed), so that a reader or a failed write never
  // leaves half a file. Throws Error when it cannot.
  void write(const std::string& dir) const;
  size_t size() const { return json_.size(); }
  const nlohmann::json& json() const { return json_; }

 private:
  EnvironmentSchema schema_;
  nlohmann::json run_ = nlohmann::json::object();
  nlohmann::json json_ = nlohmann::json::array();
  std::string csv_;
};

// The median and the p-quantile (nearest rank) of `values`; NaN when empty.
double median(std::vector<double> values);
double percentile(std::vector<double> values, double p);

}  // namespace pronk
