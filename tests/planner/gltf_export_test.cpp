// The glTF export (gltf_export.h): written with assimp's glb2 exporter, checked by reading the
// file back with assimp's importer and by parsing the glTF JSON chunk ourselves.
#include "octomotion/tools/gltf_export.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "octomotion/error.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

std::string tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "octomotion_gltf_test";
  fs::create_directories(dir);
  return (dir / name).string();
}

// A free-flying box (20 x 10 x 10 cm) over a floor slab and a post, at 2 cm.
std::shared_ptr<OctreeCollisionModel> smallModel(double resolution = 0.02) {
  CollisionElement body;
  body.geometry = Primitive{Box{Eigen::Vector3d(0.10, 0.05, 0.05)}};
  RobotModel robot = RobotModel::rigidBody("brick", {body});
  std::vector<EnvironmentObject> objects(2);
  objects[0].name = "floor";
  objects[0].primitive = Box{Eigen::Vector3d(0.5, 0.5, 0.02)};
  objects[1].name = "post";
  objects[1].primitive = Box{Eigen::Vector3d(0.05, 0.05, 0.2)};
  objects[1].X_WO.translation() = Eigen::Vector3d(0.2, 0.1, 0.2);
  CollisionModelOptions options;
  options.resolution = resolution;
  options.refine = RefineMode::kNone;  // the voxels' answers
  options.base_position_bounds =
      Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, -0.5, 0.0), Eigen::Vector3d(0.5, 0.5, 0.6));
  return std::make_shared<OctreeCollisionModel>(std::move(robot),
                                                EnvironmentGeometry::load(objects), options);
}

std::vector<RobotState> threeStatePath() {
  std::vector<RobotState> path(3);
  path[0].X_WB.translation() = Eigen::Vector3d(-0.3, -0.2, 0.3);
  path[1].X_WB.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  path[1].X_WB.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  path[2].X_WB.translation() = Eigen::Vector3d(0.3, 0.2, 0.3);
  path[2].X_WB.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return path;
}

const aiNode* findNode(const aiNode* node, const std::string& name) {
  if (name == node->mName.C_Str()) return node;
  for (unsigned i = 0; i < node->mNumChildren; ++i) {
    if (const aiNode* n = findNode(node->mChildren[i], name)) return n;
  }
  return nullptr;
}

const aiMesh* meshOf(const aiScene* scene, const aiNode* node) {
  if (node == nullptr || node->mNumMeshes != 1) return nullptr;
  return scene->mMeshes[node->mMeshes[0]];
}

// The JSON chunk of a .glb (glTF 2.0 binary: 12-byte header, then chunks of length + type).
std::string glbJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return "";
  std::uint32_t length = 0, type = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  std::memcpy(&type, bytes.data() + 16, 4);
  if (type != 0x4E4F534Au || 20 + std::size_t{length} > bytes.size()) return "";
  return bytes.substr(20, length);
}

// The boxes of a voxel mesh: 12 triangles each, in the order the exporter writes them (the
// exporter joins the corners boxes share, so vertices are not grouped by box).
std::vector<Eigen::AlignedBox3d> boxesOf(const aiMesh* mesh) {
  std::vector<Eigen::AlignedBox3d> boxes;
  for (unsigned b = 0; b + 12 <= mesh->mNumFaces; b += 12) {
    Eigen::AlignedBox3d box;
    for (unsigned f = b; f < b + 12; ++f) {
      for (unsigned k = 0; k < mesh->mFaces[f].mNumIndices; ++k) {
        const aiVector3D& v = mesh->mVertices[mesh->mFaces[f].mIndices[k]];
        box.extend(Eigen::Vector3d(v.x, v.y, v.z));
      }
    }
    boxes.push_back(box);
  }
  return boxes;
}

// `fitted` (on the same lattice) and `clipped` (on the model's grid) have the same black voxels
// inside the model's universe, and `fitted` has none that `clipped` lacks there.
void expectSameInsideUniverse(const Octree& fitted, const Octree& clipped) {
  const WorldGrid& g = clipped.grid();
  std::size_t inside = 0;
  for (const Voxel& v : fitted.blackVoxels()) {
    Voxel u;
    if (!g.voxelAt(fitted.grid().voxelCenter(v), &u)) continue;
    ++inside;
    EXPECT_TRUE(clipped.occupied(u));
  }
  EXPECT_EQ(inside, clipped.blackVoxelCount());
}

