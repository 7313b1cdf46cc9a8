// Clearance (OctreeCollisionModel::clearanceLowerBound*): the point-octree method (nearest
// black-leaf centre per leaf level, minus the level's half cube diagonal) and the environment-tree
// method (exact distance to black voxels) must both be lower bounds of the distance between the
// robot and the environment's black voxels, checked against brute force over every black leaf and
// dense samples of the links' geometry, and the point method must stay within its documented
// looseness of the tree method. The environment mixes boxes and a point cloud (an XYZ file).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "octomotion/planner/model/collision_model.h"
#include "snake_robot.h"

namespace octomotion {
namespace {

constexpr double kResolution = 0.01;

using test::snakeUrdf;

struct Fixture {
  std::string cloud_path;
  std::unique_ptr<OctreeCollisionModel> points, tree;

  Fixture() {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    // A noisy wall of points at x ~ 0.55 and a cluster above the base.
    cloud_path = ::testing::TempDir() + "clearance_cloud.xyz";
    std::ofstream out(cloud_path);
    for (int i = 0; i < 3000; ++i) {
      out << 0.55 + 0.01 * u(rng) << " " << 0.4 * u(rng) << " " << 0.3 * u(rng) << "\n";
    }
    for (int i = 0; i < 500; ++i) {
      out << 0.2 + 0.05 * u(rng) << " " << 0.05 * u(rng) << " " << 0.3 + 0.05 * u(rng) << "\n";
    }
    out.close();
    std::vector<EnvironmentObject> objects;
    EnvironmentObject cloud;
    cloud.name = "cloud";
    cloud.kind = EnvironmentObject::Kind::kPointCloud;
    cloud.file = cloud_path;
    objects.push_back(cloud);
    for (int i = 0; i < 4; ++i) {
      EnvironmentObject box;
      box.name = "box" + std::to_string(i);
      box.primitive = Box{Eigen::Vector3d(0.05 + 0.05 * std::abs(u(rng)), 0.05, 0.08)};
      box.X_WO.translation() =
          Eigen::Vector3d(0.35 * u(rng), 0.35 + 0.1 * std::abs(u(rng)), 0.2 * u(rng)) *
          (i % 2 ? 1.0 : -1.0);
      objects.push_back(box);
    }
    const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
    const RobotModel robot = RobotModel::fromUrdfString(snakeUrdf(6, 1.5), "snake.urdf", ".");
    CollisionModelOptions o;
    o.resolution = kResolution;
    o.refine = RefineMode::kNone;  // the voxels' answers
    o.clearance = ClearanceMethod::kPointOctree;
    points = std::make_unique<OctreeCollisionModel>(robot, env, o);
    o.clearance = ClearanceMethod::kEnvironmentTree;
    tree = std::make_unique<OctreeCollisionModel>(robot, env, o);
  }
  ~Fixture() { std::remove(cloud_path.c_str()); }
};

double distanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi) {
  return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
}

TEST(Clearance, PointOctreeIsALowerBoundWithinItsLooseness) {
  Fixture f;
  const OctreeCollisionModel& m = *f.points;
  ASSERT_EQ(m.environment(), f.tree->environment());
  const WorldGrid& g = m.grid();
  // Every black leaf of the environment, as world boxes: the brute-force oracle.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> leaves;
  int max_level = 0;
  m.environment().forEachBlackLeaf([&](const Cube& c) {
    leaves.emplace_back(g.cubeMin(c), g.cubeMax(c));
    max_level = std::max(max_level, c.level);
  });
  ASSERT_GT(leaves.size(), 1000u);
  // Documented looseness of the point method against the tree method: the nearest cube's half
  // diagonal, plus the float slack (far below a micrometre per metre).
  const double h_max = std::sqrt(3.0) / 2 * kResolution * (1 << max_level);
  // Against the geometry: the tree method is loose by up to the spheres' diameter (level-3
  // cells: 8 voxels a side) plus the conservative voxelization (a voxel diagonal per side).
  const double sphere_diameter = std::sqrt(3.0) * 8 * kResolution;
  const double looseness_geometry = h_max + sphere_diameter + 2 * std::sqrt(3.0) * kResolution;

  std::mt19937_64 rng(9);
  CheckScratch scratch = m.makeScratch();
  CheckScratch tree_scratch = f.tree->makeScratch();
  int free_states = 0, close_states = 0;
  for (int k = 0; k < 300; ++k) {
    std::vector<double> q;
    for (const Variable& v : m.robot().variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    const bool hit = m.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(),
                                   CheckerPath::kFused, scratch);
    f.tree->inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(), CheckerPath::kFused,
                        tree_scratch);
    if (hit) continue;
    ++free_states;
    const double by_points = m.clearanceLowerBound(scratch);
    const double by_tree = f.tree->clearanceLowerBound(tree_scratch);
    EXPECT_EQ(by_points, m.clearanceLowerBoundPoints(scratch));
    EXPECT_EQ(by_tree, m.clearanceLowerBoundTree(scratch));
    // Point method <= tree method (each cube is at least d - h away), and not much below it.
    EXPECT_LE(by_points, by_tree + 1e-12) << "state " << k;
    EXPECT_GE(by_points, std::max(0.0, by_tree - h_max - 1e-4)) << "state " << k;

    // Brute force: distance from samples of every link box (8 x 4 x 4 cm, a 1 cm lattice
    // through its volume) to every black leaf. The robot's voxels cover the geometry, so their
    // distance to the environment, and so any lower bound, is at most this. Leaves farther
    // from a link's centre than the best so far plus the box's half diagonal cannot matter.
    const double link_half_diagonal = Eigen::Vector3d(0.04, 0.02, 0.02).norm();
    double brute = std::numeric_limits<double>::infinity();
    for (int l = 0; l < m.robot().linkCount(); ++l) {
      const Eigen::Vector3d c = scratch.robot.linkPose(l) * Eigen::Vector3d(0.05, 0, 0);
      for (const auto& [lo, hi] : leaves) brute = std::min(brute, distanceToBox(c, lo, hi));
    }
    for (int l = 0; l < m.robot().linkCount(); ++l) {
      const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(l);
      const Eigen::Vector3d c = X_WL * Eigen::Vector3d(0.05, 0, 0);
      for (const auto& [lo, hi] : leaves) {
        if (distanceToBox(c, lo, hi) - link_half_diagonal >= brute) continue;
        for (double x = 0.01; x <= 0.09 + 1e-9; x += 0.01) {
          for (double y = -0.02; y <= 0.02 + 1e-9; y += 0.01) {
            for (double z = -0.02; z <= 0.02 + 1e-9; z += 0.01) {
              brute = std::min(brute, distanceToBox(X_WL * Eigen::Vector3d(x, y, z), lo, hi));
            }
          }
        }
      }
    }
    EXPECT_LE(by_points, brute) << "state " << k;
    EXPECT_LE(by_tree, brute) << "state " << k;
    EXPECT_GE(by_points, brute - looseness_geometry - 0.01) << "state " << k;
    if (brute < 0.1) ++close_states;
  }
  // The states must include free ones near obstacles, where the bound matters.
  EXPECT_GT(free_states, 100);
  EXPECT_GT(close_states, 20);
}

TEST(Clearance, EmptyEnvironmentIsInfinite) {
  const RobotModel robot = RobotModel::fromUrdfString(snakeUrdf(3, 1.0), "snake.urdf", ".");
  CollisionModelOptions o;
  o.resolution = kResolution;
  o.refine = RefineMode::kNone;  // the voxels' answers
  const OctreeCollisionModel m(robot, EnvironmentGeometry::load({}), o);
  CheckScratch scratch = m.makeScratch();
  const std::vector<double> q(static_cast<std::size_t>(robot.variableCount()), 0.0);
  m.robot().forwardKinematics(q.data(), q.size(), scratch.robot);
  EXPECT_EQ(m.clearanceLowerBound(scratch), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace octomotion
