// <expect> bounds judged on jump rows, and the JUnit report (pronk/expectations.h).
#include "pronk/expectations.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tinyxml2.h>

namespace pronk {
namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string format(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

std::string cm(double m) { return std::isfinite(m) ? format("%.1f cm", 100 * m) : "none"; }
std::string pct(double share) { return std::isfinite(share) ? format("%.1f %%", 100 * share) : "none"; }

bool isAbout(const ExpectSpec& e, const std::string& set) {
  return e.target.empty() ? e.set == set : set == "targets";
}

// The rows an <expect> is about: the whole set, or its one target's case.
std::vector<JumpRow> rowsOf(const Scenario& s, const ExpectSpec& e, const std::vector<JumpRow>& rows) {
  if (e.target.empty()) return rows;
  size_t index = 0;
  while (index < s.targets.size() && s.targets[index].name != e.target) ++index;
  std::vector<JumpRow> out;
  for (const JumpRow& r : rows)
    if (r.index == index) out.push_back(r);
  return out;
}

std::string subjectOf(const ExpectSpec& e) { return e.target.empty() ? "set " + e.set : "target " + e.target; }

// A bound every jump must keep: the first jump that does not, or the worst value.
ExpectationResult everyJump(const ExpectSpec& e, const std::vector<JumpRow>& rows, const std::string& check,
                            double bound, double (*value)(const JumpRow&), std::string (*show)(double)) {
  ExpectationResult r{e.where, subjectOf(e), check, "", true};
  double worst = -INFINITY;
  const JumpRow* worst_row = nullptr;
  for (const JumpRow& row : rows) {
    if (!row.landed()) {
      r.held = false;
      r.measured = row.label + " " + row.status + (row.reason.empty() ? "" : ": " + row.reason);
      return r;
    }
    const double v = value(row);
    if (!(v <= worst) || !std::isfinite(v)) {
      worst = std::isfinite(v) ? v : INFINITY;
      worst_row = &row;
    }
  }
  if (!worst_row) {
    r.held = false;
    r.measured = "no jump ran";
    return r;
  }
  r.held = worst <= bound;
  r.measured = "worst " + show(worst) + " (" + worst_row->label + ")";
  return r;
}

std::vector<ExpectationResult> judgeOne(const ExpectSpec& e, const std::vector<JumpRow>& rows) {
  std::vector<ExpectationResult> out;
  const SetSummary s = summarize(rows, e.within.value_or(0.2));
  const std::string subject = subjectOf(e);
  auto add = [&](const std::string& check, bool held, const std::string& measured) {
    out.push_back({e.where, subject, check, measured, held});
  };
  if (e.max_error) {
    out.push_back(everyJump(e, rows, "max_error <= " + cm(*e.max_error), *e.max_error,
                            [](const JumpRow& r) { return r.error; }, cm));
  }
  if (e.max_yaw_error) {
    out.push_back(everyJump(e, rows, "max_yaw_error <= " + format("%.1f deg", *e.max_yaw_error * kDeg),
                            *e.max_yaw_error * kDeg, [](const JumpRow& r) { return r.error_yaw_deg; },
                            [](double v) { return format("%.1f deg", v); }));
  }
  if (e.within) {
    const double share = s.withinShare();
    add("share within " + cm(*e.within) + " >= " + pct(*e.share), share >= *e.share,
        pct(share) + " (" + std::to_string(s.within) + " of " + std::to_string(s.jumps) + ")");
  }
  if (e.max_mean_error) add("mean error <= " + cm(*e.max_mean_error), s.mean <= *e.max_mean_error, cm(s.mean));
  if (e.max_median_error) {
    add("median error <= " + cm(*e.max_median_error), s.median <= *e.max_median_error, cm(s.median));
  }
  const double jumps = static_cast<double>(std::max<size_t>(s.jumps, 1));
  if (e.max_failed) {
    add("failed <= " + pct(*e.max_failed), s.jumps > 0 && s.failed / jumps <= *e.max_failed,
        pct(s.failed / jumps) + " (" + std::to_string(s.failed) + " of " + std::to_string(s.jumps) + ")");
  }
  if (e.max_rejected) {
    add("refused <= " + pct(*e.max_rejected), s.jumps > 0 && s.rejected / jumps <= *e.max_rejected,
        pct(s.rejected / jumps) + " (" + std::to_string(s.rejected) + " of " + std::to_string(s.jumps) + ")");
  }
  if (e.standing) {
    ExpectationResult r{e.where, subject, "every jump ends standing", "", s.jumps > 0};
    for (const JumpRow& row : rows) {
      if (row.landed() && row.standing) continue;
      r.held = false;
      r.measured = row.label + (row.landed() ? " did not end standing" : " " + row.status);
      break;
    }
    if (r.held) r.measured = std::to_string(s.standing) + " of " + std::to_string(s.jumps) + " standing";
    if (s.jumps == 0) r.measured = "no jump ran";
    out.push_back(r);
  }
  return out;
}

}  // namespace

std::vector<std::string> expectedSets(const Scenario& scenario) {
  std::vector<std::string> out;
  for (const ExpectSpec& e : scenario.expectations) {
    const std::string set = e.target.empty() ? e.set : "targets";
    if (std::find(out.begin(), out.end(), set) == out.end()) out.push_back(set);
  }
  return out;
}

std::vector<ExpectationResult> judgeExpectations(const Scenario& scenario, const std::string& set,
                                                 const std::vector<JumpRow>& rows) {
  std::vector<ExpectationResult> out;
  for (const ExpectSpec& e : scenario.expectations) {
    if (!isAbout(e, set)) continue;
    for (ExpectationResult& r : judgeOne(e, rowsOf(scenario, e, rows))) out.push_back(std::move(r));
  }
  return out;
}

std::vector<ExpectationResult> missedExpectations(const Scenario& scenario, const std::string& set,
                                                  const std::string& reason) {
  std::vector<ExpectationResult> out;
  for (const ExpectSpec& e : scenario.expectations) {
    if (!isAbout(e, set)) continue;
    // The bounds' names, as judging would give them, each missed for the reason.
    for (ExpectationResult& r : judgeOne(e, {})) {
      r.held = false;
      r.measured = reason;
      out.push_back(std::move(r));
    }
  }
  return out;
}

std::string junitXml(const std::vector<CheckedFile>& files) {
  tinyxml2::XMLDocument doc;
  doc.InsertEndChild(doc.NewDeclaration());
  tinyxml2::XMLElement* suites = doc.NewElement("testsuites");
  doc.InsertEndChild(suites);
  size_t tests = 0, failures = 0;
  for (const CheckedFile& f : files) {
    tinyxml2::XMLElement* suite = doc.NewElement("testsuite");
    suites->InsertEndChild(suite);
    size_t failed = 0;
    for (const ExpectationResult& r : f.results) {
      tinyxml2::XMLElement* c = doc.NewElement("testcase");
      c->SetAttribute("classname", f.file.c_str());
      c->SetAttribute("name", (r.where.str() + " " + r.subject + ": " + r.check).c_str());
      c->SetAttribute("file", r.where.file.c_str());
      c->SetAttribute("line", r.where.line);
      if (!r.held) {
        ++failed;
        tinyxml2::XMLElement* failure = c->InsertNewChildElement("failure");
        failure->SetAttribute("message", (r.check + ": " + r.measured).c_str());
        failure->SetText(r.measured.c_str());
      } else {
        c->InsertNewChildElement("system-out")->SetText(r.measured.c_str());
      }
      suite->InsertEndChild(c);
    }
    suite->SetAttribute("name", f.file.c_str());
    suite->SetAttribute("tests", static_cast<int64_t>(f.results.size()));
    suite->SetAttribute("failures", static_cast<int64_t>(failed));
    suite->SetAttribute("errors", 0);
    suite->SetAttribute("time", f.seconds);
    tests += f.results.size();
    failures += failed;
  }
  suites->SetAttribute("name", "pronk check");
  suites->SetAttribute("tests", static_cast<int64_t>(tests));
  suites->SetAttribute("failures", static_cast<int64_t>(failures));
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

}  // namespace pronk
