// Scenario files that load: the shipped scenarios, includes, angle units,
// defaults, sweeps, and the strictness of numbers.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "pronk/error.h"
#include "pronk/scenario.h"

namespace fs = std::filesystem;
using pronk::InputError;
using pronk::loadScenario;
using pronk::Scenario;

namespace {

const fs::path kSource = PRONK_SOURCE_DIR;
const fs::path kTinyUrdf = kSource / "tests" / "scenario" / "data" / "tiny_robot.urdf";
constexpr double kPi = 3.14159265358979323846;

// A scratch directory tree, removed at the end of the test.
class TempTree {
 public:
  TempTree() {
    std::string pattern = (fs::temp_directory_path() / "pronk_scenario_XXXXXX").string();
    root_ = mkdtemp(pattern.data());
  }
  ~TempTree() { fs::remove_all(root_); }
  fs::path write(const std::string& relative, const std::string& text) const {
    const fs::path p = root_ / relative;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
  fs::path copy(const fs::path& from, const std::string& relative) const {
    const fs::path p = root_ / relative;
    fs::create_directories(p.parent_path());
    fs::copy_file(from, p, fs::copy_options::overwrite_existing);
    return p;
  }
  const fs::path& root() const { return root_; }

 private:
  fs::path root_;
};

// The message of the InputError that loading `path` throws ("" if none).
std::string loadError(const fs::path& path) {
  try {
    loadScenario(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A platform on the tiny test robot, for scenarios written by the tests.
std::string tinyPlatform(const std::string& attributes = "", const std::string& children = "") {
  return "<platform name=\"tiny\" " + attributes + ">\n<robot urdf=\"" + kTinyUrdf.string() +
         "\"/>\n<feet links=\"foot\"/>\n<controller name=\"stand\"/>\n" + children + "</platform>\n";
}

std::string scenarioWith(const std::string& body, const std::string& root_attributes = "") {
  return "<scenario version=\"1\" " + root_attributes + ">\n" + body + "</scenario>\n";
}

// The shipped platform file and stand scene of `robot`, copied with a stub
// URDF at the place the real one is referenced from, so that the test checks
// the shipped files themselves whatever state the robot assets are in.
fs::path copyShippedStand(const TempTree& tree, const std::string& robot) {
  tree.copy(kSource / "scenarios" / "platforms" / (robot + ".xml"), "scenarios/platforms/" + robot + ".xml");
  tree.copy(kTinyUrdf, "assets/robots/" + robot + "/" + robot + ".urdf");
  return tree.copy(kSource / "scenarios" / robot / "stand.xml", "scenarios/" + robot + "/stand.xml");
}

void expectStandSettings(const Scenario& s) {
  EXPECT_EQ(s.platform.feet, (std::vector<std::string>{"FR_foot", "FL_foot", "RR_foot", "RL_foot"}));
  EXPECT_EQ(s.platform.stance, (std::vector<double>{0, 0.75, -1.5}));
  EXPECT_TRUE(s.platform.on_ground);
  EXPECT_EQ(s.platform.base_yaw, 0);
  EXPECT_EQ(s.platform.trunk_mass_offset, 0);
  EXPECT_EQ(s.platform.controller.factory, "stand");
  EXPECT_EQ(s.platform.controller.plugin, "");
  EXPECT_EQ(s.sim.control_rate, 1000);
  EXPECT_EQ(s.sim.integrator, "semi_explicit_euler2");
  EXPECT_DOUBLE_EQ(s.sim.step, 2e-4);
  EXPECT_DOUBLE_EQ(s.sim.flight_max_step, 5e-4);
  EXPECT_DOUBLE_EQ(s.sim.duration, 1.5);
  EXPECT_EQ(s.sim.gravity, (pronk::Vec3{0, 0, -9.81}));
  EXPECT_EQ(s.sim.contact.model, "stiction");
  EXPECT_TRUE(s.ground);
  EXPECT_EQ(s.ground_height, 0);
  EXPECT_TRUE(s.terrain.empty());
  EXPECT_TRUE(s.targets.empty());
  EXPECT_FALSE(s.render.has_value());
}

TEST(ShippedScenarios, Go1StandLoadsWithExpectedValues) {
  TempTree tree;
  const fs::path file = copyShippedStand(tree, "go1");
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.name, "go1_stand");
  EXPECT_EQ(s.file, file.string());
  EXPECT_EQ(s.platform.name, "go1");
  EXPECT_EQ(s.platform.urdf, (tree.root() / "assets/robots/go1/go1.urdf").string());
  EXPECT_TRUE(fs::is_regular_file(s.platform.urdf));
  EXPECT_EQ(s.platform.joints.kp, 100);
  EXPECT_EQ(s.platform.joints.kd, 2);
  EXPECT_EQ(s.platform.joints.effort_scale, 1);
  expectStandSettings(s);
  // The platform's elements carry the platform file's name, the rest the scene's.
  EXPECT_EQ(s.platform.where.file, (tree.root() / "scenarios/platforms/go1.xml").string());
  EXPECT_EQ(s.platform.controller.where.file, file.string());
}

TEST(ShippedScenarios, AliengoStandLoadsWithExpectedValues) {
  TempTree tree;
  const fs::path file = copyShippedStand(tree, "aliengo");
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.name, "aliengo_stand");
  EXPECT_EQ(s.platform.name, "aliengo");
  EXPECT_EQ(s.platform.urdf, (tree.root() / "assets/robots/aliengo/aliengo.urdf").string());
  EXPECT_EQ(s.platform.joints.kp, 150);
  EXPECT_EQ(s.platform.joints.kd, 4);
  expectStandSettings(s);
}

// The shipped files against the real robot assets, where they exist.
TEST(ShippedScenarios, LoadInPlaceWithTheProjectsUrdfs) {
  for (const std::string robot : {"go1", "aliengo"}) {
    const fs::path urdf = kSource / "assets" / "robots" / robot / (robot + ".urdf");
    if (!fs::exists(urdf)) GTEST_SKIP() << urdf << " not written yet";
    const Scenario s = loadScenario((kSource / "scenarios" / robot / "stand.xml").string());
    EXPECT_EQ(s.platform.urdf, urdf.lexically_normal().string());
  }
}

TEST(ShippedScenarios, TerrainDemoExercisesTheFormat) {
  const fs::path urdf = kSource / "assets" / "robots" / "go1" / "go1.urdf";
  TempTree tree;
  fs::path file = kSource / "scenarios" / "go1" / "terrain_demo.xml";
  if (!fs::exists(urdf)) {
    tree.copy(kSource / "scenarios" / "platforms" / "go1.xml", "scenarios/platforms/go1.xml");
    tree.copy(kTinyUrdf, "assets/robots/go1/go1.urdf");
    file = tree.copy(file, "scenarios/go1/terrain_demo.xml");
  }
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.platform.stance, (std::vector<double>{0, 0.75, -1.5}));  // the platform file is in rad
  ASSERT_EQ(s.terrain.size(), 1u);
  EXPECT_EQ(s.terrain[0].name, "platform");
  EXPECT_EQ(s.terrain[0].size, (pronk::Vec3{0.6, 1.0, 0.2}));
  EXPECT_EQ(s.terrain[0].position, (pronk::Vec3{0.7, 0, 0.1}));
  EXPECT_EQ(s.terrain[0].mu, 0.9);
  ASSERT_EQ(s.targets.size(), 2u);
  EXPECT_EQ(s.targets[0].name, "onto_platform");
  EXPECT_DOUBLE_EQ(s.targets[0].z, 0.2);
  EXPECT_NEAR(s.targets[1].yaw, kPi / 4, 1e-12);
  ASSERT_EQ(s.sweeps.size(), 3u);
  EXPECT_EQ(s.sweeps[0].kind, pronk::SweepSpec::Kind::Grid);
  ASSERT_EQ(s.sweeps[0].axes.size(), 3u);
  EXPECT_EQ(s.sweeps[0].axes[0].values.size(), 7u);
  EXPECT_NEAR(s.sweeps[0].axes[1].values[0], -kPi / 6, 1e-12);
  EXPECT_EQ(s.sweeps[1].kind, pronk::SweepSpec::Kind::Random);
  EXPECT_EQ(s.sweeps[1].count, 50);
  EXPECT_EQ(s.sweeps[1].seed, 7u);
  EXPECT_NEAR(s.sweeps[1].axes[2].max, kPi / 2, 1e-12);
  EXPECT_EQ(s.sweeps[2].kind, pronk::SweepSpec::Kind::Vary);
  EXPECT_EQ(s.sweeps[2].axes[0].variable, "platform.trunk_mass_offset");
  ASSERT_TRUE(s.render.has_value());
  EXPECT_EQ(s.render->camera.mode, "fixed");
  EXPECT_NEAR(s.render->camera.fovy_deg, 45, 1e-9);
  EXPECT_EQ(s.render->output, "go1_terrain_demo.mp4");
}

TEST(Training, ShippedTrainingFilesCoverThePapersRegion) {
  for (const std::string robot : {"go1", "aliengo"}) {
    const fs::path urdf = kSource / "assets" / "robots" / robot / (robot + ".urdf");
    if (!fs::exists(urdf)) GTEST_SKIP() << urdf << " not written yet";
    const Scenario s = loadScenario((kSource / "scenarios" / "train" / (robot + "_omni.xml")).string());
    ASSERT_TRUE(s.training.has_value());
    ASSERT_TRUE(s.environment.has_value());
    // Up and down targets on real boxes.
    EXPECT_EQ(s.step_platforms, pronk::StepPlatforms::edge);
    const pronk::TrainingSpec& t = *s.training;
    EXPECT_EQ(t.x.min, -0.6);
    EXPECT_EQ(t.x.max, 1.2);
    EXPECT_EQ(t.y.min, -0.6);
    EXPECT_EQ(t.y.max, 0.6);
    EXPECT_EQ(t.z.min, -0.4);
    EXPECT_EQ(t.z.max, 0.4);
    EXPECT_NEAR(t.yaw.min, -kPi / 2, 1e-12);
    EXPECT_NEAR(t.yaw.max, kPi / 2, 1e-12);
    EXPECT_TRUE(t.aim);  // the aim correction of go1_flat_aim.xml, over the region with heights
    EXPECT_TRUE(t.hindsight);
    EXPECT_TRUE(t.critic_warmup);
    EXPECT_FALSE(t.mirror);
  }
}

TEST(Training, EveryAttributeIsRead) {
  TempTree tree;
  const fs::path file = tree.write("train.xml", scenarioWith(tinyPlatform() + R"(<environment name="jump"/>
<training iterations="7" jumps_per_iteration="12" seed="5" checkpoint_every="3">
  <region x="-0.1 0.2" y="-0.3 0.4" z="0 0" yaw="-45 30"/>
  <networks actor="16 8" critic="4"/>
  <ppo epochs="2" minibatches="3" learning_rate="2e-4" clip="0.1" entropy_coefficient="0.005" desired_kl="0.02"
       initial_std="0.5"/>
  <validation count="9" seed="77" every="2"/>
  <guidance residual="false" critic_warmup="false" critic_warmup_epochs="4" mirror="false"/>
</training>
)", "angle=\"deg\""));
  const Scenario s = loadScenario(file.string());
  ASSERT_TRUE(s.training.has_value());
  const pronk::TrainingSpec& t = *s.training;
  EXPECT_EQ(t.iterations, 7);
  EXPECT_EQ(t.jumps_per_iteration, 12);
  EXPECT_EQ(t.seed, 5u);
  EXPECT_EQ(t.checkpoint_every, 3);
  EXPECT_EQ(t.x.min, -0.1);
  EXPECT_EQ(t.y.max, 0.4);
  EXPECT_EQ(t.z.max, 0);
  EXPECT_NEAR(t.yaw.min, -kPi / 4, 1e-12);
  EXPECT_NEAR(t.yaw.max, kPi / 6, 1e-12);
  EXPECT_EQ(t.actor_hidden_sizes, (std::vector<int>{16, 8}));
  EXPECT_EQ(t.critic_hidden_sizes, (std::vector<int>{4}));
  EXPECT_EQ(t.epochs, 2);
  EXPECT_EQ(t.minibatches, 3);
  EXPECT_EQ(t.learning_rate, 2e-4);
  EXPECT_EQ(t.clip, 0.1);
  EXPECT_EQ(t.entropy_coefficient, 0.005);
  EXPECT_EQ(t.desired_kl, 0.02);
  EXPECT_EQ(t.initial_std, 0.5);
  EXPECT_EQ(t.validation_count, 9);
  EXPECT_EQ(t.validation_seed, 77u);
  EXPECT_EQ(t.validate_every, 2);
  EXPECT_FALSE(t.residual);
  EXPECT_FALSE(t.critic_warmup);
  EXPECT_EQ(t.critic_warmup_epochs, 4);
  EXPECT_EQ(t.where.line, 8);
}

TEST(Includes, PathsAreRelativeToTheFileThatHoldsThem) {
  TempTree tree;
  tree.copy(kTinyUrdf, "robots/tiny/tiny.urdf");
  fs::create_directories(tree.root() / "robots" / "tiny" / "meshes");
  tree.write("parts/robot.xml",
             "<scenario_part version=\"1\">\n"
             "<platform name=\"tiny\">\n"
             "<robot urdf=\"../robots/tiny/tiny.urdf\" package_path=\"../robots ../robots/tiny/meshes\"/>\n"
             "<feet links=\"foot\"/>\n"
             "</platform>\n"
             "</scenario_part>\n");
  tree.write("parts/nested/scene_bits.xml",
             "<scenario_part version=\"1\">\n<controller name=\"stand\"/>\n</scenario_part>\n");
  const fs::path scene = tree.write("scenes/deep/scene.xml",
                                    scenarioWith("<include file=\"../../parts/robot.xml\"/>\n"
                                                 "<include file=\"../../parts/nested/scene_bits.xml\"/>\n"));
  const Scenario s = loadScenario(scene.string());
  EXPECT_EQ(s.platform.urdf, (tree.root() / "robots/tiny/tiny.urdf").string());
  EXPECT_EQ(s.platform.package_paths,
            (std::vector<std::string>{(tree.root() / "robots").string(),
                                      (tree.root() / "robots/tiny/meshes").string()}));
  EXPECT_EQ(s.platform.controller.factory, "stand");
  EXPECT_EQ(s.platform.controller.where.file, (tree.root() / "parts/nested/scene_bits.xml").string());
  EXPECT_EQ(s.platform.controller.where.line, 2);
}

TEST(Includes, CycleIsReportedAtTheIncludeThatClosesIt) {
  TempTree tree;
  tree.write("a.xml", "<scenario_part version=\"1\">\n<include file=\"sub/b.xml\"/>\n</scenario_part>\n");
  tree.write("sub/b.xml", "<scenario_part version=\"1\">\n\n<include file=\"../a.xml\"/>\n</scenario_part>\n");
  const fs::path top = tree.write("top.xml", scenarioWith(tinyPlatform() + "<include file=\"a.xml\"/>\n"));
  const std::string message = loadError(top);
  const std::string b = (tree.root() / "sub/b.xml").string();
  EXPECT_EQ(message.rfind(b + ":3: ", 0), 0u) << message;
  EXPECT_NE(message.find("include cycle: " + top.string() + " -> " + (tree.root() / "a.xml").string() + " -> " + b +
                         " -> " + (tree.root() / "a.xml").string()),
            std::string::npos)
      << message;
}

TEST(Includes, IncludingASectionTwiceIsADuplicate) {
  TempTree tree;
  tree.write("sim.xml", "<scenario_part version=\"1\">\n<sim duration=\"2\"/>\n</scenario_part>\n");
  const fs::path top =
      tree.write("top.xml", scenarioWith(tinyPlatform() + "<include file=\"sim.xml\"/>\n<include file=\"sim.xml\"/>\n"));
  EXPECT_NE(loadError(top).find("a scenario holds one <sim>"), std::string::npos) << loadError(top);
}

TEST(Includes, ParamsInsideAnIncludeOverrideTheIncludedEnvironment) {
  TempTree tree;
  tree.write("task.xml",
             "<scenario_part version=\"1\">\n"
             "<environment name=\"jump\">\n"
             "<param name=\"duration\" value=\"1.5\"/>\n"
             "<param name=\"momentum_gain\" value=\"10\"/>\n"
             "</environment>\n"
             "</scenario_part>\n");
  // Through a second level: the outer include's setting wins over the inner one's.
  tree.write("long_task.xml",
             "<scenario_part version=\"1\">\n"
             "<include file=\"task.xml\"><param name=\"duration\" value=\"3\"/></include>\n"
             "</scenario_part>\n");
  const fs::path top = tree.write("top.xml", scenarioWith(tinyPlatform() +
                                                          "<include file=\"long_task.xml\">\n"
                                                          "  <param name=\"duration\" value=\"2.0\"/>\n"
                                                          "  <param name=\"feedforward\" value=\"gravity\"/>\n"
                                                          "</include>\n"));
  const Scenario s = loadScenario(top.string());
  ASSERT_TRUE(s.environment);
  ASSERT_EQ(s.environment->params.size(), 3u);
  EXPECT_EQ(s.environment->params[0].name, "duration");
  EXPECT_EQ(s.environment->params[0].value, "2.0");
  EXPECT_EQ(s.environment->params[0].where.file, top.string());  // errors in it point at the override
  EXPECT_EQ(s.environment->params[1].name, "momentum_gain");
  EXPECT_EQ(s.environment->params[1].value, "10");
  EXPECT_EQ(s.environment->params[2].name, "feedforward");
  EXPECT_EQ(s.environment->params[2].value, "gravity");
}

TEST(Includes, ParamsInsideAnIncludeWithoutAnEnvironmentAreRefused) {
  TempTree tree;
  tree.write("sim.xml", "<scenario_part version=\"1\">\n<sim duration=\"2\"/>\n</scenario_part>\n");
  const fs::path top = tree.write(
      "top.xml", scenarioWith(tinyPlatform() + "<include file=\"sim.xml\"><param name=\"duration\" value=\"2\"/></include>\n"));
  const std::string message = loadError(top);
  EXPECT_NE(message.find("<param> in an <include> sets a parameter of the included <environment>, but"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("brings in no <environment>"), std::string::npos) << message;
  EXPECT_EQ(message.rfind(top.string() + ":", 0), 0u) << message;
}

TEST(Angles, DegreesAreConvertedToRadians) {
  TempTree tree;
  const fs::path file = tree.write(
      "deg.xml",
      scenarioWith(tinyPlatform("", "<initial stance=\"0 45 -90\" yaw=\"180\"><joint name=\"leg_joint\" "
                                    "position=\"30\"/></initial>\n") +
                       "<terrain><box name=\"b\" size=\"1 1 1\" pos=\"2 0 0.5\" yaw=\"90\"/></terrain>\n"
                       "<targets><target name=\"t\" x=\"0.5\" yaw=\"-90\" roll=\"10\" pitch=\"-15\"/></targets>\n"
                       "<sweeps><grid name=\"g\"><axis var=\"target.yaw\" from=\"-90\" to=\"90\" step=\"45\"/>"
                       "<axis var=\"target.x\" values=\"0.5\"/></grid>\n"
                       "<random name=\"r\" count=\"3\"><uniform var=\"target.roll\" min=\"-5\" max=\"5\"/></random>\n"
                       "<vary name=\"v\" var=\"target.pitch\" values=\"0 20\"/></sweeps>\n"
                       "<render><camera fovy=\"60\"/></render>\n",
                   "angle=\"deg\""));
  const Scenario s = loadScenario(file.string());
  const double d = kPi / 180;
  ASSERT_EQ(s.platform.stance.size(), 3u);
  EXPECT_NEAR(s.platform.stance[1], 45 * d, 1e-12);
  EXPECT_NEAR(s.platform.stance[2], -kPi / 2, 1e-12);
  EXPECT_NEAR(s.platform.base_yaw, kPi, 1e-12);
  EXPECT_NEAR(s.platform.joint_positions.at("leg_joint"), kPi / 6, 1e-12);
  EXPECT_NEAR(s.terrain[0].yaw, kPi / 2, 1e-12);
  EXPECT_NEAR(s.targets[0].yaw, -kPi / 2, 1e-12);
  EXPECT_NEAR(s.targets[0].roll, 10 * d, 1e-12);
  EXPECT_NEAR(s.targets[0].pitch, -15 * d, 1e-12);
  EXPECT_DOUBLE_EQ(s.targets[0].x, 0.5);  // lengths are not angles
  ASSERT_EQ(s.sweeps[0].axes[0].values.size(), 5u);
  EXPECT_NEAR(s.sweeps[0].axes[0].values[4], kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.sweeps[0].axes[1].values[0], 0.5);
  EXPECT_NEAR(s.sweeps[1].axes[0].min, -5 * d, 1e-12);
  EXPECT_NEAR(s.sweeps[2].axes[0].values[1], 20 * d, 1e-12);
  EXPECT_NEAR(s.render->camera.fovy_deg, 60, 1e-9);
}

TEST(Angles, RadiansAreTheDefaultAndEachFileHasItsOwnUnit) {
  TempTree tree;
  tree.write("platform.xml",
             "<scenario_part version=\"1\">\n" + tinyPlatform("", "<initial stance=\"0.1 0.75\" yaw=\"0.5\"/>\n") +
                 "</scenario_part>\n");
  const fs::path file = tree.write(
      "top.xml", scenarioWith("<include file=\"platform.xml\"/>\n<targets><target name=\"t\" yaw=\"90\"/></targets>\n"
                              "<render><camera fovy=\"1\"/></render>\n",
                              "angle=\"deg\""));
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.platform.stance, (std::vector<double>{0.1, 0.75}));  // the part's default rad
  EXPECT_DOUBLE_EQ(s.platform.base_yaw, 0.5);
  EXPECT_NEAR(s.targets[0].yaw, kPi / 2, 1e-12);  // the scene's deg
  EXPECT_NEAR(s.render->camera.fovy_deg, 1, 1e-12);

  const fs::path rad = tree.write("rad.xml", scenarioWith(tinyPlatform() + "<render><camera fovy=\"1\"/></render>\n"));
  EXPECT_NEAR(loadScenario(rad.string()).render->camera.fovy_deg, 180 / kPi, 1e-9);
}

TEST(Defaults, AreThoseOfTheInMemoryForm) {
  TempTree tree;
  const fs::path file = tree.write("minimal.xml", scenarioWith(tinyPlatform() + "<render/>\n"));
  const Scenario s = loadScenario(file.string());
  const pronk::SimSpec sim;
  const pronk::JointSettings joints;
  const pronk::RenderSpec render;
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.version, 1);
  EXPECT_EQ(s.sim.control_rate, sim.control_rate);
  EXPECT_EQ(s.sim.integrator, sim.integrator);
  EXPECT_EQ(s.sim.step, sim.step);
  EXPECT_EQ(s.sim.accuracy, sim.accuracy);
  EXPECT_EQ(s.sim.flight_max_step, sim.flight_max_step);
  EXPECT_EQ(s.sim.duration, sim.duration);
  EXPECT_EQ(s.sim.gravity, sim.gravity);
  EXPECT_EQ(s.sim.contact.stiffness, sim.contact.stiffness);
  EXPECT_EQ(s.sim.contact.dissipation, sim.contact.dissipation);
  EXPECT_EQ(s.sim.contact.mu_static, sim.contact.mu_static);
  EXPECT_EQ(s.sim.contact.mu_dynamic, sim.contact.mu_dynamic);
  EXPECT_EQ(s.sim.contact.tangential_stiffness, sim.contact.tangential_stiffness);
  EXPECT_EQ(s.sim.contact.tangential_damping, sim.contact.tangential_damping);
  EXPECT_EQ(s.sim.where.file, file.string());
  EXPECT_EQ(s.sim.where.line, 0);
  EXPECT_EQ(s.platform.joints.kp, joints.kp);
  EXPECT_EQ(s.platform.joints.kd, joints.kd);
  EXPECT_EQ(s.platform.joints.damping, -1);  // keep the URDF's
  EXPECT_EQ(s.platform.joints.armature, joints.armature);
  EXPECT_EQ(s.platform.joints.effort_scale, joints.effort_scale);
  EXPECT_TRUE(s.platform.stance.empty());
  EXPECT_TRUE(s.platform.on_ground);
  EXPECT_EQ(s.platform.base_position, (pronk::Vec3{0, 0, 0}));
  EXPECT_TRUE(s.ground);
  EXPECT_EQ(s.ground_height, 0);
  ASSERT_TRUE(s.render.has_value());
  EXPECT_EQ(s.render->width, render.width);
  EXPECT_EQ(s.render->height, render.height);
  EXPECT_EQ(s.render->fps, render.fps);
  EXPECT_EQ(s.render->speed, render.speed);
  EXPECT_EQ(s.render->output, "");
  EXPECT_EQ(s.render->camera.mode, "side");
  EXPECT_EQ(s.render->camera.fovy_deg, 45);
}

