// The command line's help as users read it: one metavariable per option
// (TEXT, FLOAT, INT in [1 - 1024], {side,follow,...}) instead of CLI11's type
// and validator names run together, and a suggestion for a mistyped subcommand.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace pronk::cli {

// Rewrites the type name of every option of `app` and its subcommands.
void tidyHelp(CLI::App& app);

// The subcommand of `app` nearest to `word` (at most 2 edits away, or `word`
// a prefix of exactly one); empty when there is none.
std::string closestSubcommand(const CLI::App& app, const std::string& word);

}  // namespace pronk::cli
