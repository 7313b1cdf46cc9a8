// The certified motion validator on the real Panda (issue 29): one MotionBenchMaker problem
// (the first of the first set), read from its MoveIt scene and request with
// ../shared/data/panda, planned by RRTConnect with the default (certified) validator; exact FCL
// on the full robot (fingers held at the request's 0.065 m) finds every state of the path free
// at 100 times its state density. Skipped without ../shared/data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "mbm_problems.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/held_joints.h"

namespace octomotion {
namespace {

TEST(CertifiedMbm, APandaPathIsFreeForFclAtAHundredTimesItsDensity) {
  const test::MbmProblems set;
  const std::string panda = test::MbmProblems::panda();
  if (set.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
    GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  RobotModel full = RobotModel::fromUrdfFile(panda + "/panda.urdf");
  full.loadSrdfFile(panda + "/panda.srdf");
  const test::MbmProblem p = set.firstOfEachSet().front();
  const std::string scene_path = set.folder() + "/certified.yaml";
  std::ofstream(scene_path) << "robot: {urdf: " << panda << "/panda.urdf, srdf: " << panda
                            << "/panda.srdf}\nenvironment:\n  - moveit_scene: " << p.scene
                            << "\nproblem: {moveit_request: " << p.request
                            << ", time: 60, seed: 1}\n";  // a cap: RRTConnect stops when solved
  PlanningScene scene = loadPlanningScene(scene_path, {}, [](const std::string&) {});
  ASSERT_TRUE(dynamic_cast<const CertifiedMotionValidator*>(
      scene.setup->getSpaceInformation()->getMotionValidator().get()));
  const RobotModel& robot = scene.model->robot();
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved) << p.request;
  const FclCollisionModel fcl(full, *scene.environment);
  auto scratch = fcl.makeScratch();
  ompl::geometric::PathGeometric dense(*result.path);
  dense.interpolate(static_cast<unsigned>(100 * (result.path->getStateCount() - 1) + 1));
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X));
    const std::vector<double> q_full = expandConfiguration(full, robot, q);
    fcl.setConfiguration(q_full.data(), q_full.size(), Eigen::Isometry3d::Identity(), *scratch);
    colliding += fcl.inCollision(*scratch) ? 1 : 0;
  }
  EXPECT_EQ(colliding, 0u) << "of " << dense.getStateCount() << " states, " << p.request;
}

}  // namespace
}  // namespace octomotion
