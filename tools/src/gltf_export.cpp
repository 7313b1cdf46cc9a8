#include "octomotion/tools/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/planner/robot/collision_meshes.h"

namespace octomotion {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------- path file

// strtod (not a stream) so that "nan" and "inf" parse and are reported as non-finite.
bool parseDouble(const std::string& token, double* value) {
  char* end = nullptr;
  *value = std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0';
}

// ---------------------------------------------------------------- geometry

// A float triangle mesh being assembled for one glTF mesh.
struct MeshBuffer {
  std::vector<aiVector3D> vertices;
  std::vector<std::array<unsigned, 3>> triangles;

  void append(const TriangleMesh& mesh, const Eigen::Isometry3d& X) {
    const auto base = static_cast<unsigned>(vertices.size());
    for (const Eigen::Vector3d& v : mesh.vertices) {
      const Eigen::Vector3d p = X * v;
      vertices.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                            static_cast<float>(p.z()));
    }
    for (const auto& t : mesh.triangles)
      triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }

  // An axis-aligned box; triangles counter-clockwise seen from outside. Corner c has bit 0 = +x,
  // bit 1 = +y, bit 2 = +z (the octant labels).
  void appendBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const auto base = static_cast<unsigned>(vertices.size());
    for (int c = 0; c < 8; ++c) {
      vertices.emplace_back(static_cast<float>((c & 1) ? hi.x() : lo.x()),
                            static_cast<float>((c & 2) ? hi.y() : lo.y()),
                            static_cast<float>((c & 4) ? hi.z() : lo.z()));
    }
    static constexpr unsigned kFaces[12][3] = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},
                                               {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                               {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
    for (const auto& f : kFaces) triangles.push_back({base + f[0], base + f[1], base + f[2]});
  }

  bool empty() const { return triangles.empty(); }
};

// A closed cylinder about the z axis, centred on the origin.
TriangleMesh cylinderMesh(double radius, double length, int segments) {
  TriangleMesh m;
  const double h = length / 2;
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * kPi * i / segments;
    const double x = radius * std::cos(a), y = radius * std::sin(a);
    m.vertices.emplace_back(x, y, -h);
    m.vertices.emplace_back(x, y, h);
  }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, -h);
  m.vertices.emplace_back(0, 0, h);
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    const std::uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * j, t1 = 2 * j + 1;
    m.triangles.push_back({b0, b1, t1});
    m.triangles.push_back({b0, t1, t0});
    m.triangles.push_back({bottom, b1, b0});
    m.triangles.push_back({bottom + 1, t0, t1});
  }
  return m;
}

TriangleMesh primitiveMesh(const Primitive& p) {
  if (const auto* box = std::get_if<Box>(&p)) return boxMesh(box->half_extents, 1);
  if (const auto* ball = std::get_if<Sphere>(&p)) return sphereMesh(ball->radius, 24, 12);
  const auto& c = std::get<Cylinder>(p);
  return cylinderMesh(c.radius, c.length, 24);
}

// The link's collision elements as one mesh in its frame L.
MeshBuffer linkMesh(const Link& link, CollisionMeshes& meshes) {
  MeshBuffer buffer;
  for (const CollisionElement& e : link.collision) {
    if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
      buffer.append(primitiveMesh(*p), e.X_LE);
    } else {
      buffer.append(meshes.get(std::get<MeshRef>(e.geometry)), e.X_LE);
    }
  }
  return buffer;
}