TEST(Platform, JointSettingsOverridesAndParamsAreRead) {
  TempTree tree;
  const fs::path file = tree.write(
      "joints.xml",
      scenarioWith(tinyPlatform("trunk_mass_offset=\"-2.5\"",
                                "<joints kp=\"80\" kd=\"1.5\" armature=\"0.01\" damping=\"0.2\" effort_scale=\"0.9\">\n"
                                "<joint name=\"leg_joint\" kp=\"120\" effort=\"30\"/>\n</joints>\n") +
                   "<controller name=\"guided_jump\" plugin=\"pronk_jump\">\n"
                   "<param name=\"policy\" value=\"policies/go1.bin\"/>\n<param name=\"empty\" value=\"\"/>\n"
                   "</controller>\n"));
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.platform.trunk_mass_offset, -2.5);
  EXPECT_EQ(s.platform.joints.kp, 80);
  EXPECT_EQ(s.platform.joints.damping, 0.2);
  EXPECT_EQ(s.platform.joints.armature, 0.01);
  ASSERT_EQ(s.platform.joints.overrides.size(), 1u);
  EXPECT_EQ(s.platform.joints.overrides[0].joint, "leg_joint");
  EXPECT_EQ(s.platform.joints.overrides[0].kp, 120);
  EXPECT_FALSE(s.platform.joints.overrides[0].kd.has_value());
  EXPECT_EQ(s.platform.joints.overrides[0].effort, 30);
  EXPECT_EQ(s.platform.joints.overrides[0].where.line, 7);
  // The top-level controller replaces the platform's "stand".
  EXPECT_EQ(s.platform.controller.factory, "guided_jump");
  EXPECT_EQ(s.platform.controller.plugin, "pronk_jump");
  ASSERT_EQ(s.platform.controller.params.size(), 2u);
  EXPECT_EQ(s.platform.controller.params[0].name, "policy");
  EXPECT_EQ(s.platform.controller.params[0].value, "policies/go1.bin");
  EXPECT_EQ(s.platform.controller.params[0].where.line, 11);
  EXPECT_EQ(s.platform.controller.params[1].value, "");
}

