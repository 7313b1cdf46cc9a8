// One source of geometry (docs/validation.md §1): the octree model and the FCL reference are
// built from the same loaded triangles (CollisionMeshes for the robot, EnvironmentGeometry for
// the objects), and conservative trees hold all of them. For every link and mesh object of every
// shipped scene and of the generated COLLADA scenes (tests/support/collada_scenes.h), every
// sampled point of every triangle lies in a closed black voxel of the link's source trees (in
// its own frame; none may fall outside them) and of the environment tree (inside the modelled
// universe). Primitives, links' and objects', are sampled on their surfaces the same way. The
// generated scenes are also checked against FCL: no missed contact, and every rejected free state
// within delta of contact, on both checker paths.
#include <gtest/gtest.h>

#include "collada_scenes.h"
#include "conservative_common.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "surface_coverage.h"

namespace octomotion::validation {
namespace {

std::vector<std::string> allScenes() {
  std::vector<std::string> files = sceneFiles();
  for (const std::string& f : test::colladaSceneFiles()) files.push_back(f);
  files.push_back(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/mixed_table.yaml");
  return files;
}

// A primitive as a triangle mesh whose corners lie on its surface and whose faces lie in it, so
// that every sampled point is a point of the solid.
TriangleMesh surfaceOf(const Primitive& p) {
  if (const auto* box = std::get_if<Box>(&p)) return boxMesh(box->half_extents, 3);
  if (const auto* ball = std::get_if<Sphere>(&p)) return sphereMesh(ball->radius, 24, 12);
  const auto& cylinder = std::get<Cylinder>(p);
  TriangleMesh m;
  const int n = 32;
  const double h = cylinder.length / 2;
  m.vertices = {{0, 0, -h}, {0, 0, h}};
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    m.vertices.emplace_back(cylinder.radius * std::cos(a), cylinder.radius * std::sin(a), -h);
    m.vertices.emplace_back(cylinder.radius * std::cos(a), cylinder.radius * std::sin(a), h);
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t b0 = 2 + 2 * k, t0 = b0 + 1, b1 = 2 + 2 * ((k + 1) % n), t1 = b1 + 1;
    m.triangles.push_back({0, b1, b0});
    m.triangles.push_back({1, t0, t1});
    m.triangles.push_back({b0, b1, t1});
    m.triangles.push_back({b0, t1, t0});
  }
  return m;
}

class GeometryCoverage : public ::testing::TestWithParam<std::string> {};

TEST_P(GeometryCoverage, ConservativeTreesHoldEveryTriangle) {
  const PlanningScene scene = loadValidationScene(GetParam(), Rounding::kConservative);
  const OctreeCollisionModel& model = *scene.model;
  const RobotModel& robot = model.robot();
  CollisionMeshes meshes(scene.spec.robot.keep_mesh_root_transform,
                         scene.spec.robot.center_mesh_vertices);
  std::size_t link_points = 0;
  for (const auto& tree : model.linkSourceTrees()) {
    const Link& link = robot.link(tree.link);
    for (const CollisionElement& e : link.collision) {
      const auto* ref = std::get_if<MeshRef>(&e.geometry);
      const TriangleMesh primitive_surface =
          ref ? TriangleMesh{} : surfaceOf(std::get<Primitive>(e.geometry));
      const TriangleMesh& mesh = ref ? meshes.get(*ref) : primitive_surface;
      for (const Octree* source : {tree.source, tree.self_source}) {
        if (source == nullptr) continue;
        const test::Coverage c = test::surfaceCoverage(*source, mesh, e.X_LE);
        link_points += c.points;
        EXPECT_EQ(c.uncovered + c.outside, 0u)
            << link.name << " (" << (ref ? ref->path : "a primitive") << "): " << c.uncovered
            << " uncovered and " << c.outside << " outside of " << c.points << " points, first "
            << c.first;
      }
    }
  }
  std::size_t object_points = 0;
  for (const auto& item : scene.environment->items()) {
    const bool primitive = item.spec.kind == EnvironmentObject::Kind::kPrimitive;
    if (!primitive && item.spec.kind != EnvironmentObject::Kind::kMesh) continue;  // voxels
    const test::Coverage c = test::surfaceCoverage(
        model.environment(), primitive ? surfaceOf(item.spec.primitive) : item.mesh,
        item.spec.X_WO);
    object_points += c.points - c.outside;
    EXPECT_EQ(c.uncovered, 0u) << item.spec.name << " (" << item.spec.file << "): " << c.uncovered
                               << " of " << c.points << " points uncovered, first " << c.first;
  }
  std::cout << "[ coverage ] " << sceneLabel(GetParam()) << ": " << link_points << " link points, "
            << object_points << " object points\n";
}

INSTANTIATE_TEST_SUITE_P(Scenes, GeometryCoverage, ::testing::ValuesIn(allScenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           return testName(p.param);
                         });

// The generated COLLADA scenes against FCL (docs/validation.md §1-2), 3,000 states on the fused
// path and 1,500 on the moveTree path.
class ColladaScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(ColladaScenes, FusedNeverMissesAContact) {
  checkConservative(GetParam(), CheckerKind::kOctreeFused, 0, 3000);
}

TEST_P(ColladaScenes, MoveTreeNeverMissesAContact) {
  checkConservative(GetParam(), CheckerKind::kOctree, 0, 1500);
}

INSTANTIATE_TEST_SUITE_P(Generated, ColladaScenes, ::testing::ValuesIn(test::colladaSceneFiles()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           return testName(p.param);
                         });

}  // namespace
}  // namespace octomotion::validation
