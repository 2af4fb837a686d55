// URDF -> RobotDescription: parse with urdfdom, lump fixed joints, convert
// shapes, resolve mesh URIs. Line numbers come from a tinyxml2 pass over the
// same text, because urdfdom reports none.
#include "pronk/robot_description.h"
#include "pronk/file_io.h"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <Eigen/Eigenvalues>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace pronk {
namespace {

// Collects what urdfdom prints through console_bridge while it parses, so the
// messages can be put into our error instead of stderr.
class CapturedConsole : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) lines.push_back(text);
  }
  std::vector<std::string> lines;
};

std::mutex& urdfdomMutex() {  // console_bridge's handler is process-global
  static std::mutex m;
  return m;
}

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  double x, y, z, w;
  p.rotation.getQuaternion(x, y, z, w);  // urdfdom order: x, y, z, w
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

Eigen::Vector3d toVector(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// Element name -> line, for links and joints, from a tinyxml2 pass.
struct LineIndex {
  std::map<std::string, int> link_line, joint_line;
  int robot_line = 1;
};

LineIndex indexLines(const tinyxml2::XMLDocument& doc) {
  LineIndex index;
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (!robot) return index;
  index.robot_line = robot->GetLineNum();
  for (auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const char* name = e->Attribute("name");
    if (!name) continue;
    if (std::string(e->Name()) == "link") index.link_line[name] = e->GetLineNum();
    if (std::string(e->Name()) == "joint") index.joint_line[name] = e->GetLineNum();
  }
  return index;
}

std::string formatValue(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// The URDF's numbers checked before urdfdom reads them: urdfdom drops what it
// cannot parse (a mass of "abc" became no mass at all) and takes unphysical
// values. Every number must be finite; masses, limits and shape sizes
// positive; an inertia positive definite. Errors name the line.
void checkUrdfNumbers(const tinyxml2::XMLElement& robot, const std::string& origin) {
  auto fail = [&](const tinyxml2::XMLElement& e, const std::string& what) {
    throw InputError({origin, e.GetLineNum()}, "<" + std::string(e.Name()) + ">: " + what);
  };
  auto number = [&](const tinyxml2::XMLElement& e, const char* name, const char* text) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text, &end);
    while (end && (*end == ' ' || *end == '\t')) ++end;
    const bool hexadecimal = std::strpbrk(text, "xX") != nullptr;  // strtod reads them, URDF does not
    if (end == text || (end && *end) || errno == ERANGE || !std::isfinite(v) || hexadecimal) {
      fail(e, std::string(name) + "=\"" + text + "\" is not a finite number");
    }
    return v;
  };
  auto numbers = [&](const tinyxml2::XMLElement& e, const char* name) {
    std::vector<double> out;
    const char* text = e.Attribute(name);
    if (!text) return out;
    std::istringstream in(text);
    for (std::string word; in >> word;) out.push_back(number(e, name, word.c_str()));
    return out;
  };
  auto positive = [&](const tinyxml2::XMLElement& e, const char* name, double bound) {
    for (double v : numbers(e, name)) {
      if (!(v > 0) || v > bound) {
        fail(e, std::string(name) + " must be > 0 and at most " + formatValue(bound) + " (got " + formatValue(v) + ")");
      }
    }
  };
  // Every element of the robot, depth first (links, joints and what they hold).
  std::vector<const tinyxml2::XMLElement*> stack = {&robot};
  while (!stack.empty()) {
    const tinyxml2::XMLElement& e = *stack.back();
    stack.pop_back();
    for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
    const std::string tag = e.Name();
    if (tag == "mass") positive(e, "value", 1e6);
    if (tag == "sphere") positive(e, "radius", 1e3);
    if (tag == "cylinder") {
      positive(e, "radius", 1e3);
      positive(e, "length", 1e3);
    }
    if (tag == "box") positive(e, "size", 1e3);
    if (tag == "origin") {
      numbers(e, "xyz");
      numbers(e, "rpy");
    }
    if (tag == "axis") numbers(e, "xyz");
    if (tag == "limit") {
      numbers(e, "lower");
      numbers(e, "upper");
      if (e.Attribute("effort")) positive(e, "effort", 1e6);
      if (e.Attribute("velocity")) positive(e, "velocity", 1e6);
    }
    if (tag == "dynamics") {
      numbers(e, "damping");
      numbers(e, "friction");
    }
    if (tag == "inertia") {
      double v[6];
      const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
      for (int i = 0; i < 6; ++i) {
        const char* text = e.Attribute(names[i]);
        v[i] = text ? number(e, names[i], text) : 0.0;
      }
      Eigen::Matrix3d I;
      I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
      const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
      if (!(eig.minCoeff() > 0)) {
        fail(e, "the inertia is not positive definite (principal moments " + formatValue(eig(0)) + ", " +
                    formatValue(eig(1)) + ", " + formatValue(eig(2)) + " kg m^2)");
      }
    }
  }
}