TEST(Sim, EveryAttributeIsRead) {
  TempTree tree;
  const fs::path file = tree.write(
      "sim.xml",
      scenarioWith(tinyPlatform() +
                   "<sim control_rate=\"500\" integrator=\"runge_kutta_merson\" step=\"1e-4\" accuracy=\"1e-5\"\n"
                   "     flight_max_step=\"1e-3\" duration=\"2.5\" gravity=\"0 0 -1.62\">\n"
                   "<contact model=\"stiction\" stiffness=\"1e5\" dissipation=\"0.5\" mu_static=\"1.1\" "
                   "mu_dynamic=\"0.9\" tangential_stiffness=\"3e4\" tangential_damping=\"300\"/>\n</sim>\n"));
  const Scenario s = loadScenario(file.string());
  EXPECT_EQ(s.sim.control_rate, 500);
  EXPECT_EQ(s.sim.integrator, "runge_kutta_merson");
  EXPECT_EQ(s.sim.step, 1e-4);
  EXPECT_EQ(s.sim.accuracy, 1e-5);
  EXPECT_EQ(s.sim.flight_max_step, 1e-3);
  EXPECT_EQ(s.sim.duration, 2.5);
  EXPECT_EQ(s.sim.gravity, (pronk::Vec3{0, 0, -1.62}));
  EXPECT_EQ(s.sim.where.line, 7);
  EXPECT_EQ(s.sim.contact.stiffness, 1e5);
  EXPECT_EQ(s.sim.contact.dissipation, 0.5);
  EXPECT_EQ(s.sim.contact.mu_static, 1.1);
  EXPECT_EQ(s.sim.contact.mu_dynamic, 0.9);
  EXPECT_EQ(s.sim.contact.tangential_stiffness, 3e4);
  EXPECT_EQ(s.sim.contact.tangential_damping, 300);
  EXPECT_EQ(s.sim.contact.where.line, 9);
}

