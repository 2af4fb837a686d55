// URDF reading: mass properties against sums over the file, lumping, limits,
// mesh resolution and error cases.
#include <gtest/gtest.h>
#include <iterator>
#include <tuple>

#include <filesystem>
#include <fstream>

#include "go1_fixture.h"
#include "pronk/robot_description.h"

namespace pronk {
namespace {

using testing::robotUrdf;

TEST(RobotDescription, Go1MassIsTheSumOfItsLinks) {
  const RobotDescription robot = loadUrdf(robotUrdf("go1"));
  // trunk + 4 x (hip, thigh, calf, foot) + 12 rotors, from the vendor figures.
  const double expected = 5.204 + 4 * (0.591 + 0.92 + 0.135862 + 0.06) + 12 * 0.089;
  EXPECT_NEAR(robot.totalMass(), expected, 1e-9);
  // Rotors and feet are lumped: one root and three moving bodies per leg.
  EXPECT_EQ(robot.bodies.size(), 13u);
  EXPECT_EQ(robot.joints.size(), 12u);
  EXPECT_TRUE(robot.warnings.empty());
}

TEST(RobotDescription, LumpedBodyKeepsCentreOfMassAndInertia) {
  const RobotDescription robot = loadUrdf(robotUrdf("go1"));
  // The FL thigh body = FL_thigh (0.92 kg, COM (-0.003342, -0.018054, -0.033451))
  // + FL_calf_rotor (0.089 kg at (0, -0.03235, 0)), both in the thigh frame.
  const int b = robot.findBody("FL_thigh");
  ASSERT_GE(b, 0);
  const MassProperties& m = robot.bodies[b].mass;
  EXPECT_NEAR(m.mass, 1.009, 1e-12);
  const Eigen::Vector3d com = (0.92 * Eigen::Vector3d(-0.003342, -0.018054, -0.033451) +
                               0.089 * Eigen::Vector3d(0, -0.03235, 0)) / 1.009;
  EXPECT_NEAR((m.com_body - com).norm(), 0, 1e-12);
  // Parallel-axis theorem on Ixx: the two central Ixx plus m d^2 (d in y, z).
  const Eigen::Vector3d d1 = Eigen::Vector3d(-0.003342, -0.018054, -0.033451) - com;
  const Eigen::Vector3d d2 = Eigen::Vector3d(0, -0.03235, 0) - com;
  const double ixx = 0.004431760472 + 0.92 * (d1.y() * d1.y() + d1.z() * d1.z()) + 5.9647e-05 +
                     0.089 * (d2.y() * d2.y() + d2.z() * d2.z());
  EXPECT_NEAR(m.inertia_com(0, 0), ixx, 1e-12);
}

TEST(RobotDescription, JointLimitsAndFeetAreKept) {
  const RobotDescription robot = loadUrdf(robotUrdf("go1"));
  const Joint& calf = robot.joints[robot.findJoint("RL_calf_joint")];
  EXPECT_TRUE(calf.has_position_limits);
  EXPECT_DOUBLE_EQ(calf.lower, -2.818);
  EXPECT_DOUBLE_EQ(calf.upper, -0.888);
  EXPECT_DOUBLE_EQ(calf.effort_limit, 35.55);
  EXPECT_DOUBLE_EQ(calf.velocity_limit, 20.06);
  const auto foot = robot.locateLink("RL_foot");
  ASSERT_TRUE(foot);
  EXPECT_EQ(robot.bodies[foot->first].name, "RL_calf");
  EXPECT_NEAR(foot->second.translation().z(), -0.213, 1e-12);
}

TEST(RobotDescription, VisualMeshesResolveRelativeToTheUrdf) {
  const RobotDescription robot = loadUrdf(robotUrdf("go1"));
  int meshes = 0;
  for (const Body& b : robot.bodies)
    for (const VisualShape& v : b.visuals)
      if (!v.mesh_uri.empty()) {
        ASSERT_TRUE(v.mesh_path) << v.mesh_uri;
        EXPECT_TRUE(std::filesystem::exists(*v.mesh_path));
        ++meshes;
      }
  EXPECT_GT(meshes, 0);
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "pronk_urdf_tests";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

void expectError(const std::string& name, const std::string& xml, const std::string& where,
                 const std::string& contains) {
  const std::string path = writeTemp(name, xml);
  try {
    loadUrdf(path);
    FAIL() << "no error for " << name;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + where, 0), 0u) << msg;
    EXPECT_NE(msg.find(contains), std::string::npos) << msg;
  }
}

const char* kLink = R"(<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>)";

TEST(RobotDescription, ErrorsNameTheFileAndLine) {
  try {
    loadUrdf("/nonexistent/robot.urdf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/robot.urdf: URDF file not found"), std::string::npos) << e.what();
  }
  expectError("syntax.urdf", "<robot name='r'>\n<link name='a'>\n</robot>\n", ":2: ", "XML error");
  expectError("planar.urdf",
              std::string("<robot name='r'>\n<link name='a'>") + kLink + "</link>\n<link name='b'>" + kLink +
                  "</link>\n<joint name='j' type='planar'><parent link='a'/><child link='b'/></joint>\n</robot>",
              ":4: ", "floating or planar");
  expectError("nolimits.urdf",
              std::string("<robot name='r'>\n<link name='a'>") + kLink + "</link>\n<link name='b'>" + kLink +
                  "</link>\n<joint name='j' type='revolute'><parent link='a'/><child link='b'/></joint>\n</robot>",
              ":4: ", "limits");
  expectError("massless.urdf",
              std::string("<robot name='r'>\n<link name='a'>") + kLink +
                  "</link>\n<link name='b'/>\n<joint name='j' type='continuous'><parent link='a'/><child link='b'/>"
                  "<axis xyz='0 1 0'/></joint>\n</robot>",
              ":3: ", "no mass");
  expectError("badinertia.urdf",
              "<robot name='r'>\n<link name='a'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' "
              "izz='0.5' ixy='0' ixz='0' iyz='0'/></inertial></link>\n</robot>",
              ":2: ", "not physical");
}

