// Evaluation records: jump rows, set summaries, the jump log and the CSV
// (pronk/evaluation.h, docs/results-format.md).
#include "pronk/evaluation.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pronk/error.h"
#include "pronk/file_io.h"
#include "pronk/report.h"
#include "cells.h"

namespace pronk {
namespace {

using report_cells::csvCell;
using report_cells::csvText;
using report_cells::number;

constexpr double kDeg = 180.0 / M_PI;

double numberOf(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) throw Error(where + ": the jump record has no \"" + key + "\"");
  if (it->is_null()) return NAN;
  if (!it->is_number()) throw Error(where + ": \"" + key + "\" of the jump record is not a number");
  return it->get<double>();
}

std::string textOf(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_string()) throw Error(where + ": the jump record has no text \"" + key + "\"");
  return it->get<std::string>();
}

// 64-bit FNV-1a, fed piece by piece.
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }
  void add(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    add(std::string(text));
  }
  std::string hex() const {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
  }
};

double meanOf(const std::vector<double>& v) {
  if (v.empty()) return NAN;
  double sum = 0;
  for (double x : v) sum += x;
  return sum / v.size();
}

double stdOf(const std::vector<double>& v) {
  if (v.size() < 2) return v.empty() ? NAN : 0.0;
  const double m = meanOf(v);
  double sum = 0;
  for (double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / (v.size() - 1));
}

}  // namespace

JumpRow jumpRowOf(const EpisodeRecord& r, const JumpOutcome& o) {
  JumpRow row;
  row.index = r.index;
  row.label = r.episode.label;
  const TargetSpec& t = r.episode.target;
  row.target_x = t.x;
  row.target_y = t.y;
  row.target_z = t.z;
  row.target_yaw = t.yaw;
  row.landed_x = o.landing.displacement.x();
  row.landed_y = o.landing.displacement.y();
  row.landed_z = o.landing.displacement.z();
  row.landed_yaw = o.landing.yaw;
  row.error_xy = o.landing.error_xy;
  row.landed_height = o.landing.height;
  row.error = o.landing.error;
  row.error_yaw_deg = o.landing.error_yaw * kDeg;
  row.status = o.status;
  row.reason = o.reason;
  row.standing = o.landing.standing && o.status != "failed";
  const Trace& trace = r.result.episode.trace;
  row.simulated_s = trace.samples.empty() ? 0.0 : trace.samples.back().time;
  row.wall_s = r.result.episode.wall_seconds;
  row.assignments = r.episode.assignments;
  return row;
}

nlohmann::json toJson(const JumpRow& row) {
  nlohmann::json assignments = nlohmann::json::object();
  for (const auto& [name, value] : row.assignments) assignments[name] = value;
  return {{"index", row.index},
          {"case", row.label},
          {"target", {{"x", row.target_x}, {"y", row.target_y}, {"z", row.target_z}, {"yaw", row.target_yaw}}},
          {"landed",
           {{"x", number(row.landed_x)}, {"y", number(row.landed_y)}, {"z", number(row.landed_z)},
            {"yaw", number(row.landed_yaw)}}},
          {"error_xy", number(row.error_xy)},
          {"landed_height", number(row.landed_height)},
          {"error", number(row.error)},
          {"error_yaw_deg", number(row.error_yaw_deg)},
          {"status", row.status},
          {"reason", row.reason},
          {"ended_standing", row.standing},
          {"simulated_s", row.simulated_s},
          {"wall_s", row.wall_s},
          {"assignments", assignments}};
}

JumpRow jumpRowFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where + ": a jump record is a JSON object");
  JumpRow row;
  const double index = numberOf(j, "index", where);
  if (!(index >= 0) || index != std::floor(index)) throw Error(where + ": \"index\" is not a case index");
  row.index = static_cast<size_t>(index);
  row.label = textOf(j, "case", where);
  const auto target = j.find("target"), landed = j.find("landed");
  if (target == j.end() || !target->is_object()) throw Error(where + ": the jump record has no \"target\"");
  if (landed == j.end() || !landed->is_object()) throw Error(where + ": the jump record has no \"landed\"");
  row.target_x = numberOf(*target, "x", where);
  row.target_y = numberOf(*target, "y", where);
  row.target_z = numberOf(*target, "z", where);
  row.target_yaw = numberOf(*target, "yaw", where);
  row.landed_x = numberOf(*landed, "x", where);
  row.landed_y = numberOf(*landed, "y", where);
  row.landed_z = numberOf(*landed, "z", where);
  row.landed_yaw = numberOf(*landed, "yaw", where);
  row.error_xy = numberOf(j, "error_xy", where);
  // Rows written before the paper's 3-D error had only the horizontal one,
  // which is the same for targets without a height.
  row.landed_height = j.contains("landed_height") ? numberOf(j, "landed_height", where) : NAN;
  row.error = j.contains("error") ? numberOf(j, "error", where) : row.target_z == 0 ? row.error_xy : NAN;
  row.error_yaw_deg = numberOf(j, "error_yaw_deg", where);
  row.status = textOf(j, "status", where);
  if (row.status != "ok" && row.status != "missed" && row.status != "rejected" && row.status != "failed") {
    throw Error(where + ": unknown status \"" + row.status + "\"");
  }
  row.reason = textOf(j, "reason", where);
  const auto standing = j.find("ended_standing");
  if (standing == j.end() || !standing->is_boolean()) throw Error(where + ": the jump record has no \"ended_standing\"");
  row.standing = standing->get<bool>();
  row.simulated_s = numberOf(j, "simulated_s", where);
  row.wall_s = numberOf(j, "wall_s", where);
  if (const auto a = j.find("assignments"); a != j.end() && a->is_object()) {
    for (const auto& [name, value] : a->items()) {
      if (!value.is_number()) throw Error(where + ": assignment \"" + name + "\" is not a number");
      row.assignments.emplace_back(name, value.get<double>());
    }
  }
  return row;
}

