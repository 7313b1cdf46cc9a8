// The octree's clearance (OctreeCollisionModel::clearanceLowerBoundPoints and ...Tree) is a lower
// bound on the distance FCL finds between the whole robot and the environment, on every shipped
// scene: links whose reach never meets the environment's box are left out of the per-state
// queries, and their pose-independent bound (the gap between the two boxes) keeps the answer
// below the distance of a link that never moves, such as an arm's base beside a table.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

void expectLowerBound(const std::string& name) {
  SCOPED_TRACE(name);
  const std::string path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + name;
  SceneOverrides o;
  o.resolution = 0.02;
  o.require_free_start_goal = false;
  o.checker = CheckerKind::kOctreeFused;
  o.refine = RefineMode::kNone;  // the octree's own bound, not refine exact's FCL distances
  const PlanningScene octree = loadPlanningScene(path, o, [](const std::string&) {});
  o.checker = CheckerKind::kFcl;
  const PlanningScene fcl = loadPlanningScene(path, o, [](const std::string&) {});
  ASSERT_TRUE(octree.model);
  const OctreeCollisionModel& model = *octree.model;

  const auto si = octree.setup->getSpaceInformation();
  const auto fcl_checker = fcl.setup->getSpaceInformation()->getStateValidityChecker();
  ompl::base::ScopedState<> state(si);
  auto sampler = si->allocStateSampler();
  CheckScratch scratch = model.makeScratch();
  std::vector<double> q(static_cast<std::size_t>(model.robot().variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  int compared = 0;
  for (int k = 0; k < 300; ++k) {
    sampler->sampleUniform(state.get());
    if (!fcl_checker->isValid(state.get())) continue;
    ASSERT_TRUE(stateToConfiguration(model.robot(), state.get(), q, X_WB));
    if (model.inCollision(q.data(), q.size(), X_WB, CheckerPath::kFused, scratch)) continue;
    const double exact = fcl_checker->clearance(state.get());
    EXPECT_LE(model.clearanceLowerBoundPoints(scratch), exact + 1e-9) << "state " << k;
    EXPECT_LE(model.clearanceLowerBoundTree(scratch), exact + 1e-9) << "state " << k;
    ++compared;
  }
  EXPECT_GT(compared, 30);
}

TEST(ClearanceAgainstFcl, IsALowerBoundOnEveryShippedScene) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  for (const char* name : {"bookshelf.yaml", "cluttered_table.yaml", "cage.yaml", "rooms.yaml",
                           "narrow_passage.yaml"}) {
    expectLowerBound(name);
  }
}

}  // namespace
}  // namespace octomotion
