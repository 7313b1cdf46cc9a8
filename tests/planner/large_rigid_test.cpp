// A large free-flying body in a building-sized mesh scene (tools/building_scene.h,
// docs/scenes.md "Large rigid scenes"): the generated scene is deterministic and refuses
// options that give no building; its start and goal are free and not joined by a straight
// motion; the ompl-default validator keeps OMPL's own step; RRTConnect with the scene's defaults
// (octree checker, certified motion validator, fixed seed) plans it, and exact FCL finds every
// state of the path free at 100 times its state density.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>
#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/tools/building_scene.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

std::string folder(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("octomotion_large_rigid_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(BuildingScene, TheSameSeedWritesTheSameFilesAndAnotherSeedOtherDoors) {
  const std::string a = folder("a"), b = folder("b"), c = folder("c");
  tools::writeBuildingScene(a);
  tools::writeBuildingScene(b);
  tools::BuildingOptions other;
  other.seed = 2;
  tools::writeBuildingScene(c, other);
  for (const char* file : {"building.yaml", "building.stl", "l_body.stl"}) {
    EXPECT_EQ(contents(a + "/" + file), contents(b + "/" + file)) << file;
  }
  EXPECT_NE(contents(a + "/building.stl"), contents(c + "/building.stl"));
  // Binary STL: an 80-byte header, a count, 50 bytes a triangle; 12 triangles a box.
  const std::string body = contents(a + "/l_body.stl");
  EXPECT_EQ(body.size(), 84u + 2 * 12 * 50);
}

TEST(BuildingScene, OptionsThatGiveNoBuildingAreRefused) {
  auto refused = [](auto change) {
    tools::BuildingOptions o;
    change(o);
    EXPECT_THROW(tools::writeBuildingScene(folder("refused"), o), InvalidArgument);
  };
  refused([](tools::BuildingOptions& o) { o.rooms_x = o.rooms_y = 1; });
  refused([](tools::BuildingOptions& o) { o.door_width = o.room_size; });
  refused([](tools::BuildingOptions& o) { o.door_height = o.wall_height; });
  refused([](tools::BuildingOptions& o) { o.body_short_leg = o.door_height; });
  refused([](tools::BuildingOptions& o) { o.room_size = -1; });
}

// The OMPL.app baseline: OMPL's discrete validator at OMPL's own step (its default fraction of
// the space's extent), where `discrete` sets a finer one from the voxels.
TEST(LargeRigid, TheOmplDefaultValidatorKeepsOmplsOwnStep) {
  EXPECT_EQ(parseMotionValidatorKind("ompl-default"), MotionValidatorKind::kOmplDefault);
  EXPECT_STREQ(motionValidatorKindName(MotionValidatorKind::kOmplDefault), "ompl-default");
  const std::string scene_path =
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/narrow_passage.yaml";
  const double ompl_default =
      ompl::base::SpaceInformation(std::make_shared<ompl::base::SE3StateSpace>())
          .getStateValidityCheckingResolution();
  SceneOverrides overrides;
  overrides.motion_validator = MotionValidatorKind::kOmplDefault;
  PlanningScene baseline = loadPlanningScene(scene_path, overrides);
  const auto& si = baseline.setup->getSpaceInformation();
  EXPECT_TRUE(
      dynamic_cast<const ompl::base::DiscreteMotionValidator*>(si->getMotionValidator().get()));
  EXPECT_EQ(si->getStateValidityCheckingResolution(), ompl_default);
  overrides.motion_validator = MotionValidatorKind::kDiscrete;
  PlanningScene discrete = loadPlanningScene(scene_path, overrides);
  EXPECT_LT(discrete.setup->getSpaceInformation()->getStateValidityCheckingResolution(),
            ompl_default);
}

// A pose of a free-flying body: its origin uniform in `bounds`, its rotation uniform (a
// normalised Gaussian quaternion).
Eigen::Isometry3d randomPose(const Eigen::AlignedBox3d& bounds, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  for (int a = 0; a < 3; ++a) {
    X_WB.translation()[a] = bounds.min()[a] + unit(rng) * bounds.sizes()[a];
  }
  Eigen::Quaterniond r(normal(rng), normal(rng), normal(rng), normal(rng));
  X_WB.linear() = r.normalized().toRotationMatrix();
  return X_WB;
}

// The certified validator's clearance for the octree (the grid's, read through groups of
// clearance spheres) never exceeds the exact distance, at random poses of the shipped rigid
// bodies and of the generated building's large one.
TEST(LargeRigid, TheMotionClearanceIsALowerBoundOnTheExactDistance) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string scenes = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/";
  for (const std::string& path : {scenes + "narrow_passage.yaml", scenes + "rooms.yaml",
                                  tools::writeBuildingScene(folder("clearance"))}) {
    SCOPED_TRACE(path);
    PlanningScene scene = loadPlanningScene(path);
    const std::shared_ptr<const CollisionBackend> octree = checkerBackend(scene);
    const FclCollisionModel& fcl = *scene.fclModel();
    auto octree_scratch = octree->makeBackendScratch();
    auto fcl_scratch = fcl.makeScratch();
    const Eigen::AlignedBox3d bounds = *scene.spec.problem.bounds;
    std::mt19937 rng(7);
    int free = 0, positive = 0;
    for (int i = 0; i < 1500; ++i) {
      const Eigen::Isometry3d X_WB = randomPose(bounds, rng);
      if (octree->inCollision(nullptr, 0, X_WB, *octree_scratch)) continue;
      ++free;
      const double bound = octree->motionClearance(*octree_scratch);
      fcl.setConfiguration(nullptr, 0, X_WB, *fcl_scratch);
      const double exact = fcl.environmentDistance(*fcl_scratch);
      EXPECT_LE(bound, exact + 1e-5) << "state " << i;
      positive += bound > 0 ? 1 : 0;
    }
    EXPECT_GT(free, 100);
    EXPECT_GT(positive, 0);  // the bound is not trivially 0
  }
}

