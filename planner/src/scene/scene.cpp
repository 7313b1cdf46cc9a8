#include "octomotion/planner/scene/scene.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "internal/scene_paths.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/scene/moveit_scene.h"

namespace octomotion {

namespace fs = std::filesystem;

namespace {

std::string readFile(const std::string& path) {
  return readWholeFile(path, "scene file", kMaxSceneFileBytes);
}

std::string extensionOf(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Reads YAML fields and reports every problem as "<file>: <field>: <what> (line L)".
class YamlReader {
 public:
  explicit YamlReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& field, const YAML::Node& node,
                         const std::string& what) const {
    std::string where;
    if (node.IsDefined() && node.Mark().line >= 0) {
      where = " (line " + std::to_string(node.Mark().line + 1) + ")";
    }
    throw FileError(path_, field + ": " + what + where);
  }

  double number(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) fail(field, node, "expected a number");
    double v = 0;
    try {
      v = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(field, node, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail(field, node, "must be finite");
    return v;
  }
  double positive(const YAML::Node& node, const std::string& field) const {
    const double v = number(node, field);
    if (!(v > 0)) fail(field, node, "must be > 0");
    return v;
  }
  std::string string(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(field, node, "expected a non-empty string");
    return node.Scalar();
  }
  std::vector<double> numbers(const YAML::Node& node, const std::string& field,
                              std::size_t count = 0) const {
    if (!node.IsSequence()) fail(field, node, "expected a list of numbers");
    if (count && node.size() != count) {
      fail(field, node,
           "expected " + std::to_string(count) + " numbers, got " + std::to_string(node.size()));
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
      out.push_back(number(node[i], field + "[" + std::to_string(i) + "]"));
    }
    return out;
  }
  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& field) const {
    const std::vector<double> v = numbers(node, field, 3);
    return {v[0], v[1], v[2]};
  }
  // Rejects keys this format does not know, and keys given twice (yaml-cpp keeps one of them
  // silently): a typo must not be silently ignored.
  void allowOnly(const YAML::Node& map, const std::string& field,
                 std::initializer_list<const char*> keys) const {
    if (!map.IsMap()) fail(field, map, "expected a mapping");
    std::set<std::string> seen;
    for (const auto& kv : map) {
      const std::string key = kv.first.Scalar();
      if (!seen.insert(key).second) {
        fail(field.empty() ? key : field + "." + key, kv.first,
             "key given twice in the same mapping");
      }
      bool known = false;
      for (const char* k : keys) known = known || key == k;
      if (!known) fail(field.empty() ? key : field + "." + key, kv.first, "unknown key");
    }
  }
  Eigen::Isometry3d pose(const YAML::Node& node, const std::string& field) const {
    allowOnly(node, field, {"xyz", "rpy", "quat", "axis", "theta"});
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (node["xyz"]) X.translation() = vector3(node["xyz"], field + ".xyz");
    const int rotations = (node["rpy"] ? 1 : 0) + (node["quat"] ? 1 : 0) + (node["axis"] ? 1 : 0);
    if (rotations > 1) fail(field, node, "give one of rpy, quat, axis+theta");
    if (node["rpy"]) {
      const Eigen::Vector3d rpy = vector3(node["rpy"], field + ".rpy");
      X.linear() = rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
    } else if (node["quat"]) {
      const std::vector<double> q = numbers(node["quat"], field + ".quat", 4);
      // [qx, qy, qz, qw], normalised (documented in docs/scenes.md).
      const auto unit = scaledUnitVector(Eigen::Vector4d(q[0], q[1], q[2], q[3]));
      if (!unit) fail(field + ".quat", node["quat"], "quaternion has zero length");
      X.linear() =
          Eigen::Quaterniond((*unit)[3], (*unit)[0], (*unit)[1], (*unit)[2]).toRotationMatrix();
    } else if (node["axis"]) {
      const auto axis = scaledUnitVector(vector3(node["axis"], field + ".axis"));
      if (!axis) fail(field + ".axis", node["axis"], "axis has zero length");
      if (!node["theta"]) fail(field, node, "axis needs theta (radians)");
      const double theta = number(node["theta"], field + ".theta");
      X.linear() = Eigen::AngleAxisd(theta, *axis).toRotationMatrix();
    } else if (node["theta"]) {
      fail(field + ".theta", node["theta"], "theta needs axis");
    }
    return X;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

Primitive primitiveFrom(const YamlReader& r, const std::string& kind, const YAML::Node& node,
                        const std::string& field) {
  if (kind == "box") {
    r.allowOnly(node, field, {"size"});
    const Eigen::Vector3d size = r.vector3(node["size"], field + ".size");
    for (int i = 0; i < 3; ++i) {
      if (!(size[i] > 0)) r.fail(field + ".size", node["size"], "sizes must be > 0");
    }
    return Box{size / 2};
  }
  if (kind == "sphere") {
    r.allowOnly(node, field, {"radius"});
    return Sphere{r.positive(node["radius"], field + ".radius")};
  }
  r.allowOnly(node, field, {"radius", "length"});
  return Cylinder{r.positive(node["radius"], field + ".radius"),
                  r.positive(node["length"], field + ".length")};
}

// {joint: value} in file order; allowOnly-style rejection of a key given twice.
std::vector<std::pair<std::string, double>> namedValues(const YamlReader& r, const YAML::Node& node,
                                                        const std::string& field,
                                                        std::string* group_state = nullptr) {
  std::vector<std::pair<std::string, double>> out;
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    const std::string key_field = field + "." + key;
    if (!seen.insert(key).second)
      r.fail(key_field, kv.first, "key given twice in the same mapping");
    if (group_state != nullptr && key == "group_state") {
      *group_state = r.string(kv.second, key_field);
      continue;
    }
    out.emplace_back(key, r.number(kv.second, key_field));
  }
  return out;
}

// A map of pose keys only is a pose; any other map gives joint values by name.
bool isPoseMap(const YAML::Node& node) {
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (key != "xyz" && key != "rpy" && key != "quat" && key != "axis" && key != "theta") {
      return false;
    }
  }
  return node.size() > 0;
}

StateSpec stateFrom(const YamlReader& r, const YAML::Node& node, const std::string& field,
                    bool has_joints) {
  StateSpec s;
  if (node.IsSequence()) {
    s.joints = r.numbers(node, field);
    if (s.joints.empty()) r.fail(field, node, "empty joint vector");
  } else if (node.IsMap() && isPoseMap(node)) {
    s.pose = r.pose(node, field);
  } else if (node.IsMap() && has_joints) {
    s.named = namedValues(r, node, field, &s.group_state);
  } else if (has_joints && node.IsScalar() && !node.Scalar().empty() &&
             !std::isdigit(static_cast<unsigned char>(node.Scalar()[0]))) {
    s.group_state = node.Scalar();
  } else {
    r.fail(field, node,
           "expected a joint vector [q1, q2, ...], joint values {name: value}, an SRDF "
           "group_state name or a pose {xyz, rpy|quat}");
  }
  return s;
}

void parseRobot(const YamlReader& r, const YAML::Node& node, SceneSpec& scene) {
  r.allowOnly(
      node, "robot",
      {"urdf", "srdf", "mesh", "package_path", "keep_root_transform", "center_vertices", "pose"});
  RobotSpec& robot = scene.robot;
  if (node["urdf"]) robot.urdf = resolvePath(r.path(), r.string(node["urdf"], "robot.urdf"));
  if (node["mesh"]) robot.mesh = resolvePath(r.path(), r.string(node["mesh"], "robot.mesh"));
  if (robot.urdf.empty() == robot.mesh.empty()) {
    r.fail("robot", node, "give exactly one of urdf (an arm) or mesh (a rigid body)");
  }
  if (node["srdf"]) robot.srdf = resolvePath(r.path(), r.string(node["srdf"], "robot.srdf"));
  if (const YAML::Node paths = node["package_path"]) {
    if (paths.IsScalar()) {
      robot.package_paths.push_back(resolvePath(r.path(), paths.Scalar()));
    } else if (paths.IsSequence()) {
      for (std::size_t i = 0; i < paths.size(); ++i) {
        robot.package_paths.push_back(resolvePath(
            r.path(), r.string(paths[i], "robot.package_path[" + std::to_string(i) + "]")));
      }
    } else {
      r.fail("robot.package_path", paths, "expected a path or a list of paths");
    }
  }
  robot.keep_mesh_root_transform = !robot.mesh.empty();
  if (node["keep_root_transform"]) {
    robot.keep_mesh_root_transform = node["keep_root_transform"].as<bool>();
  }
  if (node["center_vertices"]) robot.center_mesh_vertices = node["center_vertices"].as<bool>();
  if (node["pose"]) {
    // A rigid body's pose is what the planner varies; a mount would only confuse it.
    if (!robot.mesh.empty()) {
      r.fail("robot.pose", node["pose"], "a free-flying mesh robot has no mount");
    }
    robot.pose = r.pose(node["pose"], "robot.pose");
  }
}

// {moveit_scene: file}: every collision object of a MoveIt PlanningScene (moveit_scene.h).
void expandMoveItScene(const YamlReader& r, const YAML::Node& item, const std::string& field,
                       SceneSpec& scene) {
  r.allowOnly(item, field, {"moveit_scene"});
  const std::string file =
      resolvePath(r.path(), r.string(item["moveit_scene"], field + ".moveit_scene"));
  std::vector<EnvironmentObject> objects;
  try {
    objects = loadMoveItScene(file);
  } catch (const Error& e) {
    // The message names the MoveIt file, its field and line already.
    throw FileError(r.path(), field + ".moveit_scene: " + e.what());
  }
  for (EnvironmentObject& obj : objects) scene.environment.push_back(std::move(obj));
}

void parseEnvironment(const YamlReader& r, const YAML::Node& node, SceneSpec& scene) {
  if (!node.IsSequence()) r.fail("environment", node, "expected a list of objects");
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string field = "environment[" + std::to_string(i) + "]";
    const YAML::Node item = node[i];
    if (item.IsMap() && item["moveit_scene"]) {
      expandMoveItScene(r, item, field, scene);
      continue;
    }
    r.allowOnly(
        item, field,
        {"name", "pose", "frame", "box", "sphere", "cylinder", "mesh", "pointcloud", "octomap"});
    EnvironmentObject obj;
    obj.name = item["name"] ? r.string(item["name"], field + ".name") : field;
    if (item["pose"]) obj.X_WO = r.pose(item["pose"], field + ".pose");
    if (item["frame"]) obj.frame = r.string(item["frame"], field + ".frame");
    int kinds = 0;
    for (const char* kind : {"box", "sphere", "cylinder"}) {
      if (!item[kind]) continue;
      ++kinds;
      obj.kind = EnvironmentObject::Kind::kPrimitive;
      obj.primitive = primitiveFrom(r, kind, item[kind], field + "." + kind);
    }
    if (const YAML::Node mesh = item["mesh"]) {
      ++kinds;
      r.allowOnly(mesh, field + ".mesh", {"file", "scale", "keep_root_transform"});
      obj.kind = EnvironmentObject::Kind::kMesh;
      obj.file = resolvePath(r.path(), r.string(mesh["file"], field + ".mesh.file"));
      if (mesh["scale"]) obj.scale = r.vector3(mesh["scale"], field + ".mesh.scale");
      for (int a = 0; a < 3; ++a) {
        if (obj.scale[a] == 0) r.fail(field + ".mesh.scale", mesh["scale"], "scale of 0");
      }
      if (mesh["keep_root_transform"]) {
        obj.keep_mesh_root_transform = mesh["keep_root_transform"].as<bool>();
      }
    }
    for (const char* kind : {"pointcloud", "octomap"}) {
      if (!item[kind]) continue;
      ++kinds;
      r.allowOnly(item[kind], field + "." + kind, {"file"});
      obj.kind = std::strcmp(kind, "octomap") == 0 ? EnvironmentObject::Kind::kOctomap
                                                   : EnvironmentObject::Kind::kPointCloud;
      obj.file = resolvePath(
          r.path(), r.string(item[kind]["file"], field + "." + std::string(kind) + ".file"));
    }
    if (kinds != 1) {
      r.fail(field, item, "give exactly one of box, sphere, cylinder, mesh, pointcloud, octomap");
    }
    scene.environment.push_back(std::move(obj));
  }
}

void parseOctree(const YamlReader& r, const YAML::Node& node, SceneSpec& scene) {
  r.allowOnly(node, "octree",
              {"resolution", "link_resolution", "self_link_resolution", "self_pair_tables",
               "exact_primitives", "rounding", "checker", "max_surface_voxels", "refine"});
  OctreeSettings& s = scene.octree;
  if (const YAML::Node res = node["resolution"]) {
    if (!(res.IsScalar() && res.Scalar() == "auto")) {
      s.resolution = r.positive(res, "octree.resolution");
    }
  }
  if (node["link_resolution"]) {
    s.link_resolution = r.positive(node["link_resolution"], "octree.link_resolution");
  }
  if (node["self_link_resolution"]) {
    s.self_link_resolution =
        r.positive(node["self_link_resolution"], "octree.self_link_resolution");
  }
  // A true/false switch, named octree.KEY in errors.
  auto flag = [&](const char* key, bool& out) {
    if (!node[key]) return;
    const std::string field = std::string("octree.") + key;
    const std::string v = r.string(node[key], field);
    if (v != "true" && v != "false") r.fail(field, node[key], "expected true or false");
    out = v == "true";
  };
  flag("self_pair_tables", s.self_pair_tables);
  flag("exact_primitives", s.exact_primitives);
  if (node["max_surface_voxels"]) {
    s.max_surface_voxels = r.positive(node["max_surface_voxels"], "octree.max_surface_voxels");
  }
  if (node["rounding"]) {
    const std::string v = r.string(node["rounding"], "octree.rounding");
    try {
      s.rounding = roundingFromString(v.c_str());
    } catch (const InvalidArgument& e) {
      r.fail("octree.rounding", node["rounding"], e.what());
    }
  }
  if (node["refine"]) {
    const std::string v = r.string(node["refine"], "octree.refine");
    try {
      s.refine = parseRefineMode(v);
    } catch (const InvalidArgument& e) {
      r.fail("octree.refine", node["refine"], e.what());
    }
  }
  if (node["checker"]) {
    const std::string v = r.string(node["checker"], "octree.checker");
    try {
      s.checker = parseCheckerKind(v);
    } catch (const InvalidArgument& e) {
      r.fail("octree.checker", node["checker"], e.what());
    }
  }
}

// problem.moveit_request: group, start, goal and time from a MoveIt MotionPlanRequest; the scene's
// own problem.time wins over allowed_planning_time.
void parseMoveItRequestKey(const YamlReader& r, const YAML::Node& node, SceneSpec& scene) {
  const YAML::Node key = node["moveit_request"];
  for (const char* other : {"group", "start", "goal"}) {
    if (node[other]) {
      r.fail(std::string("problem.") + other, node[other],
             "give either problem.moveit_request or problem." + std::string(other) + ", not both");
    }
  }
  ProblemSpec& p = scene.problem;
  p.moveit_request = resolvePath(r.path(), r.string(key, "problem.moveit_request"));
  MoveItRequest request;
  try {
    request = loadMoveItRequest(p.moveit_request);
  } catch (const Error& e) {
    throw FileError(r.path(), std::string("problem.moveit_request: ") + e.what());
  }
  p.group = request.group;
  p.start = request.start;
  p.goal = request.goal;
  if (request.time && !node["time"]) p.time = *request.time;
}

// problem.goal as a link pose: {link, position, orientation [x, y, z, w] | rpy, tolerance}.
bool isLinkPoseGoal(const YAML::Node& node) {
  return node.IsMap() && node["link"];
}

StateSpec linkPoseGoalFrom(const YamlReader& r, const YAML::Node& node, const std::string& field) {
  r.allowOnly(node, field, {"link", "position", "orientation", "rpy", "tolerance"});
  LinkPoseGoalSpec goal;
  goal.link = r.string(node["link"], field + ".link");
  if (!node["position"]) r.fail(field + ".position", node, "missing (the link's [x, y, z])");
  goal.position = r.vector3(node["position"], field + ".position");
  if (node["orientation"] && node["rpy"]) {
    r.fail(field, node, "give one of orientation [x, y, z, w] or rpy [roll, pitch, yaw]");
  }
  if (node["orientation"]) {
    const std::vector<double> q = r.numbers(node["orientation"], field + ".orientation", 4);
    const auto unit = scaledUnitVector(Eigen::Vector4d(q[0], q[1], q[2], q[3]));
    if (!unit) r.fail(field + ".orientation", node["orientation"], "quaternion has zero length");
    goal.orientation = Eigen::Quaterniond((*unit)[3], (*unit)[0], (*unit)[1], (*unit)[2]);
  } else if (node["rpy"]) {
    const Eigen::Vector3d rpy = r.vector3(node["rpy"], field + ".rpy");
    goal.orientation = Eigen::Quaterniond(rotationFromRpy(rpy.x(), rpy.y(), rpy.z()));
  }
  if (const YAML::Node t = node["tolerance"]) {
    r.allowOnly(t, field + ".tolerance", {"position", "orientation"});
    if (t["position"]) {
      goal.position_tolerance = r.positive(t["position"], field + ".tolerance.position");
    }
    if (t["orientation"]) {
      goal.orientation_tolerance = r.positive(t["orientation"], field + ".tolerance.orientation");
    }
  }
  StateSpec s;
  s.link_pose = goal;
  return s;
}

void parseProblem(const YamlReader& r, const YAML::Node& node, SceneSpec& scene) {
  r.allowOnly(node, "problem",
              {"group", "fixed", "start", "goal", "bounds", "planner", "time", "seed",
               "moveit_request", "motion_validator", "range"});
  ProblemSpec& p = scene.problem;
  if (node["moveit_request"]) parseMoveItRequestKey(r, node, scene);
  if (node["group"]) p.group = r.string(node["group"], "problem.group");
  if (const YAML::Node fixed = node["fixed"]) {
    if (!fixed.IsMap()) r.fail("problem.fixed", fixed, "expected {joint: value, ...}");
    p.fixed = namedValues(r, fixed, "problem.fixed");
  }
  const bool joints = !scene.robot.urdf.empty();  // a URDF's states may name joints
  if (node["start"]) p.start = stateFrom(r, node["start"], "problem.start", joints);
  if (node["goal"]) {
    p.goal = isLinkPoseGoal(node["goal"]) ? linkPoseGoalFrom(r, node["goal"], "problem.goal")
                                          : stateFrom(r, node["goal"], "problem.goal", joints);
  }
  if (const YAML::Node b = node["bounds"]) {
    r.allowOnly(b, "problem.bounds", {"min", "max"});
    const Eigen::Vector3d lo = r.vector3(b["min"], "problem.bounds.min");
    const Eigen::Vector3d hi = r.vector3(b["max"], "problem.bounds.max");
    if (!(lo.array() < hi.array()).all()) r.fail("problem.bounds", b, "min must be < max");
    p.bounds = Eigen::AlignedBox3d(lo, hi);
  }
  if (node["planner"]) p.planner = r.string(node["planner"], "problem.planner");
  if (const YAML::Node v = node["motion_validator"]) {
    try {
      p.motion_validator = parseMotionValidatorKind(r.string(v, "problem.motion_validator"));
    } catch (const InvalidArgument& e) {
      r.fail("problem.motion_validator", v, e.what());
    }
  }
  if (node["time"]) {
    p.time = r.positive(node["time"], "problem.time");
    if (p.time > kMaxPlanningSeconds) {
      r.fail("problem.time", node["time"], planningTimeTooLong(p.time));
    }
  }
  if (node["range"]) p.range = r.positive(node["range"], "problem.range");
  if (node["seed"]) {
    const double seed = r.number(node["seed"], "problem.seed");
    if (seed < 0 || seed != std::floor(seed) || seed > kMaxSeed) {
      r.fail("problem.seed", node["seed"], "expected a non-negative integer");
    }
    p.seed = static_cast<std::uint64_t>(seed);
  }
}

}  // namespace

