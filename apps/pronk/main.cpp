// pronk: run quadruped jump scenarios on the Simbody host.
#include <iostream>

#include "commands.h"
#include "pronk/error.h"
#include "pronk/plugin_abi.h"

int main(int argc, char** argv) {
  using namespace pronk::cli;
  CLI::App app{"pronk: learned, precise, omnidirectional jumps of legged robots in simulation"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 internal error, 2 usage error, 3 bad input (scenario, URDF, plugin),\n"
      "4 an episode failed (non-foot contact, divergence, controller error), 130 / 143 stopped by SIGINT / SIGTERM.");
  app.set_version_flag("--version", std::string("pronk ") + PRONK_VERSION + ", plugin ABI " +
                                        std::to_string(PRONK_ABI_MAJOR) + "." + std::to_string(PRONK_ABI_MINOR) +
                                        ", commit " + PRONK_GIT_COMMIT);
  // Options of the main command (--plugin) may also follow the subcommand, as
  // docs/plugin-abi.md shows them.
  app.fallthrough();
  CommonOptions common;
  for (int i = 0; i < argc; ++i) common.command_line += (i ? " " : "") + std::string(argv[i]);
  app.add_option("--plugin", common.plugin_paths,
                 "plugin library or directory, searched before PRONK_PLUGIN_PATH and the install directory "
                 "(repeatable)");

  const std::vector<Subcommand> commands = {declarePlugins(app, common), declareValidate(app, common),
                                            declareRun(app, common), declareRender(app, common),
                                            declareBench(app, common), declareTrain(app, common),
                                            declareEval(app, common), declareCheck(app, common),
                                            declarePlot(app, common), declareCompletion(app, common),
                                            declareMan(app, common)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsageError;
  }
  try {
    for (const Subcommand& c : commands)
      if (*c.app) return c.run();
  } catch (const pronk::Error& e) {
    std::cerr << "pronk: " << e.what() << "\n";
    return kInputError;
  } catch (const std::exception& e) {
    std::cerr << "pronk: internal error: " << e.what() << "\n";
    return kInternalError;
  }
  return kUsageError;
}