// Boxes for a tree's black leaves, coarsened to the finest level that keeps the count <= cap.
MeshBuffer treeBoxes(const Octree& tree, std::size_t cap, GltfTreeReport& report) {
  MeshBuffer buffer;
  const WorldGrid& grid = tree.grid();
  report.black_leaves = tree.blackLeafCount();
  if (tree.rootColor() == Color::kWhite) return buffer;
  if (tree.rootColor() == Color::kBlack) {
    buffer.appendBox(grid.cubeMin(grid.universe()), grid.cubeMax(grid.universe()));
    report.boxes = 1;
    report.drawn_level = grid.depth();
    return buffer;
  }
  const auto& nodes = tree.nodes();
  // Black leaves and gray nodes per cube level: drawn at level L, there are
  // sum_{l >= L} black[l] + gray[L] boxes.
  std::vector<std::size_t> black(static_cast<std::size_t>(grid.depth()) + 1, 0);
  std::vector<std::size_t> gray(black.size(), 0);
  struct Item {
    std::uint32_t node;
    int level;
  };
  std::vector<Item> stack{{0, grid.depth()}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const OctreeNode& n = nodes[it.node];
    gray[static_cast<std::size_t>(it.level)] += 1;
    black[static_cast<std::size_t>(it.level - 1)] += static_cast<std::size_t>(popcount8(n.black));
    for (int k = 0; k < 8; ++k) {
      if (n.gray & (1u << k)) stack.push_back({n.childIndex(k), it.level - 1});
    }
  }
  int level = 0;
  for (;; ++level) {
    std::size_t boxes = gray[static_cast<std::size_t>(level)];
    if (level == 0) boxes = 0;
    for (std::size_t l = static_cast<std::size_t>(level); l < black.size(); ++l) boxes += black[l];
    if (boxes <= std::max<std::size_t>(cap, 1) || level == grid.depth()) break;
  }
  report.drawn_level = level;
  auto emit = [&](const Cube& c) {
    buffer.appendBox(grid.cubeMin(c), grid.cubeMax(c));
    ++report.boxes;
  };
  struct CubeItem {
    std::uint32_t node;
    Cube cube;
  };
  std::vector<CubeItem> cubes{{0, grid.universe()}};
  while (!cubes.empty()) {
    const CubeItem it = cubes.back();
    cubes.pop_back();
    if (it.cube.level == level) {
      emit(it.cube);
      continue;
    }
    const OctreeNode& n = nodes[it.node];
    for (int k = 0; k < 8; ++k) {
      if (n.black & (1u << k)) {
        emit(it.cube.child(k));
      } else if (n.gray & (1u << k)) {
        cubes.push_back({n.childIndex(k), it.cube.child(k)});
      }
    }
  }
  return buffer;
}

// ---------------------------------------------------------------- assimp scene

// Node and mesh names are restricted to [A-Za-z0-9_-] so that three.js's animation binding
// (which treats '.', ':', '/' and '[' specially) finds them unchanged.
std::string sanitize(const std::string& name) {
  std::string out = name;
  for (char& c : out) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) c = '_';
  }
  return out.empty() ? "unnamed" : out;
}

aiMatrix4x4 toAi(const Eigen::Isometry3d& X) {
  const Eigen::Matrix4d m = X.matrix();
  aiMatrix4x4 a;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) a[r][c] = static_cast<ai_real>(m(r, c));
  }
  return a;
}

aiMesh* toAiMesh(const MeshBuffer& buffer, const std::string& name, unsigned material) {
  auto mesh = std::make_unique<aiMesh>();
  mesh->mName = aiString(name);
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mMaterialIndex = material;
  mesh->mNumVertices = static_cast<unsigned>(buffer.vertices.size());
  mesh->mVertices = new aiVector3D[buffer.vertices.size()];
  std::copy(buffer.vertices.begin(), buffer.vertices.end(), mesh->mVertices);
  mesh->mNumFaces = static_cast<unsigned>(buffer.triangles.size());
  mesh->mFaces = new aiFace[buffer.triangles.size()];
  for (std::size_t i = 0; i < buffer.triangles.size(); ++i) {
    aiFace& f = mesh->mFaces[i];
    f.mNumIndices = 3;
    f.mIndices = new unsigned[3];
    std::copy(buffer.triangles[i].begin(), buffer.triangles[i].end(), f.mIndices);
  }
  return mesh.release();
}