// urdfdom (3.0) builds some error messages from the file's names and values and
// hands them to console_bridge as a printf format: a '%' there reads arguments
// that are not passed (a malformed rgba holding "%S" crashed it; found by
// fuzzing). No attribute of a URDF may hold one, so urdfdom never sees it.
void checkNoPercentSign(const tinyxml2::XMLElement& robot, const std::string& origin) {
  std::vector<const tinyxml2::XMLElement*> stack = {&robot};
  while (!stack.empty()) {
    const tinyxml2::XMLElement& e = *stack.back();
    stack.pop_back();
    for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
    for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next()) {
      if (std::strchr(a->Value(), '%')) {
        throw InputError({origin, e.GetLineNum()}, "<" + std::string(e.Name()) + ">: " + a->Name() + "=\"" +
                                                       a->Value() + "\" holds a '%', which urdfdom cannot take "
                                                       "(it prints names and values as a printf format)");
      }
    }
  }
}

// The same anywhere in the text, comments too: XML readers may disagree about
// where a comment or a broken declaration ends, and urdfdom read a robot with
// a '%' that tinyxml2 took for part of an unterminated <?xml ...?> (found by
// fuzzing). Only a ban of every '%' holds whatever urdfdom's reader makes of it.
void checkNoPercentInText(const std::string& xml, const std::string& origin) {
  const size_t at = xml.find('%');
  if (at == std::string::npos) return;
  const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  throw InputError({origin, line}, "a '%' outside any attribute (in a comment or broken markup), which pronk refuses "
                                   "anywhere: urdfdom prints parts of the file as a printf format, and XML readers "
                                   "may disagree about where a comment ends");
}

