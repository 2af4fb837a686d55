// Policy files: a valid file, an exact save -> load round trip, and one broken
// file per error in tests/learning/policies/, each refused with the file, the
// line and the key it names.
#include <gtest/gtest.h>
#include <iterator>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "pronk/error.h"
#include "pronk/policy.h"

namespace fs = std::filesystem;

namespace {

using pronk::Activation;
using pronk::MlpLayer;
using pronk::MlpPolicy;

const fs::path kPolicies = fs::path(PRONK_SOURCE_DIR) / "tests" / "learning" / "policies";

std::string fixture(const std::string& name) { return (kPolicies / name).string(); }

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Same bits, so -0.0 differs from 0.0 and nothing is "nearly" equal.
template <class A, class B>
bool sameBits(const A& a, const B& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(PolicyFile, ValidFileLoads) {
  const MlpPolicy policy = pronk::loadPolicy(fixture("valid.json"));
  EXPECT_EQ(policy.observationSize(), 3);
  EXPECT_EQ(policy.actionSize(), 2);
  ASSERT_EQ(policy.layers().size(), 2u);
  EXPECT_EQ(policy.layers()[0].activation, Activation::Tanh);
  EXPECT_EQ(policy.layers()[1].activation, Activation::Linear);
  EXPECT_EQ(policy.layers()[0].weights(3, 0), -0.7);  // row = output, column = input
  EXPECT_EQ(policy.description(), "a tiny network for the tests");
  EXPECT_EQ(policy.provenance().at("seed"), 7);
  EXPECT_EQ(policy.provenance().at("jumps"), 120000);
  EXPECT_EQ(policy.provenance().at("wall_time_s"), 3600.5);
  EXPECT_EQ(policy.provenance().at("command"), "pronk train scenarios/go1/train.xml");
  ASSERT_TRUE(policy.hasObservationNormalization());
  EXPECT_EQ(policy.observationStd()[2], 0.5);
  ASSERT_TRUE(policy.hasActionLogStd());
  EXPECT_EQ(policy.actionLogStd()[1], -1.0);

  // The mean action, computed here step by step.
  Eigen::VectorXd obs(3);
  obs << 0.3, 0.5, -0.2;
  Eigen::VectorXd x = (obs - policy.observationMean()).cwiseQuotient(policy.observationStd());
  x = (policy.layers()[0].weights * x + policy.layers()[0].bias).array().tanh();
  x = policy.layers()[1].weights * x + policy.layers()[1].bias;
  EXPECT_TRUE(sameBits(policy.act(obs), x));
}

MlpPolicy randomPolicy() {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto randomMatrix = [&](int rows, int cols) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = normal(rng) / 3.0;
    return m;
  };
  std::vector<MlpLayer> layers = {
      {randomMatrix(16, 7), randomMatrix(16, 1), Activation::Elu},
      {randomMatrix(16, 16), randomMatrix(16, 1), Activation::Relu},
      {randomMatrix(5, 16), randomMatrix(5, 1), Activation::Tanh},
      {randomMatrix(3, 5), randomMatrix(3, 1), Activation::Linear}};
  // Numbers whose text is easy to get wrong.
  layers[0].weights(0, 0) = -0.0;
  layers[0].weights(0, 1) = 5e-324;  // smallest subnormal
  layers[0].weights(0, 2) = 1e300;
  layers[0].weights(0, 3) = 1.0 / 3.0;
  layers[0].weights(0, 4) = 0.1;
  layers[0].weights(0, 5) = -2.2250738585072014e-308;
  layers[0].weights(0, 6) = 1.0;
  MlpPolicy policy(std::move(layers));
  policy.setObservationNormalization(randomMatrix(7, 1), randomMatrix(7, 1).cwiseAbs().array() + 1e-3);
  policy.setActionLogStd(randomMatrix(3, 1));
  policy.setDescription("Go1 \"forward\" jumps, \u00e9t\u00e9 \\ test");
  policy.setProvenance({{"command", "pronk train scenarios/go1/train.xml --seed 3"},
                        {"seed", 3},
                        {"jumps", 250000},
                        {"wall_time_s", 5123.25},
                        {"nested", {{"git", "abc123"}, {"lr", 3e-4}}}});
  return policy;
}

TEST(PolicyFile, SaveThenLoadIsBitExact) {
  const MlpPolicy saved = randomPolicy();
  const fs::path path = fs::path(PRONK_BINARY_DIR) / "tests" / "learning" / "round_trip.json";
  fs::create_directories(path.parent_path());
  pronk::savePolicy(saved, path.string());
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
  const MlpPolicy loaded = pronk::loadPolicy(path.string());

  ASSERT_EQ(loaded.layers().size(), saved.layers().size());
  for (std::size_t l = 0; l < saved.layers().size(); ++l) {
    EXPECT_TRUE(sameBits(loaded.layers()[l].weights, saved.layers()[l].weights)) << "layer " << l;
    EXPECT_TRUE(sameBits(loaded.layers()[l].bias, saved.layers()[l].bias)) << "layer " << l;
    EXPECT_EQ(loaded.layers()[l].activation, saved.layers()[l].activation) << "layer " << l;
  }
  EXPECT_TRUE(std::signbit(loaded.layers()[0].weights(0, 0)));
  EXPECT_TRUE(sameBits(loaded.observationMean(), saved.observationMean()));
  EXPECT_TRUE(sameBits(loaded.observationStd(), saved.observationStd()));
  EXPECT_TRUE(sameBits(loaded.actionLogStd(), saved.actionLogStd()));
  EXPECT_EQ(loaded.description(), saved.description());
  EXPECT_EQ(loaded.provenance(), saved.provenance());

  Eigen::VectorXd obs(7);
  obs << 0.1, -0.2, 0.3, 1.5, -2.0, 0.0, 0.7;
  EXPECT_TRUE(sameBits(loaded.act(obs), saved.act(obs)));
  // Writing what was read gives the same text.
  EXPECT_EQ(pronk::policyToJson(loaded), readText(path.string()));
}

TEST(PolicyFile, AResidualRecordsItsPrior) {
  const MlpPolicy policy = pronk::loadPolicy(fixture("valid_residual.json"));
  ASSERT_TRUE(policy.prior().has_value());
  EXPECT_EQ(policy.prior()->kind, "prior_action");
  EXPECT_EQ(policy.prior()->environment, "jump");
  const std::string text = pronk::policyToJson(policy);
  EXPECT_EQ(text.rfind("{\n  \"format\": \"pronk-policy\",\n  \"version\": 3,\n", 0), 0u) << text;
  const MlpPolicy again = pronk::parsePolicy(text, "residual");
  ASSERT_TRUE(again.prior().has_value());
  EXPECT_EQ(again.prior()->environment, "jump");
  // A version-2 file (valid_residual.json) and a version-1 file, both without a
  // checksum, still read; without a prior none is written.
  EXPECT_FALSE(pronk::loadPolicy(fixture("valid.json")).prior().has_value());
  MlpPolicy plain = policy;
  plain.setPrior(std::nullopt);
  EXPECT_EQ(pronk::policyToJson(plain).find("\"prior\""), std::string::npos);
  EXPECT_THROW(plain.setPrior(pronk::PolicyPrior{"prior_action", ""}), pronk::Error);
  // An aim correction keeps its kind through a round trip; an unknown kind is refused.
  MlpPolicy aim = policy;
  aim.setPrior(pronk::PolicyPrior{pronk::kAimPriorKind, "jump"});
  const MlpPolicy aim_again = pronk::parsePolicy(pronk::policyToJson(aim), "aim");
  ASSERT_TRUE(aim_again.prior().has_value());
  EXPECT_EQ(aim_again.prior()->kind, "prior_action_at_aim");
  EXPECT_THROW(plain.setPrior(pronk::PolicyPrior{"ballistic", "jump"}), pronk::Error);
}

TEST(PolicyFile, OptionalPartsMayBeLeftOut) {
  const MlpPolicy saved(
      {{Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(2), Activation::Linear}});
  const MlpPolicy loaded = pronk::parsePolicy(pronk::policyToJson(saved), "minimal");
  EXPECT_FALSE(loaded.hasObservationNormalization());
  EXPECT_FALSE(loaded.hasActionLogStd());
  EXPECT_EQ(loaded.description(), "");
  EXPECT_EQ(loaded.provenance(), nlohmann::json::object());
}

TEST(PolicyFile, WritesOneWeightRowPerLine) {
  Eigen::MatrixXd w(2, 3);
  w << 0.5, -0.25, 1.0,
       0.0, 2.0, -1.5;
  const MlpPolicy policy({{w, Eigen::VectorXd::Zero(2), Activation::Tanh}});
  const std::string text = pronk::policyToJson(policy);
  EXPECT_NE(text.find("\n        [0.5,-0.25,1.0],\n        [0.0,2.0,-1.5]\n"), std::string::npos) << text;
  EXPECT_EQ(text.rfind("{\n  \"format\": \"pronk-policy\",\n  \"version\": 3,\n", 0), 0u) << text;
}

// Where a line of `text` holding `needle` is (1-based), for the messages below.
int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  return at == std::string::npos ? -1 : 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

TEST(PolicyFile, TheChecksumRefusesAFileChangedAfterItWasWritten) {
  Eigen::MatrixXd w(2, 3);
  w << 0.5, -0.25, 1.0,
       0.0, 2.0, -1.5;
  MlpPolicy policy({{w, Eigen::VectorXd::Zero(2), Activation::Tanh}});
  policy.setDescription("checksum test");
  const std::string text = pronk::policyToJson(policy);
  const std::size_t at = text.find("\"checksum\": \"sha256:");
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_EQ(text.find("\"", at + 20) - (at + 20), 64u) << "64 hex digits";
  EXPECT_NO_THROW(pronk::parsePolicy(text, "as written"));
  // The numbers are what the checksum covers, not their spelling: 0.5 as 5e-1 still reads.
  std::string respelt = text;
  respelt.replace(respelt.find("[0.5,"), 5, "[5e-1,");
  EXPECT_NO_THROW(pronk::parsePolicy(respelt, "respelt"));

  const auto refusal = [](const std::string& changed) -> std::string {
    try {
      pronk::parsePolicy(changed, "changed.json");
    } catch (const pronk::InputError& e) {
      return e.what();
    }
    return "read";
  };
  const std::string checksum_line = "changed.json:" + std::to_string(lineOf(text, "\"checksum\"")) + ": checksum: sha256:";
  std::string weight = text;
  weight.replace(weight.find("[0.5,"), 5, "[0.6,");
  EXPECT_EQ(refusal(weight).rfind(checksum_line, 0), 0u) << refusal(weight);
  EXPECT_NE(refusal(weight).find("does not match the file's contents (sha256:"), std::string::npos);
  std::string description = text;
  description.replace(description.find("checksum test"), 13, "checksum tests");
  EXPECT_EQ(refusal(description).rfind(checksum_line, 0), 0u) << refusal(description);

  std::string missing = text;
  const std::size_t comma = missing.rfind(",\n", at);
  missing.erase(comma, missing.find("\n", at) - comma);
  EXPECT_NE(refusal(missing).find("checksum: missing"), std::string::npos) << refusal(missing) << "\n" << missing;
  std::string other_kind = text;
  other_kind.replace(at + 13, 6, "md5:00");
  EXPECT_NE(refusal(other_kind).find("checksum: expected a string \"sha256:<64 hex digits>\""), std::string::npos)
      << refusal(other_kind);
}

TEST(PolicyFile, SaveToAMissingFolderIsAnError) {
  const MlpPolicy policy({{Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(2), Activation::Linear}});
  EXPECT_THROW(pronk::savePolicy(policy, "/nonexistent-folder/policy.json"), pronk::Error);
}

TEST(PolicyFile, MissingFileIsAnInputError) {
  const std::string path = fixture("no_such_policy.json");
  try {
    pronk::loadPolicy(path);
    FAIL() << "loaded a file that does not exist";
  } catch (const pronk::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": policy file not found", 0), 0u) << e.what();
  }
}

