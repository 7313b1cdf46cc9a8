// The library's defaults solve real problems (issue 29, item 3): a grasp-like state of the real
// Panda, its fingers 4 mm from an object between them (FCL's distance), is accepted by a model
// built with the default options and by a scene loaded with the default settings (whose start
// and goal must be free), and FCL agrees that it is free. The same state is rejected by the old
// defaults (refine none: the voxels' margin), so the test is not vacuous. Skipped without the
// Panda under ../shared/data.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace octomotion {
namespace {

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
constexpr double kGap = 0.004;  // metres from each finger to the object

RobotModel loadPanda() {
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  return robot;
}

// The arm bent over the floor, hand pointing down, fingers wide open (0.04 each).
std::vector<double> graspState() {
  return {0.0, 0.3, 0.0, -2.0, 0.0, 2.3, 0.785, 0.04};
}

// A box between the fingers: 2 cm along the hand's x and z, `half_width` either side of the
// fingers' midpoint along the closing axis (the hand's y), its centre 4.5 cm down the fingers.
EnvironmentObject boxBetweenFingers(const RobotModel& robot, const std::vector<double>& q,
                                    double half_width) {
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data);
  const Eigen::Isometry3d& X_WH = data.linkPose(robot.linkIndex("panda_hand"));
  const Eigen::Vector3d left = data.linkPose(robot.linkIndex("panda_leftfinger")).translation();
  const Eigen::Vector3d right = data.linkPose(robot.linkIndex("panda_rightfinger")).translation();
  EnvironmentObject box;
  box.name = "object";
  box.primitive = Box{Eigen::Vector3d(0.01, half_width, 0.01)};
  box.X_WO = X_WH;
  box.X_WO.translation() = (left + right) / 2 + X_WH.linear() * Eigen::Vector3d(0, 0, 0.045);
  return box;
}

double fclDistance(const RobotModel& robot, const std::vector<double>& q,
                   const EnvironmentObject& object) {
  const FclCollisionModel fcl(robot, EnvironmentGeometry::load({object}));
  auto scratch = fcl.makeScratch();
  fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch);
  return fcl.environmentDistance(*scratch);
}

// The box whose FCL distance to the robot is kGap (to 20 um), by bisection on its width.
EnvironmentObject graspedObject(const RobotModel& robot, const std::vector<double>& q) {
  double narrow = 0.002, wide = 0.04;
  EXPECT_GT(fclDistance(robot, q, boxBetweenFingers(robot, q, narrow)), kGap);
  EXPECT_EQ(fclDistance(robot, q, boxBetweenFingers(robot, q, wide)), 0.0);
  for (int i = 0; i < 40; ++i) {
    const double mid = (narrow + wide) / 2;
    (fclDistance(robot, q, boxBetweenFingers(robot, q, mid)) > kGap ? narrow : wide) = mid;
    if (wide - narrow < 1e-6) break;
  }
  return boxBetweenFingers(robot, q, narrow);
}