// Mass properties of `add`, whose frame sits at `pose` in the body, merged into `into`.
void lumpMass(MassProperties& into, const MassProperties& add, const Eigen::Isometry3d& pose) {
  if (add.mass <= 0) return;
  const Eigen::Vector3d com_add = pose * add.com_body;
  const Eigen::Matrix3d inertia_add = pose.linear() * add.inertia_com * pose.linear().transpose();
  const double mass = into.mass + add.mass;
  const Eigen::Vector3d com = (into.mass * into.com_body + add.mass * com_add) / mass;
  // Parallel-axis shift of each part's central inertia to the common centre.
  auto shift = [](double m, const Eigen::Vector3d& d) {
    return Eigen::Matrix3d(m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  into.inertia_com = into.inertia_com + shift(into.mass, into.com_body - com) + inertia_add +
                     shift(add.mass, com_add - com);
  into.mass = mass;
  into.com_body = com;
}

MassProperties massOf(const urdf::Link& link) {
  MassProperties m;
  if (!link.inertial) return m;
  const urdf::Inertial& in = *link.inertial;
  m.mass = in.mass;
  const Eigen::Isometry3d frame = toIsometry(in.origin);
  m.com_body = frame.translation();
  Eigen::Matrix3d inertia;
  inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  // URDF inertia is about the COM in the <inertial><origin> axes; re-express in link axes.
  m.inertia_com = frame.linear() * inertia * frame.linear().transpose();
  return m;
}

class Builder {
 public:
  Builder(const std::string& origin, const UrdfOptions& options, const LineIndex& lines)
      : origin_(origin), options_(options), lines_(lines) {
    base_dir_ = fs::path(origin).parent_path();
  }

  RobotDescription build(const urdf::ModelInterface& model) {
    RobotDescription robot;
    robot.name = model.getName();
    robot.urdf_path = origin_;
    urdf::LinkConstSharedPtr root = model.getRoot();
    if (!root) fail(lines_.robot_line, "the robot has no root link");

    Body body;
    body.name = root->name;
    robot.bodies.push_back(body);
    addLink(robot, 0, *root, Eigen::Isometry3d::Identity());
    for (const Body& b : robot.bodies) {
      if (b.mass.mass <= 0) {
        fail(lineOfLink(b.name), "link '" + b.name + "' and the links fixed to it have no mass; " +
                                     "a moving body needs a positive <inertial><mass>");
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(b.mass.inertia_com);
      const Eigen::Vector3d p = eig.eigenvalues();
      const double tol = 1e-12 + 1e-9 * p.cwiseAbs().maxCoeff();
      if (p.minCoeff() < -tol || p(0) + p(1) < p(2) - tol) {
        fail(lineOfLink(b.name), "inertia of link '" + b.name +
                                     "' is not physical (negative or violates the triangle inequality)");
      }
    }
    robot.warnings = warnings_;
    return robot;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw InputError({origin_, line}, message);
  }
  int lineOfLink(const std::string& name) const {
    auto it = lines_.link_line.find(name);
    return it == lines_.link_line.end() ? 0 : it->second;
  }
  int lineOfJoint(const std::string& name) const {
    auto it = lines_.joint_line.find(name);
    return it == lines_.joint_line.end() ? 0 : it->second;
  }

  // Adds `link` (at `pose` in body `body_index`) and, recursively, its children.
  void addLink(RobotDescription& robot, int body_index, const urdf::Link& link,
               const Eigen::Isometry3d& pose) {
    {
      Body& body = robot.bodies[body_index];
      body.link_frames.emplace_back(link.name, pose);
      if (link.name != body.name) body.lumped_links.push_back(link.name);
      lumpMass(body.mass, massOf(link), pose);
      for (const auto& c : link.collision_array) addCollision(body, link, *c, pose);
      for (const auto& v : link.visual_array) addVisual(body, link, *v, pose);
    }
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const urdf::LinkConstSharedPtr child = findChild(link, joint->child_link_name);
      if (!child) fail(lineOfJoint(joint->name), "child link '" + joint->child_link_name + "' not found");
      const Eigen::Isometry3d joint_pose = pose * toIsometry(joint->parent_to_joint_origin_transform);
      switch (joint->type) {
        case urdf::Joint::FIXED:
          addLink(robot, body_index, *child, joint_pose);
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC: {
          Joint j;
          j.name = joint->name;
          j.type = joint->type == urdf::Joint::REVOLUTE     ? JointType::Revolute
                   : joint->type == urdf::Joint::CONTINUOUS ? JointType::Continuous
                                                            : JointType::Prismatic;
          j.parent_body = body_index;
          j.pose_in_parent = joint_pose;
          j.axis = toVector(joint->axis);
          if (j.axis.norm() < 1e-9) fail(lineOfJoint(j.name), "joint '" + j.name + "' has a zero axis");
          j.axis.normalize();
          if (joint->limits) {
            j.velocity_limit = joint->limits->velocity;
            j.effort_limit = joint->limits->effort;
            if (j.type != JointType::Continuous) {
              j.has_position_limits = true;
              j.lower = joint->limits->lower;
              j.upper = joint->limits->upper;
              if (j.lower > j.upper) {
                fail(lineOfJoint(j.name), "joint '" + j.name + "' has lower limit above upper limit");
              }
            }
          }
          if (joint->dynamics) {
            j.damping = joint->dynamics->damping;
            j.friction = joint->dynamics->friction;
            if (j.friction > 0) {
              warnings_.push_back(origin_ + ":" + std::to_string(lineOfJoint(j.name)) + ": joint '" + j.name +
                                  "' has friction " + std::to_string(j.friction) +
                                  "; Coulomb joint friction is not modelled (damping is)");
            }
          }
          Body body;
          body.name = child->name;
          body.parent = body_index;
          body.joint = static_cast<int>(robot.joints.size());
          j.child_body = static_cast<int>(robot.bodies.size());
          robot.joints.push_back(j);
          robot.bodies.push_back(body);
          addLink(robot, j.child_body, *child, Eigen::Isometry3d::Identity());
          break;
        }
        case urdf::Joint::FLOATING:
        case urdf::Joint::PLANAR:
        default:
          fail(lineOfJoint(joint->name), "joint '" + joint->name +
                                             "' is floating or planar; only revolute, continuous, "
                                             "prismatic and fixed joints are supported");
      }
    }
  }

  static urdf::LinkConstSharedPtr findChild(const urdf::Link& link, const std::string& name) {
    for (const auto& c : link.child_links) {
      if (c->name == name) return c;
    }
    return nullptr;
  }

  std::optional<Shape> primitive(const urdf::Geometry& g, const Eigen::Isometry3d& pose) const {
    Shape s;
    s.pose_body = pose;
    switch (g.type) {
      case urdf::Geometry::SPHERE:
        s.type = ShapeType::Sphere;
        s.radius = static_cast<const urdf::Sphere&>(g).radius;
        return s;
      case urdf::Geometry::BOX:
        s.type = ShapeType::Box;
        s.box_size = toVector(static_cast<const urdf::Box&>(g).dim);
        return s;
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(g);
        s.type = ShapeType::Cylinder;
        s.radius = c.radius;
        s.length = c.length;
        return s;
      }
      default:
        return std::nullopt;
    }
  }

  // Resolves package://, file:// and relative URIs; nullopt when not found.
  std::optional<std::string> resolveUri(const std::string& uri) const {
    const std::string package_prefix = "package://";
    const std::string file_prefix = "file://";
    std::vector<fs::path> candidates;
    if (uri.rfind(package_prefix, 0) == 0) {
      const std::string rest = uri.substr(package_prefix.size());
      const auto slash = rest.find('/');
      const std::string package = rest.substr(0, slash);
      const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
      std::vector<fs::path> roots(options_.package_paths.begin(), options_.package_paths.end());
      // A URDF inside <pkg>/urdf/ finds its own package without configuration.
      roots.push_back(base_dir_.parent_path().parent_path());
      for (const fs::path& root : roots) {
        candidates.push_back(root / package / inside);
        if (root.filename() == package) candidates.push_back(root / inside);
      }
    } else if (uri.rfind(file_prefix, 0) == 0) {
      candidates.push_back(uri.substr(file_prefix.size()));
    } else {
      fs::path p(uri);
      candidates.push_back(p.is_absolute() ? p : base_dir_ / p);
    }
    for (const fs::path& c : candidates) {
      std::error_code ec;
      if (fs::is_regular_file(c, ec)) return fs::weakly_canonical(c).string();
    }
    return std::nullopt;
  }

  // Axis-aligned bounds of a mesh file in its own frame (after scale), via assimp.
  std::optional<Shape> meshBoundingBox(const std::string& path, const Eigen::Vector3d& scale,
                                       const Eigen::Isometry3d& pose) const {
    Assimp::Importer importer;
    // The URDF places the mesh in its own file frame: a COLLADA <up_axis> must not rotate it
    // (the vendors' Z_UP files would otherwise lie on their side).
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (!scene) return std::nullopt;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e30), hi = Eigen::Vector3d::Constant(-1e30);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[m];
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const Eigen::Vector3d p(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
        lo = lo.cwiseMin(p.cwiseProduct(scale));
        hi = hi.cwiseMax(p.cwiseProduct(scale));
      }
    }
    if (lo.x() > hi.x()) return std::nullopt;
    Shape s;
    s.type = ShapeType::Box;
    s.box_size = (hi - lo).cwiseAbs();
    s.pose_body = pose * Eigen::Translation3d(0.5 * (lo + hi));
    return s;
  }

  void addCollision(Body& body, const urdf::Link& link, const urdf::Collision& c,
                    const Eigen::Isometry3d& link_pose) {
    if (!c.geometry) return;
    const Eigen::Isometry3d pose = link_pose * toIsometry(c.origin);
    if (auto s = primitive(*c.geometry, pose)) {
      body.collisions.push_back({*s, link.name, false});
      return;
    }
    const auto& mesh = static_cast<const urdf::Mesh&>(*c.geometry);
    const auto path = resolveUri(mesh.filename);
    std::optional<Shape> box;
    if (path) box = meshBoundingBox(*path, toVector(mesh.scale), pose);
    if (!box) {
      warnings_.push_back(origin_ + ":" + std::to_string(lineOfLink(link.name)) + ": collision mesh '" +
                          mesh.filename + "' of link '" + link.name +
                          "' could not be read; the link has no collision shape from it");
      return;
    }
    body.collisions.push_back({*box, link.name, true});
  }

  void addVisual(Body& body, const urdf::Link& link, const urdf::Visual& v,
                 const Eigen::Isometry3d& link_pose) {
    if (!v.geometry) return;
    VisualShape visual;
    visual.link = link.name;
    visual.pose_body = link_pose * toIsometry(v.origin);
    if (v.material) {
      const urdf::Color& c = v.material->color;
      visual.rgba = Eigen::Vector4d(c.r, c.g, c.b, c.a);
    }
    if (auto s = primitive(*v.geometry, Eigen::Isometry3d::Identity())) {
      visual.primitive = s;
    } else {
      const auto& mesh = static_cast<const urdf::Mesh&>(*v.geometry);
      visual.mesh_uri = mesh.filename;
      visual.mesh_scale = toVector(mesh.scale);
      visual.mesh_path = resolveUri(mesh.filename);
      if (!visual.mesh_path) {
        // Fall back to the link's first collision primitive, else a small box.
        Shape fallback;
        fallback.type = ShapeType::Box;
        fallback.box_size = Eigen::Vector3d::Constant(0.05);
        for (const auto& c : link.collision_array) {
          if (!c->geometry) continue;
          if (auto s = primitive(*c->geometry, toIsometry(v.origin).inverse() * toIsometry(c->origin))) {
            fallback = *s;
            break;
          }
        }
        visual.primitive = fallback;
        warnings_.push_back(origin_ + ":" + std::to_string(lineOfLink(link.name)) + ": visual mesh '" +
                            mesh.filename + "' of link '" + link.name +
                            "' not found; drawing a primitive instead");
      }
    }
    body.visuals.push_back(visual);
  }

  std::string origin_;
  fs::path base_dir_;
  const UrdfOptions& options_;
  const LineIndex& lines_;
  std::vector<std::string> warnings_;
};

