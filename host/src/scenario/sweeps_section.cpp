// <sweeps>: named sets of episodes. <grid> crosses its axes, <random> draws
// seeded uniform samples, <vary> runs one variable through a list of values.
#include <cmath>
#include <map>

#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

// Per sweep: a run keeps every jump's results in memory (some 20 kB each) and
// writes them as one results.json; 100 000 jumps are about 2 GB and a day of a
// 2-core machine's time.
constexpr std::int64_t kMaxCases = 100'000;

const SweepVariable& readVariable(ElementReader& r) {
  const std::string name = r.requiredText("var");
  std::string list;
  for (const SweepVariable& v : kSweepVariables) {
    if (v.name == name) return v;
    list += (list.empty() ? "" : ", ") + std::string(v.name);
  }
  r.fail("unknown sweep variable \"" + name + "\" (known: " + list + ")");
}

bool isAngle(const SweepVariable& v) { return v.unit == "rad"; }

// The values a variable may take whatever else the file says. Limits that
// depend on other elements (trunk mass, mu_dynamic) are checked after parsing.
Range rangeOf(const SweepVariable& v) {
  const std::string_view n = v.name;
  if (n == "target.roll" || n == "target.pitch") return Range::open(-kMaxTiltRad, kMaxTiltRad);
  if (n == "joints.kp" || n == "joints.kd" || n == "joints.damping" || n == "contact.mu_static") {
    return Range::nonNegative();
  }
  if (n == "terrain.edge") return Range::closed(0.0, 1.0);
  return Range::any();
}

std::vector<double> readList(ElementReader& r, const char* name, const SweepVariable& v) {
  return isAngle(v) ? r.angles(name, rangeOf(v)) : r.numbers(name, rangeOf(v));
}

std::optional<double> readOne(ElementReader& r, const char* name, const SweepVariable& v, const Range& range) {
  return isAngle(v) ? r.optionalAngle(name, range) : r.optionalNumber(name, range);
}

// <axis var values/> or <axis var from to step/>.
SweepAxis readGridAxis(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SweepAxis axis;
  axis.where = r.where();
  const SweepVariable& v = readVariable(r);
  axis.variable = std::string(v.name);
  axis.values = readList(r, "values", v);
  const auto from = readOne(r, "from", v, rangeOf(v));
  const auto to = readOne(r, "to", v, rangeOf(v));
  const auto step = readOne(r, "step", v, Range::positive());
  r.rejectUnknownAttributes();
  r.children({});
  const bool any_span = from || to || step;
  if (!axis.values.empty() && any_span) r.fail("give either values or from/to/step, not both");
  if (axis.values.empty()) {
    if (!(from && to && step)) r.fail("needs values, or all of from, to and step");
    if (*to < *from) r.fail("to must be >= from");
    const double n = std::floor((*to - *from) / *step + 1e-9) + 1;
    if (n > static_cast<double>(kMaxCases)) r.fail("from/to/step give more than " + std::to_string(kMaxCases) + " values");
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) axis.values.push_back(*from + i * *step);
  }
  return axis;
}

SweepAxis readUniform(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SweepAxis axis;
  axis.where = r.where();
  const SweepVariable& v = readVariable(r);
  axis.variable = std::string(v.name);
  const auto lo = readOne(r, "min", v, rangeOf(v));
  const auto hi = readOne(r, "max", v, rangeOf(v));
  r.rejectUnknownAttributes();
  r.children({});
  if (!lo || !hi) r.fail("needs both min and max");
  if (*hi < *lo) r.fail("max must be >= min");
  axis.min = *lo;
  axis.max = *hi;
  return axis;
}

void rejectRepeatedVariables(const std::vector<SweepAxis>& axes, const SourceFile& file) {
  std::map<std::string, int> seen;
  for (const SweepAxis& a : axes) {
    const auto [it, inserted] = seen.emplace(a.variable, a.where.line);
    if (!inserted) {
      throw InputError(a.where, "variable \"" + a.variable + "\" is already swept at line " +
                                    std::to_string(it->second) + " of this sweep");
    }
  }
}

SweepSpec readGrid(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SweepSpec s;
  s.kind = SweepSpec::Kind::Grid;
  s.where = r.where();
  s.name = r.requiredText("name");
  r.rejectUnknownAttributes();
  for (const XMLElement* k : r.children({"axis"})) s.axes.push_back(readGridAxis(*k, file));
  if (s.axes.empty()) r.fail("needs at least one <axis>");
  rejectRepeatedVariables(s.axes, file);
  double cases = 1;
  for (const SweepAxis& a : s.axes) cases *= static_cast<double>(a.values.size());
  if (cases > static_cast<double>(kMaxCases)) {
    r.fail("the axes cross to " + formatNumber(cases) + " cases, more than " + std::to_string(kMaxCases));
  }
  return s;
}

SweepSpec readRandom(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SweepSpec s;
  s.kind = SweepSpec::Kind::Random;
  s.where = r.where();
  s.name = r.requiredText("name");
  const std::int64_t count = r.integer("count", -1, 1, kMaxCases);
  if (count < 0) r.fail("missing attribute count");
  s.count = static_cast<int>(count);
  s.seed = static_cast<unsigned long>(r.integer("seed", 0, 0, 4294967295LL));
  r.rejectUnknownAttributes();
  for (const XMLElement* k : r.children({"uniform"})) s.axes.push_back(readUniform(*k, file));
  if (s.axes.empty()) r.fail("needs at least one <uniform>");
  rejectRepeatedVariables(s.axes, file);
  return s;
}

SweepSpec readVary(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SweepSpec s;
  s.kind = SweepSpec::Kind::Vary;
  s.where = r.where();
  s.name = r.requiredText("name");
  SweepAxis axis;
  axis.where = s.where;
  const SweepVariable& v = readVariable(r);
  axis.variable = std::string(v.name);
  axis.values = readList(r, "values", v);
  r.rejectUnknownAttributes();
  r.children({});
  if (axis.values.empty()) r.fail("missing attribute values");
  s.axes.push_back(std::move(axis));
  return s;
}

}  // namespace

const char* axisElementName(SweepSpec::Kind kind) {
  switch (kind) {
    case SweepSpec::Kind::Grid: return "axis";
    case SweepSpec::Kind::Random: return "uniform";
    case SweepSpec::Kind::Vary: return "vary";
  }
  return "axis";
}

std::vector<SweepSpec> readSweeps(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  r.rejectUnknownAttributes();
  std::vector<SweepSpec> sweeps;
  std::map<std::string, int> names;
  for (const XMLElement* k : r.children({"grid", "random", "vary"})) {
    const std::string kind = k->Name();
    SweepSpec s = kind == "grid" ? readGrid(*k, file) : kind == "random" ? readRandom(*k, file) : readVary(*k, file);
    const auto [it, inserted] = names.emplace(s.name, s.where.line);
    if (!inserted) {
      failAt(*k, file, "duplicate sweep name \"" + s.name + "\" (also at line " + std::to_string(it->second) + ")");
    }
    sweeps.push_back(std::move(s));
  }
  return sweeps;
}

}  // namespace pronk::scenario_file
