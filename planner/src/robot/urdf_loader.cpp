// URDF -> RobotModel. Three passes, because urdfdom alone is too lenient for us (it drops a
// <collision> it cannot parse and still returns the model, accepts negative sizes and zero axes,
// and reports problems only on the console):
//   1. a tinyxml pass: syntax, joint types, names and the tree structure, with line numbers;
//   2. urdfdom, with its console messages captured: any error it reports fails the load;
//   3. conversion with numeric checks (finite, positive sizes, limits, mimic references) and
//      mesh URI resolution.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "internal/robot_model_builder.h"
#include "internal/xml_text.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/robot/package_locator.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

struct XmlLink {
  std::string name;
  int line = 0;
  std::vector<int> collision_lines;
};

struct XmlJoint {
  std::string name;
  std::string type;
  std::string parent;
  std::string child;
  int line = 0;
};

// What pass 1 learns: links and joints in file order, and the depth-first layout.
struct XmlRobot {
  std::string name;
  std::vector<XmlLink> links;
  std::vector<XmlJoint> joints;
  std::vector<int> link_order;   // XmlLink indices, depth-first from the root
  std::vector<int> joint_order;  // XmlJoint indices; joint_order[k] is the parent of link k + 1
};

class Loader {
 public:
  Loader(std::string source, std::string base_dir, const RobotModelOptions& options)
      : source_(std::move(source)),
        base_dir_(std::move(base_dir)),
        options_(options),
        locator_(options.package_paths, options.use_environment_package_paths) {}

  RobotModel load(const std::string& xml) {
    scanXml(xml);
    urdf::ModelInterfaceSharedPtr urdf_model = parseWithUrdfdom(xml);
    return convert(*urdf_model);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw FileError(source_, what); }

  static std::string at(int line) { return " (line " + std::to_string(line) + ")"; }

  // --- Pass 1 ---
  void scanXml(const std::string& xml) {
    detail::requireXmlText(xml, source_);
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    if (doc.Error()) {
      fail("XML syntax error at line " + std::to_string(doc.ErrorRow()) + ", column " +
           std::to_string(doc.ErrorCol()) + ": " + doc.ErrorDesc());
    }
    const TiXmlElement* robot = doc.RootElement();
    if (robot == nullptr) fail("no XML element: not a URDF file");
    if (std::string(robot->Value()) != "robot") {
      fail(std::string("root element is <") + robot->Value() + ">, expected <robot>");
    }
    if (const char* name = robot->Attribute("name")) xml_.name = name;
    // An unexpanded xacro file parses as XML but its links hide in macros: say so.
    for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr;
         e = e->NextSiblingElement()) {
      if (std::string(e->Value()).compare(0, 6, "xacro:") == 0) {
        fail("<" + std::string(e->Value()) + ">" + at(e->Row()) +
             ": this is a xacro file; expand it first (xacro robot.urdf.xacro > robot.urdf)");
      }
    }
    std::map<std::string, int> link_index;
    for (const TiXmlElement* e = robot->FirstChildElement("link"); e != nullptr;
         e = e->NextSiblingElement("link")) {
      XmlLink link;
      link.line = e->Row();
      const char* name = e->Attribute("name");
      if (name == nullptr || *name == '\0') fail("<link>" + at(link.line) + " has no name");
      link.name = name;
      if (!link_index.emplace(link.name, static_cast<int>(xml_.links.size())).second) {
        fail("link '" + link.name + "'" + at(link.line) + " is defined twice");
      }
      for (const TiXmlElement* c = e->FirstChildElement("collision"); c != nullptr;
           c = c->NextSiblingElement("collision")) {
        link.collision_lines.push_back(c->Row());
      }
      xml_.links.push_back(std::move(link));
    }
    if (xml_.links.empty()) fail("the robot has no <link>");
    // Checked before urdfdom and the links x links collision filter allocate anything.
    if (xml_.links.size() > static_cast<std::size_t>(kMaxRobotLinks)) {
      fail("the robot has " + std::to_string(xml_.links.size()) +
           " links, more than the limit of " + std::to_string(kMaxRobotLinks) +
           " (docs/robustness.md, input limits)");
    }