// urdfdom parses with TinyXML 1, which can read a file otherwise than tinyxml2
// does: a declared legacy encoding turns "&#x161;" into "a", a broken
// declaration hides markup from one reader only. A loop that only urdfdom saw
// overflowed the stack (found by fuzzing). So urdfdom reads tinyxml2's printout
// of the <robot> element that pronk checked: elements, attributes and text,
// without declaration, comments or unknown nodes, and with only the five named
// entities, which both readers decode alike. With no declaration TinyXML 1
// keeps every other byte as it is.
class CheckedTreePrinter : public tinyxml2::XMLPrinter {
 public:
  CheckedTreePrinter() : tinyxml2::XMLPrinter(nullptr, /*compact=*/true) {}
  bool Visit(const tinyxml2::XMLDeclaration&) override { return true; }
  bool Visit(const tinyxml2::XMLComment&) override { return true; }
  bool Visit(const tinyxml2::XMLUnknown&) override { return true; }
};

std::string checkedTreeText(const tinyxml2::XMLElement& robot) {
  CheckedTreePrinter printer;
  robot.Accept(&printer);
  return std::string(printer.CStr(), static_cast<size_t>(printer.CStrSize() - 1));
}

// The line a urdfdom message points at, when it names a link or joint in brackets.
int lineForMessage(const std::string& message, const LineIndex& lines) {
  static const std::regex bracketed(R"(\[([^\]]+)\])");
  for (auto it = std::sregex_iterator(message.begin(), message.end(), bracketed);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    if (auto j = lines.joint_line.find(name); j != lines.joint_line.end()) return j->second;
    if (auto l = lines.link_line.find(name); l != lines.link_line.end()) return l->second;
  }
  return 0;
}

}  // namespace