TEST(RobotDescription, MissingVisualMeshIsAWarningWithAPrimitive) {
  const std::string path = writeTemp(
      "missing_mesh.urdf",
      std::string("<robot name='r'>\n<link name='a'>") + kLink +
          "<visual><geometry><mesh filename='package://nowhere/meshes/trunk.dae'/></geometry></visual>"
          "<collision><geometry><box size='0.3 0.1 0.1'/></geometry></collision></link>\n</robot>");
  const RobotDescription robot = loadUrdf(path);
  ASSERT_EQ(robot.warnings.size(), 1u);
  EXPECT_NE(robot.warnings[0].find("not found"), std::string::npos);
  ASSERT_EQ(robot.bodies[0].visuals.size(), 1u);
  ASSERT_TRUE(robot.bodies[0].visuals[0].primitive);
  EXPECT_EQ(robot.bodies[0].visuals[0].primitive->type, ShapeType::Box);
  EXPECT_NEAR(robot.bodies[0].visuals[0].primitive->box_size.x(), 0.3, 1e-12);
}

TEST(RobotDescription, PackageUrisResolveThroughSearchPaths) {
  const std::string mesh_dir = std::string(PRONK_SOURCE_DIR) + "/assets/robots";
  const std::string path = writeTemp(
      "package_mesh.urdf",
      std::string("<robot name='r'>\n<link name='a'>") + kLink +
          "<visual><geometry><mesh filename='package://go1/meshes/calf.obj'/></geometry></visual>"
          "<collision><geometry><mesh filename='package://go1/meshes/calf.obj' scale='2 2 2'/></geometry></collision>"
          "</link>\n</robot>");
  UrdfOptions options;
  options.package_paths = {mesh_dir};
  const RobotDescription robot = loadUrdf(path, options);
  EXPECT_TRUE(robot.warnings.empty());
  ASSERT_EQ(robot.bodies[0].visuals.size(), 1u);
  ASSERT_TRUE(robot.bodies[0].visuals[0].mesh_path);
  EXPECT_EQ(*robot.bodies[0].visuals[0].mesh_path, std::filesystem::canonical(mesh_dir + "/go1/meshes/calf.obj").string());
  // A collision mesh becomes its bounding box (scaled): the calf bar is about 0.2 m long.
  ASSERT_EQ(robot.bodies[0].collisions.size(), 1u);
  const CollisionShape& c = robot.bodies[0].collisions[0];
  EXPECT_TRUE(c.from_mesh);
  EXPECT_EQ(c.shape.type, ShapeType::Box);
  EXPECT_GT(c.shape.box_size.z(), 2 * 0.2);
  EXPECT_LT(c.shape.box_size.z(), 2 * 0.26);
  // Without the search path the visual is missing: a warning and a primitive.
  const RobotDescription bare = loadUrdf(path);
  EXPECT_FALSE(bare.warnings.empty());
}

}  // namespace
TEST(RobotDescription, AZUpColladaCollisionMeshIsBoundedInItsFileFrame) {
  // The fixture declares Z_UP (as the vendors' Unitree DAE files do): a 0.04 x 0.04 x 0.6 m bar
  // along the file's z, centred at z = 0.1. Its bounds stay along z, not turned onto y.
  const std::string mesh = std::string(PRONK_SOURCE_DIR) + "/tests/fixtures/meshes/zup_bar.dae";
  const std::string path = writeTemp(
      "zup_mesh.urdf", std::string("<robot name='r'>\n<link name='a'>") + kLink +
                           "<collision><geometry><mesh filename='" + mesh + "'/></geometry></collision>"
                           "</link>\n</robot>");
  const RobotDescription robot = loadUrdf(path);
  ASSERT_EQ(robot.bodies[0].collisions.size(), 1u);
  const CollisionShape& c = robot.bodies[0].collisions[0];
  EXPECT_TRUE(c.from_mesh);
  EXPECT_TRUE(c.shape.box_size.isApprox(Eigen::Vector3d(0.04, 0.04, 0.6), 1e-6)) << c.shape.box_size.transpose();
  EXPECT_TRUE(c.shape.pose_body.translation().isApprox(Eigen::Vector3d(0, 0, 0.1), 1e-6))
      << c.shape.pose_body.translation().transpose();
}