SetSummary summarize(const std::vector<JumpRow>& rows, double radius) {
  SetSummary s;
  s.radius = radius;
  s.jumps = rows.size();
  std::vector<double> errors, ex, ey, yaw;
  for (const JumpRow& r : rows) {
    s.simulated_s += r.simulated_s;
    s.wall_s += r.wall_s;
    if (r.status == "failed") ++s.failed;
    if (r.status == "rejected") ++s.rejected;
    if (r.status == "missed") ++s.missed;
    if (!r.landed()) continue;
    ++s.landed;
    if (r.standing) ++s.standing;
    errors.push_back(r.error);
    if (r.error <= radius) ++s.within;
    // Signed errors along the start heading's x and y (the paper's e_x, e_y).
    ex.push_back(r.landed_x - r.target_x);
    ey.push_back(r.landed_y - r.target_y);
    if (std::isfinite(r.error_yaw_deg)) yaw.push_back(r.error_yaw_deg);
  }
  s.mean = meanOf(errors);
  s.median = median(errors);
  s.p90 = percentile(errors, 0.9);
  s.max = percentile(errors, 1.0);
  s.error_x_mean = meanOf(ex);
  s.error_x_std = stdOf(ex);
  s.error_y_mean = meanOf(ey);
  s.error_y_std = stdOf(ey);
  s.yaw_mean_deg = meanOf(yaw);
  s.yaw_max_deg = yaw.empty() ? NAN : *std::max_element(yaw.begin(), yaw.end());
  return s;
}

nlohmann::json toJson(const SetSummary& s) {
  auto share = [&](size_t n) { return s.jumps ? number(double(n) / s.jumps) : nlohmann::json(nullptr); };
  return {{"jumps", s.jumps},
          {"landed", s.landed},
          {"failed", s.failed},
          {"rejected", s.rejected},
          {"missed_tolerance", s.missed},
          {"ended_standing", s.standing},
          {"failure_share", share(s.failed)},
          {"rejected_share", share(s.rejected)},
          {"radius_m", s.radius},
          {"within_radius", s.within},
          {"within_radius_share", share(s.within)},
          {"error_m", {{"mean", number(s.mean)}, {"median", number(s.median)}, {"p90", number(s.p90)},
                       {"max", number(s.max)}}},
          {"error_x_m", {{"mean", number(s.error_x_mean)}, {"std", number(s.error_x_std)}}},
          {"error_y_m", {{"mean", number(s.error_y_mean)}, {"std", number(s.error_y_std)}}},
          {"yaw_error_deg", {{"mean", number(s.yaw_mean_deg)}, {"max", number(s.yaw_max_deg)}}},
          {"simulated_s", s.simulated_s},
          {"episode_wall_s", s.wall_s}};
}

void writeJumpsCsv(const std::vector<JumpRow>& rows, const std::string& path) {
  std::vector<std::string> variables;  // the sweep's non-target variables, in first-seen order
  for (const JumpRow& r : rows)
    for (const auto& a : r.assignments)
      if (std::find(variables.begin(), variables.end(), a.first) == variables.end()) variables.push_back(a.first);
  std::string csv =
      "index,case,target_x,target_y,target_z,target_yaw_deg,landed_x,landed_y,landed_z,landed_yaw_deg,error_xy,"
      "landed_height,error,error_yaw_deg,status,ended_standing,simulated_s,wall_s,";
  for (const std::string& v : variables) csv += v + ',';
  csv += "reason\n";
  for (const JumpRow& r : rows) {
    csv += std::to_string(r.index) + ',' + csvText(r.label) + ',';
    for (double v : {r.target_x, r.target_y, r.target_z, r.target_yaw * kDeg, r.landed_x, r.landed_y, r.landed_z,
                     r.landed_yaw * kDeg, r.error_xy, r.landed_height, r.error, r.error_yaw_deg}) {
      csv += csvCell(v) + ',';
    }
    csv += r.status + ',' + (r.standing ? "1" : "0") + ',' + csvCell(r.simulated_s) + ',' + csvCell(r.wall_s) + ',';
    for (const std::string& v : variables) {
      double value = NAN;
      for (const auto& a : r.assignments)
        if (a.first == v) value = a.second;
      csv += csvCell(value) + ',';
    }
    csv += csvText(r.reason) + '\n';
  }
  replaceFileAtomically(path, csv, "jumps file");
}