TEST(Defaults, AcceptAGraspFourMillimetresFromAnObjectAsFclDoes) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) {
    GTEST_SKIP() << "no Panda under ../shared/data";
  }
  const RobotModel robot = loadPanda();
  const std::vector<double> q = graspState();
  ASSERT_EQ(q.size(), static_cast<std::size_t>(robot.variableCount()));
  const EnvironmentObject object = graspedObject(robot, q);
  const EnvironmentGeometry environment = EnvironmentGeometry::load({object});

  // FCL: free, the fingers kGap from the object, and no self contact.
  const FclCollisionModel fcl(robot, environment);
  auto exact = fcl.makeScratch();
  fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
  EXPECT_NEAR(fcl.environmentDistance(*exact), kGap, 2e-5);
  ASSERT_FALSE(fcl.inCollision(*exact));

  // The defaults accept it, on both checker paths.
  const OctreeCollisionModel defaults(robot, environment, CollisionModelOptions{});
  EXPECT_EQ(defaults.refine(), RefineMode::kExact);
  EXPECT_EQ(defaults.report().refine, RefineMode::kExact);
  CheckScratch scratch = defaults.makeScratch();
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(defaults.inCollision(q.data(), q.size(), I, CheckerPath::kFused, scratch));
  EXPECT_FALSE(defaults.inCollision(q.data(), q.size(), I, CheckerPath::kMoveTree, scratch));

  // The voxels alone (the old defaults) reject it: it lies within their margin.
  CollisionModelOptions voxels;
  voxels.refine = RefineMode::kNone;
  const OctreeCollisionModel old_defaults(robot, environment, voxels);
  CheckScratch old_scratch = old_defaults.makeScratch();
  EXPECT_TRUE(old_defaults.inCollision(q.data(), q.size(), I, CheckerPath::kFused, old_scratch));

  // And so does the object moved into the fingers by 2 mm more than the gap: every default
  // still reports the contact FCL finds.
  EnvironmentObject touching = object;
  Box& box = std::get<Box>(touching.primitive);
  box.half_extents.y() += kGap + 0.002;
  const EnvironmentGeometry touching_environment = EnvironmentGeometry::load({touching});
  const FclCollisionModel fcl_touching(robot, touching_environment);
  auto touching_exact = fcl_touching.makeScratch();
  fcl_touching.setConfiguration(q.data(), q.size(), I, *touching_exact);
  ASSERT_TRUE(fcl_touching.inCollision(*touching_exact));
  const OctreeCollisionModel defaults_touching(robot, touching_environment, {});
  CheckScratch touching_scratch = defaults_touching.makeScratch();
  EXPECT_TRUE(
      defaults_touching.inCollision(q.data(), q.size(), I, CheckerPath::kFused, touching_scratch));
}

TEST(Defaults, ASceneWhoseGoalIsTheGraspLoadsWithTheDefaultSettings) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) {
    GTEST_SKIP() << "no Panda under ../shared/data";
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const RobotModel robot = loadPanda();
  const std::vector<double> goal = graspState();
  const EnvironmentObject object = graspedObject(robot, goal);
  const Eigen::Vector3d p = object.X_WO.translation();
  const Eigen::Quaterniond r(object.X_WO.linear());
  const Eigen::Vector3d half = std::get<Box>(object.primitive).half_extents;
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "octomotion_defaults_grasp.yaml";
  {
    std::ofstream out(path);
    out.precision(17);
    out << "robot: {urdf: " << kPanda << "/panda.urdf, srdf: " << kPanda << "/panda.srdf}\n"
        << "environment:\n  - {name: object, box: {size: [" << 2 * half.x() << ", " << 2 * half.y()
        << ", " << 2 * half.z() << "]}, pose: {xyz: [" << p.x() << ", " << p.y() << ", " << p.z()
        << "], quat: [" << r.x() << ", " << r.y() << ", " << r.z() << ", " << r.w() << "]}}\n"
        << "problem:\n  start: [0, 0, 0, -1.5, 0, 1.5, 0.785, 0.04]\n  goal: [";
    for (std::size_t i = 0; i < goal.size(); ++i) out << (i ? ", " : "") << goal[i];
    out << "]\n";
  }
  // The default settings (require_free_start_goal: a goal the model rejects is an error).
  const PlanningScene scene = loadPlanningScene(path.string());
  EXPECT_EQ(scene.model->refine(), RefineMode::kExact);
  const auto fcl = scene.fclModel();
  auto exact = fcl->makeScratch();
  fcl->setConfiguration(goal.data(), goal.size(), Eigen::Isometry3d::Identity(), *exact);
  EXPECT_FALSE(fcl->inCollision(*exact));
  EXPECT_LT(fcl->environmentDistance(*exact), kGap + 1e-4);
  // The old defaults refuse it: the goal lies within the voxels' margin.
  SceneOverrides voxels;
  voxels.refine = RefineMode::kNone;
  EXPECT_THROW(loadPlanningScene(path.string(), voxels), Error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace octomotion
