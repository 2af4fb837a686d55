// pronk: run quadruped jump scenarios on the Simbody host.
#include <algorithm>
#include <csignal>
#include <iostream>
#include <vector>

#include "commands.h"
#include "help_text.h"
#include "pronk/communicator.h"
#include "pronk/error.h"
#include "pronk/plugin_abi.h"
#include "pronk/plugin_registry.h"

int main(int argc, char** argv) {
  using namespace pronk::cli;
  // Past a file-size limit (ulimit -f) a write fails with EFBIG, and the
  // writer's error says so; the signal would end pronk without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  pronk::reportPluginCrashes();
  CLI::App app{"pronk: learned, precise, omnidirectional jumps of legged robots in simulation"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 internal error, 2 usage error, 3 bad input (scenario, URDF, plugin),\n"
      "4 an episode failed (non-foot contact, divergence, controller error), 128 + N stopped by signal N: 130 SIGINT, 143 SIGTERM, 129 SIGHUP, 141 a closed stdout.");
  app.set_version_flag("--version", std::string("pronk ") + PRONK_VERSION + ", plugin ABI " +
                                        std::to_string(PRONK_ABI_MAJOR) + "." + std::to_string(PRONK_ABI_MINOR) +
                                        ", commit " + buildCommit());
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

  tidyHelp(app);
  requireDecimalIntegers(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A first word that is no option and no subcommand: say which it may be.
    const std::string word = argc > 1 ? argv[1] : "";
    const auto named = [&word](const CLI::App* sub) { return sub->check_name(word); };
    const std::vector<CLI::App*> subs = app.get_subcommands({});
    if (!word.empty() && word[0] != '-' && std::none_of(subs.begin(), subs.end(), named)) {
      const std::string near = closestSubcommand(app, word);
      std::cerr << "pronk: '" << word << "' is not a command"
                << (near.empty() ? std::string() : "; did you mean 'pronk " + near + "'?") << "\n"
                << "Run with --help for the commands.\n";
      return kUsageError;
    }
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsageError;
  }
  // Under mpirun every rank runs this; the ranks of an eval or a training share its jumps.
  // One rank's error ends them all: the others would wait in a collective.
  const pronk::Communicator* comm = nullptr;
  auto fail = [&](int code, const std::string& text) {
    std::cerr << "pronk" << (comm && comm->distributed() ? " (rank " + std::to_string(comm->rank()) + ")" : "")
              << ": " << text << "\n";
    if (comm && comm->distributed()) comm->abort(code);
    return code;
  };
  try {
    comm = &pronk::Communicator::world();
    for (const Subcommand& c : commands) {
      if (!*c.app) continue;
      if (comm->distributed() && c.app->get_name() != "eval" && c.app->get_name() != "train") {
        return fail(kUsageError, "pronk " + c.app->get_name() + " runs in one process; under mpirun only pronk eval " +
                                     "and pronk train share their jumps over the ranks");
      }
      return c.run();
    }
  } catch (const UsageError& e) {
    return fail(kUsageError, e.what());
  } catch (const pronk::SharedError& e) {
    // Every rank has it: rank 0 says it once and all end normally.
    if (!comm || comm->root()) std::cerr << "pronk: " << e.what() << "\n";
    return kInputError;
  } catch (const pronk::Error& e) {
    return fail(kInputError, e.what());
  } catch (const std::exception& e) {
    return fail(kInternalError, std::string("internal error: ") + e.what());
  }
  return kUsageError;
}