aiMaterial* makeMaterial(const std::string& name, const std::array<float, 4>& rgba) {
  auto m = std::make_unique<aiMaterial>();
  const aiString n(name);
  m->AddProperty(&n, AI_MATKEY_NAME);
  // Alpha goes in the opacity only: assimp multiplies the colour's alpha by it.
  const aiColor4D color(rgba[0], rgba[1], rgba[2], 1.0f);
  m->AddProperty(&color, 1, AI_MATKEY_BASE_COLOR);
  m->AddProperty(&color, 1, AI_MATKEY_COLOR_DIFFUSE);
  const float opacity = rgba[3];
  m->AddProperty(&opacity, 1, AI_MATKEY_OPACITY);
  const float metallic = 0.0f, roughness = 0.8f;
  m->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  m->AddProperty(&roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  if (rgba[3] < 1.0f) {
    const int two_sided = 1;
    m->AddProperty(&two_sided, 1, AI_MATKEY_TWOSIDED);
  }
  return m.release();
}

// Nodes are owned by unique_ptrs until they are attached to their parent.
std::unique_ptr<aiNode> makeNode(const std::string& name, aiNode* parent) {
  auto node = std::make_unique<aiNode>(name);
  node->mParent = parent;
  return node;
}

void setChildren(aiNode* parent, std::vector<std::unique_ptr<aiNode>>& children) {
  if (children.empty()) return;
  parent->mNumChildren = static_cast<unsigned>(children.size());
  parent->mChildren = new aiNode*[children.size()];
  for (std::size_t i = 0; i < children.size(); ++i) parent->mChildren[i] = children[i].release();
  children.clear();
}

void setMesh(aiNode* node, unsigned mesh) {
  node->mNumMeshes = 1;
  node->mMeshes = new unsigned[1];
  node->mMeshes[0] = mesh;
}

}  // namespace

// ---------------------------------------------------------------- public

std::vector<RobotState> readPath(const RobotModel& robot, std::istream& in,
                                 const std::string& source_name) {
  const bool free = robot.isFreeFlying();
  const std::size_t expected = free ? 7 : static_cast<std::size_t>(robot.variableCount());
  std::vector<RobotState> path;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = "line " + std::to_string(line_no);
    std::istringstream ss(line);
    std::vector<double> values;
    std::string token;
    while (ss >> token) {
      double v = 0;
      if (!parseDouble(token, &v))
        throw FileError(source_name, where + ": '" + token + "' is not a number");
      if (!std::isfinite(v)) throw FileError(source_name, where + ": non-finite value " + token);
      values.push_back(v);
    }
    if (values.size() != expected) {
      throw FileError(source_name, where + ": expected " + std::to_string(expected) +
                                       (free ? " values (x y z qx qy qz qw)"
                                             : " joint values (the robot's variables)") +
                                       ", got " + std::to_string(values.size()));
    }
    RobotState s;
    if (free) {
      // Scaled: a plain norm of (1e200, 1e200, 0, 0) overflows and q / inf is no rotation.
      const auto r = scaledUnitVector(Eigen::Vector4d(values[6], values[3], values[4], values[5]));
      if (!r) throw FileError(source_name, where + ": zero quaternion");
      s.X_WB.linear() = Eigen::Quaterniond((*r)[0], (*r)[1], (*r)[2], (*r)[3]).toRotationMatrix();
      s.X_WB.translation() = Eigen::Vector3d(values[0], values[1], values[2]);
    } else {
      s.q = std::move(values);
    }
    path.push_back(std::move(s));
  }
  if (path.empty()) throw FileError(source_name, "the path has no states");
  return path;
}

std::vector<RobotState> readPathFile(const RobotModel& robot, const std::string& path) {
  requireRegularFile(path, "path file", kMaxDataFileBytes);
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open the path file");
  return readPath(robot, in, path);
}

