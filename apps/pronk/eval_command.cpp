// `pronk eval FILE... --policy POLICY|ballistic`: every target set and sweep of
// the files through the rollout engine; per set a summary counted as the
// paper counts, the jump log (resumable), the per-jump CSV and the figures;
// summary.json over all sets (docs/evaluation.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "commands.h"
#include "output_paths.h"
#include "progress.h"
#include "pronk/communicator.h"
#include "pronk/evaluation.h"
#include "pronk/file_io.h"
#include "pronk/report.h"
#include "pronk/rollout.h"
#include "render/plot/evaluation_plots.h"
#include "evaluation_sets.h"
#include "run_jumps.h"
#include "stop_signal.h"

namespace pronk::cli {
namespace {

namespace fs = std::filesystem;

struct EvalOptions {
  std::vector<std::string> files;
  std::string policy;               // "" = each file's <environment policy>
  std::vector<std::string> sweeps;  // only these sets ("targets" = the <targets>); empty = all
  std::string out_dir = "pronk-eval";
  bool resume = false;
  bool no_plots = false;
  double radius = 0.2;
  int jobs = 0;
};

std::vector<SetToRun> setsOf(const EvalOptions& o) {
  std::vector<SetToRun> out;
  for (const std::string& file : o.files) addSets(out, file, loadScenario(file), o.sweeps);
  return out;
}

std::string policyLabel(const std::string& policy) {
  return policy == "ballistic" ? policy : fs::path(policy).stem().string();
}

struct SetResult {
  std::string name, file, set;
  SetSummary summary;
  std::vector<std::string> plots;
  bool complete = false;
  std::string error;       // the set could not run: it fails alone
  std::string plot_error;  // it ran, its figures could not be drawn (its figures and summary stay)
};

void printSummaryTable(const std::vector<SetResult>& results, double radius) {
  std::printf("\n| set | jumps | within %.2g m | mean cm | median cm | p90 cm | failed | refused | yaw mean/max deg | standing |\n",
              radius);
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const SetResult& r : results) {
    const SetSummary& s = r.summary;
    if (!r.error.empty()) {
      std::printf("| %s | %zu | error: %s |\n", r.name.c_str(), s.jumps, r.error.c_str());
      continue;
    }
    std::printf("| %s%s | %zu | %.1f %% | %.1f | %.1f | %.1f | %zu (%.1f %%) | %zu (%.1f %%) | %.1f / %.1f | %zu |\n",
                r.name.c_str(), r.complete ? "" : " (unfinished)", s.jumps, 100 * s.withinShare(), 100 * s.mean,
                100 * s.median, 100 * s.p90, s.failed, s.jumps ? 100.0 * s.failed / s.jumps : 0.0, s.rejected,
                s.jumps ? 100.0 * s.rejected / s.jumps : 0.0, s.yaw_mean_deg, s.yaw_max_deg, s.standing);
  }
}

void writeSummary(const EvalOptions& o, const std::vector<SetResult>& results) {
  nlohmann::json sets = nlohmann::json::array();
  for (const SetResult& r : results) {
    nlohmann::json j = {{"set", r.name}, {"file", r.file}, {"sweep", r.set}, {"complete", r.complete},
                        {"summary", toJson(r.summary)}, {"plots", nlohmann::json::array()}};
    for (const std::string& p : r.plots) j["plots"].push_back(fs::path(p).lexically_relative(o.out_dir).string());
    if (!r.error.empty()) j["error"] = r.error;
    if (!r.plot_error.empty()) j["plot_error"] = r.plot_error;
    sets.push_back(j);
  }
  const nlohmann::json summary = {{"pronk_version", PRONK_VERSION}, {"git_commit", buildCommit()},
                                  {"policy", o.policy.empty() ? "(each file's)" : o.policy}, {"sets", sets}};
  replaceFileAtomically((fs::path(o.out_dir) / "summary.json").string(), summary.dump(2) + "\n", "summary file");
}

// Runs `step` on rank 0 alone (what touches --out) and gives its Error, if
// any, to every rank, so that all ranks stop together instead of some waiting
// in a collective.
template <class Step>
void onRootForAll(const Communicator& comm, Step step) {
  std::string error;  // "R" + message: an --out of another run refused; "E" + message: any other error
  if (comm.root()) {
    try {
      step();
    } catch (const ResumeRefused& e) {
      error = std::string("R") + e.what();
    } catch (const Error& e) {
      error = std::string("E") + e.what();
    }
  }
  error = comm.broadcast(error);
  if (error.empty()) return;
  if (error[0] == 'R') throw ResumeRefused(error.substr(1));
  throw SharedError(error.substr(1));
}

// The cases of `todo` over the ranks of an MPI run: in rounds of 16 cases
// per worker thread, rank r runs the round's cases k with k mod K = r, rank 0
// gathers the rows and appends them to the log in `todo`'s order, as one
// process would (an episode's seed is its case index, so a row does not depend
// on the rank that ran it). A round at a time, so that an interrupted run
// keeps every round it finished (--resume).
void runDistributed(const Communicator& comm, RolloutPool& pool, const std::vector<EpisodeCase>& cases,
                    const std::vector<size_t>& todo, JumpLog* log, Progress* progress, const StopOnSignal& stop) {
  const size_t round = static_cast<size_t>(comm.size()) * static_cast<size_t>(pool.threads()) * 16;
  size_t finished = 0;
  for (size_t begin = 0; begin < todo.size(); begin += round) {
    const std::vector<size_t> part(todo.begin() + static_cast<std::ptrdiff_t>(begin),
                                   todo.begin() + static_cast<std::ptrdiff_t>(std::min(begin + round, todo.size())));
    nlohmann::json rows = nlohmann::json::array();
    pool.run(cases, casesOfRank(part, comm.rank(), comm.size()),
             [&](EpisodeRecord& r) { rows.push_back(toJson(jumpRowOf(r, judgeJump(r)))); });
    const nlohmann::json mine = {{"rows", rows}, {"stopped", stop.stopped()}};
    const std::vector<std::string> all = comm.gather(mine.dump());
    bool stopped = false;
    if (comm.root()) {
      std::map<size_t, JumpRow> by_case;
      for (size_t r = 0; r < all.size(); ++r) {
        const nlohmann::json j = nlohmann::json::parse(all[r]);
        stopped = stopped || j.at("stopped").get<bool>();
        for (const nlohmann::json& row : j.at("rows")) {
          JumpRow jump = jumpRowFromJson(row, "the rows of rank " + std::to_string(r));
          by_case.emplace(jump.index, std::move(jump));
        }
      }
      for (size_t index : part) {
        const auto it = by_case.find(index);
        if (it == by_case.end()) continue;  // a stopped rank's unstarted case: --resume runs it
        log->append(it->second);
        progress->done(++finished);
      }
    }
    if (comm.broadcast(stopped ? "stop" : "") == "stop") return;
  }
}

SetResult runSet(const CommonOptions& common, const EvalOptions& o, const SetToRun& set, const StopOnSignal& stop) {
  SetResult result{set.name, set.file, set.set, {}, {}, false, "", ""};
  const std::unique_ptr<SetRollout> run = prepareSet(common, set, o.policy, o.jobs, stop.flag());
  const std::string& policy = run->policy;
  const std::vector<EpisodeCase>& cases = run->cases;
  RolloutPool& pool = *run->pool;
  const nlohmann::json manifest = {{"file", fs::absolute(set.file).lexically_normal().string()},
                                   {"set", set.set},
                                   {"policy", policy == "ballistic" ? policy : fs::absolute(policy).string()},
                                   {"policy_fingerprint", policy == "ballistic" ? "" : fileFingerprint(policy)},
                                   {"cases", cases.size()},
                                   {"cases_fingerprint", casesFingerprint(cases)}};
  // Under mpirun rank 0 alone owns the set's directory; the others run jumps.
  const Communicator& comm = Communicator::world();
  std::optional<EvaluationSetDir> owned;
  std::vector<size_t> todo;
  onRootForAll(comm, [&] {
    owned.emplace((fs::path(o.out_dir) / set.name).string(), manifest, o.resume);
    todo = owned->remaining(cases.size());
  });
  if (comm.distributed()) {
    const nlohmann::json left = comm.broadcast(nlohmann::json(todo).dump());
    todo = nlohmann::json::parse(left.get<std::string>()).get<std::vector<size_t>>();
  }

  const std::string robot = set.scenario.platform.name;
  if (comm.root()) {
    std::printf("set %s: %s, policy %s, %zu jump(s)", set.name.c_str(), set.file.c_str(), policy.c_str(), cases.size());
    if (todo.size() < cases.size()) std::printf(", %zu done before (--resume)", cases.size() - todo.size());
    if (comm.distributed()) std::printf(", %d ranks", comm.size());
    std::printf(", %d thread(s)%s\n", pool.threads(), comm.distributed() ? " each" : "");
    std::fflush(stdout);
  }

  if (comm.distributed()) {
    std::optional<Progress> progress;
    if (comm.root()) progress.emplace("jump", todo.size());
    runDistributed(comm, pool, cases, todo, comm.root() ? &owned->log() : nullptr, progress ? &*progress : nullptr,
                   stop);
    if (!comm.root()) return result;
  } else if (!todo.empty()) {
    Progress progress("jump", todo.size());
    size_t finished = 0;
    pool.run(cases, todo, [&](EpisodeRecord& r) {
      owned->log().append(jumpRowOf(r, judgeJump(r)));
      progress.done(++finished);
    });
  }
  EvaluationSetDir& dir = *owned;
  std::vector<JumpRow> rows = dir.log().rows();
  std::sort(rows.begin(), rows.end(), [](const JumpRow& a, const JumpRow& b) { return a.index < b.index; });
  result.summary = summarize(rows, o.radius);
  result.complete = rows.size() == cases.size();
  writeJumpsCsv(rows, (fs::path(dir.dir()) / "jumps.csv").string());
  const SetSummary& s = result.summary;
  std::printf("  %zu jump(s): %.1f %% within %.2g m; landed %zu: mean %.1f cm, median %.1f cm, p90 %.1f cm; "
              "%zu failed, %zu refused; yaw error mean %.1f deg, max %.1f deg\n",
              s.jumps, 100 * s.withinShare(), o.radius, s.landed, 100 * s.mean, 100 * s.median, 100 * s.p90, s.failed,
              s.rejected, s.yaw_mean_deg, s.yaw_max_deg);
  if (!o.no_plots && result.complete) {
    render::plot::PlotContext context{robot.empty() ? pool.robot().name : robot, policyLabel(policy),
                                      fs::path(set.file).stem().string() + " / " + set.set, o.radius};
    try {
      result.plots = render::plot::plotEvaluationSet(rows, context, dir.dir());
    } catch (const Error& e) {
      // The jumps and the summary are kept; `--resume` draws the figures again.
      result.plot_error = e.what();
      std::fprintf(stderr, "pronk eval: set %s: no figures: %s\n", set.name.c_str(), e.what());
    }
    for (const std::string& p : result.plots) std::printf("  plot %s\n", p.c_str());
  }
  return result;
}

int runEval(const CommonOptions& common, const EvalOptions& o) {
  // Every file is read and checked before any jump runs.
  const std::vector<SetToRun> sets = setsOf(o);
  const Communicator& comm = Communicator::world();
  onRootForAll(comm, [&] {
    std::error_code ec;
    checkOutputDirectory(o.out_dir, "--out");
    if (!o.resume && fs::exists(fs::path(o.out_dir) / "summary.json", ec)) {
      throw Error("--out " + o.out_dir + ": holds an earlier evaluation (summary.json): give --resume, or another --out");
    }
    fs::create_directories(o.out_dir, ec);
    if (ec) throw Error("--out " + o.out_dir + ": cannot create the directory: " + ec.message());
  });

  const StopOnSignal stop;
  const auto start = std::chrono::steady_clock::now();
  std::vector<SetResult> results;
  bool errors = false;
  for (const SetToRun& set : sets) {
    // Every rank takes the same decision (rank 0's), or one would wait for ever.
    if (comm.broadcast(stop.stopped() ? "stop" : "") == "stop") break;
    try {
      results.push_back(runSet(common, o, set, stop));
      errors = errors || !results.back().plot_error.empty();
    } catch (const ResumeRefused&) {
      throw;  // another run's directory: nothing of it, its summary included, is rewritten
    } catch (const Error& e) {
      // The set fails alone, with its reason; the others run.
      if (comm.root()) std::fprintf(stderr, "pronk eval: set %s: %s\n", set.name.c_str(), e.what());
      SetResult failed{set.name, set.file, set.set, {}, {}, false, e.what(), ""};
      results.push_back(failed);
      errors = true;
    }
    if (comm.root()) writeSummary(o, results);
  }
  if (!comm.root()) return kOk;  // rank 0 reports the run and gives its exit status
  printSummaryTable(results, o.radius);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  size_t jumps = 0;
  for (const SetResult& r : results) jumps += r.summary.jumps;
  std::printf("\n%zu set(s), %zu jump(s) in %.1f s; wrote %s\n", results.size(), jumps, wall,
              (fs::path(o.out_dir) / "summary.json").c_str());
  if (stop.signal()) {
    std::fprintf(stderr, "pronk eval: stopped by signal %d; every finished jump is in its set's jumps.jsonl: "
                         "--resume continues\n", stop.signal());
    return 128 + stop.signal();
  }
  return errors ? kInputError : kOk;
}

}  // namespace

