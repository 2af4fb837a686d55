// The `pronk` subcommands: each file declares its own options (declareX) and
// runs them; main() only chooses. Each returns the process exit status.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pronk::cli {

// Documented in the README and in `pronk --help`.
enum ExitCode : int {
  kOk = 0,
  kInternalError = 1,    // a bug: an unexpected exception
  kUsageError = 2,       // bad flags or arguments
  kInputError = 3,       // a scenario, URDF or plugin that cannot be used
  kEpisodeFailed = 4,    // the run completed but an episode failed (non-foot contact, divergence ...)
};

// A flag or argument refused after parsing (exit 2); its message names the flag.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CommonOptions {
  std::vector<std::string> plugin_paths;  // --plugin, repeatable
  std::string command_line;               // as typed, for the provenance of results files
};

// Flag checks. CLI11's own Range lets NaN through (every comparison with it is
// false) and an empty string is no value: these refuse both, naming the flag.
inline CLI::Validator finiteIn(double lo, double hi, bool lo_open = false) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        try {
          size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!std::isfinite(v)) return "'" + text + "' is not a finite number";
        // Decimal notation only: std::stod also reads " 2" and hexadecimal "0x1p3".
        if (text.find_first_not_of("0123456789+-.eE") != std::string::npos) {
          return "'" + text + "' is not a decimal number";
        }
        if (v > hi || v < lo || (lo_open && v == lo)) {
          char range[96];
          std::snprintf(range, sizeof range, "%s%g, %g]", lo_open ? "(" : "[", lo, hi);
          return text + " is not in " + range;
        }
        return std::string();
      },
      "NUMBER");
}
inline const CLI::Validator kNonEmpty(
    [](std::string& text) { return text.empty() ? std::string("an empty value") : std::string(); }, "TEXT");

// Whole numbers as people write them: decimal digits with an optional sign (CLI11
// alone reads "0x10" as 16 and lets " 2" through).
inline const CLI::Validator kDecimal(
    [](std::string& text) {
      const size_t start = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
      const bool digits = text.size() > start && text.find_first_not_of("0123456789", start) == std::string::npos;
      return digits ? std::string() : "'" + text + "' is not a decimal whole number";
    },
    "");

// Every option of `app` and its subcommands that takes a whole number gets kDecimal.
inline void requireDecimalIntegers(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    const std::string type = opt->get_type_name();
    if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) opt->check(kDecimal);
  }
  for (CLI::App* sub : app.get_subcommands({})) requireDecimalIntegers(*sub);
}

// A declared subcommand and what runs it once the command line is parsed.
struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
// `common` must outlive the returned Subcommand.
Subcommand declarePlugins(CLI::App& app, const CommonOptions& common);
Subcommand declareValidate(CLI::App& app, const CommonOptions& common);
Subcommand declareRun(CLI::App& app, const CommonOptions& common);
Subcommand declareRender(CLI::App& app, const CommonOptions& common);
Subcommand declareBench(CLI::App& app, const CommonOptions& common);
Subcommand declareTrain(CLI::App& app, const CommonOptions& common);
Subcommand declareEval(CLI::App& app, const CommonOptions& common);
Subcommand declareCheck(CLI::App& app, const CommonOptions& common);
Subcommand declarePlot(CLI::App& app, const CommonOptions& common);
// Generated from the declared command line: a bash completion script, the man page.
Subcommand declareCompletion(CLI::App& app, const CommonOptions& common);
Subcommand declareMan(CLI::App& app, const CommonOptions& common);

struct RunOptions {
  std::string scenario;
  std::string out_dir;        // "" = no files
  std::string controller;     // overrides the scenario's controller when set
  double duration = 0;        // 0 = the scenario's
  std::string video;          // the video file; "" = none, unless video_requested
  bool video_requested = false;  // --video given, with or without a file name
  double speed = 0;           // playback speed; 0 = the scenario's (default 1)
  double fps = 0;             // 0 = the scenario's (default 30)
  std::string size;           // "WxH"; "" = the scenario's (default 1280x720)
  std::string camera;         // side | follow | top | fixed; "" = the scenario's
  std::vector<double> stills; // simulated times to save as PNG beside the video
  std::string policy;         // "ballistic" or a policy file; "" = the scenario's <environment policy>
  std::string sweep;          // run this sweep's cases instead of the targets
  std::optional<unsigned long> seed;  // replaces the <random> sweep's seed
  bool video_per_jump = false;  // one video file per jump instead of one for all
  std::vector<std::string> params;  // NAME=VALUE: the environment's parameters in a jump run, else the controller's
  int jobs = 0;               // worker threads of a jump run; 0 = one per core
  bool trace = false;         // a jump run writes each jump's trace CSV into --out
  bool full_episodes = false; // a jump run does not end its episodes at rest
};

// `pronk render`: the video alone. From a trace CSV of an earlier run (body
// poses recomputed by forward kinematics, no simulation), or by simulating.
struct RenderOptions : RunOptions {
  std::string trace;          // trace.csv from `pronk run --out`; "" = simulate
};

struct BenchOptions {
  std::string scenario;       // "" = the built-in Go1 scenario
  int repeats = 3;
  bool sweep = false;         // the whole speed-vs-accuracy table
  bool video = false;         // end-to-end video throughput instead
  bool rollout = false;       // the rollout engine's throughput on the region sweep instead
  int jobs = 0;               // threads of the engine's multi-threaded row; 0 = one per core
};

// Where the project's data (robots, scenarios) is: the source tree in a build,
// or <prefix>/share/pronk when installed.
std::string dataDirectory();

// The commit the binary was built from ("-dirty" with changed tracked files,
// "unknown" outside a git checkout).
const char* buildCommit();

}  // namespace pronk::cli