JumpLog::JumpLog(std::string path, bool resume) : path_(std::move(path)) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool exists = fs::exists(path_, ec);
  if (exists && !resume) throw Error(path_ + ": exists (an earlier evaluation): give --resume, or another --out");
  long keep = 0;  // bytes of whole lines to keep
  if (exists) {
    const std::string text = readInputFile(path_, "jump log");
    size_t start = 0;
    int line = 0;
    while (start < text.size()) {
      ++line;
      const size_t end = text.find('\n', start);
      if (end == std::string::npos) break;  // a last line without its newline: cut short by a kill
      const std::string where = path_ + ":" + std::to_string(line);
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(text.begin() + start, text.begin() + end);
      } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": not a jump record (" + e.what() + ")");
      }
      rows_.push_back(jumpRowFromJson(j, where));
      start = end + 1;
      keep = static_cast<long>(start);
    }
    // Drop the torn tail so that the next append starts a line of its own.
    fs::resize_file(path_, static_cast<std::uintmax_t>(keep), ec);
    if (ec) throw Error(path_ + ": cannot cut the unfinished last line: " + ec.message());
  }
  file_ = std::fopen(path_.c_str(), "ab");
  if (!file_) throw Error("cannot write the jump log " + path_ + ": " + std::strerror(errno));
}

JumpLog::~JumpLog() {
  if (file_) std::fclose(file_);
}

void JumpLog::append(const JumpRow& row) {
  const std::string line = toJson(row).dump() + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) {
    throw Error("cannot write the jump log " + path_ + ": " + std::strerror(errno));
  }
  rows_.push_back(row);
}

EvaluationSetDir::EvaluationSetDir(const std::string& dir, const nlohmann::json& manifest, bool resume) : dir_(dir) {
  namespace fs = std::filesystem;
  const std::string manifest_path = (fs::path(dir) / "set.json").string();
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!resume) throw ResumeRefused(dir + ": exists (an earlier evaluation): give --resume, or another --out");
    if (!fs::exists(manifest_path, ec)) {
      throw ResumeRefused(manifest_path + ": missing: " + dir + " is no evaluation set's directory");
    }
    nlohmann::json old;
    try {
      old = nlohmann::json::parse(readInputFile(manifest_path, "set manifest"));
    } catch (const nlohmann::json::exception& e) {
      throw Error(manifest_path + ": not JSON (" + e.what() + ")");
    }
    for (const auto& [key, value] : manifest.items()) {
      if (!old.contains(key) || old[key] != value) {
        throw ResumeRefused(manifest_path + ": written for " + key + " " + (old.contains(key) ? old[key].dump() : "(none)") +
                    ", this run has " + value.dump() + ": --resume continues only the same run; use another --out");
      }
    }
  } else {
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir + ": cannot create the directory: " + ec.message());
    replaceFileAtomically(manifest_path, manifest.dump(2) + "\n", "set manifest");
  }
  log_ = std::make_unique<JumpLog>((fs::path(dir) / "jumps.jsonl").string(), resume);
}

std::vector<size_t> EvaluationSetDir::remaining(size_t cases) const {
  std::vector<bool> done(cases, false);
  for (const JumpRow& r : log_->rows()) {
    if (r.index >= cases) throw Error(log_->path() + ": case " + std::to_string(r.index) + " is not one of the set's " +
                                      std::to_string(cases));
    done[r.index] = true;
  }
  std::vector<size_t> out;
  for (size_t i = 0; i < cases; ++i)
    if (!done[i]) out.push_back(i);
  return out;
}

std::string casesFingerprint(const std::vector<EpisodeCase>& cases) {
  Fnv f;
  for (const EpisodeCase& c : cases) {
    f.add(c.label);
    for (double v : {c.target.x, c.target.y, c.target.z, c.target.yaw, c.target.roll, c.target.pitch}) f.add(v);
    for (const auto& [name, value] : c.assignments) {
      f.add(name);
      f.add(value);
    }
  }
  return f.hex();
}

std::string fileFingerprint(const std::string& path) {
  Fnv f;
  const std::string text = readInputFile(path, "policy file");
  f.add(text.data(), text.size());
  return f.hex();
}

}  // namespace pronk
