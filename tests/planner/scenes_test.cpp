// Every scene shipped in robots/scenes/*.yaml (docs/scenes.md lists them) loads, has a valid
// start and goal, and RRTConnect solves it with the scene's seed within the scene's time limit;
// the path is then re-checked by FCL at ten times the planner's state density and must be free.
// FCL is the exact reference for primitives and meshes; a scene whose environment is a point
// cloud or an OctoMap has no exact geometry, so FCL checks against the OctoMap of its points
// (fcl-octomap, the reference MoveIt users run with sensor data).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "slowdown.h"

namespace octomotion {
namespace {

using test::kSlowdown;

std::string scenesDir() {
  return std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes";
}

std::vector<std::string> sceneFiles() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(scenesDir())) {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool hasSensorData(const SceneSpec& spec) {
  return std::any_of(spec.environment.begin(), spec.environment.end(), [](const auto& object) {
    return object.kind == EnvironmentObject::Kind::kPointCloud ||
           object.kind == EnvironmentObject::Kind::kOctomap;
  });
}

// How many of the states collide according to an FCL-based model (FclCollisionModel or
// FclOctomapCollisionModel, which share this interface).
template <class Model>
std::size_t collidingStates(const Model& model,
                            const std::vector<const ompl::base::State*>& states) {
  const RobotModel& robot = model.robot();
  auto scratch = model.makeScratch();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (const ompl::base::State* state : states) {
    EXPECT_TRUE(stateToConfiguration(robot, state, q, X_WB));
    model.setConfiguration(q.data(), q.size(), X_WB, *scratch);
    colliding += model.inCollision(*scratch) ? 1 : 0;
  }
  return colliding;
}

std::size_t fclCollidingStates(const PlanningScene& scene,
                               const std::vector<const ompl::base::State*>& states) {
  return hasSensorData(scene.spec) ? collidingStates(*scene.fclOctomapModel(), states)
                                   : collidingStates(*scene.fclModel(), states);
}

TEST(Scenes, TheShippedScenesAreAllHere) {
  // The scenes docs/scenes.md describes; a new scene is picked up by the test below by itself.
  const std::vector<std::string> names = sceneFiles();
  for (const char* expected : {"bookshelf.yaml", "cage.yaml", "cluttered_table.yaml",
                               "narrow_passage.yaml", "rooms.yaml", "scan_table.yaml"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
}

class Scene : public ::testing::TestWithParam<std::string> {};

TEST_P(Scene, StartAndGoalAreValidAndRrtConnectFindsAPathFclAgreesIsFree) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string path = scenesDir() + "/" + GetParam();
  SceneOverrides overrides;
  const SceneSpec spec = loadScene(path);
  if (!spec.problem.seed) overrides.seed = 1;  // every run of this test plans the same way
  overrides.time = spec.problem.time * kSlowdown;
  // OMPL takes a seed only before its first random number: the first scene seeds the process and
  // the later ones continue its fixed sequence (the test order is fixed, so every run plans the
  // same way). Silence OMPL's complaint about the later seeds.
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  PlanningScene scene = loadPlanningScene(path, overrides);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ASSERT_TRUE(scene.spec.problem.start && scene.spec.problem.goal)
      << "a shipped scene poses a problem";
  EXPECT_EQ(scene.spec.problem.planner, "RRTConnect");

  const auto& si = scene.setup->getSpaceInformation();
  si->setup();
  const auto& pdef = scene.setup->getProblemDefinition();
  ASSERT_EQ(pdef->getStartStateCount(), 1u);
  const ompl::base::State* start = pdef->getStartState(0);
  ompl::base::ScopedState<> goal(si);
  si->copyState(goal.get(), pdef->getGoal()->as<ompl::base::GoalState>()->getState());
  EXPECT_TRUE(si->isValid(start)) << "start of " << GetParam();
  EXPECT_TRUE(si->isValid(goal.get())) << "goal of " << GetParam();
  EXPECT_EQ(fclCollidingStates(scene, {start, goal.get()}), 0u) << "start or goal, by FCL";

  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved) << GetParam() << ": no path in " << scene.spec.problem.time << " s";
  ASSERT_TRUE(result.path);
  EXPECT_LT(si->distance(result.path->getState(0), start), 1e-9);
  EXPECT_LT(si->distance(result.path->getState(result.path->getStateCount() - 1), goal.get()),
            1e-9);
  for (std::size_t i = 0; i < result.path->getStateCount(); ++i) {
    EXPECT_TRUE(si->isValid(result.path->getState(static_cast<unsigned>(i)))) << "state " << i;
  }

  // FCL at ten times the planner's density.
  ompl::geometric::PathGeometric dense(*result.path);
  dense.interpolate(static_cast<unsigned>(10 * (result.path->getStateCount() - 1) + 1));
  std::vector<const ompl::base::State*> states;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    states.push_back(dense.getState(static_cast<unsigned>(i)));
  }
  EXPECT_EQ(fclCollidingStates(scene, states), 0u)
      << GetParam() << ": of " << states.size() << " path states, checked by "
      << (hasSensorData(scene.spec) ? "fcl-octomap" : "fcl");
}

INSTANTIATE_TEST_SUITE_P(Shipped, Scene, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) {
                           std::string name =
                               param_info.param.substr(0, param_info.param.find('.'));
                           for (char& c : name) {
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace octomotion