TEST(GltfExport, LinkTreesAreNotClippedToTheUniverse) {
  const auto model = smallModel();
  const auto trees = model->linkSourceTrees();
  ASSERT_EQ(trees.size(), 1u);
  const WorldGrid& grid = model->grid();
  // Poses around the universe's faces, turned arbitrarily: half in, half out, and inside.
  const Eigen::Vector3d lo = grid.origin(), hi = lo + Eigen::Vector3d::Constant(grid.sideMetres());
  const Eigen::Vector3d mid = (lo + hi) / 2;
  int partly_outside = 0;
  for (int i = 0; i < 7; ++i) {
    Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
    X_WL.linear() =
        Eigen::AngleAxisd(0.3 + i, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    X_WL.translation() = mid;
    if (i < 6) X_WL.translation()[i / 2] = (i % 2) ? hi[i / 2] : lo[i / 2];
    bool outside = false;
    const Octree fitted = movedLinkTree(*model, *trees[0].source, X_WL, &outside);
    const Octree clipped = moveTree(*trees[0].source, X_WL, grid, model->rounding());
    partly_outside += outside ? 1 : 0;
    EXPECT_EQ(outside, i < 6) << i;
    expectSameInsideUniverse(fitted, clipped);
    // The whole link: the same volume wherever it is (the source tree's, moved, within the
    // conservative dilation of one voxel layer).
    EXPECT_GT(fitted.volume(), 0.2 * 0.1 * 0.1 * 0.99) << i;
    if (outside) {
      EXPECT_GT(fitted.blackVoxelCount(), clipped.blackVoxelCount()) << i;
    }
  }
  EXPECT_EQ(partly_outside, 6);
}

TEST(GltfExport, WritesTreesRobotAndPathAnimation) {
  const auto model = smallModel();
  const std::vector<RobotState> path = threeStatePath();
  GltfExportOptions options;
  options.state_index = 1;
  const std::string file = tempFile("small.glb");
  const GltfExportReport report = exportGlb(*model, path, options, file);
  ASSERT_EQ(report.trees.size(), 2u);  // environment + the brick's moved tree
  EXPECT_EQ(report.trees[0].name, "environment");
  EXPECT_EQ(report.trees[0].black_leaves, model->environment().blackLeafCount());
  EXPECT_EQ(report.trees[0].boxes, report.trees[0].black_leaves);  // under the cap: exact
  EXPECT_EQ(report.trees[0].drawn_level, 0);
  EXPECT_EQ(report.link_meshes, 1u);
  EXPECT_EQ(report.path_states, 3u);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();

  // Environment: one box (8 vertices, 12 triangles) per black leaf, exactly the leaves' cubes.
  const aiMesh* env = meshOf(scene, findNode(scene->mRootNode, "environment_voxels"));
  ASSERT_NE(env, nullptr);
  EXPECT_LE(env->mNumVertices, 8 * report.trees[0].black_leaves);
  EXPECT_EQ(env->mNumFaces, 12 * report.trees[0].black_leaves);
  std::vector<Eigen::AlignedBox3d> expected;
  const WorldGrid& grid = model->grid();
  model->environment().forEachBlackLeaf(
      [&](const Cube& c) { expected.emplace_back(grid.cubeMin(c), grid.cubeMax(c)); });
  const std::vector<Eigen::AlignedBox3d> written = boxesOf(env);
  ASSERT_EQ(written.size(), expected.size());
  auto key = [](const Eigen::AlignedBox3d& b) {
    return std::make_tuple(std::lround(b.min().x() * 1e4), std::lround(b.min().y() * 1e4),
                           std::lround(b.min().z() * 1e4), std::lround(b.max().x() * 1e4),
                           std::lround(b.max().y() * 1e4), std::lround(b.max().z() * 1e4));
  };
  std::set<decltype(key(written[0]))> written_keys, expected_keys;
  for (const auto& b : written) written_keys.insert(key(b));
  for (const auto& b : expected) expected_keys.insert(key(b));
  EXPECT_EQ(written_keys, expected_keys);
  double volume = 0;
  for (const auto& b : written) volume += b.volume();
  EXPECT_NEAR(volume, model->environment().volume(), 1e-4 * model->environment().volume());

  // Environment material: opaque, the documented colour.
  const aiMaterial* env_material = scene->mMaterials[env->mMaterialIndex];
  aiColor4D color;
  ASSERT_EQ(env_material->Get(AI_MATKEY_COLOR_DIFFUSE, color), aiReturn_SUCCESS);
  EXPECT_NEAR(color.r, kEnvironmentColor[0], 1e-3);
  EXPECT_NEAR(color.g, kEnvironmentColor[1], 1e-3);
  EXPECT_NEAR(color.b, kEnvironmentColor[2], 1e-3);

  // The brick's tree at state 1: what movedLinkTree gives, which matches moveTree onto the
  // model's grid inside the model's universe.
  const auto trees = model->linkSourceTrees();
  ASSERT_EQ(trees.size(), 1u);
  const Eigen::Isometry3d X_WL = linkPoses(*model, path[1])[0];
  const Octree moved = movedLinkTree(*model, *trees[0].source, X_WL);
  const aiMesh* link_tree = meshOf(scene, findNode(scene->mRootNode, "voxels_brick"));
  ASSERT_NE(link_tree, nullptr);
  EXPECT_EQ(link_tree->mNumFaces, 12 * moved.blackLeafCount());
  expectSameInsideUniverse(moved, moveTree(*trees[0].source, X_WL, grid, model->rounding()));

  // The robot: a link node at the chosen state's pose with the box mesh in the link frame.
  const aiNode* link = findNode(scene->mRootNode, "link_brick");
  ASSERT_NE(link, nullptr);
  const aiMesh* brick = meshOf(scene, link);
  ASSERT_NE(brick, nullptr);
  EXPECT_EQ(brick->mNumFaces, 12u);
  const aiMatrix4x4& m = link->mTransformation;
  EXPECT_NEAR(m.a4, 0.0, 1e-6);
  EXPECT_NEAR(m.c4, 0.4, 1e-6);
  EXPECT_NEAR(m.a1, std::cos(0.5), 1e-6);

  // The animation: one channel per link, one key per state at time = index.
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation* anim = scene->mAnimations[0];
  ASSERT_EQ(anim->mNumChannels, 1u);
  const aiNodeAnim* ch = anim->mChannels[0];
  EXPECT_STREQ(ch->mNodeName.C_Str(), "link_brick");
  ASSERT_EQ(ch->mNumPositionKeys, 3u);
  ASSERT_EQ(ch->mNumRotationKeys, 3u);
  const double ticks = anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 1.0;
  for (unsigned s = 0; s < 3; ++s) {
    EXPECT_NEAR(ch->mPositionKeys[s].mTime / ticks, s, 1e-6);
    const Eigen::Vector3d t = path[s].X_WB.translation();
    EXPECT_NEAR(ch->mPositionKeys[s].mValue.x, t.x(), 1e-6);
    EXPECT_NEAR(ch->mPositionKeys[s].mValue.y, t.y(), 1e-6);
    EXPECT_NEAR(ch->mPositionKeys[s].mValue.z, t.z(), 1e-6);
    const Eigen::Quaterniond r(path[s].X_WB.linear());
    const aiQuaternion& k = ch->mRotationKeys[s].mValue;
    EXPECT_NEAR(std::abs(k.w * r.w() + k.x * r.x() + k.y * r.y() + k.z * r.z()), 1.0, 1e-6);
  }

  // The JSON chunk, as three.js's GLTFLoader reads it.
  const std::string json = glbJson(file);
  ASSERT_FALSE(json.empty());
  EXPECT_NE(json.find("\"animations\""), std::string::npos);
  EXPECT_NE(json.find("\"translation\""), std::string::npos);
  EXPECT_NE(json.find("\"rotation\""), std::string::npos);
  EXPECT_NE(json.find("\"BLEND\""), std::string::npos);  // the translucent link tree
  EXPECT_NE(json.find("\"environment_voxels\""), std::string::npos);
}

TEST(GltfExport, CapCoarsensConservatively) {
  const auto model = smallModel(0.01);
  const std::size_t leaves = model->environment().blackLeafCount();
  ASSERT_GT(leaves, 200u);
  GltfExportOptions options;
  options.max_boxes_per_tree = 100;
  options.link_trees = false;
  const std::string file = tempFile("capped.glb");
  const GltfExportReport report = exportGlb(*model, threeStatePath(), options, file);
  ASSERT_EQ(report.trees.size(), 1u);
  EXPECT_LE(report.trees[0].boxes, 100u);
  EXPECT_GT(report.trees[0].drawn_level, 0);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  const aiMesh* env = meshOf(scene, findNode(scene->mRootNode, "environment_voxels"));
  ASSERT_NE(env, nullptr);
  const std::vector<Eigen::AlignedBox3d> boxes = boxesOf(env);
  EXPECT_EQ(boxes.size(), report.trees[0].boxes);
  EXPECT_EQ(findNode(scene->mRootNode, "voxels_brick"), nullptr);
  // Every black voxel lies in a drawn box (the coarse drawing covers the tree).
  const WorldGrid& grid = model->grid();
  std::size_t uncovered = 0;
  for (const Voxel& v : model->environment().blackVoxels()) {
    const Eigen::Vector3d c = grid.voxelCenter(v);
    bool inside = false;
    for (const auto& b : boxes) inside = inside || b.contains(c);
    uncovered += inside ? 0 : 1;
  }
  EXPECT_EQ(uncovered, 0u);
}

TEST(GltfExport, ArmFromSceneHasEveryLink) {
  SceneOverrides overrides;
  overrides.resolution = 0.04;
  // At 4 cm the start's self pairs are within the voxels' margin; the export shows any state.
  overrides.require_free_start_goal = false;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml", overrides);
  const RobotModel& robot = scene.model->robot();
  ASSERT_TRUE(scene.spec.problem.start && scene.spec.problem.goal);
  // A two-state path through the path reader.
  std::ostringstream text;
  text.precision(17);
  for (const auto* s : {&*scene.spec.problem.start, &*scene.spec.problem.goal}) {
    for (std::size_t k = 0; k < s->joints.size(); ++k) text << (k ? " " : "") << s->joints[k];
    text << "\n";
  }
  std::istringstream in(text.str());
  const std::vector<RobotState> path = readPath(robot, in, "two_states.path");
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[1].q, scene.spec.problem.goal->joints);

  GltfExportOptions options;
  options.keep_mesh_root_transform = scene.spec.robot.keep_mesh_root_transform;
  const std::string file = tempFile("arm.glb");
  const GltfExportReport report = exportGlb(*scene.model, path, options, file);
  std::size_t with_geometry = 0;
  for (const Link& l : robot.links()) with_geometry += l.hasCollision() ? 1 : 0;
  EXPECT_EQ(report.link_meshes, with_geometry);
  EXPECT_EQ(report.trees.size(), 1 + scene.model->linkSourceTrees().size());

  Assimp::Importer importer;
  const aiScene* imported = importer.ReadFile(file, 0);
  ASSERT_NE(imported, nullptr) << importer.GetErrorString();
  ASSERT_EQ(imported->mNumAnimations, 1u);
  EXPECT_EQ(imported->mAnimations[0]->mNumChannels, with_geometry);
  for (const Link& l : robot.links()) {
    if (!l.hasCollision()) continue;
    const aiNode* node = findNode(imported->mRootNode, "link_" + l.name);
    ASSERT_NE(node, nullptr) << l.name;
    EXPECT_NE(meshOf(imported, node), nullptr) << l.name;
  }
}