TEST(Sweeps, EveryListedVariableIsAccepted) {
  for (const pronk::SweepVariable& v : pronk::kSweepVariables) {
    TempTree tree;
    const fs::path file = tree.write(
        "vary.xml", scenarioWith(tinyPlatform() +
                                 (std::string(v.name) == "terrain.edge" ? "<terrain step_platforms=\"true\"/>\n" : "") +
                                 "<sweeps><vary name=\"v\" var=\"" + std::string(v.name) +
                                 "\" values=\"0.9 1.0\"/></sweeps>\n"));
    const Scenario s = loadScenario(file.string());
    ASSERT_EQ(s.sweeps.size(), 1u) << v.name;
    EXPECT_EQ(s.sweeps[0].axes[0].values, (std::vector<double>{0.9, 1.0})) << v.name;  // rad file: no scaling
  }
}

TEST(Sweeps, GridSpanIncludesTheEndPointDespiteRounding) {
  TempTree tree;
  const fs::path file = tree.write(
      "grid.xml", scenarioWith(tinyPlatform() + "<sweeps><grid name=\"g\">"
                                                "<axis var=\"target.x\" from=\"0.3\" to=\"0.9\" step=\"0.1\"/>"
                                                "<axis var=\"joints.kp\" from=\"50\" to=\"75\" step=\"10\"/>"
                                                "</grid></sweeps>\n"));
  const Scenario s = loadScenario(file.string());
  const auto& x = s.sweeps[0].axes[0].values;
  ASSERT_EQ(x.size(), 7u);
  EXPECT_NEAR(x.back(), 0.9, 1e-12);
  EXPECT_EQ(s.sweeps[0].axes[1].values, (std::vector<double>{50, 60, 70}));  // 75 is not on the grid
}

