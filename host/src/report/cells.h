// How the report's files write a number: JSON null and an empty CSV cell for
// a value that does not exist (NaN, infinite). Shared by results.json/csv and
// the evaluation files, so that both read the same way.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace pronk::report_cells {

inline nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

inline std::string csvCell(double v) {
  if (!std::isfinite(v)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// A text cell as RFC 4180 has it: always quoted, a quote doubled; commas and
// line breaks stay inside the quotes, so a reason or label reads back as written.
inline std::string csvText(const std::string& s) {
  std::string cell = "\"";
  for (char c : s) {
    if (c == '"') cell += '"';
    cell += c;
  }
  return cell + '"';
}

}  // namespace pronk::report_cells