// Exact refine cuts the building's one mesh into pieces of nearby triangles, each with its own
// hull and FCL model (refine.cpp, meshPieces). At random poses of the large body near the walls
// (fixed seed): the octree's answer with exact refine is FCL's on the whole mesh, and its
// clearance for the certified validator, capped at a random value, is at most FCL's exact
// distance and at least the least of that distance, the cap and an eighth of a voxel (below
// that, FCL decides).
TEST(LargeRigid, TheBuildingsMeshPiecesGiveFclsAnswersAndLowerBounds) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  PlanningScene scene = loadPlanningScene(tools::writeBuildingScene(folder("pieces")));
  const std::shared_ptr<const CollisionBackend> octree = checkerBackend(scene);
  ASSERT_TRUE(octree->exactAnswers());
  const std::shared_ptr<const FclCollisionModel> fcl = scene.fclModel();
  auto octree_scratch = octree->makeBackendScratch();
  auto fcl_scratch = fcl->makeBackendScratch();
  const double voxel = scene.model->grid().voxelSize();
  const Eigen::AlignedBox3d bounds = *scene.spec.problem.bounds;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int colliding = 0, near = 0, tight = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Isometry3d X_WB = randomPose(bounds, rng);
    const bool fcl_hit = fcl->inCollision(nullptr, 0, X_WB, *fcl_scratch);
    const double exact = fcl_hit ? 0.0 : fcl->clearance(*fcl_scratch);
    if (!fcl_hit && exact > 4 * voxel) continue;  // far from every wall: the octree decides
    ASSERT_EQ(octree->inCollision(nullptr, 0, X_WB, *octree_scratch), fcl_hit) << "state " << i;
    if (fcl_hit) {
      ++colliding;
      continue;
    }
    ++near;
    const double cap = unit(rng) * 3 * voxel;
    double refined = 0;
    octree->motionClearances(*octree_scratch, &cap, &refined, nullptr);
    EXPECT_LE(refined, exact + 1e-5) << "state " << i;  // FCL's GJK tolerance aside
    EXPECT_GE(refined, std::min({exact, cap, voxel / 8}) - 1e-5) << "state " << i;
    tight += exact < cap;
  }
  EXPECT_GT(colliding, 100);
  EXPECT_GT(near, 100);
  EXPECT_GT(tight, 20);
}

TEST(LargeRigid, TheGeneratedBuildingIsPlannedAndFclFindsThePathFree) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string scene_path = tools::writeBuildingScene(folder("plan"));
  SceneOverrides overrides;
  overrides.time = 120;  // a cap for sanitizer builds; RRTConnect stops when it solves
  overrides.seed = 1;
  PlanningScene scene = loadPlanningScene(scene_path, overrides);
  const ompl::base::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  ASSERT_TRUE(dynamic_cast<const CertifiedMotionValidator*>(si->getMotionValidator().get()));
  const auto& pdef = scene.setup->getProblemDefinition();
  ASSERT_EQ(pdef->getStartStateCount(), 1u);
  const auto* goal = pdef->getGoal()->as<ompl::base::GoalState>();
  ASSERT_TRUE(goal);
  // Free ends, but walls between them: the problem is not one straight motion.
  EXPECT_TRUE(si->isValid(pdef->getStartState(0)));
  EXPECT_TRUE(si->isValid(goal->getState()));
  EXPECT_FALSE(si->checkMotion(pdef->getStartState(0), goal->getState()));

  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved);
  std::size_t checked = 0;
  const std::size_t colliding =
      test::fclCollisionsOnPath(*scene.fclModel(), *result.path, 100, &checked);
  EXPECT_EQ(colliding, 0u) << "of " << checked << " states";
}

}  // namespace
}  // namespace octomotion