// One broken file in tests/learning/policies/ and the error it must give:
// the message starts with "<path>:<line>: " and contains `message`.
struct Broken {
  std::string file;
  int line;
  std::string message;
};

// Test names and failures show the file, not the struct's bytes.
void PrintTo(const Broken& b, std::ostream* out) { *out << b.file; }

const std::vector<Broken> kBroken = {
    {"syntax_error.json", 4, "column 15: invalid JSON: syntax error while parsing object"},
    {"nan_literal.json", 17, "column 15: invalid JSON: syntax error while parsing value - invalid literal"},
    {"number_overflow.json", 21, "column 21: number overflow parsing '1e999'"},
    {"not_an_object.json", 1, "a policy file is a JSON object, this is array"},
    {"missing_format.json", 1, "format: missing"},
    {"wrong_format.json", 2, "format: string \"pronk-scenario\" is not \"pronk-policy\""},
    // Found by fuzzing: the shown string was cut at byte 40, inside the "é", and nlohmann threw on it.
    {"format_cut_in_a_character.json", 2,
     "format: string \"pronk-policy, Go1, trained in Zürich r\"... is not \"pronk-policy\""},
    {"version_4.json", 3, "version: 4 is not supported; this pronk reads versions 1 to 3"},
    {"prior_in_version_1.json", 6, "prior: unknown key (known keys here: format, version, description, provenance, "
                                    "observation_size"},
    {"unknown_prior_kind.json", 6, "prior.kind: string \"ballistic\" is not a known prior (known: \"prior_action\", a residual over the "
                                  "environment's prior_action, and \"prior_action_at_aim\""},
    {"unknown_top_level_key.json", 4, "seed: unknown key"},
    {"duplicate_key.json", 22, "layers[0].activation: duplicate key (first written on line 14)"},
    {"observation_size_zero.json", 6, "observation_size: expected a positive integer, got number 0"},
    {"missing_layers.json", 1, "layers: missing"},
    {"unknown_layer_key.json", 25, "layers[1].dropout: unknown key"},
    {"missing_bias.json", 23, "layers[1].bias: missing"},
    {"unknown_activation.json", 14, "layers[0].activation: unknown activation \"sigmoid\" (known: tanh, relu, elu, linear)"},
    {"string_in_weights.json", 18, "layers[0].weights[2][1]: expected a number, got string \"NaN\""},
    {"ragged_weights.json", 18, "layers[0].weights[2]: 2 columns, expected 3 as in row 0"},
    {"mismatched_chain.json", 25,
     "layers[1].weights: 3 columns (inputs), expected 4 (the rows of layers[0].weights)"},
    {"bias_size.json", 29, "layers[1].bias: 1 value, expected 2 (the rows of layers[1].weights)"},
    {"wrong_observation_size.json", 6, "observation_size: 4, but layers[0].weights has 3 columns (inputs)"},
    {"wrong_action_size.json", 7, "action_size: 3, but layers[1].weights has 2 rows (outputs)"},
    {"std_not_positive.json", 10, "observation_normalization.std[1]: 0.0 must be > 0"},
    {"log_std_size.json", 32, "action_log_std: 1 value, expected 2 (action_size)"},
};