std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> linkPoses(
    const OctreeCollisionModel& model, const RobotState& state) {
  const RobotModel& robot = model.robot();
  RobotData data = robot.makeData();
  robot.forwardKinematics(state.q.data(), state.q.size(), data,
                          robot.isFreeFlying() ? state.X_WB : model.baseMount());
  return data.X_WL;
}

Octree movedLinkTree(const OctreeCollisionModel& model, const Octree& source,
                     const Eigen::Isometry3d& X_WL, bool* outside_universe) {
  const WorldGrid& grid = model.grid();
  if (outside_universe) *outside_universe = false;
  const std::optional<VoxelBounds> bounds = source.bounds();
  if (!bounds) return Octree(grid);
  // World box of the moved black voxels (the corners of their bounding box).
  const WorldGrid& sg = source.grid();
  const Eigen::Vector3d lo_S =
      sg.toWorld(Eigen::Vector3d(bounds->min.x, bounds->min.y, bounds->min.z));
  const Eigen::Vector3d hi_S =
      sg.toWorld(Eigen::Vector3d(bounds->max.x + 1.0, bounds->max.y + 1.0, bounds->max.z + 1.0));
  Eigen::AlignedBox3d box_W;
  for (int c = 0; c < 8; ++c) {
    box_W.extend(X_WL * Eigen::Vector3d((c & 1) ? hi_S.x() : lo_S.x(),
                                        (c & 2) ? hi_S.y() : lo_S.y(),
                                        (c & 4) ? hi_S.z() : lo_S.z()));
  }
  const Eigen::AlignedBox3d universe_W(
      grid.origin(), grid.origin() + Eigen::Vector3d::Constant(grid.sideMetres()));
  if (outside_universe) *outside_universe = !universe_W.contains(box_W);
  // Whole voxels from the model's origin, with one voxel of margin on each side.
  const double vs = grid.voxelSize();
  Eigen::Vector3d first, last;
  for (int a = 0; a < 3; ++a) {
    first[a] = std::floor((box_W.min()[a] - grid.origin()[a]) / vs) - 1.0;
    last[a] = std::ceil((box_W.max()[a] - grid.origin()[a]) / vs) + 1.0;
  }
  const double side = (last - first).maxCoeff();
  int depth = 1;
  while (depth < kMaxDepth && static_cast<double>(std::uint32_t{1} << depth) < side) ++depth;
  if (static_cast<double>(std::uint32_t{1} << depth) < side) {
    return moveTree(source, X_WL, grid, model.rounding());  // absurdly large: clip instead
  }
  const Eigen::Vector3d origin = grid.origin() + first * vs;
  const WorldGrid fitted(origin, vs, depth);
  return moveTree(source, X_WL, fitted, model.rounding());
}

std::string GltfExportReport::toString() const {
  std::ostringstream out;
  for (const GltfTreeReport& t : trees) {
    out << "  " << t.name << ": " << t.black_leaves << " black leaves, " << t.boxes << " boxes";
    if (t.drawn_level > 0) out << " (coarsened to cubes of 2^" << t.drawn_level << " voxels)";
    if (t.outside_universe) out << " (partly outside the modelled universe)";
    out << "\n";
  }
  out << "  robot: " << link_meshes << " link meshes; path: " << path_states
      << " states, links shown at state " << state_index << "\n";
  return out.str();
}

