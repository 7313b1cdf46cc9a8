// innerBoxes: every box lies in black voxels (brute force over small random trees), a solid
// block is found whole, thin or empty trees give none.
#include "octomotion/octree/inner_boxes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "octomotion/error.h"

namespace octomotion {
namespace {

// Every voxel whose open cube meets the open box is black (up to rounding of the corners).
void expectInsideBlack(const Octree& tree, const Eigen::AlignedBox3d& box) {
  const WorldGrid& g = tree.grid();
  const Eigen::Vector3d lo = g.toGrid(box.min()), hi = g.toGrid(box.max());
  ASSERT_TRUE((hi.array() > lo.array()).all()) << "degenerate box";
  const std::uint32_t side = g.sideVoxels();
  for (std::uint32_t z = 0; z < side; ++z) {
    for (std::uint32_t y = 0; y < side; ++y) {
      for (std::uint32_t x = 0; x < side; ++x) {
        const Eigen::Vector3d v(x, y, z);
        // (1e-9: the corners went through metres and back)
        const bool meets =
            (v.array() < hi.array() - 1e-9).all() && ((v.array() + 1) > lo.array() + 1e-9).all();
        if (meets) {
          EXPECT_TRUE(tree.occupied({x, y, z})) << x << " " << y << " " << z;
        }
      }
    }
  }
}

TEST(InnerBoxes, BoxesLieInBlackVoxelsOfRandomBlobs) {
  std::mt19937 rng(11);
  int found = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const WorldGrid grid(Eigen::Vector3d(-0.3, 0.1, 2.0), 0.05, 4);  // 16^3 voxels
    // A union of random solid blocks, with random holes punched in it.
    std::vector<Voxel> voxels;
    std::uniform_int_distribution<int> corner(0, 12), extent(1, 8), coin(0, 19);
    std::vector<std::uint8_t> on(16 * 16 * 16, 0);
    for (int b = 0; b < 3; ++b) {
      const int x0 = corner(rng), y0 = corner(rng), z0 = corner(rng);
      const int ex = extent(rng), ey = extent(rng), ez = extent(rng);
      for (int z = z0; z < std::min(16, z0 + ez); ++z) {
        for (int y = y0; y < std::min(16, y0 + ey); ++y) {
          for (int x = x0; x < std::min(16, x0 + ex); ++x) on[(z * 16 + y) * 16 + x] = 1;
        }
      }
    }
    for (std::size_t i = 0; i < on.size(); ++i) {
      if (on[i] && coin(rng) != 0) {
        voxels.push_back({static_cast<std::uint32_t>(i % 16),
                          static_cast<std::uint32_t>(i / 16 % 16),
                          static_cast<std::uint32_t>(i / 256)});
      }
    }
    const Octree tree = Octree::fromVoxels(grid, voxels);
    for (int cells : {16, 8, 4}) {
      InnerBoxOptions o;
      o.max_cells_per_axis = cells;
      o.max_boxes = 4;
      o.min_cells = 1;
      const auto boxes = innerBoxes(tree, o);
      ASSERT_LE(boxes.size(), 4u);
      for (const Eigen::AlignedBox3d& box : boxes) expectInsideBlack(tree, box);
      found += static_cast<int>(boxes.size());
    }
  }
  EXPECT_GT(found, 100);  // the property was exercised
}

TEST(InnerBoxes, FindsASolidBlockWhole) {
  const WorldGrid grid(Eigen::Vector3d(1, 2, 3), 0.01, 5);  // 32^3
  std::vector<Voxel> voxels;
  for (std::uint32_t z = 4; z < 9; ++z) {
    for (std::uint32_t y = 10; y < 14; ++y) {
      for (std::uint32_t x = 7; x < 27; ++x) voxels.push_back({x, y, z});
    }
  }
  const Octree tree = Octree::fromVoxels(grid, voxels);
  InnerBoxOptions o;
  o.max_cells_per_axis = 32;
  const auto boxes = innerBoxes(tree, o);
  ASSERT_EQ(boxes.size(), 1u);  // nothing is left outside the first box
  EXPECT_TRUE(boxes[0].min().isApprox(grid.cubeMin(Cube{0, {7, 10, 4}})));
  EXPECT_TRUE(boxes[0].max().isApprox(grid.cubeMax(Cube{0, {26, 13, 8}})));
  // At 2-voxel cells the block's cells that are entirely black: x 8..25, y 10..13, z 4..7.
  o.max_cells_per_axis = 16;
  const auto coarse = innerBoxes(tree, o);
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_TRUE(coarse[0].min().isApprox(grid.cubeMin(Cube{0, {8, 10, 4}})));
  EXPECT_TRUE(coarse[0].max().isApprox(grid.cubeMax(Cube{0, {25, 13, 7}})));
}

TEST(InnerBoxes, AnLShapeGivesTwoBoxes) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, 4);
  std::vector<Voxel> voxels;
  for (std::uint32_t z = 0; z < 4; ++z) {
    for (std::uint32_t y = 0; y < 4; ++y) {
      for (std::uint32_t x = 0; x < 16; ++x) voxels.push_back({x, y, z});      // long bar along x
      for (std::uint32_t y2 = 4; y2 < 12; ++y2) voxels.push_back({y, y2, z});  // leg along y
    }
  }
  const Octree tree = Octree::fromVoxels(grid, voxels);
  const auto boxes = innerBoxes(tree);
  ASSERT_EQ(boxes.size(), 2u);
  for (const auto& b : boxes) expectInsideBlack(tree, b);
  // Together they cover the L (the second may grow back into the first).
  for (const Voxel& v : voxels) {
    const Eigen::Vector3d c = grid.voxelCenter(v);
    EXPECT_TRUE(boxes[0].contains(c) || boxes[1].contains(c)) << v.x << " " << v.y << " " << v.z;
  }
}

TEST(InnerBoxes, ThinOrEmptyTreesGiveNone) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.1, 4);
  EXPECT_TRUE(innerBoxes(Octree(grid)).empty());
  std::vector<Voxel> sheet;
  for (std::uint32_t y = 0; y < 16; ++y) {
    for (std::uint32_t x = 0; x < 16; ++x) sheet.push_back({x, y, 5});
  }
  InnerBoxOptions o;
  o.max_cells_per_axis = 16;
  EXPECT_TRUE(innerBoxes(Octree::fromVoxels(grid, sheet), o).empty());  // one voxel thick
  o.min_cells = 1;
  EXPECT_EQ(innerBoxes(Octree::fromVoxels(grid, sheet), o).size(), 1u);
}

TEST(InnerBoxes, RejectsBadOptions) {
  const Octree tree = Octree::full(WorldGrid(Eigen::Vector3d::Zero(), 1.0, 2));
  InnerBoxOptions o;
  o.max_boxes = 0;
  EXPECT_THROW(innerBoxes(tree, o), InvalidArgument);
  o = {};
  o.min_cells = 0;
  EXPECT_THROW(innerBoxes(tree, o), InvalidArgument);
  // A full tree is one box: the universe.
  const auto boxes = innerBoxes(tree);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_DOUBLE_EQ(boxes[0].volume(), 64.0);
}

}  // namespace
}  // namespace octomotion
