// `pronk check FILE... [--policy P] [--junit REPORT.xml]`: the sets that the
// files' <expect> elements are about run through the rollout engine, and each
// bound is judged; exit 0 only when every bound holds (docs/evaluation.md).
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "output_paths.h"
#include "evaluation_sets.h"
#include "progress.h"
#include "pronk/evaluation.h"
#include "pronk/expectations.h"
#include "pronk/file_io.h"
#include "pronk/report.h"
#include "stop_signal.h"
#include "video_settings.h"

namespace pronk::cli {
namespace {

struct CheckOptions {
  std::vector<std::string> files;
  std::string policy;  // "" = each file's <environment policy>
  std::string junit;   // "" = no report file
  int jobs = 0;
};

void printResult(const ExpectationResult& r) {
  std::printf("%s %s: %s: %s: %s\n", r.held ? "ok  " : "MISS", r.where.str().c_str(), r.subject.c_str(),
              r.check.c_str(), r.measured.c_str());
}

int runCheck(const CommonOptions& common, const CheckOptions& o) {
  // Every file is read and checked before any jump runs.
  struct FileToCheck {
    std::string file;
    Scenario scenario;
    std::vector<SetToRun> sets;
  };
  std::vector<FileToCheck> files;
  std::vector<SetToRun> all;  // for unique set names across files
  for (const std::string& file : o.files) {
    Scenario s = loadScenario(file);
    if (s.expectations.empty()) {
      throw InputError({s.file, 0}, "no <expectations>: nothing for pronk check to check (docs/scenario-format.md)");
    }
    const size_t first = all.size();
    addSets(all, file, s, expectedSets(s));
    files.push_back({file, s, std::vector<SetToRun>(all.begin() + static_cast<std::ptrdiff_t>(first), all.end())});
  }
  if (!o.junit.empty()) {
    checkWritableFile(o.junit, "--junit");
    std::vector<NamedInput> inputs = {{o.policy, "--policy"}};
    for (const std::string& f : o.files) inputs.push_back({f, "FILE"});
    checkNotAnInput(o.junit, "--junit", inputs);
  }

  const StopOnSignal stop;
  std::vector<CheckedFile> checked;
  size_t held = 0, missed = 0;
  for (const FileToCheck& f : files) {
    CheckedFile report{f.file, {}, 0};
    const auto start = std::chrono::steady_clock::now();
    for (const SetToRun& set : f.sets) {
      std::vector<ExpectationResult> results;
      try {
        if (stop.stopped()) throw Error("not run: stopped by a signal");
        const std::unique_ptr<SetRollout> run = prepareSet(common, set, o.policy, o.jobs, stop.flag());
        std::printf("set %s: %s, policy %s, %zu jump(s), %d thread(s)\n", set.name.c_str(), set.file.c_str(),
                    run->policy.c_str(), run->cases.size(), run->pool->threads());
        std::fflush(stdout);
        std::vector<JumpRow> rows;
        Progress progress("jump", run->cases.size());
        run->pool->run(run->cases, [&](EpisodeRecord& r) {
          rows.push_back(jumpRowOf(r, judgeJump(r)));
          progress.done(rows.size());
        });
        if (rows.size() < run->cases.size()) throw Error("stopped by a signal after " + std::to_string(rows.size()) +
                                                         " of " + std::to_string(run->cases.size()) + " jump(s)");
        results = judgeExpectations(f.scenario, set.set, rows);
      } catch (const Error& e) {
        // The set could not run: its bounds miss with the reason; the other sets run.
        results = missedExpectations(f.scenario, set.set, e.what());
      }
      for (const ExpectationResult& r : results) {
        printResult(r);
        (r.held ? held : missed)++;
      }
      std::fflush(stdout);
      report.results.insert(report.results.end(), results.begin(), results.end());
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    checked.push_back(std::move(report));
  }
  std::printf("\n%zu expectation(s): %zu held, %zu missed\n", held + missed, held, missed);
  if (!o.junit.empty()) {
    replaceFileAtomically(o.junit, junitXml(checked), "JUnit report");
    std::printf("wrote %s\n", o.junit.c_str());
  }
  if (stop.signal()) return 128 + stop.signal();
  return missed > 0 ? kEpisodeFailed : kOk;
}

}  // namespace

Subcommand declareCheck(CLI::App& app, const CommonOptions& common) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Run the sets that scenario files' <expect> elements are about and judge each bound; exit 0 only "
               "when every one holds, 4 when one misses (docs/evaluation.md)");
  cmd->add_option("files", options->files, "scenario files with <expectations>")->required()->check(kNonEmpty);
  cmd->add_option("--policy", options->policy, "ballistic (the planner) or a policy file; default: each file's "
                                                "<environment policy>")
      ->check(kNonEmpty);
  cmd->add_option("--junit", options->junit, "write a JUnit XML report: one test case per bound")->check(kNonEmpty);
  cmd->add_option("--jobs,-j", options->jobs, "worker threads (default: one per core)")->check(CLI::Range(1, 1024));
  return {cmd, [&common, options] { return runCheck(common, *options); }};
}

}  // namespace pronk::cli
