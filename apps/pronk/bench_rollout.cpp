// `pronk bench --rollout`: the Go1 region sweep (scenarios/go1/region.xml, 40
// targets) through the path `pronk run` took before the rollout engine (a World
// built from the URDF per case, every episode to the environment's end, a
// sample per tick written as a trace CSV, the controller's Newton IK), then
// with each lever added in turn, then on N threads: jumps/s of each, side by
// side in one run, and the largest change of a landing against the first row.
#include "bench_rollout.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "pronk/controller_factory.h"
#include "pronk/report.h"
#include "run_jumps.h"

namespace pronk::cli {
namespace {

namespace fs = std::filesystem;

struct Row {
  std::string label;
  bool newton_ik = false;  // the controller's IK as it was: Newton steps on the host's kinematics
  RolloutOptions options;
  bool write_traces = false;
  double wall_s = 0, simulated_s = 0;  // wall_s: the median over the repeats
  std::vector<double> walls;
  size_t jumps = 0, worlds = 0;
  std::vector<double> errors;  // landing error per case (NaN unless landed)
};

void measure(Row& row, const RolloutSetup& exact, const RolloutSetup& newton, const std::vector<EpisodeCase>& cases,
             const fs::path& trace_dir) {
  const RolloutSetup& setup = row.newton_ik ? newton : exact;
  const auto start = std::chrono::steady_clock::now();
  RolloutPool pool(setup, row.options);
  row.errors.assign(cases.size(), NAN);
  row.simulated_s = 0;
  row.jumps = 0;
  pool.run(cases, [&](EpisodeRecord& r) {
    const JumpOutcome o = judgeJump(r);
    const Trace& trace = r.result.episode.trace;
    if (!trace.samples.empty()) row.simulated_s += trace.samples.back().time;
    if (o.status == "ok" || o.status == "missed") row.errors[r.index] = o.landing.error_xy;
    if (row.write_traces && !trace.samples.empty()) {
      writeTraceCsv(trace, (trace_dir / ("jump-" + std::to_string(r.index) + ".csv")).string());
    }
    ++row.jumps;
  });
  row.walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  row.wall_s = median(row.walls);
  row.worlds = pool.worldsBuilt();
}

// The largest change of a landing error against the first row (mm), over the
// cases both landed.
double largestChange(const Row& row, const Row& base) {
  double worst = 0;
  for (size_t i = 0; i < row.errors.size(); ++i) {
    if (std::isfinite(row.errors[i]) && std::isfinite(base.errors[i])) {
      worst = std::max(worst, std::abs(row.errors[i] - base.errors[i]));
    }
  }
  return 1e3 * worst;
}

}  // namespace

int rolloutBench(const CommonOptions& common, const BenchOptions& options) {
  const std::string path =
      options.scenario.empty() ? dataDirectory() + "/scenarios/go1/region.xml" : options.scenario;
  const Scenario scenario = loadScenario(path);
  if (scenario.sweeps.empty()) throw InputError({path, 0}, "pronk bench --rollout: the scenario has no sweep");
  const std::string sweep = scenario.sweeps.front().name;
  PluginRegistry registry;
  if (!scenario.environment) throw InputError({path, 0}, "pronk bench --rollout: the scenario has no <environment>");
  ControllerSpec as_controller{scenario.environment->factory, scenario.environment->plugin, {}, scenario.environment->where};
  loadPlugins(registry, common.plugin_paths, &as_controller);
  const RolloutSetup setup = environmentSetup(scenario, registry, {}, "ballistic");
  // The environment's `leg_ik` parameter, where it has one: today's path ran the
  // controller's old Newton IK.
  bool has_leg_ik = false;
  for (int32_t i = 0; i < setup.factory->param_count; ++i) has_leg_ik |= std::string(setup.factory->params[i].name) == "leg_ik";
  const RolloutSetup newton =
      has_leg_ik ? environmentSetup(scenario, registry, {{"leg_ik", "newton", {"pronk bench", 0}}}, "ballistic") : setup;
  const std::vector<EpisodeCase> cases = sweepCases(scenario, sweep);
  const int threads = jobsOf(options.jobs);
  const fs::path trace_dir = fs::temp_directory_path() / "pronk-bench-rollout-traces";
  fs::create_directories(trace_dir);

  std::vector<Row> rows(6);
  rows[0].label = "one world per case, full episodes, traces";
  rows[0].newton_ik = has_leg_ik;
  rows[0].options.reuse_worlds = false;
  rows[0].options.end_at_rest = 0;
  rows[0].options.record_samples = true;
  rows[0].write_traces = true;
  rows[1] = rows[0];
  rows[1].label = "+ the controller's exact leg IK";
  rows[1].newton_ik = false;
  rows[2] = rows[1];
  rows[2].label = "+ worlds reused";
  rows[2].options.reuse_worlds = true;
  rows[3] = rows[2];
  rows[3].label = "+ episodes end at rest";
  rows[3].options.end_at_rest = RolloutOptions{}.end_at_rest;
  rows[4] = rows[3];
  rows[4].label = "+ no trace (the engine, 1 thread)";
  rows[4].options.record_samples = false;
  rows[4].write_traces = false;
  rows[5] = rows[4];
  rows[5].label = "the engine, " + std::to_string(threads) + " threads";
  for (size_t i = 0; i + 1 < rows.size(); ++i) rows[i].options.threads = 1;
  rows[5].options.threads = threads;

  std::printf("pronk bench --rollout: %s, sweep %s (%zu cases), policy ballistic, %u core(s), %d round(s) of the "
              "rows in turn, median wall time per row\n\n",
              path.c_str(), sweep.c_str(), cases.size(), std::thread::hardware_concurrency(), options.repeats);
  // Rows run in turn, round after round, so that a drift of the machine's speed
  // reaches every row alike.
  for (int round = 0; round < options.repeats; ++round) {
    for (Row& row : rows) measure(row, setup, newton, cases, trace_dir);
    std::fprintf(stderr, "round %d of %d done\n", round + 1, options.repeats);
  }
  std::printf("| %-44s | %7s | %6s | %11s | %8s | %7s | %8s | %13s |\n", "path", "threads", "worlds", "simulated s",
              "wall s", "jumps/s", "x real", "max d err mm");
  std::printf("|%s|---------|--------|-------------|----------|---------|----------|---------------|\n",
              std::string(46, '-').c_str());
  for (Row& row : rows) {
    std::printf("| %-44s | %7d | %6zu | %11.1f | %8.2f | %7.2f | %7.2fx | %13.2f |\n", row.label.c_str(),
                row.options.threads, row.worlds, row.simulated_s, row.wall_s, row.jumps / row.wall_s,
                row.simulated_s / row.wall_s, largestChange(row, rows[0]));
    std::fflush(stdout);
  }
  fs::remove_all(trace_dir);
  const double speed_up = rows[0].wall_s / rows.back().wall_s;
  std::printf("\nrollout speed-up: %.2fx (%d threads) over one world per case with full episodes and traces\n",
              speed_up, threads);
  return kOk;
}

}  // namespace pronk::cli
