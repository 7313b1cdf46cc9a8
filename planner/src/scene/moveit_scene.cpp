// A MoveIt PlanningScene's collision objects as environment objects (moveit_scene.h).
#include "octomotion/planner/scene/moveit_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "internal/moveit_yaml.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion {

namespace {

using detail::MessageYaml;

// moveit_msgs/CollisionObject operations and shape_msgs/SolidPrimitive types.
enum Operation { kAdd = 0, kRemove = 1, kAppend = 2, kMove = 3 };
enum PrimitiveType { kBox = 1, kSphere = 2, kCylinder = 3, kCone = 4 };

struct SceneObject {
  std::string id;
  std::vector<EnvironmentObject> shapes;  // named once every operation is applied
};

Primitive primitiveOf(const MessageYaml& r, const YAML::Node& node, const std::string& field,
                      const std::string& id) {
  r.allowOnly(node, field, {"type", "dimensions"});
  const int type =
      r.constant(r.child(node, field, "type"), field + ".type",
                 {{"box", kBox}, {"sphere", kSphere}, {"cylinder", kCylinder}, {"cone", kCone}});
  if (type == kCone) {
    r.fail(field + ".type", node["type"],
           "object '" + id +
               "': cones are not supported (the octree has no cone primitive); "
               "give the cone as a mesh");
  }
  const std::string dims_field = field + ".dimensions";
  const YAML::Node dims_node = r.required(node, field, "dimensions");
  const std::vector<double> d = r.numbers(dims_node, dims_field);
  const std::size_t expected = type == kBox ? 3 : type == kCylinder ? 2 : 1;
  const char* meaning = type == kBox        ? "[x, y, z] (full sizes)"
                        : type == kCylinder ? "[height, radius]"
                                            : "[radius]";
  if (d.size() != expected) {
    r.fail(dims_field, dims_node,
           "expected " + std::to_string(expected) + " numbers " + meaning + ", got " +
               std::to_string(d.size()));
  }
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!(d[i] > 0)) r.fail(MessageYaml::index(dims_field, i), dims_node[i], "must be > 0");
  }
  if (type == kBox) return Box{Eigen::Vector3d(d[0], d[1], d[2]) / 2};
  if (type == kCylinder) return Cylinder{d[1], d[0]};
  return Sphere{d[0]};
}

std::shared_ptr<const TriangleMesh> meshOf(const MessageYaml& r, const YAML::Node& node,
                                           const std::string& field) {
  r.allowOnly(node, field, {"vertices", "triangles"});
  auto mesh = std::make_shared<TriangleMesh>();
  const std::vector<YAML::Node> vertices =
      r.list(r.required(node, field, "vertices"), field + ".vertices");
  const std::vector<YAML::Node> triangles =
      r.list(r.required(node, field, "triangles"), field + ".triangles");
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    mesh->vertices.push_back(r.vector3(vertices[i], MessageYaml::index(field + ".vertices", i)));
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const std::string tf = MessageYaml::index(field + ".triangles", t);
    r.allowOnly(triangles[t], tf, {"vertex_indices"});
    const YAML::Node idx = r.required(triangles[t], tf, "vertex_indices");
    const std::vector<double> v = r.numbers(idx, tf + ".vertex_indices");
    if (v.size() != 3) {
      r.fail(tf + ".vertex_indices", idx,
             "expected 3 vertex indices, got " + std::to_string(v.size()));
    }
    std::array<std::uint32_t, 3> tri{};
    for (int c = 0; c < 3; ++c) {
      if (!(v[c] >= 0 && v[c] == std::floor(v[c]) && v[c] < static_cast<double>(vertices.size()))) {
        r.fail(tf + ".vertex_indices", idx,
               "vertex index " + std::to_string(v[c]) + " is not one of the " +
                   std::to_string(vertices.size()) + " vertices");
      }
      tri[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(v[c]);
    }
    mesh->triangles.push_back(tri);
  }
  if (mesh->triangles.empty()) r.fail(field + ".triangles", node, "a mesh needs triangles");
  return mesh;
}

// The object's shapes, posed in its frame (header.frame_id).
std::vector<EnvironmentObject> shapesOf(const MessageYaml& r, const YAML::Node& node,
                                        const std::string& field, const std::string& id) {
  std::string frame;
  if (const YAML::Node header = r.child(node, field, "header")) {
    r.allowOnly(header, field + ".header", {"seq", "stamp", "frame_id"});
    frame = r.text(r.child(header, field + ".header", "frame_id"), field + ".header.frame_id");
  }
  // Noetic and later: shape poses are relative to the object's pose; before: absolute.
  Eigen::Isometry3d X_FO = Eigen::Isometry3d::Identity();
  if (const YAML::Node pose = r.child(node, field, "pose")) {
    X_FO = r.pose(pose, field + ".pose", true);
  }
  const std::vector<YAML::Node> planes = r.list(r.child(node, field, "planes"), field + ".planes");
  if (!planes.empty()) {
    r.fail(field + ".planes", node["planes"],
           "object '" + id + "': planes are not supported (an infinite plane has no octree)");
  }
  std::vector<EnvironmentObject> shapes;
  auto add = [&](EnvironmentObject obj, const YAML::Node& pose, const std::string& pose_field) {
    obj.X_WO = X_FO * r.pose(pose, pose_field, true);
    obj.frame = frame;
    obj.robot_root_frame = frame.empty();
    shapes.push_back(std::move(obj));
  };
  // A list of shapes and the list of their poses, one each.
  auto paired = [&](const char* shapes_key, const char* poses_key) {
    const std::vector<YAML::Node> items =
        r.list(r.child(node, field, shapes_key), field + "." + shapes_key);
    const std::vector<YAML::Node> poses =
        r.list(r.child(node, field, poses_key), field + "." + poses_key);
    if (poses.size() != items.size()) {
      r.fail(field + "." + poses_key, node[poses_key] ? node[poses_key] : node,
             "expected one pose per " + std::string(shapes_key) + " entry (" +
                 std::to_string(items.size()) + "), got " + std::to_string(poses.size()));
    }
    return std::make_pair(items, poses);
  };
  const auto [primitives, primitive_poses] = paired("primitives", "primitive_poses");
  for (std::size_t k = 0; k < primitives.size(); ++k) {
    EnvironmentObject obj;
    obj.kind = EnvironmentObject::Kind::kPrimitive;
    obj.primitive = primitiveOf(r, primitives[k], MessageYaml::index(field + ".primitives", k), id);
    add(std::move(obj), primitive_poses[k], MessageYaml::index(field + ".primitive_poses", k));
  }
  const auto [meshes, mesh_poses] = paired("meshes", "mesh_poses");
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    EnvironmentObject obj;
    obj.kind = EnvironmentObject::Kind::kMesh;
    obj.mesh = meshOf(r, meshes[k], MessageYaml::index(field + ".meshes", k));
    add(std::move(obj), mesh_poses[k], MessageYaml::index(field + ".mesh_poses", k));
  }
  return shapes;
}

