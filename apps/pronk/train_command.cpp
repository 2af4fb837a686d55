// `pronk train FILE --out POLICY`: trains a policy for the scenario's
// environment as its <training> element says (the loop is the library's,
// pronk/training.h); here the options, a progress line per iteration, and
// SIGINT / SIGTERM turned into a checkpoint.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "output_paths.h"
#include "pronk/communicator.h"
#include "pronk/controller_factory.h"
#include "pronk/training.h"
#include "render/plot/training_plots.h"
#include "run_jumps.h"
#include "stop_signal.h"

namespace pronk::cli {
namespace {

struct TrainOptions {
  std::string file;
  std::string out;
  std::string resume;
  int jobs = 0;
  int iterations = 0;  // 0: the file's
  int jumps = 0;       // 0: the file's
  unsigned long seed = 0;
  bool seed_given = false;
};

// "1:02:03", or "-" when unknown.
std::string hms(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "-";
  const long s = std::lround(seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

// The mean of the penalties' sum per jump and the three largest means: what
// the reward is losing most to.
void printPenalties(const TrainingIteration& r) {
  if (!std::isfinite(r.penalty_sum_mean)) return;
  std::vector<size_t> order;
  for (size_t i = 0; i < r.penalty_means.size(); ++i)
    if (std::isfinite(r.penalty_means[i])) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return r.penalty_means[a] > r.penalty_means[b]; });
  std::printf("  penalties %.2f", r.penalty_sum_mean);
  for (size_t k = 0; k < order.size() && k < 3; ++k) {
    std::printf("%s%s %.2f", k == 0 ? " (" : ", ", r.penalty_names[order[k]].c_str(), r.penalty_means[order[k]]);
  }
  if (!order.empty()) std::printf(")");
}

void printRow(const TrainingIteration& r) {
  std::printf("iter %4d/%d  jumps %7lld", r.iteration, r.iterations, r.jumps);
  if (r.iteration > 0) {
    std::printf("  reward %.3f  landed %d/%d (failed %d, rejected %d)", r.reward_mean, r.batch.landed, r.batch.jumps,
                r.batch.failed, r.batch.rejected);
    if (std::isfinite(r.hindsight_pairs)) std::printf("  pairs %.0f", r.hindsight_pairs);
    printPenalties(r);
  }
  if (r.validated) {
    std::printf("  val median %.3f m, mean %.3f m, %.0f %% < 0.2 m, failed %d, rejected %d", r.validation.error_median,
                r.validation.error_mean, 100 * r.validation.within_02, r.validation.failed, r.validation.rejected);
  }
  if (r.iteration > 0) std::printf("  %.1f jumps/s  ETA %s", r.jumps_per_s, hms(r.eta_s).c_str());
  std::printf("\n");
  std::fflush(stdout);
}

std::string commandLine(const TrainOptions& o) {
  std::string c = "pronk train " + o.file + " --out " + o.out;
  if (o.jobs > 0) c += " --jobs " + std::to_string(o.jobs);
  if (o.iterations > 0) c += " --iterations " + std::to_string(o.iterations);
  if (o.jumps > 0) c += " --jumps " + std::to_string(o.jumps);
  if (o.seed_given) c += " --seed " + std::to_string(o.seed);
  if (!o.resume.empty()) c += " --resume " + o.resume;
  return c;
}

// The policy and the files beside it: none replaces a device or a folder, none is an input.
void checkTrainingOutputs(const TrainOptions& o) {
  namespace fs = std::filesystem;
  const std::string curves = trainingCurvesPathFor(o.out);
  const std::string script = (fs::path(curves).parent_path() / (fs::path(curves).stem().string() + ".gp")).string();
  const std::vector<std::pair<std::string, std::string>> outputs = {{o.out, "--out"},
                                                                    {checkpointPathFor(o.out), "--out's checkpoint"},
                                                                    {trainingLogPathFor(o.out), "--out's log"},
                                                                    {curves, "--out's curves"},
                                                                    {script, "--out's plot script"}};
  for (const auto& [path, flag] : outputs) {
    checkOutputFile(path, flag);
    // Resuming rewrites the checkpoint it resumes from, as it should.
    if (path == checkpointPathFor(o.out)) checkNotAnInput(path, flag, {{o.file, "FILE"}});
    else checkNotAnInput(path, flag, {{o.file, "FILE"}, {o.resume, "--resume"}});
  }
}

int trainCommand(const CommonOptions& common, const TrainOptions& o) {
  checkTrainingOutputs(o);
  const Scenario scenario = loadScenario(o.file);
  if (!scenario.training) {
    throw InputError({o.file, 0}, "no <training> element: nothing to train (docs/scenario-format.md)");
  }
  PluginRegistry registry;
  const EnvironmentSpec& spec = *scenario.environment;  // loadScenario: <training> needs an <environment>
  ControllerSpec as_controller{spec.factory, spec.plugin, spec.params, spec.where};
  loadPlugins(registry, common.plugin_paths, &as_controller);

  TrainingRunOptions run;
  run.threads = jobsOf(o.jobs);
  if (o.iterations > 0) run.iterations = o.iterations;
  if (o.jumps > 0) run.jumps_per_iteration = o.jumps;
  if (o.seed_given) run.seed = o.seed;
  run.policy_path = o.out;
  run.resume = o.resume;
  run.command = commandLine(o);
  run.pronk_version = PRONK_VERSION;
  run.git_commit = buildCommit();

  const TrainingSpec& t = *scenario.training;
  // Under mpirun rank 0 learns and reports; the other ranks roll out in silence.
  const Communicator& comm = Communicator::world();
  if (!comm.root()) {
    // A signal (mpirun passes SIGINT and SIGTERM to every rank) leaves a rank to
    // finish its share of the round; rank 0 stops the run and writes what finished.
    const StopOnSignal outlast;
    trainPolicy(scenario, registry, run, nullptr, nullptr);
    return kOk;
  }
  std::printf("training    %s\n", o.file.c_str());
  std::string guidance = t.aim ? "aim correction of its prior_action" : t.residual ? "residual over its prior_action"
                                                                                  : "no prior";
  if (t.hindsight) guidance += ", hindsight";
  if (!t.ppo_actor) guidance += ", PPO fits the critic only";
  std::printf("environment %s, %s, %d iteration(s) x %d jumps, seed %lu, %s%d thread(s)%s%s\n", spec.factory.c_str(),
              guidance.c_str(), run.iterations.value_or(t.iterations),
              run.jumps_per_iteration.value_or(t.jumps_per_iteration), run.seed.value_or(t.seed),
              comm.distributed() ? (std::to_string(comm.size()) + " ranks of ").c_str() : "", run.threads,
              comm.distributed() ? " each" : "", o.resume.empty() ? "" : (", resuming " + o.resume).c_str());
  std::fflush(stdout);

  std::optional<TrainingOutcome> outcome_or;
  int stop_signal = 0;
  {
    const StopOnSignal stop;
    outcome_or = trainPolicy(scenario, registry, run, printRow, stop.flag());
    stop_signal = stop.signal();
  }
  const TrainingOutcome& outcome = *outcome_or;

  if (outcome.interrupted) {
    std::printf("stopped after iteration %d (%lld jumps, %s); continue with --resume %s\n", outcome.iterations_done,
                outcome.jumps, hms(outcome.wall_s).c_str(), outcome.checkpoint_path.c_str());
  } else {
    std::printf("trained %d iteration(s), %lld jumps in %s\n", outcome.iterations_done, outcome.jumps,
                hms(outcome.wall_s).c_str());
  }
  std::printf("wrote %s, %s, %s\n", outcome.policy_path.c_str(), outcome.checkpoint_path.c_str(),
              outcome.log_path.c_str());
  // The curves beside the log; a plotting failure loses nothing trained.
  const std::string curves = trainingCurvesPathFor(outcome.policy_path);
  try {
    render::plot::plotTrainingCurves(render::plot::readTrainingLog(outcome.log_path), scenario.platform.name,
                                     std::filesystem::path(outcome.policy_path).stem().string(), curves);
    std::printf("plot %s\n", curves.c_str());
  } catch (const Error& e) {
    std::fprintf(stderr, "warning: no training curves: %s\n", e.what());
  }
  return outcome.interrupted && stop_signal ? 128 + stop_signal : kOk;
}

}  // namespace

Subcommand declareTrain(CLI::App& app, const CommonOptions& common) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* sub = app.add_subcommand("train", "train a policy with PPO as a scenario's <training> element says");
  sub->add_option("file", o->file, "training file: a scenario with <environment> and <training>")->required();
  sub->add_option("--out", o->out, "the policy file to write; its checkpoint (STEM.checkpoint.json), its "
                                   "log (STEM.train_log.csv) and curves (STEM.train_curves.png) go beside it")
      ->required();
  sub->add_option("--jobs,-j", o->jobs, "worker threads, one World each (default: one per core); the result does not "
                                     "depend on it")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--iterations", o->iterations, "iterations of the whole run (default: the file's)")
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--jumps", o->jumps, "jumps per iteration (default: the file's jumps_per_iteration)")
      ->check(CLI::Range(1, 1000000));
  CLI::Option* seed = sub->add_option("--seed", o->seed, "random seed (default: the file's)")
                          ->check(CLI::Range(0ul, 4294967295ul));
  sub->add_option("--resume", o->resume, "continue from this checkpoint (a run with the same file, --jumps and "
                                         "--seed continues bit for bit)")
      ->check(CLI::ExistingFile);
  return {sub, [&common, o, seed] {
            o->seed_given = seed->count() > 0;
            return trainCommand(common, *o);
          }};
}

}  // namespace pronk::cli