TEST(GltfExport, RejectsBadInput) {
  const auto model = smallModel();
  GltfExportOptions options;
  options.state_index = 3;
  EXPECT_THROW(exportGlb(*model, threeStatePath(), options, tempFile("x.glb")), InvalidArgument);
  EXPECT_THROW(exportGlb(*model, {}, GltfExportOptions{}, tempFile("x.glb")), InvalidArgument);

  const RobotModel& robot = model->robot();
  auto read = [&](const std::string& text) {
    std::istringstream in(text);
    return readPath(robot, in, "bad.path");
  };
  auto expectError = [&](const std::string& text, const std::string& fragment) {
    try {
      read(text);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.path"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expectError("", "no states");
  expectError("0 0 0 0 0 0 1\n0 0 0 0 0 1\n", "line 2");
  expectError("0 0 zero 0 0 0 1\n", "'zero'");
  expectError("0 0 0 0 0 0 0\n", "zero quaternion");
  expectError("0 0 nan 0 0 0 1\n", "non-finite");
  // Comments and blank lines are skipped; quaternions are normalised.
  const auto path = read("# x y z qx qy qz qw\n\n1 2 3 0 0 0 2\n");
  ASSERT_EQ(path.size(), 1u);
  EXPECT_TRUE(path[0].X_WB.linear().isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_EQ(path[0].X_WB.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(readPathFile(robot, tempFile("does_not_exist.path")), FileError);
}

}  // namespace
}  // namespace octomotion