std::string resolvePath(const std::string& scene_path, const std::string& file) {
  fs::path p(file);
  if (p.is_relative()) {
    // A scene named without a directory lives in the current one.
    const fs::path dir = fs::path(scene_path).parent_path();
    p = (dir.empty() ? fs::current_path() : fs::absolute(dir)) / p;
  }
  return p.lexically_normal().string();
}

Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::string planningTimeTooLong(double seconds) {
  std::ostringstream s;
  s << seconds << " s is more than the limit of " << kMaxPlanningSeconds
    << " s (OMPL's deadline would overflow)";
  return s.str();
}

const char* checkerKindName(CheckerKind kind) {
  switch (kind) {
    case CheckerKind::kOctree:
      return "octree";
    case CheckerKind::kOctreeFused:
      return "octree-fused";
    case CheckerKind::kFcl:
      return "fcl";
    case CheckerKind::kFclOctomap:
      return "fcl-octomap";
  }
  return "?";
}

CheckerKind parseCheckerKind(const std::string& name) {
  for (CheckerKind kind : kCheckerKinds) {
    if (name == checkerKindName(kind)) return kind;
  }
  throw InvalidArgument("checker: expected octree, octree-fused, fcl or fcl-octomap, got '" + name +
                        "'");
}

const char* motionValidatorKindName(MotionValidatorKind kind) {
  switch (kind) {
    case MotionValidatorKind::kDiscrete:
      return "discrete";
    case MotionValidatorKind::kOmplDefault:
      return "ompl-default";
    case MotionValidatorKind::kCertified:
      break;
  }
  return "certified";
}

