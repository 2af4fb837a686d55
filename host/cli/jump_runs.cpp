// `pronk run SCENARIO --policy ...`: one episode of the scenario's environment
// per target (or per sweep case), a table of landings, results files and videos.
#include "jump_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <Eigen/Geometry>

#include "controller_factory.h"
#include "jump_landing.h"
#include "pronk/episode.h"
#include "pronk/world.h"
#include "render/episode_video.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = 180.0 / M_PI;

// A metric of the trace, NaN when absent or not finite (JSON null, empty CSV cell).
double metricOrNaN(const Trace& trace, const char* name) {
  const double* v = trace.findMetric(name);
  return v && std::isfinite(*v) ? *v : NAN;
}

struct JumpReport {
  EpisodeCase episode;
  EnvironmentEpisodeResult result;
  Landing landing;
  std::string status;  // ok | missed | rejected | failed
  std::string reason;
};

std::string statusOf(const JumpReport& r) {
  if (r.result.rejected) return "rejected";
  if (r.result.episode.failure || !r.landing.end_failure.empty()) return "failed";
  const TargetSpec& t = r.episode.target;
  if ((t.tolerance_xy && !(r.landing.error_xy <= *t.tolerance_xy)) ||
      (t.tolerance_yaw && !(r.landing.error_yaw <= *t.tolerance_yaw))) {
    return "missed";
  }
  return "ok";
}

std::string reasonOf(const JumpReport& r) {
  if (r.result.rejected) return *r.result.rejected;
  if (r.result.episode.failure) return r.result.episode.failure->reason + ": " + r.result.episode.failure->detail;
  if (!r.landing.end_failure.empty()) return r.landing.end_failure;
  if (r.status == "missed") {
    char text[160];
    std::snprintf(text, sizeof text, "error %.1f cm / %.1f deg beyond the tolerance %.1f cm / %.1f deg",
                  100 * r.landing.error_xy, r.landing.error_yaw * kDeg,
                  100 * r.episode.target.tolerance_xy.value_or(INFINITY),
                  r.episode.target.tolerance_yaw.value_or(INFINITY) * kDeg);
    return text;
  }
  return "";
}

const TraceEvent* event(const Trace& trace, const char* name) { return trace.findEvent(name); }

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json toJson(const JumpReport& r, const std::string& trace_file) {
  const Trace& trace = r.result.episode.trace;
  const TargetSpec& t = r.episode.target;
  nlohmann::json j;
  j["case"] = r.episode.label;
  j["target"] = {{"name", t.name}, {"x", t.x}, {"y", t.y}, {"z", t.z}, {"yaw", t.yaw}, {"roll", t.roll}, {"pitch", t.pitch}};
  j["landing"] = {{"x", number(r.landing.displacement.x())},
                  {"y", number(r.landing.displacement.y())},
                  {"z", number(r.landing.displacement.z())},
                  {"yaw", number(r.landing.yaw)}};
  j["error_xy"] = number(r.landing.error_xy);
  j["error_yaw_deg"] = number(r.landing.error_yaw * kDeg);
  j["status"] = r.status;
  j["failed"] = r.status == "failed";
  j["rejected"] = r.status == "rejected";
  j["failure_reason"] = r.reason;
  j["ended_standing"] = r.landing.standing && r.status != "failed";
  j["reward"] = r.result.reward;
  j["observation"] = r.result.observation;
  j["action"] = r.result.action;
  nlohmann::json penalties = nlohmann::json::object(), metrics = nlohmann::json::object();
  for (const TraceMetric& m : trace.metrics) {
    if (m.name.rfind("penalty_", 0) == 0) penalties[m.name.substr(8)] = number(m.value);
    else metrics[m.name] = number(m.value);
  }
  j["penalties"] = penalties;
  j["metrics"] = metrics;
  nlohmann::json events = nlohmann::json::object();
  for (const char* name : {"lift_off", "touchdown"}) {
    const TraceEvent* e = event(trace, name);
    events[name] = e ? nlohmann::json(e->time) : nlohmann::json(nullptr);
  }
  for (const char* name : {"planned_lift_off_time", "planned_apex_time", "planned_touchdown_time", "apex_time",
                           "rest_time"}) {
    events[name] = number(metricOrNaN(trace, name));
  }
  j["events"] = events;
  j["event_log"] = nlohmann::json::array();
  for (const TraceEvent& e : trace.events) j["event_log"].push_back({{"time", e.time}, {"name", e.name}, {"detail", e.detail}});
  j["simulated_s"] = trace.samples.empty() ? 0.0 : trace.samples.back().time;
  j["wall_s"] = r.result.episode.wall_seconds;
  j["trace"] = trace_file;
  return j;
}