// A Go1-sized footprint: feet 0.2 m ahead and behind, 0.12 m to the sides.
const pronk::Footprint kFootprint{{{0.2, -0.12, -0.3}, {0.2, 0.12, -0.3}, {-0.2, -0.12, -0.3}, {-0.2, 0.12, -0.3}}};

TEST(StepPlatforms, UpAndDownTargetsGetTheirPlatformWithTheEdgeBetweenTheStances) {
  TempTree tree;
  const fs::path file = tree.write(
      "steps.xml", scenarioWith(tinyPlatform() + "<terrain step_platforms=\"true\"/>\n<targets>"
                                                 "<target name=\"up\" x=\"0.6\" y=\"0.8\" z=\"0.2\"/>"
                                                 "<target name=\"down\" x=\"-0.6\" z=\"-0.1\"/>"
                                                 "<target name=\"flat\" x=\"0.4\"/></targets>\n"));
  const Scenario s = loadScenario(file.string());
  ASSERT_EQ(s.step_platforms, pronk::StepPlatforms::edge);
  const std::vector<pronk::EpisodeCase> cases = pronk::targetCases(s);
  ASSERT_EQ(cases.size(), 3u);
  // Up, 1 m away along u = (0.6, 0.8): the start's foremost foot reaches
  // (0.2, 0.12) u = 0.216 m along u, the landing's rearmost foot 1 - 0.216 m. The
  // edge goes halfway between the two 0.05 m clearances, at 0.5 m, and the box,
  // 0.2 high and turned to u, runs from it to 0.6 m beyond the target.
  const Scenario up = pronk::applyCase(s, cases[0], kFootprint);
  ASSERT_EQ(up.terrain.size(), s.terrain.size() + 1);
  const pronk::TerrainBox& landing = up.terrain.back();
  EXPECT_NEAR(landing.size[2], 0.2, 1e-12);
  EXPECT_NEAR(landing.position[2], s.ground_height + 0.1, 1e-12);
  EXPECT_NEAR(landing.yaw, std::atan2(0.8, 0.6), 1e-12);
  EXPECT_NEAR(landing.size[0], 1.6 - 0.5, 1e-12);
  const double middle = (0.5 + 1.6) / 2.0;
  EXPECT_NEAR(landing.position[0], s.platform.base_position[0] + 0.6 * middle, 1e-12);
  EXPECT_NEAR(landing.position[1], s.platform.base_position[1] + 0.8 * middle, 1e-12);
  // Down, 0.6 m backwards: the room between the stances is [0.25, 0.35] m along
  // u = -x; a start platform from 0.8 m against u to the edge at 0.3 m.
  const Scenario down = pronk::applyCase(s, cases[1], kFootprint);
  const pronk::TerrainBox& start = down.terrain.back();
  EXPECT_EQ(start.name, "start_platform");
  EXPECT_NEAR(start.size[2], 0.1, 1e-12);
  EXPECT_NEAR(start.size[0], 0.8 + 0.3, 1e-12);
  // Along u it spans [-0.8, 0.3] m: its centre is -0.25 u = +0.25 m in x.
  EXPECT_NEAR(start.position[0], s.platform.base_position[0] + 0.25, 1e-12);
  // terrain.edge places it in the room: 0 next to the start's feet, 1 next to the landing's.
  pronk::EpisodeCase near_start = cases[1], near_landing = cases[1];
  near_start.assignments = {{"terrain.edge", 0.0}};
  near_landing.assignments = {{"terrain.edge", 1.0}};
  EXPECT_NEAR(pronk::applyCase(s, near_start, kFootprint).terrain.back().size[0], 0.8 + 0.25, 1e-12);
  EXPECT_NEAR(pronk::applyCase(s, near_landing, kFootprint).terrain.back().size[0], 0.8 + 0.35, 1e-12);
  // The landing stance turns with the target's yaw: a quarter turn puts the
  // landing's feet 0.12 m (not 0.2 m) behind the target along u.
  pronk::EpisodeCase turned = cases[1];
  turned.target.yaw = M_PI / 2;
  EXPECT_NEAR(pronk::applyCase(s, turned, kFootprint).terrain.back().size[0], 0.8 + (0.25 + 0.43) / 2, 1e-12);
  // A flat target adds nothing.
  EXPECT_EQ(pronk::applyCase(s, cases[2], kFootprint).terrain.size(), s.terrain.size());
}