class BrokenPolicy : public ::testing::TestWithParam<Broken> {};

TEST_P(BrokenPolicy, IsRefusedAtItsLineNamingTheKey) {
  const Broken& expect = GetParam();
  const std::string path = fixture(expect.file);
  ASSERT_TRUE(fs::exists(path)) << path;
  const std::string prefix = path + ":" + std::to_string(expect.line) + ": ";
  try {
    pronk::loadPolicy(path);
    FAIL() << expect.file << " loaded without error; expected " << prefix << "..." << expect.message;
  } catch (const pronk::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(expect.message), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << expect.message;
    EXPECT_EQ(e.where().line, expect.line);
  }
}

std::string testName(const ::testing::TestParamInfo<Broken>& info) {
  std::string name = fs::path(info.param.file).stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, BrokenPolicy, ::testing::ValuesIn(kBroken), testName);

// Every fixture but valid.json is a broken case listed above.
TEST(BrokenPolicyFolder, EveryFileIsListed) {
  std::set<std::string> listed;
  for (const Broken& b : kBroken) listed.insert(b.file);
  for (const auto& entry : fs::directory_iterator(kPolicies)) {
    const std::string name = entry.path().filename().string();
    if (name == "valid.json" || name == "valid_residual.json") continue;
    EXPECT_TRUE(listed.count(name)) << name << " is not in kBroken";
  }
  EXPECT_EQ(listed.size(), kBroken.size());
}

TEST(PolicyFile, DeeplyNestedMetadataIsRefusedBeforeParsing) {
  // 200,000 nested objects in the free-form provenance overflowed the stack
  // (ASan saw it at 50,000); the nesting is refused at the level that goes too deep.
  std::ifstream in(fixture("valid.json"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find('{') + 1;
  std::string deep = "\"provenance\": ";
  for (int i = 0; i < 200000; ++i) deep += "{\"a\": ";
  deep += "1";
  for (int i = 0; i < 200000; ++i) deep += "}";
  text.insert(at, deep + ",");
  try {
    pronk::parsePolicy(text, "deep.json");
    FAIL() << "a 200,000-level document was read";
  } catch (const pronk::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nested more than 64 levels deep"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("deep.json:", 0), 0u) << e.what();
  }
}

}  // namespace
