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

}  // namespace pronk::report_cells