TEST(StepPlatforms, ApexPlatformsAddNoBoxAndSitOnTheTargetInTheStartsHeading) {
  TempTree tree;
  const fs::path file = tree.write(
      "apex.xml", scenarioWith(tinyPlatform() + "<terrain ground_height=\"0.1\" step_platforms=\"apex\"/>\n"
                                                "<targets><target name=\"up\" x=\"0.3\" y=\"0.4\" z=\"0.2\" yaw=\"0.5\"/>"
                                                "<target name=\"hop\" x=\"0\" z=\"0.1\"/>"
                                                "<target name=\"flat\" x=\"0.4\"/></targets>\n"));
  Scenario s = loadScenario(file.string());
  ASSERT_EQ(s.step_platforms, pronk::StepPlatforms::apex);
  s.platform.base_position = {1.0, 2.0, 0.0};
  s.platform.base_yaw = M_PI / 2;
  const std::vector<pronk::EpisodeCase> cases = pronk::targetCases(s);
  const Scenario up = pronk::applyCase(s, cases[0], kFootprint);
  EXPECT_EQ(up.terrain.size(), s.terrain.size());
  ASSERT_TRUE(up.apex_platform.has_value());
  // Turned a quarter: the target's x runs along the world's y, its y against x.
  EXPECT_NEAR(up.apex_platform->x, 1.0 - 0.4, 1e-12);
  EXPECT_NEAR(up.apex_platform->y, 2.0 + 0.3, 1e-12);
  EXPECT_NEAR(up.apex_platform->yaw, M_PI / 2 + 0.5, 1e-12);
  EXPECT_NEAR(up.apex_platform->top, 0.3, 1e-12);
  EXPECT_NEAR(up.apex_platform->floor, 0.1 - 0.5, 1e-12);
  // Straight above the start is fine: there is no edge to place.
  EXPECT_TRUE(pronk::applyCase(s, cases[1], kFootprint).apex_platform.has_value());
  EXPECT_FALSE(pronk::applyCase(s, cases[2], kFootprint).apex_platform.has_value());
}

