// The MotionBenchMaker Panda problems load without conversion and plan in the group's 7
// dimensions (issue 27): one problem of each of the 7 sets, read straight from its MoveIt
// PlanningScene and MotionPlanRequest YAML with the Panda's own URDF and SRDF, is solved by
// RRTConnect on the default octree checker with the discrete motion validator, and exact FCL on
// the *full* robot (fingers held at the request's 0.065 m) finds every state of the path
// interpolated at 100x its density free. Skipped without ../shared/data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "mbm_problems.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/held_joints.h"

namespace octomotion {
namespace {

TEST(MbmPlanning, OneProblemOfEachSetPlansInSevenDimensionsAndFclFindsThePathFreeAt100x) {
  const test::MbmProblems set;
  const std::string panda = test::MbmProblems::panda();
  if (set.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
    GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  RobotModel full = RobotModel::fromUrdfFile(panda + "/panda.urdf");
  full.loadSrdfFile(panda + "/panda.srdf");
  const std::vector<test::MbmProblem> problems = set.firstOfEachSet();
  ASSERT_EQ(problems.size(), 7u);
  for (const test::MbmProblem& p : problems) {
    SCOPED_TRACE(p.request);
    const std::string scene_path = set.folder() + "/" + p.set + ".yaml";
    test::MbmProblems::writeScene(scene_path, p,
                                  ", time: 60, seed: 1");  // a cap: RRTConnect stops when solved
    // The discrete validator: the certified one is slow on some of these problems under the
    // sanitizers (its self pairs are checked at a voxel of travel); FCL re-checks either way.
    SceneOverrides o;
    o.motion_validator = MotionValidatorKind::kDiscrete;
    PlanningScene scene = loadPlanningScene(scene_path, o, [](const std::string&) {});
    const RobotModel& robot = scene.model->robot();
    ASSERT_EQ(robot.variableCount(), 7);
    EXPECT_EQ(scene.setup->getStateSpace()->getDimension(), 7u);
    const PlanResult result = plan(scene);
    ASSERT_TRUE(result.solved);
    const FclCollisionModel fcl(full, *scene.environment);
    auto scratch = fcl.makeScratch();
    ompl::geometric::PathGeometric dense(*result.path);
    dense.interpolate(static_cast<unsigned>(100 * (result.path->getStateCount() - 1) + 1));
    std::vector<double> q(7);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
      ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X));
      const std::vector<double> q_full = expandConfiguration(full, robot, q);
      ASSERT_EQ(q_full.size(), 8u);  // panda_finger_joint2 mimics joint 1
      EXPECT_DOUBLE_EQ(q_full[7], 0.065);
      fcl.setConfiguration(q_full.data(), q_full.size(), Eigen::Isometry3d::Identity(), *scratch);
      colliding += fcl.inCollision(*scratch) ? 1 : 0;
    }
    EXPECT_EQ(colliding, 0u) << "of " << dense.getStateCount() << " states";
  }
}

}  // namespace
}  // namespace octomotion