std::string csvCell(double v) {
  if (!std::isfinite(v)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

void writeResultsCsv(const std::vector<JumpReport>& reports, const std::string& path) {
  std::ofstream out(path);
  out << "case,target_x,target_y,target_z,target_yaw,landing_x,landing_y,landing_z,landing_yaw,error_xy,error_yaw_deg,"
         "status,reward,lift_off,planned_lift_off,apex,planned_apex,touchdown,planned_touchdown,predicted_landing_x,"
         "predicted_landing_y,rest_time,ended_standing,reason\n";
  for (const JumpReport& r : reports) {
    const Trace& trace = r.result.episode.trace;
    const TargetSpec& t = r.episode.target;
    auto ev = [&](const char* name) { return csvCell(event(trace, name) ? event(trace, name)->time : NAN); };
    auto m = [&](const char* name) { return csvCell(metricOrNaN(trace, name)); };
    std::string reason = r.reason;
    for (char& c : reason)
      if (c == '"') c = '\'';
    out << '"' << r.episode.label << "\"," << csvCell(t.x) << ',' << csvCell(t.y) << ',' << csvCell(t.z) << ','
        << csvCell(t.yaw) << ',' << csvCell(r.landing.displacement.x()) << ',' << csvCell(r.landing.displacement.y())
        << ',' << csvCell(r.landing.displacement.z()) << ',' << csvCell(r.landing.yaw) << ','
        << csvCell(r.landing.error_xy) << ',' << csvCell(r.landing.error_yaw * kDeg) << ',' << r.status << ','
        << csvCell(r.result.reward) << ',' << ev("lift_off") << ',' << m("planned_lift_off_time") << ','
        << m("apex_time") << ',' << m("planned_apex_time") << ',' << ev("touchdown") << ','
        << m("planned_touchdown_time") << ',' << m("predicted_landing_x") << ',' << m("predicted_landing_y") << ','
        << m("rest_time") << ',' << (r.landing.standing && r.status != "failed" ? 1 : 0) << ",\"" << reason << "\"\n";
  }
  if (!out) throw Error(path + ": cannot write");
}

std::string timePair(const Trace& trace, const char* planned, const char* actual_event, const char* actual_metric) {
  const double* p = trace.findMetric(planned);
  double a = NAN;
  if (actual_event && event(trace, actual_event)) a = event(trace, actual_event)->time;
  if (actual_metric && trace.findMetric(actual_metric)) a = *trace.findMetric(actual_metric);
  char text[32];
  std::snprintf(text, sizeof text, "%5.3f/%5.3f", p ? *p : NAN, a);
  return text;
}

void printRow(size_t index, const JumpReport& r) {
  const Trace& trace = r.result.episode.trace;
  const TargetSpec& t = r.episode.target;
  const Landing& l = r.landing;
  const double* px = trace.findMetric("predicted_landing_x");
  const double* py = trace.findMetric("predicted_landing_y");
  std::printf("| %3zu | %5.2f %5.2f %5.2f %6.1f | %5.2f %5.2f %5.2f %6.1f | %6.1f | %5.1f | %s | %s | %s | %5.2f %5.2f | "
              "%-8s | %5.3f |\n",
              index, t.x, t.y, t.z, t.yaw * kDeg, l.displacement.x(), l.displacement.y(), l.displacement.z(),
              l.yaw * kDeg, 100 * l.error_xy, l.error_yaw * kDeg,
              timePair(trace, "planned_lift_off_time", "lift_off", nullptr).c_str(),
              timePair(trace, "planned_apex_time", nullptr, "apex_time").c_str(),
              timePair(trace, "planned_touchdown_time", "touchdown", nullptr).c_str(), px ? *px : NAN, py ? *py : NAN,
              r.status.c_str(), r.result.reward);
  if (!r.reason.empty()) std::printf("|     |   %s\n", r.reason.c_str());
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

// The world-frame target marker, planned arc and predicted landing of a jump for the video.
render::SceneMarkers jumpMarkers(const JumpReport& r, const World& world) {
  render::SceneMarkers m;
  const Trace& trace = r.result.episode.trace;
  const TraceSample& s0 = trace.samples.front();
  const double yaw0 = yawOf(s0.base_quaternion);
  const Eigen::AngleAxisd heading(yaw0, Eigen::Vector3d::UnitZ());
  const TargetSpec& t = r.episode.target;
  const auto ground = world.terrain().topAt(s0.base_position.x(), s0.base_position.y());
  const double surface = ground ? ground->height : 0.0;
  const Eigen::Vector3d start_ground(s0.com_position.x(), s0.com_position.y(), surface);
  // The target marks where the trunk should come to rest, on the landing surface.
  const Eigen::Vector3d trunk_ground(s0.base_position.x(), s0.base_position.y(), surface);
  m.target = trunk_ground + heading * Eigen::Vector3d(t.x, t.y, t.z);
  m.target_yaw = yaw0 + t.yaw;
  m.landing_error = r.landing.error_xy;
  const double* x = trace.findMetric("planned_lift_off_x");
  const double* px = trace.findMetric("predicted_landing_x");
  if (x && px) {
    const double* y = trace.findMetric("planned_lift_off_y");
    const double* z = trace.findMetric("planned_lift_off_z");
    const double* vx = trace.findMetric("planned_lift_off_vx");
    const double* vy = trace.findMetric("planned_lift_off_vy");
    const double* vz = trace.findMetric("planned_lift_off_vz");
    const double* tf = trace.findMetric("planned_flight_time");
    if (y && z && vx && vy && vz && tf && std::isfinite(*tf)) {
      const Eigen::Vector3d p(*x, *y, *z), v(*vx, *vy, *vz), g = world.gravity();
      for (int i = 0; i <= 40; ++i) {
        const double tt = *tf * i / 40;
        m.planned_arc.push_back(start_ground + heading * (p + v * tt) + 0.5 * g * tt * tt);
      }
      m.predicted_landing = m.planned_arc.back();
      m.predicted_landing->z() = surface + t.z;
    }
  }
  return m;
}

// --duration sets the episode length, which the environment's `duration`
// parameter owns in a jump run (resolveParams refuses it, naming the flag, for
// an environment without one or a value out of its range).
std::vector<ParamSetting> withDurationOption(std::vector<ParamSetting> params, const RunOptions& options) {
  if (options.duration <= 0) return params;
  char value[32];
  std::snprintf(value, sizeof value, "%.17g", options.duration);
  setParam(params, {"duration", value, SourceLocation{"--duration", 0}});
  return params;
}

}  // namespace

std::vector<ParamSetting> withParamOptions(std::vector<ParamSetting> params, const RunOptions& options) {
  for (const std::string& option : options.params) {
    const size_t eq = option.find('=');  // main() checked there is one, after a name
    setParam(params, {option.substr(0, eq), option.substr(eq + 1), SourceLocation{"--param", 0}});
  }
  return params;
}

bool runsJumps(const Scenario& scenario, const RunOptions& options) {
  return scenario.environment && options.controller.empty();
}

int runJumps(const CommonOptions& common, const RunOptions& options, const Scenario& scenario) {
  const EnvironmentSpec& spec = *scenario.environment;
  std::string policy_name = options.policy.empty() ? spec.policy : options.policy;
  if (policy_name.empty()) {
    throw InputError(spec.where, "<environment>: no policy: give --policy ballistic or --policy FILE (or the "
                                 "element's policy attribute)");
  }
  PluginRegistry registry;
  ControllerSpec as_controller{spec.factory, spec.plugin, spec.params, spec.where};
  loadPlugins(registry, common.plugin_paths, &as_controller);
  const pronk_factory& factory = findEnvironment(spec, registry);
  const std::string origin = registry.libraryOf(&factory)->path();
  const ResolvedParams params =
      resolveParams(factory, withDurationOption(withParamOptions(spec.params, options), options), spec.where);

  const Policy policy = makePolicy(policy_name, factory);

  const std::vector<EpisodeCase> cases = options.sweep.empty() ? targetCases(scenario) : sweepCases(scenario, options.sweep);
  const render::VideoOptions video = videoOptions(scenario, options);
  if (!video.path.empty()) checkWritable(video.path);
  if (!options.out_dir.empty()) {
    std::error_code ec;
    fs::create_directories(options.out_dir, ec);
    if (ec) throw Error("--out " + options.out_dir + ": cannot create the directory: " + ec.message());
  }

  std::printf("scenario    %s\n", options.scenario.c_str());
  std::printf("environment %s (%s), policy %s, %zu jump(s)%s\n", factory.name, origin.c_str(), policy_name.c_str(),
              cases.size(), options.sweep.empty() ? "" : (", sweep " + options.sweep).c_str());
  std::printf("\n| %3s | %-25s | %-25s | %6s | %5s | %-11s | %-11s | %-11s | %-11s | %-8s | %5s |\n", "#",
              "target x y z [m] yaw[deg]", "landing x y z [m] yaw[deg]", "err cm", "yaw ", "lift-off s", "apex s",
              "touchdown s", "pred. xy m", "status", "reward");
  std::printf("|-----|---------------------------|---------------------------|--------|-------|-------------|"
              "-------------|-------------|-------------|----------|-------|\n");
  std::fflush(stdout);

  std::unique_ptr<render::EpisodeVideo> movie;
  nlohmann::json results = nlohmann::json::array();
  std::vector<JumpReport> reports;
  std::vector<double> errors, yaw_errors, rest_times;
  int standing = 0, failed = 0, rejected = 0, missed = 0;
  double wall = 0, simulated = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    JumpReport r;
    r.episode = cases[i];
    const Scenario s = applyCase(scenario, r.episode);
    World world(s);
    if (i == 0)
      for (const std::string& w : world.robot().warnings) std::cerr << "warning: " << w << "\n";
    const TargetSpec& t = r.episode.target;
    EpisodeOptions episode;
    episode.duration = 120;  // the environment ends the episode; this only bounds a runaway one
    episode.record_body_poses = !video.path.empty();
    r.result = runEnvironmentEpisode(world, factory, origin, params, {t.x, t.y, t.z, t.yaw, t.roll, t.pitch}, i,
                                     policy, episode);
    r.landing = landingOf(r.result.episode.trace, t);
    r.status = statusOf(r);
    r.reason = reasonOf(r);
    printRow(i, r);
    std::fflush(stdout);
    wall += r.result.episode.wall_seconds;
    if (!r.result.episode.trace.samples.empty()) simulated += r.result.episode.trace.samples.back().time;
    if (r.status == "failed") ++failed;
    if (r.status == "rejected") ++rejected;
    if (r.status == "missed") ++missed;
    if (r.status == "ok" || r.status == "missed") {
      errors.push_back(r.landing.error_xy);
      yaw_errors.push_back(r.landing.error_yaw * kDeg);
      if (r.landing.standing) ++standing;
      if (const double* rest = r.result.episode.trace.findMetric("rest_time"); rest && std::isfinite(*rest)) {
        rest_times.push_back(*rest);
      }
    }
    std::string trace_file;
    if (!options.out_dir.empty() && !r.result.episode.trace.samples.empty()) {
      char name[32];
      std::snprintf(name, sizeof name, "jump-%03zu.csv", i);
      trace_file = name;
      writeTraceCsv(r.result.episode.trace, (fs::path(options.out_dir) / name).string());
    }
    results.push_back(toJson(r, trace_file));
    if (!video.path.empty() && !r.result.episode.trace.samples.empty()) {
      if (options.video_per_jump) {
        render::VideoOptions one = video;
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "-%03zu", i);
        one.path = (fs::path(video.path).parent_path() / (fs::path(video.path).stem().string() + suffix +
                                                           fs::path(video.path).extension().string()))
                       .string();
        const render::VideoSummary v = render::renderEpisodeVideo(r.result.episode.trace, world.robot(), world.terrain(),
                                                                  jumpMarkers(r, world), one, &std::cerr);
        std::printf("video %s: %d frames, %.2f s\n", v.path.c_str(), v.frames, v.duration_s);
      } else {
        if (!movie) movie = std::make_unique<render::EpisodeVideo>(video, &std::cerr);
        movie->add(r.result.episode.trace, world.robot(), world.terrain(), jumpMarkers(r, world), r.episode.label);
      }
    }
    r.result.episode.trace.samples.clear();  // keep memory bounded over long sweeps
    r.result.episode.trace.samples.shrink_to_fit();
    reports.push_back(std::move(r));
  }

  const size_t landed = errors.size();
  std::printf("\n%zu jump(s): %zu landed (%d missed their tolerance), %d rejected before running, %d failed\n",
              cases.size(), landed, missed, rejected, failed);
  if (landed > 0) {
    std::printf("landing error: median %.1f cm, 90th percentile %.1f cm, max %.1f cm; yaw error median %.1f deg\n",
                100 * median(errors), 100 * percentile(errors, 0.9), 100 * percentile(errors, 1.0), median(yaw_errors));
    std::printf("ended standing: %d of %zu; time to rest (CoM < 0.05 m/s): median %.2f s\n", standing, landed,
                median(rest_times));
  }
  const int ran = static_cast<int>(cases.size()) - rejected;  // a rejected jump simulates nothing
  if (ran > 0 && wall > 0) {
    std::printf("simulated %.1f s in %.1f s wall (%.1fx real time, %.2f jumps/s)\n", simulated, wall,
                simulated / wall, ran / wall);
  } else {
    std::printf("simulated nothing\n");
  }

  if (!options.out_dir.empty()) {
    const std::string json_path = (fs::path(options.out_dir) / "results.json").string();
    std::ofstream out(json_path);
    if (!(out << results.dump(2) << "\n")) throw Error(json_path + ": cannot write");
    const std::string csv_path = (fs::path(options.out_dir) / "results.csv").string();
    writeResultsCsv(reports, csv_path);
    std::printf("wrote %s, %s and a trace per jump\n", json_path.c_str(), csv_path.c_str());
  }
  if (movie) {
    const render::VideoSummary v = movie->finish();
    for (const std::string& w : v.warnings) std::cerr << "warning: " << w << "\n";
    for (const std::string& png : v.stills) std::printf("still %s\n", png.c_str());
    std::printf("video %s: %d frames, %.2f s at %.0f fps (speed %.2f), %.1f MB, rendered in %.1f s\n", v.path.c_str(),
                v.frames, v.duration_s, video.fps, video.speed, v.bytes / 1e6, v.wall_s);
  }
  return failed + rejected + missed > 0 ? kEpisodeFailed : kOk;
}

}  // namespace pronk::cli
