// Planning latency: what a jump costs before its first control tick.
//
//   observation (target) -> action -> safety check -> trajectory ready
//
// Each benchmark cycles through the same 256 targets, drawn once with a fixed
// seed from the paper's region (x [-0.6, 1.2] m, y [-0.6, 0.6] m,
// z [-0.4, 0.4] m, yaw [-90, 90] deg), so that the mix of planner branches
// (feasible at the first candidate, candidate search, every candidate failing)
// is that of the region. One benchmark iteration is one whole cycle (the Time
// column); the counters (see runCycles) are per target: `per_target` the mean
// latency, `p50` the median latency, `p90`, `max`, and the shares `feasible`
// (planJump) and `safe` (the safety filter).
//
// Benchmarks: BM_Pipeline (target -> planJump -> raw action -> mapAction ->
// safety check -> ThrustPlan + OrientationTrajectory), BM_ActionToTrajectory
// (raw action -> ... -> trajectory ready: a learned policy's cost after its
// MLP), BM_PlanJump (planJump alone); each for the Go1 with its leg workspace
// (go1_legs) and with the action ranges only (ranges_only).
//
// The default run repeats each benchmark 5 times and prints only the aggregates
// (mean, median, stddev, cv); the goal is a median latency of at most 50 us for
// the whole pipeline (docs/method-planner.md, "Planning latency").
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <random>
#include <vector>

#include "method/action_mapping.h"
#include "method/ballistics.h"
#include "method/explosive_phase.h"
#include "method/leg_ik.h"
#include "method/orientation_trajectory.h"
#include "method/planner.h"
#include "method/safety_filter.h"
#include "method/thrust_trajectory.h"

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kTargetCount = 256;
constexpr std::uint32_t kSeed = 20240607;

// Go1 standing at (0, 0.75, -1.5) with the prototype's CoM 0.0134 m behind and
// 0.0036 m below the trunk centre (as in tests/jump_method/planner_test.cpp).
const Eigen::Vector3d kStanceQ(0.0, 0.75, -1.5);
const Eigen::Vector3d kComToTrunk(0.0134, 0.0, 0.0036);

// Uniform in [lo, hi] from mt19937's raw output (which the standard fixes),
// not from std::uniform_real_distribution (which it does not): the same
// targets with every standard library.
double uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967295.0);
}

const std::vector<JumpTarget>& targets() {
  static const std::vector<JumpTarget> all = [] {
    std::mt19937 rng(kSeed);
    std::vector<JumpTarget> t(kTargetCount);
    for (JumpTarget& target : t) {
      const double x = uniform(rng, -0.6, 1.2);
      const double y = uniform(rng, -0.6, 0.6);
      const double z = uniform(rng, -0.4, 0.4);
      target.displacement = Eigen::Vector3d(x, y, z);
      target.yaw_rad = uniform(rng, -kPi / 2, kPi / 2);
    }
    return t;
  }();
  return all;
}

PlannerConfig go1Config(bool with_legs) {
  PlannerConfig cfg;
  cfg.start_com = {0.0, 0.0, 0.3081};
  if (with_legs) cfg.workspace = standingWorkspace(go1Legs(), kStanceQ, cfg.start_com, kComToTrunk);
  return cfg;
}

// The target CoM the planner aims at (docs/method-planner.md, step 1).
Eigen::Vector3d targetCom(const JumpTarget& target, const PlannerConfig& cfg) {
  return cfg.polarOrigin() + target.displacement + Eigen::Vector3d(0.0, 0.0, cfg.standingHeight());
}

// The physical feasibility check: ballistic (the apex reaches the target
// height, the CoM comes down within 5 cm of the target CoM) and, with legs,
// every stance foot reachable at the lift-off pose (the trunk at the lift-off
// CoM with the action's lift-off orientation).
struct SafetyFilter {
  SafetyCheck ballistic;
  const LegWorkspace* legs = nullptr;

