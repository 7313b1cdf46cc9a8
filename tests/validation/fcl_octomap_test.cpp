// The fcl-octomap reference (what MoveIt users run with sensor data): selectable like the other
// checkers, and, since its OctoMap holds the conservative voxels of the environment, it never
// misses a contact exact FCL finds; its self pairs are exact FCL's.
#include <fstream>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/planner/reference/fcl_octomap_collision_model.h"
#include "validation_common.h"

namespace octomotion::validation {
namespace {

constexpr std::size_t kStates = 3000;
constexpr std::uint64_t kSeed = 0x5eed0003;

TEST(FclOctomap, IsSelectableAndChecksStates) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.checker = CheckerKind::kFclOctomap;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml", overrides);
  EXPECT_EQ(scene.checker, CheckerKind::kFclOctomap);
  EXPECT_TRUE(scene.fcl_octomap_model.built());
  EXPECT_FALSE(scene.fcl_model.built()) << "the exact reference is built on demand only";
  const auto& si = scene.setup->getSpaceInformation();
  const auto* checker =
      dynamic_cast<const FclOctomapValidityChecker*>(si->getStateValidityChecker().get());
  ASSERT_NE(checker, nullptr);
  EXPECT_GT(checker->model().octomapBytes(), 0u);
  EXPECT_GE(checker->model().buildSeconds(), 0.0);
  EXPECT_DOUBLE_EQ(checker->model().resolution(), *scene.spec.octree.resolution);

  ompl::base::ScopedState<> state(si);
  si->copyState(state.get(), scene.setup->getProblemDefinition()->getStartState(0));
  EXPECT_TRUE(si->isValid(state.get()));
  // Joint 2 bent far forward folds the arm into the shelf's boards or onto itself.
  auto* values = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  values[1] = 1.7;
  values[3] = -0.1;
  const bool exact_free = [&] {
    auto fcl = scene.fclModel();
    auto s = fcl->makeScratch();
    std::vector<double> q(values, values + fcl->robot().variableCount());
    fcl->setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *s);
    return !fcl->inCollision(*s);
  }();
  if (!exact_free) {
    EXPECT_FALSE(si->isValid(state.get()));
  }
  values[1] = std::nan("");
  EXPECT_FALSE(si->isValid(state.get()));
  values[1] = 100.0;
  EXPECT_FALSE(si->isValid(state.get()));
}

TEST(FclOctomap, SceneFileSelectsIt) {
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/fcl_octomap_scene.yaml";
  std::ofstream(path) << "robot:\n  mesh: " << OCTOMOTION_SOURCE_DIR
                      << "/robots/meshes/rigid/l_piece.stl\n"
                         "environment:\n  - {box: {size: [0.05, 1.2, 0.5]}, pose: {xyz: [0, 0, "
                         "0.25]}}\n"
                         "octree: {resolution: 0.02, checker: fcl-octomap}\n"
                         "problem: {bounds: {min: [-1, -1, 0], max: [1, 1, 1]}}\n";
  const PlanningScene scene = loadPlanningScene(path);
  EXPECT_EQ(scene.checker, CheckerKind::kFclOctomap);
  EXPECT_NE(dynamic_cast<const FclOctomapValidityChecker*>(
                scene.setup->getSpaceInformation()->getStateValidityChecker().get()),
            nullptr);
}

class FclOctomapScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(FclOctomapScenes, NeverMissesWhatExactFclFinds) {
  const PlanningScene scene = loadValidationScene(GetParam(), Rounding::kConservative);
  for (const auto& item : scene.environment->items()) {
    if (item.spec.kind == EnvironmentObject::Kind::kPointCloud ||
        item.spec.kind == EnvironmentObject::Kind::kOctomap) {
      // Their exact geometry is voxels of the octree model's grid, which OctoMap's grid need not
      // share: a point's voxel on one grid straddles voxels of the other, so nothing to compare.
      GTEST_SKIP() << item.spec.name << " is made of voxels on another grid";
    }
  }
  const std::shared_ptr<const FclCollisionModel> exact_model = exactReference(scene);
  const FclOctomapCollisionModel& octomap = *scene.fcl_octomap_model;
  auto exact = exact_model->makeScratch();
  auto mapped = octomap.makeScratch();
  std::size_t contacts = 0, missed = 0, self_differs = 0;
  for (const Sample& s : uniformSamples(scene, kStates, kSeed)) {
    exact_model->setConfiguration(s.q.data(), s.q.size(), s.X_WB, *exact);
    octomap.setConfiguration(s.q.data(), s.q.size(), s.X_WB, *mapped);
    const bool hit = exact_model->environmentInCollision(*exact);
    contacts += hit;
    missed += hit && !octomap.environmentInCollision(*mapped);
    self_differs += exact_model->selfInCollision(*exact) != octomap.selfInCollision(*mapped);
    EXPECT_EQ(octomap.inCollision(*mapped),
              octomap.environmentInCollision(*mapped) || octomap.selfInCollision(*mapped));
  }
  EXPECT_GT(contacts, 0u);
  EXPECT_EQ(missed, 0u) << "of " << contacts << " contacts";
  EXPECT_EQ(self_differs, 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, FclOctomapScenes, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
