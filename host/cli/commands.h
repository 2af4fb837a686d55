// The `pronk` subcommands. Each returns the process exit status (see exit_codes).
#pragma once

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

struct CommonOptions {
  std::vector<std::string> plugin_paths;  // --plugin, repeatable
};

int pluginsCommand(const CommonOptions& common);
int validateCommand(const CommonOptions& common, const std::vector<std::string>& files);

struct RunOptions {
  std::string scenario;
  std::string out_dir;        // "" = no files
  std::string controller;     // overrides the scenario's controller when set
  double duration = 0;        // 0 = the scenario's
  std::string video;          // "" = no video (unless the scenario's <render> names an output)
  double speed = 0;           // playback speed; 0 = the scenario's (default 1)
  double fps = 0;             // 0 = the scenario's (default 30)
  std::string size;           // "WxH"; "" = the scenario's (default 1280x720)
  std::string camera;         // side | follow | top | fixed; "" = the scenario's
  std::vector<double> stills; // simulated times to save as PNG beside the video
  std::string policy;         // "ballistic" or a policy file; "" = the scenario's <environment policy>
  std::string sweep;          // run this sweep's cases instead of the targets
  bool video_per_jump = false;  // one video file per jump instead of one for all
  std::vector<std::string> params;  // NAME=VALUE: the environment's parameters in a jump run, else the controller's
};
int runCommand(const CommonOptions& common, const RunOptions& options);

// `pronk render`: the video alone. From a trace CSV of an earlier run (body
// poses recomputed by forward kinematics, no simulation), or by simulating.
struct RenderOptions : RunOptions {
  std::string trace;          // trace.csv from `pronk run --out`; "" = simulate
};
int renderCommand(const CommonOptions& common, const RenderOptions& options);

struct BenchOptions {
  std::string scenario;       // "" = the built-in Go1 scenario
  int repeats = 3;
  bool sweep = false;         // the whole speed-vs-accuracy table
  bool video = false;         // end-to-end video throughput instead
};
int benchCommand(const CommonOptions& common, const BenchOptions& options);

// Where the project's data (robots, scenarios) is: the source tree in a build,
// or <prefix>/share/pronk when installed.
std::string dataDirectory();

}  // namespace pronk::cli