int RobotDescription::findBody(const std::string& name) const {
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int RobotDescription::findJoint(const std::string& name) const {
  for (size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::optional<std::pair<int, Eigen::Isometry3d>> RobotDescription::locateLink(const std::string& link) const {
  for (size_t i = 0; i < bodies.size(); ++i) {
    for (const auto& [name, pose] : bodies[i].link_frames) {
      if (name == link) return std::make_pair(static_cast<int>(i), pose);
    }
  }
  return std::nullopt;
}

double RobotDescription::totalMass() const {
  double m = 0;
  for (const Body& b : bodies) m += b.mass.mass;
  return m;
}

RobotDescription parseUrdf(const std::string& xml, const std::string& origin, const UrdfOptions& options) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError({origin, doc.ErrorLineNum()}, std::string("XML error: ") + doc.ErrorStr());
  }
  if (!doc.FirstChildElement("robot")) throw InputError({origin, 1}, "the root element is not <robot>");
  const LineIndex lines = indexLines(doc);
  checkUrdfNumbers(*doc.FirstChildElement("robot"), origin);
  checkNoPercentSign(*doc.FirstChildElement("robot"), origin);
  checkNoPercentInText(xml, origin);
  // A URDF is a tree: a link that is the child of two joints closes a loop,
  // which urdfdom accepts and the recursive build would follow forever.
  struct Inboard {
    std::string joint, parent;  // the joint that has the link as its child, and its parent link
    int line = 0;
  };
  std::map<std::string, Inboard> inboard;  // child link -> its joint
  for (const tinyxml2::XMLElement* j = doc.FirstChildElement("robot")->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    const tinyxml2::XMLElement* child = j->FirstChildElement("child");
    const tinyxml2::XMLElement* parent = j->FirstChildElement("parent");
    const char* link = child ? child->Attribute("link") : nullptr;
    const char* parent_link = parent ? parent->Attribute("link") : nullptr;
    const char* name = j->Attribute("name");
    if (!link || !parent_link) continue;  // urdfdom reports it
    const auto [it, fresh] = inboard.emplace(link, Inboard{name ? name : "", parent_link, j->GetLineNum()});
    if (!fresh) {
      throw InputError({origin, j->GetLineNum()}, "link '" + std::string(link) + "' is the child of joints '" +
                                                      it->second.joint + "' and '" + (name ? name : "") +
                                                      "': a URDF is a tree (kinematic loops are not supported)");
    }
  }
  // A loop with no second parent: a link jointed to itself, or links that are
  // each other's ancestors apart from the root's tree. urdfdom accepts it when
  // the rest has one root; its links were left out of the robot without a word
  // (and urdfdom's shared pointers around the loop never freed: found by fuzzing).
  std::map<std::string, bool> settled;  // link -> false while on the current walk up, true once it reached a root
  for (const auto& start : inboard) {
    std::vector<std::string> walk;
    std::string link = start.first;
    for (;;) {
      const auto seen = settled.find(link);
      if (seen != settled.end()) {
        if (seen->second) break;
        std::string loop = "'" + link + "'";
        for (std::string l = inboard.at(link).parent; ; l = inboard.at(l).parent) {
          loop += " <- '" + l + "'";
          if (l == link) break;
        }
        const Inboard& j = inboard.at(link);
        throw InputError({origin, j.line}, "joint '" + j.joint + "' closes a kinematic loop (child <- parent: " + loop +
                                               "): a URDF is a tree (kinematic loops are not supported)");
      }
      settled.emplace(link, false);
      walk.push_back(link);
      const auto up = inboard.find(link);
      if (up == inboard.end()) break;  // a root
      link = up->second.parent;
    }
    for (const std::string& l : walk) settled[l] = true;
  }

  urdf::ModelInterfaceSharedPtr model;
  CapturedConsole console;
  {
    std::lock_guard<std::mutex> lock(urdfdomMutex());
    console_bridge::useOutputHandler(&console);
    try {
      model = urdf::parseURDF(checkedTreeText(*doc.FirstChildElement("robot")));
    } catch (const std::exception& e) {
      console.lines.push_back(e.what());
    }
    console_bridge::restorePreviousOutputHandler();
  }
  if (!model) {
    std::string message = console.lines.empty() ? "urdfdom could not parse the file" : console.lines.back();
    for (const std::string& l : console.lines) {
      if (l.find("[") != std::string::npos && lineForMessage(l, lines) > 0) {
        message = l;
        break;
      }
    }
    throw InputError({origin, lineForMessage(message, lines)}, "invalid URDF: " + message);
  }
  return Builder(origin, options, lines).build(*model);
}

RobotDescription loadUrdf(const std::string& path, const UrdfOptions& options) {
  const std::string text = readInputFile(path, "URDF file");
  std::error_code ec;
  const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
  return parseUrdf(text, ec ? path : absolute, options);
}

}  // namespace pronk
