// The real Panda planning its SRDF group panda_arm with the fingers held at 0.065 m
// (tests/data/scenes/panda_arm_group.yaml): the plan has the group's 7 dimensions and is free
// for exact FCL on the *full* robot (fingers at 0.065); the octree model of the reduced robot
// agrees with FCL on random states within the conservative contract (no missed contact; a
// rejection FCL calls free lies within the margin of docs/validation.md §2). Skipped without
// ../shared/data/panda.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "joint_states.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/held_joints.h"

namespace octomotion {
namespace {

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
const std::string kScene = std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/panda_arm_group.yaml";

class PandaGroup : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    full_ = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
    full_->loadSrdfFile(kPanda + "/panda.srdf");
  }
  PlanningScene load(CheckerKind checker, std::vector<std::string>* warnings) {
    SceneOverrides overrides;
    overrides.resolution = 0.02;
    // Finer self trees: at 2 cm the held-open fingers' voxels reach the wrist's.
    overrides.self_link_resolution = 0.005;
    overrides.checker = checker;
    return loadPlanningScene(kScene, overrides,
                             [warnings](const std::string& m) { warnings->push_back(m); });
  }
  std::optional<RobotModel> full_;
};

TEST_F(PandaGroup, PlansInSevenDimensionsAndTheFullRobotFindsThePathFree) {
  std::vector<std::string> warnings;
  PlanningScene scene = load(CheckerKind::kOctreeFused, &warnings);
  const RobotModel& robot = scene.model->robot();
  ASSERT_EQ(robot.variableCount(), 7);
  for (int v = 0; v < 7; ++v) {
    EXPECT_EQ(robot.variables()[static_cast<std::size_t>(v)].name,
              "panda_joint" + std::to_string(v + 1));
  }
  EXPECT_EQ(scene.setup->getStateSpace()->getDimension(), 7u);
  // The fingers beyond their limit: one warning naming the joint (its mimic follows silently).
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("panda_finger_joint1"), std::string::npos);
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved);
  // Exact FCL on the full robot, at the expanded states: fingers at 0.065, the arm as planned.
  const FclCollisionModel fcl(*full_, *scene.environment);
  auto scratch = fcl.makeScratch();
  std::vector<double> q(7);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  ompl::geometric::PathGeometric dense(*result.path);
  dense.interpolate(static_cast<unsigned>(10 * (result.path->getStateCount() - 1) + 1));
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X));
    const std::vector<double> q_full = expandConfiguration(*full_, robot, q);
    ASSERT_EQ(q_full.size(), 8u);
    EXPECT_DOUBLE_EQ(q_full[7], 0.065);
    fcl.setConfiguration(q_full.data(), q_full.size(), Eigen::Isometry3d::Identity(), *scratch);
    colliding += fcl.inCollision(*scratch) ? 1 : 0;
  }
  EXPECT_EQ(colliding, 0u) << "of " << dense.getStateCount() << " states";
  // The written path names the group's joints.
  std::ostringstream out;
  writePath(scene, *result.path, out);
  EXPECT_EQ(out.str().rfind("# joints: panda_joint1 panda_joint2", 0), 0u);
}

TEST_F(PandaGroup, OctreeAgreesWithFclWithinTheConservativeContract) {
  std::vector<std::string> warnings;
  for (CheckerKind checker : {CheckerKind::kOctreeFused, CheckerKind::kOctree}) {
    PlanningScene scene = load(checker, &warnings);
    const RobotModel& robot = scene.model->robot();
    const OctreeBackend octree(scene.model, octreeCheckerPath(checker));
    const FclCollisionModel& fcl = *scene.fclModel();
    auto o = octree.makeBackendScratch();
    auto f = fcl.makeScratch();
    const CollisionModelReport& report = scene.model->report();
    // docs/validation.md §2: conservative voxels add at most a voxel diagonal of each tree.
    const double s3 = std::sqrt(3.0);
    const double env_margin = s3 * (report.grid.voxelSize() + report.link_resolution) + 1e-6;
    const double self_margin = 2 * s3 * report.self_link_resolution + 1e-6;
    std::size_t contacts = 0;
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    for (const std::vector<double>& q : test::uniformJointStates(robot, 400, 11)) {
      fcl.setConfiguration(q.data(), q.size(), I, *f);
      const bool fe = fcl.environmentInCollision(*f), fs = fcl.selfInCollision(*f);
      const bool oe = octree.environmentInCollision(q.data(), q.size(), I, *o);
      const bool os = octree.selfInCollision(q.data(), q.size(), I, *o);
      contacts += fe || fs;
      EXPECT_FALSE(fe && !oe) << "missed environment contact";
      EXPECT_FALSE(fs && !os) << "missed self contact";
      if (oe && !fe) {
        EXPECT_LE(fcl.environmentDistance(*f, 2 * env_margin), env_margin);
      }
      if (os && !fs) {
        EXPECT_LE(fcl.selfDistance(*f, 2 * self_margin), self_margin);
      }
    }
    EXPECT_GT(contacts, 0u);  // the states test both answers
  }
}

}  // namespace
}  // namespace octomotion