Subcommand declareEval(CLI::App& app, const CommonOptions& common) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "Evaluate a policy over every target set and sweep of scenario files: summaries as the paper counts, "
              "per-jump CSV, figures (docs/evaluation.md)");
  cmd->add_option("files", options->files, "scenario files")->required()->check(kNonEmpty);
  cmd->add_option("--policy", options->policy, "ballistic (the planner) or a policy file; default: each file's "
                                                "<environment policy>")
      ->check(kNonEmpty);
  cmd->add_option("--sweep", options->sweeps, "only these sets: a sweep's name, or 'targets' (repeatable)")
      ->check(kNonEmpty);
  cmd->add_option("--out", options->out_dir, "output directory")->check(kNonEmpty)->capture_default_str();
  cmd->add_flag("--resume", options->resume, "continue the evaluation in --out: only the jumps not yet done run");
  cmd->add_flag("--no-plots", options->no_plots, "write no figures");
  cmd->add_option("--radius", options->radius, "accuracy threshold for the shares and the contour, m")
      ->check(finiteIn(0, 100, true))
      ->capture_default_str();
  cmd->add_option("--jobs,-j", options->jobs, "worker threads (default: one per core)")->check(CLI::Range(1, 1024));
  return {cmd, [&common, options] { return runEval(common, *options); }};
}

}  // namespace pronk::cli