    std::set<std::string> joint_names;
    std::vector<int> parent_joint(xml_.links.size(), -1);
    for (const TiXmlElement* e = robot->FirstChildElement("joint"); e != nullptr;
         e = e->NextSiblingElement("joint")) {
      XmlJoint joint;
      joint.line = e->Row();
      const char* name = e->Attribute("name");
      if (name == nullptr || *name == '\0') fail("<joint>" + at(joint.line) + " has no name");
      joint.name = name;
      const std::string where = "joint '" + joint.name + "'" + at(joint.line);
      if (!joint_names.insert(joint.name).second) fail(where + " is defined twice");
      const char* type = e->Attribute("type");
      if (type == nullptr) fail(where + " has no type");
      joint.type = type;
      if (joint.type == "floating" || joint.type == "planar") {
        fail(where + " is " + joint.type +
             ": floating and planar joints are not supported (load the robot with "
             "RobotModelOptions::base = BaseMotion::kFreeFlying for a free-flying base)");
      }
      if (joint.type != "revolute" && joint.type != "continuous" && joint.type != "prismatic" &&
          joint.type != "fixed") {
        fail(where + " has unknown type '" + joint.type +
             "' (expected revolute, continuous, prismatic or fixed)");
      }
      for (const char* role : {"parent", "child"}) {
        const TiXmlElement* r = e->FirstChildElement(role);
        const char* link = r != nullptr ? r->Attribute("link") : nullptr;
        if (link == nullptr) fail(where + " has no <" + role + " link=\"...\"/>");
        if (link_index.count(link) == 0) {
          fail(where + ": " + role + " link '" + link + "' is not defined");
        }
        (std::string(role) == "parent" ? joint.parent : joint.child) = link;
      }
      const int child = link_index.at(joint.child);
      if (parent_joint[static_cast<std::size_t>(child)] >= 0) {
        const XmlJoint& other =
            xml_.joints[static_cast<std::size_t>(parent_joint[static_cast<std::size_t>(child)])];
        fail("link '" + joint.child + "' is the child of both joint '" + other.name + "'" +
             at(other.line) + " and " + where + ": a URDF must be a tree");
      }
      parent_joint[static_cast<std::size_t>(child)] = static_cast<int>(xml_.joints.size());
      xml_.joints.push_back(std::move(joint));
    }

    std::vector<int> roots;
    for (std::size_t i = 0; i < xml_.links.size(); ++i) {
      if (parent_joint[i] < 0) roots.push_back(static_cast<int>(i));
    }
    if (roots.size() > 1) {
      std::string names;
      for (int r : roots) {
        names += (names.empty() ? "'" : ", '") + xml_.links[static_cast<std::size_t>(r)].name + "'";
      }
      fail("several root links (" + names + "): a URDF must be one tree connected by joints");
    }
    if (roots.empty()) {
      const XmlJoint& j = xml_.joints.front();
      fail("the joints form a kinematic cycle (no link is without a parent), e.g. through joint '" +
           j.name + "'" + at(j.line));
    }

