// OMPL integration: RRTConnect solves a rigid-body narrow passage and an arm-in-shelf problem with
// both octree checker paths, and the paths, re-checked by FCL at ten times the planner's state
// density, never collide (conservative rounding never under-approximates).
#include <gtest/gtest.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/octree_validity_checker.h"
#include "octomotion/planner/planning_scene.h"

namespace octomotion {
namespace {

struct Case {
  const char* scene;
  const char* checker;
};

class Planning : public ::testing::TestWithParam<Case> {};

TEST_P(Planning, SolvesAndFclFindsThePathFree) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.checker = GetParam().checker;
  overrides.time = 60;  // a cap for slow (sanitizer) builds; the planner stops when it solves
  overrides.seed = 7;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + GetParam().scene, overrides);
  EXPECT_EQ(scene.checker, GetParam().checker);
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved) << GetParam().scene << " with " << GetParam().checker;
  ASSERT_TRUE(result.path);

  // The planner's own checker accepts every state of the path.
  const auto& si = scene.setup->getSpaceInformation();
  for (std::size_t i = 0; i < result.path->getStateCount(); ++i) {
    ASSERT_TRUE(si->isValid(result.path->getState(static_cast<unsigned>(i))));
  }
  // FCL, at ten times the density.
  ompl::geometric::PathGeometric dense(*result.path);
  dense.interpolate(static_cast<unsigned>(10 * (result.path->getStateCount() - 1) + 1));
  const RobotModel& robot = scene.fcl_model->robot();
  auto fcl = scene.fcl_model->makeScratch();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X_WB));
    scene.fcl_model->setConfiguration(q.data(), q.size(), X_WB, *fcl);
    colliding += scene.fcl_model->inCollision(*fcl) ? 1 : 0;
  }
  EXPECT_EQ(colliding, 0u) << "of " << dense.getStateCount() << " states";
  // The path starts and ends where the scene says.
  EXPECT_LT(si->distance(dense.getState(0), scene.setup->getProblemDefinition()->getStartState(0)),
            1e-9);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Planning,
                         ::testing::Values(Case{"narrow_passage.yaml", "octree-fused"},
                                           Case{"narrow_passage.yaml", "octree"},
                                           Case{"bookshelf.yaml", "octree-fused"},
                                           Case{"bookshelf.yaml", "octree"}),
                         [](const auto& param_info) {
                           std::string name =
                               std::string(param_info.param.scene) + "_" + param_info.param.checker;
                           for (char& c : name) {
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(Planning, OneLinkUrdfIsAFreeFlyingBody) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.seed = 5;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/l_piece_urdf.yaml", overrides);
  EXPECT_TRUE(scene.model->robot().isFreeFlying());
  // auto resolution for a rigid body: max(scene diagonal / 1024, robot diagonal / 32).
  EXPECT_GT(*scene.spec.octree.resolution, 0.005);
  EXPECT_LT(*scene.spec.octree.resolution, 0.02);
  const auto si = scene.setup->getSpaceInformation();
  const auto pdef = scene.setup->getProblemDefinition();
  EXPECT_TRUE(si->isValid(pdef->getStartState(0)));
  ompl::base::ScopedState<> in_wall(si);
  si->copyState(in_wall.get(), pdef->getStartState(0));
  in_wall->as<ompl::base::SE3StateSpace::StateType>()->setX(0.0);  // upright, inside the wall
  EXPECT_FALSE(si->isValid(in_wall.get()));
}

TEST(Planning, CheckerRejectsNonFiniteAndOutOfBoundsStates) {
  PlanningScene scene =
      loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml");
  const auto& si = scene.setup->getSpaceInformation();
  ompl::base::ScopedState<> state(si);
  const auto start = scene.setup->getProblemDefinition()->getStartState(0);
  si->copyState(state.get(), start);
  EXPECT_TRUE(si->isValid(state.get()));
  auto* values = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  values[1] = std::nan("");
  EXPECT_FALSE(si->isValid(state.get()));
  values[1] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(si->isValid(state.get()));
  values[1] = 100.0;  // beyond the joint limit
  EXPECT_FALSE(si->isValid(state.get()));
  EXPECT_EQ(si->getStateValidityChecker()->clearance(state.get()), 0.0);
}

}  // namespace
}  // namespace octomotion
