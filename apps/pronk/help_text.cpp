#include "help_text.h"

#include <algorithm>
#include <sstream>
#include <vector>

namespace pronk::cli {
namespace {

// "INT:INT in [1 - 1024]" -> "INT in [1 - 1024]"; "TEXT:{side,top}" ->
// "{side,top}"; "FLOAT:NUMBER" -> "FLOAT"; "TEXT:TEXT" -> "TEXT".
std::string metavariable(const std::string& full) {
  std::vector<std::string> parts;
  std::stringstream in(full);
  for (std::string part; std::getline(in, part, ':');) {
    if (!part.empty()) parts.push_back(part);
  }
  if (parts.empty()) return "";
  for (const std::string& p : parts) {
    if (p.find(" in [") != std::string::npos || p.front() == '{') return p;
  }
  return parts.front();
}

}  // namespace

void tidyHelp(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_type_size() == 0) continue;  // a flag
    const std::string name = metavariable(opt->get_type_name());
    for (int i = 0;; ++i) {
      try {
        opt->get_validator(i)->description("");
      } catch (const CLI::OptionNotFound&) {
        break;
      }
    }
    opt->type_name(name);
  }
  for (CLI::App* sub : app.get_subcommands({})) tidyHelp(*sub);
}

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string closestSubcommand(const CLI::App& app, const std::string& word) {
  std::string best, prefixed;
  size_t best_distance = 3, prefixes = 0;
  for (const CLI::App* sub : app.get_subcommands({})) {
    const std::string& name = sub->get_name();
    if (!word.empty() && name.rfind(word, 0) == 0) {
      ++prefixes;
      prefixed = name;
    }
    const size_t d = editDistance(word, name);
    if (d < best_distance) {
      best_distance = d;
      best = name;
    }
  }
  if (!best.empty()) return best;
  return prefixes == 1 ? prefixed : "";
}

}  // namespace pronk::cli