    // Depth-first from the root, children in file order; explicit stack (deep chains are legal).
    std::vector<std::vector<int>> child_joints(xml_.links.size());
    for (std::size_t j = 0; j < xml_.joints.size(); ++j) {
      child_joints[static_cast<std::size_t>(link_index.at(xml_.joints[j].parent))].push_back(
          static_cast<int>(j));
    }
    std::vector<bool> visited(xml_.links.size(), false);
    std::vector<int> stack{-1};  // joint indices; -1 stands for "the root link"
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      const int link =
          j < 0 ? roots.front() : link_index.at(xml_.joints[static_cast<std::size_t>(j)].child);
      visited[static_cast<std::size_t>(link)] = true;
      xml_.link_order.push_back(link);
      if (j >= 0) xml_.joint_order.push_back(j);
      const auto& children = child_joints[static_cast<std::size_t>(link)];
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
    }
    for (std::size_t i = 0; i < xml_.links.size(); ++i) {
      if (visited[i]) continue;
      const XmlJoint& j = xml_.joints[static_cast<std::size_t>(parent_joint[i])];
      fail("joint '" + j.name + "'" + at(j.line) + " closes a kinematic cycle (link '" +
           xml_.links[i].name + "' is not reachable from the root link '" +
           xml_.links[static_cast<std::size_t>(roots.front())].name + "')");
    }
  }

  // --- Pass 2 ---
  class CapturingHandler : public console_bridge::OutputHandler {
   public:
    void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
             int /*line*/) override {
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
        errors.push_back(text);
      } else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
        warnings.push_back(text);
      }
    }
    std::vector<std::string> errors;
    std::vector<std::string> warnings;
  };

  urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& xml) {
    // console_bridge's handler is process-global: serialize our parses and restore it after.
    static std::mutex console_mutex;
    CapturingHandler handler;
    urdf::ModelInterfaceSharedPtr model;
    std::string exception_text;
    {
      std::lock_guard<std::mutex> lock(console_mutex);
      console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
      const console_bridge::LogLevel previous_level = console_bridge::getLogLevel();
      console_bridge::useOutputHandler(&handler);
      console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
      try {
        model = urdf::parseURDF(xml);
      } catch (const std::exception& e) {
        exception_text = e.what();
      }
      console_bridge::useOutputHandler(previous);
      console_bridge::setLogLevel(previous_level);
    }
    if (!exception_text.empty()) handler.errors.push_back(exception_text);
    if (!handler.errors.empty() || !model) {
      std::string all;
      for (const std::string& e : handler.errors) all += (all.empty() ? "" : "; ") + e;
      fail("urdfdom rejected the file: " + (all.empty() ? std::string("unknown error") : all));
    }
    // urdfdom repeats some warnings (once per parse attempt of the same element).
    std::set<std::string> seen;
    for (const std::string& w : handler.warnings) {
      if (seen.insert(w).second) warn(options_.warnings, source_ + ": " + w);
    }
    return model;
  }

  // --- Pass 3 ---
  static Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    const auto q = scaledUnitVector(
        Eigen::Vector4d(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z));
    // checkPose refused a non-finite or degenerate rotation before.
    if (q) X.linear() = Eigen::Quaterniond((*q)[0], (*q)[1], (*q)[2], (*q)[3]).toRotationMatrix();
    return X;
  }

  void checkPose(const urdf::Pose& pose, const std::string& where) const {
    const double values[] = {pose.position.x, pose.position.y, pose.position.z, pose.rotation.x,
                             pose.rotation.y, pose.rotation.z, pose.rotation.w};
    for (double v : values) {
      if (!std::isfinite(v)) fail(where + ": <origin> is not finite");
    }
    const double norm2 = pose.rotation.x * pose.rotation.x + pose.rotation.y * pose.rotation.y +
                         pose.rotation.z * pose.rotation.z + pose.rotation.w * pose.rotation.w;
    if (!(norm2 > 0.5)) fail(where + ": <origin> rotation is degenerate");
  }

  static std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  static std::string vec(const urdf::Vector3& v) {
    std::ostringstream s;
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
  }

  CollisionElement convertCollision(const urdf::Collision& collision, const std::string& where) {
    CollisionElement element;
    element.name = collision.name;
    checkPose(collision.origin, where);
    element.X_LE = toIsometry(collision.origin);
    if (!collision.geometry) fail(where + " has no <geometry>");
    const urdf::Geometry& geometry = *collision.geometry;
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(geometry);
        if (!positive(box.dim.x) || !positive(box.dim.y) || !positive(box.dim.z)) {
          fail(where + ": <box size=\"" + vec(box.dim) + "\"> must be three positive sizes");
        }
        // URDF gives full extents.
        element.geometry = Primitive(Box{0.5 * Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z)});
        break;
      }
      case urdf::Geometry::SPHERE: {
        const auto& sphere = static_cast<const urdf::Sphere&>(geometry);
        if (!positive(sphere.radius)) {
          fail(where + ": <sphere radius=\"" + num(sphere.radius) + "\"> must be positive");
        }
        element.geometry = Primitive(Sphere{sphere.radius});
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        if (!positive(cylinder.radius) || !positive(cylinder.length)) {
          fail(where + ": <cylinder radius=\"" + num(cylinder.radius) + "\" length=\"" +
               num(cylinder.length) + "\"> must be positive");
        }
        element.geometry = Primitive(Cylinder{cylinder.radius, cylinder.length});
        break;
      }
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        if (!scale.allFinite() || (scale.array() == 0.0).any()) {
          fail(where + ": <mesh scale=\"" + vec(mesh.scale) + "\"> must be finite and non-zero");
        }
        std::string path;
        try {
          path = locator_.resolve(mesh.filename, base_dir_);
        } catch (const Error& e) {
          fail(where + ": mesh '" + mesh.filename + "': " + e.what());
        }
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) {
          fail(where + ": mesh '" + mesh.filename + "' resolves to '" + path +
               "', which does not exist");
        }
        element.geometry = MeshRef{path, scale};
        break;
      }
      default:
        fail(where + " has an unsupported geometry type");
    }
    return element;
  }

  Joint convertJoint(const urdf::Joint& uj, const XmlJoint& xj,
                     const std::map<std::string, int>& link_of) const {
    const std::string where = "joint '" + xj.name + "'" + at(xj.line);
    Joint joint;
    joint.name = uj.name;
    joint.parent_link = link_of.at(uj.parent_link_name);
    joint.child_link = link_of.at(uj.child_link_name);
    checkPose(uj.parent_to_joint_origin_transform, where);
    joint.X_PJ = toIsometry(uj.parent_to_joint_origin_transform);
    switch (uj.type) {
      case urdf::Joint::REVOLUTE:
        joint.type = JointType::kRevolute;
        break;
      case urdf::Joint::CONTINUOUS:
        joint.type = JointType::kContinuous;
        break;
      case urdf::Joint::PRISMATIC:
        joint.type = JointType::kPrismatic;
        break;
      case urdf::Joint::FIXED:
        joint.type = JointType::kFixed;
        break;
      default:
        fail(where + " has an unsupported type");
    }
    if (joint.movable()) {
      const auto axis = scaledUnitVector(Eigen::Vector3d(uj.axis.x, uj.axis.y, uj.axis.z));
      if (!axis) {
        fail(where + ": <axis xyz=\"" + vec(uj.axis) + "\"> must be a finite non-zero vector");
      }
      joint.axis = *axis;
    }
    if (uj.limits) {
      joint.max_velocity = uj.limits->velocity;
      joint.max_effort = uj.limits->effort;
    }
    if (joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic) {
      if (!uj.limits) fail(where + " is " + toString(joint.type) + " but has no <limit>");
      joint.lower = uj.limits->lower;
      joint.upper = uj.limits->upper;
      if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) || joint.lower > joint.upper) {
        fail(where + ": <limit lower=\"" + num(joint.lower) + "\" upper=\"" + num(joint.upper) +
             "\"> must be finite with lower <= upper");
      }
    }
    return joint;
  }

  // Points every mimic joint at its ultimate non-mimic master with the composed affine map.
  void resolveMimics(const urdf::ModelInterface& model, std::vector<Joint>& joints) const {
    std::map<std::string, int> joint_of;
    for (std::size_t j = 0; j < joints.size(); ++j) joint_of[joints[j].name] = static_cast<int>(j);
    std::map<std::string, int> line_of;
    for (const XmlJoint& xj : xml_.joints) line_of[xj.name] = xj.line;
    for (Joint& joint : joints) {
      const urdf::JointConstSharedPtr uj = model.getJoint(joint.name);
      if (!uj->mimic) continue;
      const std::string where = "joint '" + joint.name + "'" + at(line_of.at(joint.name));
      if (!joint.movable()) fail(where + " is fixed and cannot <mimic> another joint");
      double multiplier = 1.0;
      double offset = 0.0;
      std::string current = joint.name;
      urdf::JointMimicSharedPtr mimic = uj->mimic;
      for (std::size_t hops = 0; mimic; ++hops) {
        if (hops > joints.size()) fail(where + ": its <mimic> references form a cycle");
        if (!std::isfinite(mimic->multiplier) || !std::isfinite(mimic->offset)) {
          fail("joint '" + current + "'" + at(line_of.at(current)) +
               ": <mimic> multiplier and offset must be finite");
        }
        // current = m * next + o, so joint = multiplier * (m * next + o) + offset.
        offset += multiplier * mimic->offset;
        multiplier *= mimic->multiplier;
        // A composition that overflows would give the joint a NaN or infinite value, and its
        // links non-finite poses, at every state.
        if (!std::isfinite(multiplier) || !std::isfinite(offset)) {
          fail(where + ": its <mimic> chain composes to a multiplier of " + num(multiplier) +
               " and an offset of " + num(offset) + " (through joint '" + mimic->joint_name +
               "'), which are not finite");
        }
        auto next = joint_of.find(mimic->joint_name);
        if (next == joint_of.end()) {
          fail("joint '" + current + "'" + at(line_of.at(current)) + ": <mimic joint=\"" +
               mimic->joint_name + "\"> names no joint");
        }
        current = mimic->joint_name;
        const Joint& master = joints[static_cast<std::size_t>(next->second)];
        if (!master.movable()) {
          fail(where + " mimics fixed joint '" + master.name + "'");
        }
        mimic = model.getJoint(current)->mimic;
        if (!mimic) joint.mimic_master = next->second;
      }
      joint.mimic_multiplier = multiplier;
      joint.mimic_offset = offset;
    }
  }

  RobotModel convert(const urdf::ModelInterface& model) {
    std::map<std::string, int> link_of;  // name -> depth-first index
    for (std::size_t k = 0; k < xml_.link_order.size(); ++k) {
      link_of[xml_.links[static_cast<std::size_t>(xml_.link_order[k])].name] = static_cast<int>(k);
    }
    std::vector<Link> links(xml_.link_order.size());
    for (std::size_t k = 0; k < links.size(); ++k) {
      const XmlLink& xl = xml_.links[static_cast<std::size_t>(xml_.link_order[k])];
      Link& link = links[k];
      link.name = xl.name;
      const urdf::LinkConstSharedPtr ul = model.getLink(xl.name);
      if (!ul) fail("link '" + xl.name + "'" + at(xl.line) + " was dropped by urdfdom");
      if (ul->collision_array.size() != xl.collision_lines.size()) {
        fail("link '" + xl.name + "'" + at(xl.line) + ": urdfdom parsed " +
             std::to_string(ul->collision_array.size()) + " of its " +
             std::to_string(xl.collision_lines.size()) + " <collision> elements");
      }
      for (std::size_t c = 0; c < ul->collision_array.size(); ++c) {
        const std::string where = "link '" + xl.name + "' <collision>" + at(xl.collision_lines[c]);
        link.collision.push_back(convertCollision(*ul->collision_array[c], where));
      }
    }
    std::vector<Joint> joints;
    joints.reserve(xml_.joint_order.size());
    for (int j : xml_.joint_order) {
      const XmlJoint& xj = xml_.joints[static_cast<std::size_t>(j)];
      const urdf::JointConstSharedPtr uj = model.getJoint(xj.name);
      if (!uj) fail("joint '" + xj.name + "'" + at(xj.line) + " was dropped by urdfdom");
      joints.push_back(convertJoint(*uj, xj, link_of));
    }
    for (std::size_t j = 0; j < joints.size(); ++j) {
      Link& child = links[static_cast<std::size_t>(joints[j].child_link)];
      child.parent_joint = static_cast<int>(j);
      child.parent_link = joints[j].parent_link;
      links[static_cast<std::size_t>(joints[j].parent_link)].child_joints.push_back(
          static_cast<int>(j));
    }
    resolveMimics(model, joints);
    return RobotModelBuilder::build(xml_.name, source_, options_.base, std::move(links),
                                    std::move(joints));
  }

  std::string source_;
  std::string base_dir_;
  const RobotModelOptions& options_;
  PackageLocator locator_;
  XmlRobot xml_;
};

}  // namespace

RobotModel RobotModel::fromUrdfFile(const std::string& path, const RobotModelOptions& options) {
  const std::string text = readWholeFile(path, "URDF file", kMaxXmlFileBytes);
  std::error_code ec;
  const fs::path absolute = fs::absolute(fs::path(path), ec);
  const fs::path dir = (ec ? fs::path(path) : absolute).parent_path();
  return Loader(path, dir.string(), options).load(text);
}

RobotModel RobotModel::fromUrdfString(const std::string& urdf_xml, const std::string& source_name,
                                      const std::string& base_dir,
                                      const RobotModelOptions& options) {
  return Loader(source_name, base_dir, options).load(urdf_xml);
}

}  // namespace octomotion
