// `pronk check`: a scenario's <expect> bounds judged on a set's jump rows, one
// result per bound, and the JUnit XML report CI systems read (one test case
// per bound).
#pragma once

#include <string>
#include <vector>

#include "pronk/evaluation.h"
#include "pronk/scenario.h"

namespace pronk {

struct ExpectationResult {
  SourceLocation where;  // the <expect>
  std::string subject;   // "set eval" or "target forward"
  std::string check;     // "max_error <= 0.05 m"
  std::string measured;  // "worst 3.1 cm (ahead #3)"
  bool held = false;
};

// The sets ("targets" or sweeps) the scenario's <expect>s are about, each once.
std::vector<std::string> expectedSets(const Scenario& scenario);

// The results of every bound of every <expect> about `set` (a target's <expect>
// is about the set "targets"), judged on the set's rows (row.index = case index).
std::vector<ExpectationResult> judgeExpectations(const Scenario& scenario, const std::string& set,
                                                 const std::vector<JumpRow>& rows);

// Every bound of every <expect> about `set` missed for one reason (the set
// could not run): what a check reports instead of judging.
std::vector<ExpectationResult> missedExpectations(const Scenario& scenario, const std::string& set,
                                                  const std::string& reason);

// JUnit XML: one <testsuite> per file (name = the file), one <testcase> per
// result, a <failure> with the measurement for each miss.
struct CheckedFile {
  std::string file;
  std::vector<ExpectationResult> results;
  double seconds = 0;
};
std::string junitXml(const std::vector<CheckedFile>& files);

}  // namespace pronk
