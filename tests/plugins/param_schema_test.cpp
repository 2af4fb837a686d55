// Scenario parameters checked against a factory's declared schema, each error
// at the right file:line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

using ::testing::HasSubstr;

class ParamSchema : public ::testing::Test {
 protected:
  void SetUp() override {
    registry_.load(PRONK_FIXTURE_MINIMAL);
    factory_ = registry_.find(PRONK_FACTORY_CONTROLLER, "fixture_hold");
    ASSERT_NE(factory_, nullptr);
  }
  static ParamSetting set(const std::string& name, const std::string& value, int line) {
    return {name, value, {"scenario.xml", line}};
  }
  // The InputError resolveParams throws for these settings.
  InputError errorFor(const std::vector<ParamSetting>& settings) {
    try {
      resolveParams(*factory_, settings, owner_);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError";
    return InputError({}, "");
  }

  PluginRegistry registry_;
  const pronk_factory* factory_ = nullptr;
  const SourceLocation owner_{"scenario.xml", 12};
};

TEST_F(ParamSchema, DefaultsAreFilledInInDeclarationOrder) {
  const ResolvedParams p = resolveParams(*factory_, {set("count", "3", 14)}, owner_);
  ASSERT_EQ(p.size(), 4);
  const pronk_param_value* v = p.data();
  EXPECT_STREQ(v[0].name, "gain");
  EXPECT_STREQ(v[0].value, "1.5");
  EXPECT_STREQ(v[1].name, "count");
  EXPECT_STREQ(v[1].value, "3");
  EXPECT_STREQ(v[2].value, "none");
  EXPECT_STREQ(v[3].value, "0 0 0");
  ASSERT_NE(p.find("offset"), nullptr);
  EXPECT_EQ(*p.find("offset"), "0 0 0");
  EXPECT_EQ(p.find("nothing"), nullptr);

  // Copies and moves keep data() valid.
  ResolvedParams copy = p;
  const ResolvedParams moved = std::move(copy);
  EXPECT_STREQ(moved.data()[1].value, "3");
  EXPECT_STREQ(p.data()[1].value, "3");
}

TEST_F(ParamSchema, SetValuesOverrideDefaults) {
  const ResolvedParams p = resolveParams(
      *factory_, {set("offset", " 0.5 -1 1 ", 15), set("count", "5", 14), set("gain", "1e1", 16)}, owner_);
  EXPECT_EQ(*p.find("gain"), "1e1");
  EXPECT_EQ(*p.find("offset"), " 0.5 -1 1 ");
}

TEST_F(ParamSchema, UnknownParameterIsAnErrorAtItsLineListingTheKnownOnes) {
  const InputError e = errorFor({set("count", "3", 14), set("gian", "2", 15)});
  EXPECT_EQ(e.where().line, 15);
  EXPECT_STREQ(e.what(),
               "scenario.xml:15: unknown parameter 'gian' for controller 'fixture_hold'; known: gain, count, label, "
               "offset");
}

TEST_F(ParamSchema, OutOfRangeNamesTheRange) {
  const InputError e = errorFor({set("count", "3", 14), set("gain", "12.5", 17)});
  EXPECT_EQ(e.where().str(), "scenario.xml:17");
  EXPECT_THAT(e.what(), HasSubstr("parameter 'gain' of controller 'fixture_hold': 12.5 is out of range [0, 10] N m/rad"));

  const InputError i = errorFor({set("count", "9", 18)});
  EXPECT_EQ(i.where().line, 18);
  EXPECT_THAT(i.what(), HasSubstr("9 is out of range [1, 5]"));

  const InputError v = errorFor({set("count", "1", 14), set("offset", "0 2 0", 19)});
  EXPECT_EQ(v.where().line, 19);
  EXPECT_THAT(v.what(), HasSubstr("element 2 (2) is out of range [-1, 1] m"));
}

TEST_F(ParamSchema, WrongTypesAndUnparsableNumbersAreErrors) {
  const InputError real = errorFor({set("count", "3", 14), set("gain", "fast", 20)});
  EXPECT_EQ(real.where().line, 20);
  EXPECT_THAT(real.what(), HasSubstr("'fast' is not a number"));

  const InputError integer = errorFor({set("count", "2.5", 21)});
  EXPECT_EQ(integer.where().line, 21);
  EXPECT_THAT(integer.what(), HasSubstr("'2.5' is not an integer"));

  const InputError trailing = errorFor({set("count", "3", 14), set("gain", "1.0x", 22)});
  EXPECT_THAT(trailing.what(), HasSubstr("'1.0x' is not a number"));

  const InputError nan = errorFor({set("count", "3", 14), set("gain", "nan", 23)});
  EXPECT_THAT(nan.what(), HasSubstr("'nan' is not a number"));
}

TEST_F(ParamSchema, WrongVectorSizeIsAnError) {
  const InputError e = errorFor({set("count", "3", 14), set("offset", "0.1 0.2", 24)});
  EXPECT_EQ(e.where().str(), "scenario.xml:24");
  EXPECT_THAT(e.what(), HasSubstr("parameter 'offset' of controller 'fixture_hold': needs 3 numbers, got 2"));
}

TEST_F(ParamSchema, MissingRequiredParameterIsAnErrorAtTheOwner) {
  const InputError e = errorFor({set("gain", "2", 16)});
  EXPECT_EQ(e.where().str(), "scenario.xml:12");
  EXPECT_THAT(e.what(), HasSubstr("missing required parameter 'count' of controller 'fixture_hold'"));
}

TEST_F(ParamSchema, DuplicateSettingIsAnError) {
  const InputError e = errorFor({set("count", "3", 14), set("gain", "2", 15), set("gain", "3", 16)});
  EXPECT_EQ(e.where().line, 16);
  EXPECT_THAT(e.what(), HasSubstr("parameter 'gain' of controller 'fixture_hold' is set twice (first at scenario.xml:15)"));
}

TEST_F(ParamSchema, GuidedJumpDefaultsResolve) {
  registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
  const pronk_factory* f = registry_.find(PRONK_FACTORY_CONTROLLER, "guided_jump");
  ASSERT_NE(f, nullptr);
  const ResolvedParams p = resolveParams(*f, {set("kp", "60", 30)}, owner_);
  EXPECT_EQ(*p.find("kp"), "60");
  EXPECT_EQ(*p.find("kd"), "2");
  EXPECT_EQ(*p.find("stance"), "0 0.75 -1.5");
  EXPECT_EQ(*p.find("motor"), "effort");
  try {
    resolveParams(*f, {set("kp", "2000", 31)}, owner_);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scenario.xml:31: parameter 'kp' of controller 'guided_jump': 2000 is out of range [0, 1000] N m/rad");
  }
}

// ABI 1.5: stance, kp and kd default to the platform's, when the scenario
// leaves them out; the declared default stays for a scene without a platform.
TEST_F(ParamSchema, GuidedJumpTakesTheStanceAndGainsFromThePlatform) {
  registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
  const pronk_factory* f = registry_.find(PRONK_FACTORY_ENVIRONMENT, "jump");
  ASSERT_NE(f, nullptr);
  PlatformSpec platform;
  platform.stance = {0.0, 0.8, -1.5};
  platform.initial_where = {"a1.xml", 7};
  platform.joints.kp = 60;
  platform.joints.kd = 4.5;
  platform.joints_where = {"a1.xml", 9};
  const ResolvedParams p = resolveParams(*f, {set("kd", "3", 30)}, owner_, &platform);
  EXPECT_EQ(*p.find("stance"), "0 0.8 -1.5");
  EXPECT_EQ(*p.find("kp"), "60");
  EXPECT_EQ(*p.find("kd"), "3");  // the scenario's setting wins
  // A platform that places its joints by name gives no per-leg stance: the declared default.
  platform.stance.clear();
  EXPECT_EQ(*resolveParams(*f, {}, owner_, &platform).find("stance"), "0 0.75 -1.5");
  // A platform stance the parameter cannot take is an error at the platform's line.
  platform.stance = {0.0, 0.8};
  try {
    resolveParams(*f, {}, owner_, &platform);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a1.xml:7: the platform's stance '0 0.8' for parameter 'stance' of environment "
                                    "'jump'"));
  }
}

// The jump environment keeps at most 25 parameters (docs/method.md,
// "Parameters"), each with a range and a one-line reason for `pronk plugins`.
TEST_F(ParamSchema, TheJumpEnvironmentDeclaresAtMost25ParametersEachWithARangeAndAReason) {
  registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
  const pronk_factory* f = registry_.find(PRONK_FACTORY_ENVIRONMENT, "jump");
  ASSERT_NE(f, nullptr);
  EXPECT_LE(f->param_count, 25);
  for (int32_t i = 0; i < f->param_count; ++i) {
    const pronk_param_decl& d = f->params[i];
    ASSERT_NE(d.name, nullptr);
    ASSERT_NE(d.description, nullptr) << d.name;
    ASSERT_NE(d.unit, nullptr) << d.name;
    EXPECT_GE(std::string(d.description).size(), 20u) << d.name;
    EXPECT_EQ(std::string(d.description).find('\n'), std::string::npos) << d.name;
    if (d.type == PRONK_PARAM_REAL || d.type == PRONK_PARAM_INT) {
      EXPECT_LT(d.min_value, d.max_value) << d.name;
    }
  }
}

}  // namespace
}  // namespace pronk