MotionValidatorKind parseMotionValidatorKind(const std::string& name) {
  for (MotionValidatorKind kind : {MotionValidatorKind::kCertified, MotionValidatorKind::kDiscrete,
                                   MotionValidatorKind::kOmplDefault}) {
    if (name == motionValidatorKindName(kind)) return kind;
  }
  throw InvalidArgument(
      "motion validator: expected certified or discrete (or ompl-default, a baseline), got '" +
      name + "'");
}

SceneSpec parseSceneYaml(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw FileError(path,
                    "YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  const YamlReader r(path);
  if (!root.IsMap()) throw FileError(path, "expected a YAML mapping with robot, environment, ...");
  r.allowOnly(root, "", {"name", "robot", "environment", "octree", "problem"});
  SceneSpec scene;
  scene.path = path;
  scene.name = root["name"] ? r.string(root["name"], "name") : fs::path(path).stem().string();
  try {
    if (!root["robot"]) throw FileError(path, "robot: missing (give robot.urdf or robot.mesh)");
    parseRobot(r, root["robot"], scene);
    if (root["environment"]) parseEnvironment(r, root["environment"], scene);
    if (root["octree"]) parseOctree(r, root["octree"], scene);
    if (root["problem"]) parseProblem(r, root["problem"], scene);
  } catch (const YAML::Exception& e) {
    // Type conversion failures that slipped through (e.g. a bool that is not one).
    throw FileError(path,
                    "invalid value at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  return scene;
}

SceneSpec loadScene(const std::string& path) {
  const std::string ext = extensionOf(path);
  if (ext == ".cfg") return parseOmplAppCfg(readFile(path), path);
  if (ext == ".yaml" || ext == ".yml") return parseSceneYaml(readFile(path), path);
  throw FileError(path, "unknown scene format (expected .yaml, .yml or an OMPL.app .cfg)");
}

}  // namespace octomotion