TEST(StepPlatforms, AnEdgePlacementNeedsStepPlatformsAndAFraction) {
  TempTree tree;
  const std::string sweep = "<sweeps><random name=\"r\" count=\"3\" seed=\"1\"><uniform var=\"target.x\" min=\"0.6\" "
                            "max=\"1\"/><uniform var=\"terrain.edge\" min=\"0\" max=\"HI\"/></random></sweeps>\n";
  auto with = [&](const std::string& terrain, const std::string& hi) {
    std::string body = sweep;
    body.replace(body.find("HI"), 2, hi);
    return tree.write("edge.xml", scenarioWith(tinyPlatform() + terrain + body));
  };
  EXPECT_NO_THROW(loadScenario(with("<terrain step_platforms=\"true\"/>\n", "1").string()));
  std::string message = loadError(with("<terrain step_platforms=\"apex\"/>\n", "1"));
  EXPECT_NE(message.find("terrain.edge places a step platform's edge"), std::string::npos) << message;
  message = loadError(with("<terrain step_platforms=\"true\"/>\n", "1.5"));
  EXPECT_NE(message.find("must be in [0, 1]"), std::string::npos) << message;
}

TEST(StepPlatforms, AnUnknownKindIsRefusedWithItsLine) {
  TempTree tree;
  const fs::path file = tree.write("bad.xml", scenarioWith(tinyPlatform() + "<terrain step_platforms=\"teleport\"/>\n"));
  const std::string message = loadError(file);
  EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
  EXPECT_NE(message.find("apex"), std::string::npos) << message;
}

