// Every file in tests/scenario/broken/ must be refused with the error its first
// line announces:
//   <!-- expect: LINE: substring -->         the error is in that file
//   <!-- expect: FILE:LINE: substring -->    the error is in FILE (relative to
//                                            broken/), a file it includes
// The message must start with "<path>:<LINE>: " and contain the substring.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "pronk/scenario.h"

namespace fs = std::filesystem;

namespace {

const fs::path kBrokenDir = fs::path(PRONK_SOURCE_DIR) / "tests" / "scenario" / "broken";

std::vector<std::string> brokenFiles() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kBrokenDir)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml") names.push_back(entry.path().filename());
  }
  std::sort(names.begin(), names.end());
  return names;
}

struct Expectation {
  std::string file;  // relative to broken/
  int line = 0;
  std::string substring;
};

Expectation readExpectation(const std::string& name) {
  std::ifstream in(kBrokenDir / name);
  std::string first;
  std::getline(in, first);
  static const std::regex pattern(R"(^<!-- expect: (?:([^ :]+):)?(\d+): (.+) -->$)");
  std::smatch m;
  if (!std::regex_match(first, m, pattern)) return {};
  return {m[1].matched ? m[1].str() : name, std::stoi(m[2].str()), m[3].str()};
}

class BrokenScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(BrokenScenario, IsRefusedWithItsExpectedError) {
  const Expectation expect = readExpectation(GetParam());
  ASSERT_GT(expect.line, 0) << GetParam() << ": first line must be <!-- expect: [FILE:]LINE: substring -->";
  const std::string path = (kBrokenDir / GetParam()).string();
  const std::string prefix =
      (kBrokenDir / expect.file).lexically_normal().string() + ":" + std::to_string(expect.line) + ": ";
  try {
    pronk::loadScenario(path);
    FAIL() << GetParam() << " loaded without error; expected: " << prefix << "..." << expect.substring;
  } catch (const pronk::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(expect.substring), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << expect.substring;
  }
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, BrokenScenario, ::testing::ValuesIn(brokenFiles()), testName);

TEST(BrokenScenarioFolder, HoldsAtLeastFifteenCases) { EXPECT_GE(brokenFiles().size(), 15u); }

}  // namespace