void applyCollisionObject(const MessageYaml& r, const YAML::Node& node, const std::string& field,
                          std::vector<SceneObject>& objects) {
  r.allowOnly(
      node, field,
      {"header", "pose", "id", "type", "primitives", "primitive_poses", "meshes", "mesh_poses",
       "planes", "plane_poses", "subframe_names", "subframe_poses", "operation"});
  int operation = kAdd;
  if (const YAML::Node op = r.child(node, field, "operation")) {
    operation =
        r.constant(op, field + ".operation",
                   {{"add", kAdd}, {"remove", kRemove}, {"append", kAppend}, {"move", kMove}});
  }
  const std::string id = r.text(r.child(node, field, "id"), field + ".id");
  auto existing = std::find_if(objects.begin(), objects.end(),
                               [&](const SceneObject& o) { return o.id == id; });
  if (operation == kRemove) {
    if (id.empty()) {
      objects.clear();
    } else if (existing != objects.end()) {
      objects.erase(existing);
    }
    return;
  }
  if (id.empty()) r.fail(field + ".id", node, "missing (every object needs an id)");
  if (operation == kMove) {
    r.fail(field + ".operation", node["operation"],
           "object '" + id + "': MOVE is not supported; give the object with ADD at its pose");
  }
  std::vector<EnvironmentObject> shapes = shapesOf(r, node, field, id);
  if (shapes.empty()) {
    r.fail(field, node, "object '" + id + "' has no primitives or meshes");
  }
  if (operation == kAppend && existing != objects.end()) {
    for (EnvironmentObject& s : shapes) existing->shapes.push_back(std::move(s));
    return;
  }
  if (existing != objects.end()) objects.erase(existing);  // ADD replaces
  objects.push_back({id, std::move(shapes)});
}

}  // namespace

std::vector<EnvironmentObject> parseMoveItScene(const std::string& text, const std::string& path) {
  const MessageYaml r(path);
  const YAML::Node root = r.parse(text);
  r.allowOnly(root, "",
              {"name", "robot_state", "robot_model_name", "fixed_frame_transforms",
               "allowed_collision_matrix", "link_padding", "link_scale", "object_colors", "world",
               "is_diff"});
  try {
    if (const YAML::Node state = r.child(root, "", "robot_state")) {
      const YAML::Node attached = r.child(state, "robot_state", "attached_collision_objects");
      if (!r.list(attached, "robot_state.attached_collision_objects").empty()) {
        r.fail("robot_state.attached_collision_objects", attached,
               "attached objects are not supported; give them as world objects");
      }
    }
    const YAML::Node world = r.required(root, "", "world");
    r.allowOnly(world, "world", {"collision_objects", "octomap"});
    if (const YAML::Node map = r.child(world, "world", "octomap")) {
      const YAML::Node inner = r.child(map, "world.octomap", "octomap");
      if (inner &&
          !r.list(r.child(inner, "world.octomap.octomap", "data"), "world.octomap.octomap.data")
               .empty()) {
        r.fail("world.octomap", map,
               "an OctoMap in the message is not supported; give it as an octomap .bt file");
      }
    }
    std::vector<SceneObject> objects;
    const std::vector<YAML::Node> items =
        r.list(r.child(world, "world", "collision_objects"), "world.collision_objects");
    for (std::size_t i = 0; i < items.size(); ++i) {
      applyCollisionObject(r, items[i], MessageYaml::index("world.collision_objects", i), objects);
    }
    std::vector<EnvironmentObject> out;
    for (SceneObject& o : objects) {
      for (std::size_t k = 0; k < o.shapes.size(); ++k) {
        o.shapes[k].name = o.shapes.size() == 1 ? o.id : o.id + "/" + std::to_string(k);
        out.push_back(std::move(o.shapes[k]));
      }
    }
    return out;
  } catch (const YAML::Exception& e) {
    throw FileError(path,
                    "invalid value at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

std::vector<EnvironmentObject> loadMoveItScene(const std::string& path) {
  // Inline meshes make these files as large as mesh files.
  return parseMoveItScene(readWholeFile(path, "MoveIt planning scene", kMaxMeshFileBytes), path);
}

}  // namespace octomotion