TEST(StepPlatforms, ATargetStraightAboveTheStartHasNoRoomForAnEdge) {
  TempTree tree;
  const fs::path file = tree.write(
      "steps.xml", scenarioWith(tinyPlatform() + "<terrain step_platforms=\"true\"/>\n<targets>"
                                                 "<target name=\"hop\" x=\"0.02\" z=\"0.2\"/></targets>\n"));
  const Scenario s = loadScenario(file.string());
  const std::vector<pronk::EpisodeCase> cases = pronk::targetCases(s);
  try {
    pronk::applyCase(s, cases[0], kFootprint);
    FAIL() << "expected an InputError";
  } catch (const pronk::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << message;
    EXPECT_NE(message.find("step_platforms"), std::string::npos) << message;
  }
}

TEST(Numbers, ParseStrictly) {
  TempTree tree;
  for (const std::string bad : {"1.2abc", "nan", "inf", "-inf", "", " ", "0x10", "1,5", "1e999", "1.5 2", "--1", "one"}) {
    const fs::path file = tree.write("bad.xml", scenarioWith(tinyPlatform() + "<sim duration=\"" + bad + "\"/>\n"));
    const std::string message = loadError(file);
    EXPECT_EQ(message.rfind(file.string() + ":7: <sim>: duration: \"" + bad + "\" is not a finite number", 0), 0u)
        << "value \"" << bad << "\": " << message;
  }
  for (const auto& [good, value] : std::vector<std::pair<std::string, double>>{
           {"+1.5", 1.5}, {" 2 ", 2}, {"1e-3", 1e-3}, {"3", 3}, {".5", 0.5}}) {
    const fs::path file = tree.write("good.xml", scenarioWith(tinyPlatform() + "<sim duration=\"" + good + "\"/>\n"));
    EXPECT_DOUBLE_EQ(loadScenario(file.string()).sim.duration, value) << good;
  }
  // Whole numbers take padding as every number does; a fraction or a blank is no integer.
  const fs::path padded = tree.write("padded.xml", scenarioWith(tinyPlatform() + "<render width=\" 640 \"/>\n"));
  EXPECT_EQ(loadScenario(padded.string()).render->width, 640);
  for (const std::string bad : {" ", "6.5", "0x10", "1 2"}) {
    const fs::path file = tree.write("int.xml", scenarioWith(tinyPlatform() + "<render width=\"" + bad + "\"/>\n"));
    EXPECT_NE(loadError(file).find("width: \"" + bad + "\" is not an integer"), std::string::npos) << loadError(file);
  }
}

TEST(Numbers, VectorsNeedTheirExactCount) {
  TempTree tree;
  for (const std::string bad : {"0 0", "0 0 -9.81 0", ""}) {
    const fs::path file = tree.write("g.xml", scenarioWith(tinyPlatform() + "<sim gravity=\"" + bad + "\"/>\n"));
    EXPECT_NE(loadError(file).find("gravity needs exactly 3 numbers"), std::string::npos) << loadError(file);
  }
}

TEST(Errors, MissingTopLevelFileNamesIt) {
  const std::string path = "/nonexistent/pronk/scenario.xml";
  EXPECT_EQ(loadError(path), path + ": scenario file not found");
}

TEST(Errors, UnknownAttributeListsTheKnownOnes) {
  TempTree tree;
  const fs::path file =
      tree.write("t.xml", scenarioWith(tinyPlatform() + "<targets>\n<target name=\"a\" dx=\"1\"/>\n</targets>\n"));
  EXPECT_EQ(loadError(file),
            file.string() + ":8: <target>: unknown attribute \"dx\" (known: name, x, y, z, yaw, roll, pitch, tolerance_xy, tolerance_yaw)");
}

TEST(Errors, PackagePathMustExist) {
  TempTree tree;
  tree.copy(kTinyUrdf, "r.urdf");
  const fs::path file = tree.write(
      "p.xml", scenarioWith("<platform name=\"p\">\n<robot urdf=\"r.urdf\" package_path=\"nowhere\"/>\n"
                            "<feet links=\"foot\"/><controller name=\"stand\"/></platform>\n"));
  EXPECT_EQ(loadError(file),
            file.string() + ":3: <robot>: package_path directory not found: " + (tree.root() / "nowhere").string());
}

TEST(Errors, TrunkMassOffsetJustAboveTheRootMassIsAccepted) {
  TempTree tree;
  const fs::path ok = tree.write("ok.xml", scenarioWith(tinyPlatform("trunk_mass_offset=\"-5.49\"")));
  EXPECT_DOUBLE_EQ(loadScenario(ok.string()).platform.trunk_mass_offset, -5.49);
  const fs::path bad = tree.write("bad.xml", scenarioWith(tinyPlatform("trunk_mass_offset=\"-5.5\"")));
  EXPECT_NE(loadError(bad).find("trunk_mass_offset must be > -5.5 kg"), std::string::npos) << loadError(bad);
}

}  // namespace
