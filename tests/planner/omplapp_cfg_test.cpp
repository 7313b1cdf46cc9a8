// OMPL.app problems load and plan with OMPL.app's conventions: the robot is shifted so that the
// mean of its vertices is its origin, and the default resolution follows the scene's and the
// robot's size.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

// An axis-aligned box as an OBJ file (outward faces).
void writeBoxObj(const fs::path& path, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::ofstream out(path);
  for (int i = 0; i < 8; ++i) {
    out << "v " << ((i & 1) ? hi.x() : lo.x()) << ' ' << ((i & 2) ? hi.y() : lo.y()) << ' '
        << ((i & 4) ? hi.z() : lo.z()) << '\n';
  }
  // Vertex i+1 has bits x=1, y=2, z=4.
  out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 2 4 8 6\nf 1 5 7 3\n";
}

class OmplAppCfg : public ::testing::Test {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    dir_ = fs::temp_directory_path() / "octomotion_omplapp_cfg_test";
    fs::create_directories(dir_);
    // The world: a 0.4 m cube at the origin. The robot: a 0.1 m cube whose vertices are centred
    // on (1.05, 0, 0) in its file, so only OMPL.app's centring puts it at the state's position.
    writeBoxObj(dir_ / "world.obj", Eigen::Vector3d::Constant(-0.2),
                Eigen::Vector3d::Constant(0.2));
    writeBoxObj(dir_ / "robot.obj", Eigen::Vector3d(1.0, -0.05, -0.05),
                Eigen::Vector3d(1.1, 0.05, 0.05));
    std::ofstream cfg(dir_ / "cube.cfg");
    cfg << "[problem]\nname = cube\nrobot = robot.obj\nworld = world.obj\n"
        << "start.x = -0.6\nstart.y = 0\nstart.z = 0\nstart.theta = 0\n"
        << "start.axis.x = 1\nstart.axis.y = 0\nstart.axis.z = 0\n"
        << "goal.x = 0.6\ngoal.y = 0\ngoal.z = 0\ngoal.theta = 1.5707963\n"
        << "goal.axis.x = 0\ngoal.axis.y = 0\ngoal.axis.z = 1\n"
        << "volume.min.x = -1\nvolume.min.y = -1\nvolume.min.z = -1\n"
        << "volume.max.x = 1\nvolume.max.y = 1\nvolume.max.z = 1\n"
        << "[benchmark]\ntime_limit = 30\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  bool validAt(PlanningScene& scene, double x, double y, double z) {
    const auto si = scene.setup->getSpaceInformation();
    ompl::base::ScopedState<ompl::base::SE3StateSpace> s(si);
    s->setXYZ(x, y, z);
    s->rotation().setIdentity();
    return si->isValid(s.get());
  }

  fs::path dir_;
};

TEST_F(OmplAppCfg, RobotIsCentredOnItsVertexMean) {
  // The voxels (refine none): FCL's mesh surfaces do not meet with one cube inside the other.
  SceneOverrides voxels;
  voxels.refine = RefineMode::kNone;
  PlanningScene scene = loadPlanningScene((dir_ / "cube.cfg").string(), voxels);
  EXPECT_TRUE(scene.model->robot().isFreeFlying());
  // Centred, the robot cube at the origin overlaps the world cube; uncentred it would sit at
  // x = 1.0..1.1, clear of it.
  EXPECT_FALSE(validAt(scene, 0, 0, 0));
  EXPECT_FALSE(validAt(scene, 0.22, 0, 0));  // 2 cm of overlap
  EXPECT_TRUE(validAt(scene, 0.3, 0, 0));    // 5 cm of gap
  EXPECT_TRUE(validAt(scene, -0.6, 0, 0));
  EXPECT_FALSE(validAt(scene, 2.0, 0, 0));  // outside volume.max
}

TEST_F(OmplAppCfg, DefaultResolutionFollowsSceneAndRobotSize) {
  PlanningScene scene = loadPlanningScene((dir_ / "cube.cfg").string());
  // max(scene diagonal / 1024, robot diagonal / 32): the volume's diagonal is 2*sqrt(3) m, the
  // robot's 0.1*sqrt(3) m (its vertices pass through assimp's single precision).
  const double expected = std::max(2 * std::sqrt(3.0) / 1024, 0.1 * std::sqrt(3.0) / 32);
  ASSERT_TRUE(scene.spec.octree.resolution.has_value());
  EXPECT_NEAR(*scene.spec.octree.resolution, expected, 1e-8);
  EXPECT_DOUBLE_EQ(scene.model->report().grid.voxelSize(), *scene.spec.octree.resolution);
  EXPECT_DOUBLE_EQ(scene.spec.problem.time, 30.0);
  // The command line can still choose.
  SceneOverrides overrides;
  overrides.resolution = 0.02;
  EXPECT_DOUBLE_EQ(
      loadPlanningScene((dir_ / "cube.cfg").string(), overrides).model->report().grid.voxelSize(),
      0.02);
}

TEST_F(OmplAppCfg, PlansAroundTheObstacle) {
  SceneOverrides overrides;
  overrides.seed = 11;
  PlanningScene scene = loadPlanningScene((dir_ / "cube.cfg").string(), overrides);
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved);
  std::ostringstream path;
  writePath(scene, *result.path, path);
  std::istringstream lines(path.str());
  std::string first;
  std::getline(lines, first);
  std::istringstream fields(first);
  double x = 0;
  fields >> x;
  EXPECT_NEAR(x, -0.6, 1e-9);
}

}  // namespace
}  // namespace octomotion