TEST(RobotDescription, AKinematicLoopIsRefusedAtItsJointNotFollowedForever) {
  // urdfdom accepts a link that is the child of two joints; the builder used to
  // recurse until the stack overflowed.
  const std::string urdf =
    "<?xml version=\"1.0\"?>\n"
    "<robot name=\"loop\">\n"
    "  <link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>\n"
    "  <link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>\n"
    "  <link name=\"c\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>\n"
    "  <joint name=\"ab\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
    "  <joint name=\"bc\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
    "  <joint name=\"cb\" type=\"revolute\"><parent link=\"c\"/><child link=\"b\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
    "</robot>\n"
    "";
  try {
    parseUrdf(urdf, "loop.urdf");
    FAIL() << "a URDF with a loop was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("loop.urdf:8: link 'b' is the child of joints 'ab' and 'cb'"),
              std::string::npos)
        << e.what();
  }
}

// The path of a fixture under tests/sim/urdf/.
std::string urdfFixture(const std::string& file) {
  return (std::filesystem::path(PRONK_SOURCE_DIR) / "tests" / "sim" / "urdf" / file).string();
}

// The message loadUrdf refuses a fixture with; a test failure (and "") if it
// accepts it.
std::string refusalOf(const std::string& path) {
  try {
    loadUrdf(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RobotDescription, APercentSignIsRefusedBeforeUrdfdomPrintsIt) {
  // Found by fuzzing: urdfdom used a malformed rgba's text as a printf format.
  const std::string path = urdfFixture("percent_in_a_value.urdf");
  const std::string message = refusalOf(path);
  EXPECT_EQ(message.rfind(path + ":6: <color>: rgba=\"0.7 0.%S 0.7 1\" holds a '%'", 0), 0u) << message;
}

TEST(RobotDescription, APercentSignAnywhereIsRefusedWhateverTheXmlReaderMakesOfIt) {
  // Found by fuzzing: a broken <?xml declaration that tinyxml2 ends further down
  // hid a robot with "%S" in an rgba from the check above, and urdfdom read it.
  const std::string path = urdfFixture("percent_in_a_broken_declaration.urdf");
  const std::string message = refusalOf(path);
  EXPECT_EQ(message.rfind(path + ":2: a '%' outside any attribute", 0), 0u) << message;
}

TEST(RobotDescription, ALoopWithoutASecondParentIsRefusedAtItsJoint) {
  // Found by fuzzing (urdfdom's links around the loop were never freed): a
  // link jointed to itself, or links each other's parent apart from the
  // root's tree. urdfdom accepts both; their links were left out of the robot.
  const std::pair<std::string, std::string> cases[] = {
      {"self_parent.urdf", ":12: joint 'foot_fixed' closes a kinematic loop (child <- parent: 'foot' <- 'foot')"},
      {"loop_beside_the_tree.urdf",
       ":15: joint 'knee' closes a kinematic loop (child <- parent: 'calf' <- 'thigh' <- 'calf')"},
  };
  for (const auto& [file, expected] : cases) {
    const std::string path = urdfFixture(file);
    const std::string message = refusalOf(path);
    EXPECT_EQ(message.rfind(path + expected + ": a URDF is a tree", 0), 0u) << message;
  }
}

TEST(RobotDescription, UrdfdomReadsTheTreeThatPronkChecked) {
  // Found by fuzzing: urdfdom's reader (TinyXML 1) decoded a name otherwise
  // than tinyxml2 under a declared legacy encoding, so urdfdom built a loop that
  // pronk's loop check never saw, and the robot's build overflowed the stack.
  // urdfdom now reads tinyxml2's printout: the joint's child "\u0161" is a
  // missing link to both.
  const std::string path = urdfFixture("loop_through_a_legacy_encoding.urdf");
  const std::string message = refusalOf(path);
  EXPECT_EQ(message.rfind(path + ":17: invalid URDF: ", 0), 0u) << message;
  EXPECT_NE(message.find("\u0161"), std::string::npos) << message;
}

TEST(RobotDescription, UnparseableAndUnphysicalNumbersAreRefusedWithTheirLine) {
  // urdfdom silently dropped these (a trunk mass of "abc" gave a lighter robot
  // that still jumped) or took them; each is now an error at its line.
  std::ifstream in(std::string(PRONK_SOURCE_DIR) + "/tests/scenario/data/tiny_robot.urdf");
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NO_THROW(parseUrdf(good, "tiny.urdf"));
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"<mass value=\"5\"/>", "<mass value=\"abc\"/>", "<mass>: value=\"abc\" is not a finite number"},
      {"<mass value=\"5\"/>", "<mass value=\"-1\"/>", "<mass>: value must be > 0"},
      {"<mass value=\"5\"/>", "<mass value=\"0\"/>", "<mass>: value must be > 0"},
      {"<mass value=\"5\"/>", "<mass value=\"1e308\"/>", "<mass>: value must be > 0 and at most 1e+06"},
      {"ixx=\"0.01\"", "ixx=\"nan\"", "<inertia>: ixx=\"nan\" is not a finite number"},
      {"ixx=\"0.01\" ixy=\"0\"", "ixx=\"0.01\" ixy=\"0.05\"", "<inertia>: the inertia is not positive definite"},
      {"effort=\"10\"", "effort=\"0\"", "<limit>: effort must be > 0"},
      {"velocity=\"10\"", "velocity=\"-1\"", "<limit>: velocity must be > 0"},
      {"<sphere radius=\"0.02\"/>", "<sphere radius=\"0\"/>", "<sphere>: radius must be > 0"},
      {"<origin xyz=\"0 0 -0.3\"/>", "<origin xyz=\"0 0 0x1p-2\"/>", "<origin>: xyz=\"0x1p-2\" is not a finite number"},
  };
  for (const auto& [from, to, message] : cases) {
    std::string bad = good;
    const size_t at = bad.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    bad.replace(at, from.size(), to);
    try {
      parseUrdf(bad, "tiny.urdf");
      ADD_FAILURE() << to << " was accepted";
    } catch (const InputError& e) {
      EXPECT_GT(e.where().line, 0) << e.what();
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace pronk