  explicit SafetyFilter(const PlannerConfig& cfg) : legs(cfg.workspace ? &*cfg.workspace : nullptr) {
    ballistic.gravity = cfg.gravity;
    ballistic.max_landing_miss = 0.05;
  }

  bool operator()(const PointState& lift_off, const Eigen::Vector3d& target_com, const JumpAction& action) const {
    if (!ballistic(FlightState{lift_off.position, lift_off.velocity}, target_com).safe()) return false;
    if (!legs) return true;
    const Eigen::Matrix3d R = rotationFromRpy(action.liftoff_rpy_rad);
    return feetReachable(legs->legs, legs->feet, lift_off.position + R * legs->com_to_trunk, R,
                         legs->require_within_limits);
  }
};

// Everything after the action is known: the raw 13 numbers (as a policy's MLP
// outputs them) -> physical action -> thrust plan and its lift-off state ->
// safety check -> orientation trajectory (trajectory ready). Returns whether
// the jump is safe.
bool actionToTrajectory(const ActionVector& raw, const Eigen::Vector3d& displacement, const Eigen::Vector3d& target_com,
                        const PlannerConfig& cfg, const SafetyFilter& filter) {
  const MappedAction mapped = mapAction(raw, cfg.ranges);
  const double azimuth = jumpPlaneAzimuth(displacement);
  const ThrustPlan thrust(mapped.action, azimuth, cfg.start_com, cfg.polarOrigin());
  const bool safe = filter(thrust.liftOff(), target_com, mapped.action);
  const OrientationTrajectory orientation(Eigen::Vector3d::Zero(), mapped.action, thrust.duration());
  benchmark::DoNotOptimize(&thrust);
  benchmark::DoNotOptimize(&orientation);
  return safe;
}

// What one target's step reports: whether planJump found it feasible and
// whether the safety filter passed it (-1: not part of this step).
struct Outcome {
  int feasible = -1;
  int safe = -1;
};

// Runs `step(i)` for every target i. The timed loop: one iteration is a whole
// cycle over the 256 targets, so every repetition sees the region's exact
// branch mix; the `per_target` counter is the CPU time of a cycle / 256 (the
// mean latency). Then, untimed by the library, a distribution pass times each
// target on its own (steady_clock; the median of up to 9 passes for cheap
// steps) and reports the per-target latency quantiles p50 (the median
// latency), p90 and max, in seconds, and the feasible and safe shares.
template <typename Step>
void runCycles(benchmark::State& state, Step step) {
  const std::size_t n = targets().size();
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) benchmark::DoNotOptimize(step(i));
  }
  state.counters["per_target"] = benchmark::Counter(static_cast<double>(n),
                                                    benchmark::Counter::kIsIterationInvariantRate |
                                                        benchmark::Counter::kInvert);

  using Clock = std::chrono::steady_clock;
  std::vector<std::vector<double>> samples(n);
  int feasible = 0, safe = 0;
  bool has_feasible = false, has_safe = false;
  double pass_time = 0.0;
  for (int pass = 0; pass < 9 && (pass == 0 || pass_time * pass < 0.02); ++pass) {
    const Clock::time_point pass_start = Clock::now();
    for (std::size_t i = 0; i < n; ++i) {
      const Clock::time_point t0 = Clock::now();
      const Outcome outcome = step(i);
      const Clock::time_point t1 = Clock::now();
      benchmark::DoNotOptimize(outcome);
      samples[i].push_back(std::chrono::duration<double>(t1 - t0).count());
      if (pass == 0) {
        has_feasible = outcome.feasible >= 0;
        has_safe = outcome.safe >= 0;
        feasible += outcome.feasible > 0;
        safe += outcome.safe > 0;
      }
    }
    pass_time = std::chrono::duration<double>(Clock::now() - pass_start).count();
  }
  std::vector<double> latency(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double>& v = samples[i];
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    latency[i] = v[v.size() / 2];
  }
  std::sort(latency.begin(), latency.end());
  state.counters["p50"] = latency[n / 2];
  state.counters["p90"] = latency[(n * 9) / 10];
  state.counters["max"] = latency.back();
  if (has_feasible) state.counters["feasible"] = static_cast<double>(feasible) / n;
  if (has_safe) state.counters["safe"] = static_cast<double>(safe) / n;
}

