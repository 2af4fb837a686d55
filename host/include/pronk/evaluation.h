// An evaluation's records (`pronk eval`, `pronk check`): one row per jump, all
// that the summary and the plots need, kept in an append-only log so that an
// interrupted run resumes; the summary of a set counted as the paper counts;
// the per-jump CSV. No simulation types: the plots read these rows.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "pronk/error.h"

#include <nlohmann/json.hpp>

namespace pronk {

struct EpisodeRecord;
struct EpisodeCase;
struct JumpOutcome;

// One jump. Positions in the start's heading frame (m), yaw in rad; NaN where
// the jump has none (rejected, or failed before it landed).
struct JumpRow {
  size_t index = 0;  // the case's index in its set (its seed)
  std::string label;
  double target_x = 0, target_y = 0, target_z = 0, target_yaw = 0;
  double landed_x = NAN, landed_y = NAN, landed_z = NAN, landed_yaw = NAN;
  double error_xy = NAN;       // m, horizontal distance from the target
  double landed_height = NAN;  // m, the feet's surface at the end, from the take-off one (Landing::height)
  double error = NAN;          // m, as the paper counts it: error_xy, 3-D for a target with a height (Landing::error)
  double error_yaw_deg = NAN;  // |wrapped heading error|
  std::string status;          // ok | missed | rejected | failed
  std::string reason;          // why, for every status but ok
  bool standing = false;       // ended on its feet, upright
  double simulated_s = 0, wall_s = 0;
  // The case's non-target sweep variables (joint damping, mass offset ...).
  std::vector<std::pair<std::string, double>> assignments;

  bool landed() const { return status == "ok" || status == "missed"; }
};

JumpRow jumpRowOf(const EpisodeRecord& record, const JumpOutcome& outcome);
nlohmann::json toJson(const JumpRow& row);
// Throws Error naming `where` (file:line) for a row that is not one.
JumpRow jumpRowFromJson(const nlohmann::json& j, const std::string& where);

// A set's figures as the paper counts them: errors over the jumps that landed
// (not failed, not refused); the share within `radius` over every jump of the
// set (a failure or a refusal is not within); failures and refusals as shares
// of every jump. Signed errors along the target frame's x and y (the paper's
// e_x, e_y: mean and standard deviation).
struct SetSummary {
  size_t jumps = 0, landed = 0, within = 0, failed = 0, rejected = 0, missed = 0, standing = 0;
  double radius = 0.2;
  double mean = NAN, median = NAN, p90 = NAN, max = NAN;  // m, landed
  double error_x_mean = NAN, error_x_std = NAN, error_y_mean = NAN, error_y_std = NAN;
  double yaw_mean_deg = NAN, yaw_max_deg = NAN;
  double simulated_s = 0, wall_s = 0;
  double withinShare() const { return jumps ? double(within) / jumps : NAN; }
};

SetSummary summarize(const std::vector<JumpRow>& rows, double radius = 0.2);
nlohmann::json toJson(const SetSummary& s);

// DIR/jumps.csv of a set: one line per row, the header first.
void writeJumpsCsv(const std::vector<JumpRow>& rows, const std::string& path);

// The append-only record of a set's finished jumps (JSON lines). A run opens
// it empty (the file must not exist); a resumed run reads the rows there,
// dropping a last line a kill cut short, and appends. Each append is written
// and flushed before the next jump is reported: a kill loses no finished jump.
class JumpLog {
 public:
  JumpLog(std::string path, bool resume);
  ~JumpLog();
  JumpLog(const JumpLog&) = delete;
  JumpLog& operator=(const JumpLog&) = delete;
  const std::vector<JumpRow>& rows() const { return rows_; }
  void append(const JumpRow& row);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<JumpRow> rows_;
  std::FILE* file_ = nullptr;
};

// A set's directory in an evaluation's output: set.json (what the set was run
// with: file, set, policy and their fingerprints) and the jump log. A new
// directory is created with the manifest; an existing one needs `resume` and
// the same manifest (else ResumeRefused naming set.json and the field that
// differs), so that results are never mixed or overwritten.
class ResumeRefused : public Error {
 public:
  using Error::Error;
};
class EvaluationSetDir {
 public:
  EvaluationSetDir(const std::string& dir, const nlohmann::json& manifest, bool resume);
  JumpLog& log() { return *log_; }
  // The case indices of [0, cases) the log does not hold yet, in order.
  std::vector<size_t> remaining(size_t cases) const;
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::unique_ptr<JumpLog> log_;
};

// A fingerprint of a set's cases (labels, targets, assignments), so that a
// resumed run refuses a directory written for other cases.
std::string casesFingerprint(const std::vector<EpisodeCase>& cases);
// FNV-1a 64 of a file's bytes, in hex (a policy's identity for --resume).
// Throws Error naming the file when it cannot be read.
std::string fileFingerprint(const std::string& path);

}  // namespace pronk