GltfExportReport exportGlb(const OctreeCollisionModel& model, const std::vector<RobotState>& path,
                           const GltfExportOptions& options, const std::string& glb_path) {
  if (path.empty()) throw InvalidArgument("exportGlb: the path has no states");
  if (options.state_index >= path.size()) {
    throw InvalidArgument("exportGlb: state index " + std::to_string(options.state_index) +
                          " is out of range (the path has " + std::to_string(path.size()) +
                          " states)");
  }
  const RobotModel& robot = model.robot();
  std::vector<std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>> poses;
  poses.reserve(path.size());
  for (const RobotState& s : path) poses.push_back(linkPoses(model, s));
  const auto& X_WL_shown = poses[options.state_index];

  GltfExportReport report;
  report.path_states = path.size();
  report.state_index = options.state_index;

  // Each link's name in the file: sanitised, and made unique when sanitising merges two names.
  std::vector<std::string> link_ids;
  {
    std::set<std::string> used;
    for (const Link& link : robot.links()) {
      std::string id = sanitize(link.name);
      for (int k = 2; used.count(id); ++k) id = sanitize(link.name) + "_" + std::to_string(k);
      used.insert(id);
      link_ids.push_back(id);
    }
  }

  std::vector<aiMesh*> meshes;
  std::vector<aiMaterial*> materials;
  // On any exception the scene below does not own these yet.
  struct Cleanup {
    std::vector<aiMesh*>& meshes;
    std::vector<aiMaterial*>& materials;
    bool armed = true;
    ~Cleanup() {
      if (!armed) return;
      for (aiMesh* m : meshes) delete m;
      for (aiMaterial* m : materials) delete m;
    }
  } cleanup{meshes, materials};

  auto scene = std::make_unique<aiScene>();
  // Z-up (robotics) to Y-up (glTF): (x, y, z) -> (x, z, -y).
  scene->mRootNode = makeNode("octomotion", nullptr).release();
  aiNode* root = scene->mRootNode;
  Eigen::Isometry3d Y_from_Z = Eigen::Isometry3d::Identity();
  Y_from_Z.linear() = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  root->mTransformation = toAi(Y_from_Z);
  std::vector<std::unique_ptr<aiNode>> root_children;

  // Environment.
  {
    GltfTreeReport tr;
    tr.name = "environment";
    const MeshBuffer boxes = treeBoxes(model.environment(), options.max_boxes_per_tree, tr);
    root_children.push_back(makeNode("environment_voxels", root));
    aiNode* node = root_children.back().get();
    if (!boxes.empty()) {
      materials.push_back(makeMaterial("environment", kEnvironmentColor));
      meshes.push_back(
          toAiMesh(boxes, "voxels_environment", static_cast<unsigned>(materials.size() - 1)));
      setMesh(node, static_cast<unsigned>(meshes.size() - 1));
    }
    report.trees.push_back(tr);
  }

  // Each modelled link's whole tree at the chosen state (movedLinkTree).
  {
    root_children.push_back(makeNode("link_voxels", root));
    aiNode* group = root_children.back().get();
    std::vector<std::unique_ptr<aiNode>> children;
    if (options.link_trees) {
      std::size_t colour = 0;
      for (const auto& lst : model.linkSourceTrees()) {
        const std::string link_name = robot.link(lst.link).name;
        GltfTreeReport tr;
        tr.name = link_name;
        const Octree moved =
            movedLinkTree(model, *lst.source, X_WL_shown[static_cast<std::size_t>(lst.link)],
                          &tr.outside_universe);
        const MeshBuffer boxes = treeBoxes(moved, options.max_boxes_per_tree, tr);
        report.trees.push_back(tr);
        if (boxes.empty()) continue;
        const std::string name = "voxels_" + link_ids[static_cast<std::size_t>(lst.link)];
        materials.push_back(makeMaterial(name, kLinkTreeColors[colour++ % kLinkTreeColors.size()]));
        meshes.push_back(toAiMesh(boxes, name, static_cast<unsigned>(materials.size() - 1)));
        children.push_back(makeNode(name, group));
        setMesh(children.back().get(), static_cast<unsigned>(meshes.size() - 1));
      }
    }
    setChildren(group, children);
  }

  // The robot: one node per link with geometry, at the chosen state, and the path animation.
  std::vector<int> animated_links;
  {
    root_children.push_back(makeNode("robot", root));
    aiNode* group = root_children.back().get();
    std::vector<std::unique_ptr<aiNode>> children;
    materials.push_back(makeMaterial("robot", kRobotColor));
    const auto robot_material = static_cast<unsigned>(materials.size() - 1);
    CollisionMeshes robot_meshes(options.keep_mesh_root_transform, options.center_mesh_vertices);
    for (int i = 0; i < robot.linkCount(); ++i) {
      const Link& link = robot.link(i);
      if (!link.hasCollision()) continue;
      const MeshBuffer mesh = linkMesh(link, robot_meshes);
      if (mesh.empty()) continue;
      const std::string& id = link_ids[static_cast<std::size_t>(i)];
      const std::string name = "link_" + id;
      meshes.push_back(toAiMesh(mesh, "mesh_" + id, robot_material));
      children.push_back(makeNode(name, group));
      children.back()->mTransformation = toAi(X_WL_shown[static_cast<std::size_t>(i)]);
      setMesh(children.back().get(), static_cast<unsigned>(meshes.size() - 1));
      animated_links.push_back(i);
      ++report.link_meshes;
    }
    setChildren(group, children);
  }
  setChildren(root, root_children);

  if (!animated_links.empty()) {
    auto anim = std::make_unique<aiAnimation>();
    anim->mName = aiString("path");
    anim->mTicksPerSecond = 1.0;  // state i at time i
    anim->mDuration = static_cast<double>(path.size() - 1);
    anim->mNumChannels = static_cast<unsigned>(animated_links.size());
    anim->mChannels = new aiNodeAnim*[animated_links.size()];
    for (std::size_t c = 0; c < animated_links.size(); ++c) {
      auto* ch = new aiNodeAnim();
      anim->mChannels[c] = ch;
      const auto link = static_cast<std::size_t>(animated_links[c]);
      ch->mNodeName = aiString("link_" + link_ids[link]);
      ch->mNumPositionKeys = static_cast<unsigned>(path.size());
      ch->mPositionKeys = new aiVectorKey[path.size()];
      ch->mNumRotationKeys = static_cast<unsigned>(path.size());
      ch->mRotationKeys = new aiQuatKey[path.size()];
      Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
      for (std::size_t s = 0; s < path.size(); ++s) {
        const Eigen::Isometry3d& X = poses[s][link];
        const auto t = static_cast<double>(s);
        ch->mPositionKeys[s] =
            aiVectorKey(t, aiVector3D(static_cast<ai_real>(X.translation().x()),
                                      static_cast<ai_real>(X.translation().y()),
                                      static_cast<ai_real>(X.translation().z())));
        Eigen::Quaterniond r(X.linear());
        // Same hemisphere as the previous key, so interpolation takes the short way.
        if (s > 0 && r.dot(previous) < 0) r.coeffs() = -r.coeffs();
        previous = r;
        ch->mRotationKeys[s] =
            aiQuatKey(t, aiQuaternion(static_cast<ai_real>(r.w()), static_cast<ai_real>(r.x()),
                                      static_cast<ai_real>(r.y()), static_cast<ai_real>(r.z())));
      }
    }
    scene->mNumAnimations = 1;
    scene->mAnimations = new aiAnimation*[1];
    scene->mAnimations[0] = anim.release();
  }

  scene->mNumMeshes = static_cast<unsigned>(meshes.size());
  scene->mMeshes = new aiMesh*[meshes.size()];
  std::copy(meshes.begin(), meshes.end(), scene->mMeshes);
  scene->mNumMaterials = static_cast<unsigned>(materials.size());
  scene->mMaterials = new aiMaterial*[materials.size()];
  std::copy(materials.begin(), materials.end(), scene->mMaterials);
  cleanup.armed = false;

  Assimp::Exporter exporter;
  if (exporter.Export(scene.get(), "glb2", glb_path) != aiReturn_SUCCESS) {
    throw FileError(glb_path,
                    std::string("cannot write the glTF file: ") + exporter.GetErrorString());
  }
  return report;
}

}  // namespace octomotion