// 1 and 2: target -> planJump -> unmapAction (the raw action a policy would
// output) -> mapAction -> safety check -> ThrustPlan + OrientationTrajectory.
void BM_Pipeline(benchmark::State& state, bool with_legs) {
  const PlannerConfig cfg = go1Config(with_legs);
  const std::vector<JumpTarget>& all = targets();
  const SafetyFilter filter(cfg);
  runCycles(state, [&](std::size_t i) {
    const JumpTarget& target = all[i];
    const PlannedJump plan = planJump(target, cfg);
    const ActionVector raw = unmapAction(plan.action, cfg.ranges);
    return Outcome{plan.feasible, actionToTrajectory(raw, target.displacement, plan.target_com, cfg, filter)};
  });
}

// The planner's actions for targets(), unmapped (as a policy would output
// them); planned once per configuration, outside any timing.
const std::vector<ActionVector>& plannedRawActions(bool with_legs) {
  static std::array<std::vector<ActionVector>, 2> cache;
  std::vector<ActionVector>& raws = cache[with_legs ? 1 : 0];
  if (raws.empty()) {
    const PlannerConfig cfg = go1Config(with_legs);
    for (const JumpTarget& target : targets()) raws.push_back(unmapAction(planJump(target, cfg).action, cfg.ranges));
  }
  return raws;
}

// 3: only what a learned policy's action costs after the MLP: raw action ->
// mapAction -> safety check -> trajectory ready. The raw actions are the
// planner's (plannedRawActions).
void BM_ActionToTrajectory(benchmark::State& state, bool with_legs) {
  const PlannerConfig cfg = go1Config(with_legs);
  const std::vector<JumpTarget>& all = targets();
  const std::vector<ActionVector>& raws = plannedRawActions(with_legs);
  std::vector<Eigen::Vector3d> target_coms;
  for (const JumpTarget& target : all) target_coms.push_back(targetCom(target, cfg));
  const SafetyFilter filter(cfg);
  runCycles(state, [&](std::size_t i) {
    return Outcome{-1, actionToTrajectory(raws[i], all[i].displacement, target_coms[i], cfg, filter)};
  });
}

// 4: planJump alone.
void BM_PlanJump(benchmark::State& state, bool with_legs) {
  const PlannerConfig cfg = go1Config(with_legs);
  const std::vector<JumpTarget>& all = targets();
  runCycles(state, [&](std::size_t i) {
    const PlannedJump plan = planJump(all[i], cfg);
    benchmark::DoNotOptimize(&plan);
    return Outcome{plan.feasible, -1};
  });
}

BENCHMARK_CAPTURE(BM_Pipeline, go1_legs, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Pipeline, ranges_only, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ActionToTrajectory, go1_legs, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ActionToTrajectory, ranges_only, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanJump, go1_legs, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlanJump, ranges_only, false)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pronk::jump

// Default flags, before the user's (the last occurrence of a flag wins): 5
// repetitions, aggregates only (so the median prints), 0.2 s per repetition.
// Not set per benchmark, because per-benchmark settings would override the
// command line (the smoke test passes a tiny --benchmark_min_time).
int main(int argc, char** argv) {
  std::vector<char*> args{argv[0]};
  static char repetitions[] = "--benchmark_repetitions=5";
  static char aggregates[] = "--benchmark_report_aggregates_only=true";
  static char min_time[] = "--benchmark_min_time=0.2";
  args.insert(args.end(), {repetitions, aggregates, min_time});
  args.insert(args.end(), argv + 1, argv + argc);
  int count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
