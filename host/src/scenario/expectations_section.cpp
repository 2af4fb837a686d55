// <expectations>: the <expect> bounds `pronk check` holds a set's jumps to.
// Names (sets, targets) are checked against the scenario in scenario_file.cpp.
#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

ExpectSpec readExpect(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  ExpectSpec x;
  x.where = r.where();
  const std::optional<std::string> set = r.optionalText("set"), target = r.optionalText("target");
  if (set.has_value() == target.has_value()) {
    r.fail("names what it is about with exactly one of set=\"targets|SWEEP\" and target=\"NAME\"");
  }
  if (set && set->empty()) r.fail("set=\"\" names no set");
  if (target && target->empty()) r.fail("target=\"\" names no target");
  x.set = set.value_or("");
  x.target = target.value_or("");
  const Range share = Range::closed(0, 1);
  x.max_error = r.optionalNumber("max_error", Range::positive());
  x.max_yaw_error = r.optionalAngle("max_yaw_error", Range::positive());
  x.within = r.optionalNumber("within", Range::positive());
  x.share = r.optionalNumber("share", share);
  x.max_mean_error = r.optionalNumber("max_mean_error", Range::positive());
  x.max_median_error = r.optionalNumber("max_median_error", Range::positive());
  x.max_failed = r.optionalNumber("max_failed", share);
  x.max_rejected = r.optionalNumber("max_rejected", share);
  x.standing = r.boolean("standing", false);
  r.rejectUnknownAttributes();
  r.children({});
  if (x.within.has_value() != x.share.has_value()) {
    r.fail("within and share go together: at least `share` of the jumps land within `within` m");
  }
  if (!x.max_error && !x.max_yaw_error && !x.within && !x.max_mean_error && !x.max_median_error && !x.max_failed &&
      !x.max_rejected && !x.standing) {
    r.fail("expects nothing: give at least one of max_error, max_yaw_error, within + share, max_mean_error, "
           "max_median_error, max_failed, max_rejected, standing=\"true\"");
  }
  return x;
}

}  // namespace

std::vector<ExpectSpec> readExpectations(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  r.rejectUnknownAttributes();
  std::vector<ExpectSpec> out;
  for (const XMLElement* k : r.children({"expect"})) out.push_back(readExpect(*k, file));
  if (out.empty()) r.fail("holds no <expect>");
  return out;
}

}  // namespace pronk::scenario_file
