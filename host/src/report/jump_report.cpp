// Jump reports from rollout records: status, statistics, the console table and
// the results files (pronk/report.h, docs/results-format.md).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <filesystem>

#include <fmt/format.h>

#include "pronk/file_io.h"
#include "pronk/report.h"
#include "cells.h"

namespace pronk {
namespace {

using report_cells::csvCell;
using report_cells::csvText;
using report_cells::number;

constexpr double kDeg = 180.0 / M_PI;

// A metric of the trace, NaN when absent or not finite (JSON null, empty CSV cell).
double metricOrNaN(const Trace& trace, const char* name) {
  const double* v = trace.findMetric(name);
  return v && std::isfinite(*v) ? *v : NAN;
}

const TraceEvent* event(const Trace& trace, const char* name) { return trace.findEvent(name); }

std::string statusOf(const EpisodeRecord& r, const Landing& landing) {
  if (r.setup_error) return r.setup_refused ? "rejected" : "failed";
  if (r.result.rejected) return "rejected";
  if (r.result.episode.failure || !landing.end_failure.empty()) return "failed";
  const TargetSpec& t = r.episode.target;
  if (!(landing.error <= t.tolerance_xy.value_or(kDefaultMissRadius)) ||
      (t.tolerance_yaw && !(landing.error_yaw <= *t.tolerance_yaw))) {
    return "missed";
  }
  return "ok";
}

std::string reasonOf(const EpisodeRecord& r, const JumpOutcome& o) {
  if (r.setup_error) return (r.setup_refused ? "terrain: " : "setup: ") + *r.setup_error;
  if (r.result.rejected) return *r.result.rejected;
  if (r.result.episode.failure) return r.result.episode.failure->reason + ": " + r.result.episode.failure->detail;
  if (!o.landing.end_failure.empty()) return o.landing.end_failure;
  if (o.status == "missed") {
    const TargetSpec& t = r.episode.target;
    if (t.tolerance_xy || t.tolerance_yaw) {
      return fmt::format("error {:.1f} cm / {:.1f} deg beyond the tolerance {:.1f} cm / {:.1f} deg",
                         100 * o.landing.error, o.landing.error_yaw * kDeg,
                         100 * t.tolerance_xy.value_or(kDefaultMissRadius), t.tolerance_yaw.value_or(INFINITY) * kDeg);
    }
    return fmt::format("error {:.1f} cm beyond {:.0f} cm (the target sets no tolerance_xy: the paper's success radius)",
                       100 * o.landing.error, 100 * kDefaultMissRadius);
  }
  return "";
}

// The time of a host event, or the value of a metric, by name; NaN when absent.
double eventOrMetric(const Trace& trace, const std::string& name) {
  if (const TraceEvent* e = trace.findEvent(name)) return e->time;
  return metricOrNaN(trace, name.c_str());
}

std::vector<const MetricSpec*> tableColumns(const EnvironmentSchema& schema) {
  std::vector<const MetricSpec*> out;
  for (const MetricSpec& m : schema.metrics)
    if (!m.column.empty()) out.push_back(&m);
  return out;
}

// A number in a table cell, right-aligned; "-" where it does not exist.
std::string cell(double v, int width, int precision) {
  if (std::fabs(v) < 0.5 * std::pow(10.0, -precision)) v = 0;  // no "-0.00" for a tiny negative
  return std::isfinite(v) ? fmt::format("{:>{}.{}f}", v, width, precision) : fmt::format("{:>{}}", "-", width);
}

// A column's text: the metric, and beside it what it pairs with ("planned/detected").
std::string columnCell(const Trace& trace, const MetricSpec& m) {
  const int precision = m.unit == "s" ? 3 : 2;
  const std::string a = cell(metricOrNaN(trace, m.name.c_str()), 5, precision);
  if (m.pairs_with.empty()) return a;
  return a + "/" + cell(eventOrMetric(trace, m.pairs_with), 5, precision);
}

size_t columnWidth(const MetricSpec& m) { return std::max<size_t>(m.column.size(), m.pairs_with.empty() ? 5 : 11); }

double simulatedOf(const Trace& trace) { return trace.samples.empty() ? 0.0 : trace.samples.back().time; }

}  // namespace

JumpOutcome judgeJump(const EpisodeRecord& record) {
  JumpOutcome o;
  o.landing = landingOf(record.result.episode.trace, record.episode.target);
  o.status = statusOf(record, o.landing);
  o.reason = reasonOf(record, o);
  o.ran = !record.setup_error && !record.result.rejected;
  return o;
}

void JumpStatistics::add(const EpisodeRecord& r, const JumpOutcome& o) {
  ++jumps;
  if (o.ran) ++ran;
  wall_s += r.result.episode.wall_seconds;
  simulated_s += simulatedOf(r.result.episode.trace);
  if (o.status == "failed") ++failed;
  if (o.status == "rejected") ++rejected;
  if (o.status == "missed") ++missed;
  if (o.status == "ok" || o.status == "missed") {
    errors.push_back(o.landing.error);
    yaw_errors_deg.push_back(o.landing.error_yaw * kDeg);
    if (o.landing.standing) ++standing;
    if (const TraceEvent* rest = r.result.episode.trace.findEvent("at_rest")) rest_times.push_back(rest->time);
  }
}

void printJumpTableHeader(std::FILE* out, const EnvironmentSchema& schema) {
  // Which value of a paired cell is which: the environment's metric, then what it pairs with.
  std::string legend;
  for (const MetricSpec* m : tableColumns(schema)) {
    if (m->pairs_with.empty()) continue;
    legend += fmt::format("{}{}: {} / {}", legend.empty() ? "" : "; ", m->column, m->name, m->pairs_with);
  }
  if (!legend.empty()) fmt::print(out, "\npaired columns, planned / detected: {}\n", legend);
  std::string header = fmt::format("| {:>3} | {:<25} | {:<25} | {:>6} | {:>7} |", "#", "target x y z [m] yaw[deg]",
                                   "landing x y z [m] yaw[deg]", "err cm", "yaw deg");
  std::string rule = "|-----|---------------------------|---------------------------|--------|---------|";
  for (const MetricSpec* m : tableColumns(schema)) {
    header += fmt::format(" {:<{}} |", m->column, columnWidth(*m));
    rule += std::string(columnWidth(*m) + 2, '-') + "|";
  }
  header += fmt::format(" {:<8} | {:>6} | reason |", "status", "reward");
  rule += "----------|--------|--------|";
  fmt::print(out, "\n{}\n{}\n", header, rule);
}

void printJumpRow(std::FILE* out, const EpisodeRecord& r, const JumpOutcome& o, const EnvironmentSchema& schema) {
  const Trace& trace = r.result.episode.trace;
  const TargetSpec& t = r.episode.target;
  const Landing& l = o.landing;
  std::string row = fmt::format("| {:>3} | {} {} {} {} | {} {} {} {} | {} | {} |", r.index, cell(t.x, 5, 2),
                                cell(t.y, 5, 2), cell(t.z, 5, 2), cell(t.yaw * kDeg, 6, 1), cell(l.displacement.x(), 5, 2),
                                cell(l.displacement.y(), 5, 2), cell(l.displacement.z(), 5, 2), cell(l.yaw * kDeg, 6, 1),
                                cell(100 * l.error_xy, 6, 1), cell(l.error_yaw * kDeg, 7, 1));
  for (const MetricSpec* m : tableColumns(schema)) {
    row += fmt::format(" {:>{}} |", columnCell(trace, *m), columnWidth(*m));
  }
  // One markdown row per jump: the reason is its last cell ("|" in it would split the row).
  std::string reason = o.reason;
  std::replace(reason.begin(), reason.end(), '|', '/');
  row += fmt::format(" {:<8} | {} | {} |", o.status, cell(r.result.reward, 6, 3), reason);
  fmt::print(out, "{}\n", row);
}

void printJumpSummary(std::FILE* out, const JumpStatistics& s, double wall_clock_s) {
  const size_t landed = s.landed();
  std::fprintf(out, "\n%zu jump(s): %zu landed (%d missed their tolerance), %d rejected before running, %d failed\n",
               s.jumps, landed, s.missed, s.rejected, s.failed);
  if (landed > 0) {
    std::fprintf(out,
                 "landing error: median %.1f cm, 90th percentile %.1f cm, max %.1f cm; yaw error median %.1f deg\n",
                 100 * median(s.errors), 100 * percentile(s.errors, 0.9), 100 * percentile(s.errors, 1.0),
                 median(s.yaw_errors_deg));
    std::fprintf(out, "ended standing: %d of %zu; ", s.standing, landed);
    if (s.rest_times.empty()) {
      std::fprintf(out, "none came to rest (feet down, CoM < %.2f m/s, trunk < %.1f rad/s)\n", kRestSpeed, kRestRate);
    } else {
      std::fprintf(out, "%zu at rest (feet down, CoM < %.2f m/s, trunk < %.1f rad/s) from a median %.2f s\n",
                   s.rest_times.size(), kRestSpeed, kRestRate, median(s.rest_times));
    }
  }
  if (s.ran > 0 && s.wall_s > 0) {
    std::fprintf(out, "simulated %.1f s in %.1f s of episode wall time (%.1fx real time per episode)", s.simulated_s,
                 s.wall_s, s.simulated_s / s.wall_s);
    if (wall_clock_s > 0) std::fprintf(out, "; %.2f jumps/s over the run's %.1f s", s.jumps / wall_clock_s, wall_clock_s);
    std::fprintf(out, "\n");
  } else {
    std::fprintf(out, "simulated nothing\n");
  }
}

void JumpResultsFiles::add(const EpisodeRecord& r, const JumpOutcome& o, const std::string& trace_file) {
  const Trace& trace = r.result.episode.trace;
  const TargetSpec& t = r.episode.target;
  const Landing& l = o.landing;
  nlohmann::json j;
  j["case"] = r.episode.label;
  j["target"] = {{"name", t.name}, {"x", t.x}, {"y", t.y}, {"z", t.z}, {"yaw", t.yaw}, {"roll", t.roll}, {"pitch", t.pitch}};
  j["landing"] = {{"x", number(l.displacement.x())},
                  {"y", number(l.displacement.y())},
                  {"z", number(l.displacement.z())},
                  {"yaw", number(l.yaw)}};
  j["error_xy"] = number(l.error_xy);
  j["landed_height"] = number(l.height);
  j["error"] = number(l.error);
  j["error_yaw_deg"] = number(l.error_yaw * kDeg);
  j["status"] = o.status;
  j["failed"] = o.status == "failed";
  j["rejected"] = o.status == "rejected";
  j["failure_reason"] = o.reason;
  j["ended_standing"] = l.standing && o.status != "failed";
  j["reward"] = r.result.reward;
  j["observation"] = r.result.observation;
  j["action"] = r.result.action;
  // Metrics filed by their declared kind; one the environment did not declare
  // (or an ABI 1.2 plugin's) is a plain metric.
  nlohmann::json penalties = nlohmann::json::object(), metrics = nlohmann::json::object();
  for (const TraceMetric& m : trace.metrics) {
    const MetricSpec* spec = schema_.find(m.name);
    (spec && spec->kind == MetricSpec::Kind::Penalty ? penalties : metrics)[m.name] = number(m.value);
  }
  j["penalties"] = penalties;
  j["metrics"] = metrics;
  // The host's contact events and rest, then every declared time (null when it did not happen).
  nlohmann::json events = nlohmann::json::object();
  std::vector<std::string> event_names = hostContactEvents();
  event_names.push_back("at_rest");
  for (const std::string& name : event_names) {
    const TraceEvent* e = trace.findEvent(name);
    events[name] = e ? nlohmann::json(e->time) : nlohmann::json(nullptr);
  }
  for (const MetricSpec& m : schema_.metrics) {
    if (m.kind == MetricSpec::Kind::Time) events[m.name] = number(metricOrNaN(trace, m.name.c_str()));
  }
  j["events"] = events;
  if (!schema_.task_names.empty() && schema_.task_names.size() == r.result.task.size()) {
    nlohmann::json task = nlohmann::json::object();
    for (size_t i = 0; i < r.result.task.size(); ++i) task[schema_.task_names[i]] = number(r.result.task[i]);
    j["task"] = task;
  }
  j["event_log"] = nlohmann::json::array();
  for (const TraceEvent& e : trace.events) j["event_log"].push_back({{"time", e.time}, {"name", e.name}, {"detail", e.detail}});
  j["simulated_s"] = simulatedOf(trace);
  j["wall_s"] = r.result.episode.wall_seconds;
  j["trace"] = trace_file;  // "" when no trace was written (--trace)
  json_.push_back(std::move(j));

  auto ev = [&](const char* name) { return csvCell(event(trace, name) ? event(trace, name)->time : NAN); };
  std::string row = csvText(r.episode.label) + ',';
  // pronk eval's jumps.csv names and units: angles in degrees.
  for (double v : {t.x, t.y, t.z, t.yaw * kDeg, l.displacement.x(), l.displacement.y(), l.displacement.z(),
                   l.yaw * kDeg, l.error_xy, l.height, l.error, l.error_yaw * kDeg}) {
    row += csvCell(v) + ',';
  }
  row += o.status + ',' + csvCell(r.result.reward) + ',' + ev("lift_off") + ',' + ev("touchdown") + ',' + ev("at_rest") + ',';
  for (const MetricSpec* spec : tableColumns(schema_)) row += csvCell(metricOrNaN(trace, spec->name.c_str())) + ',';
  row += std::string(l.standing && o.status != "failed" ? "1" : "0") + "," + csvText(o.reason) + '\n';
  csv_ += row;
}

void JumpResultsFiles::write(const std::string& dir) const {
  namespace fs = std::filesystem;
  const nlohmann::json document = {{"format", "pronk-results"}, {"version", 2}, {"run", run_}, {"jumps", json_}};
  replaceFileAtomically((fs::path(dir) / "results.json").string(), document.dump(2) + "\n", "results file");
  std::string csv =
      "case,target_x,target_y,target_z,target_yaw_deg,landed_x,landed_y,landed_z,landed_yaw_deg,error_xy,landed_height,"
      "error,"
      "error_yaw_deg,"
      "status,reward,lift_off,touchdown,at_rest,";
  for (const MetricSpec* spec : tableColumns(schema_)) csv += spec->name + ',';
  csv += "ended_standing,reason\n" + csv_;
  replaceFileAtomically((fs::path(dir) / "results.csv").string(), csv, "results file");
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(std::ceil(p * v.size())) - (p > 0 ? 1 : 0))];
}

}  // namespace pronk
