// distanceToBlack: the distance from a point to the nearest black voxel, against brute force over
// every voxel of small random trees (fixed seed), with and without a distance to beat.
#include "octomotion/octree/distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "dense_grid.h"

namespace octomotion {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Minimum over the black voxels of the distance from p to the closed voxel box.
double bruteForce(const test::DenseGrid& dense, const WorldGrid& grid, const Eigen::Vector3d& p) {
  double best = kInf;
  for (const Voxel& v : dense.voxels()) {
    const Cube c{0, v};
    const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
    best = std::min(best, (p - p.cwiseMax(lo).cwiseMin(hi)).norm());
  }
  return best;
}

TEST(DistanceToBlack, MatchesBruteForceOnRandomTrees) {
  std::mt19937_64 rng(26);
  const WorldGrid grid(Eigen::Vector3d(-0.3, 0.1, 0.2), 0.05, 4);
  const Eigen::Vector3d lo = grid.origin().array() - 0.2;
  const Eigen::Vector3d size = Eigen::Vector3d::Constant(grid.sideMetres() + 0.4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const test::DenseGrid dense = test::randomShape(grid.depth(), rng, 2, 6);
    const Octree tree = dense.toTree(grid);
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d p =
          lo + size.cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
      const double expected = bruteForce(dense, grid, p);
      EXPECT_NEAR(distanceToBlack(tree, p, kInf), expected, 1e-12) << trial << " " << i;
      // With a distance to beat: the smaller of the two, and exactly `best` when not beaten.
      const double best = 0.2 * unit(rng);
      const double bounded = distanceToBlack(tree, p, best);
      if (expected < best - 1e-12) {
        EXPECT_NEAR(bounded, expected, 1e-12) << trial << " " << i;
      } else if (expected > best + 1e-12) {
        EXPECT_EQ(bounded, best) << trial << " " << i;
      }
    }
  }
}

TEST(DistanceToBlack, InsideABlackVoxelIsZero) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.1, 3);
  const Octree tree = Octree::fromVoxels(grid, {{2, 5, 1}});
  EXPECT_EQ(distanceToBlack(tree, grid.voxelCenter({2, 5, 1}), kInf), 0.0);
  EXPECT_NEAR(distanceToBlack(tree, grid.voxelCenter({4, 5, 1}), kInf), 0.15, 1e-12);
}

TEST(DistanceToBlack, EmptyAndFullTrees) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.1, 3);
  EXPECT_EQ(distanceToBlack(Octree(grid), Eigen::Vector3d(0.3, 0.3, 0.3), kInf), kInf);
  EXPECT_EQ(distanceToBlack(Octree(grid), Eigen::Vector3d(0.3, 0.3, 0.3), 2.0), 2.0);
  const Octree full = Octree::full(grid);
  EXPECT_EQ(distanceToBlack(full, Eigen::Vector3d(0.3, 0.3, 0.3), kInf), 0.0);
  EXPECT_NEAR(distanceToBlack(full, Eigen::Vector3d(-0.3, 0.4, 0.2), kInf), 0.3, 1e-12);
  EXPECT_EQ(distanceToBlack(full, Eigen::Vector3d(-0.3, 0.4, 0.2), 0.1), 0.1);
}

}  // namespace
}  // namespace octomotion
