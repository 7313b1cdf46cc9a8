// ClearanceGrid::addBlack (world updates lower the grid instead of rebuilding it): after black
// voxels are added within a voxel box, the lowered grid is a lower bound of the grid rebuilt on
// the changed tree in every cell (so of the true distance) and never above the old grid.
#include <gtest/gtest.h>

#include <random>

#include "dense_grid.h"
#include "octomotion/motion/clearance_grid.h"
#include "octomotion/octree/set_ops.h"

namespace octomotion {
namespace {

TEST(ClearanceGridUpdate, AddBlackStaysBelowTheRebuiltGrid) {
  std::mt19937_64 rng(41);
  const int depth = 5;
  const std::uint32_t side = 1u << depth;
  const WorldGrid grid(Eigen::Vector3d(-0.3, 0.2, 0.0), 0.05, depth);
  int lowered_cells = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Octree before = test::randomShape(depth, rng, 1, 2).toTree(grid);
    // A few voxels added in a random box.
    std::uniform_int_distribution<std::uint32_t> at(0, side - 4);
    const Voxel lo{at(rng), at(rng), at(rng)};
    const VoxelBounds added{lo, {lo.x + 3, lo.y + 2, lo.z + 1}};
    std::vector<Voxel> voxels = {lo, added.max};
    const Octree after = unite(before, Octree::fromVoxels(grid, voxels));
    for (int level = 0; level <= 2; ++level) {
      const std::size_t cells = std::size_t{1} << (3 * (depth - level));
      ClearanceGrid lowered(before, cells);
      lowered.addBlack(added);
      const ClearanceGrid rebuilt(after, cells);
      const ClearanceGrid old(before, cells);
      const double c = rebuilt.cellVoxels();
      for (double z = c / 2; z < side; z += c) {
        for (double y = c / 2; y < side; y += c) {
          for (double x = c / 2; x < side; x += c) {
            const double g[3] = {x, y, z};
            ASSERT_LE(lowered.clearance(g), rebuilt.clearance(g)) << x << " " << y << " " << z;
            ASSERT_LE(lowered.clearance(g), old.clearance(g));
            lowered_cells += lowered.clearance(g) < old.clearance(g);
          }
        }
      }
    }
  }
  EXPECT_GT(lowered_cells, 0);  // additions changed the grids
}

}  // namespace
}  // namespace octomotion
