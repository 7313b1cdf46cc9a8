// Property tests of the compact octree against the dense oracle (depths 3-7, fixed seeds).
#include <gtest/gtest.h>

#include <random>

#include "dense_grid.h"
#include "octomotion/error.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/octree_builder.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/traversal.h"

namespace octomotion {
namespace {

using test::DenseGrid;
using test::randomShape;

WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d(-1, 2, 0.5), 0.05, depth);
}

TEST(Octree, EmptyAndFull) {
  const WorldGrid grid = gridOfDepth(4);
  Octree empty(grid);
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.blackLeafCount(), 0u);
  EXPECT_FALSE(empty.bounds().has_value());
  const Octree full = Octree::full(grid);
  EXPECT_EQ(full.blackVoxelCount(), 16u * 16u * 16u);
  EXPECT_TRUE(full.occupied({15, 0, 3}));
  EXPECT_TRUE(intersects(full, full));
  EXPECT_FALSE(intersects(full, empty));
  // Painting every voxel condenses to the black universe.
  OctreeBuilder b(grid);
  for (std::uint32_t z = 0; z < 16; ++z)
    for (std::uint32_t y = 0; y < 16; ++y)
      for (std::uint32_t x = 0; x < 16; ++x) b.setVoxel({x, y, z});
  EXPECT_EQ(b.build(), full);
  EXPECT_EQ(b.liveNodeCount(), 1u);  // only the root node remains
}

TEST(Octree, LabelsFollowAhujaNash) {
  // r057 in a depth-3 universe: octant 0, then 5 (+x,+z), then 7 (+x,+y,+z).
  const WorldGrid grid = gridOfDepth(3);
  const Cube r057 = grid.universe().child(0).child(5).child(7);
  EXPECT_EQ(r057.level, 0);
  EXPECT_EQ(r057.origin, (Voxel{3, 1, 3}));
}

TEST(Octree, AgreesWithDenseOracle) {
  std::mt19937_64 rng(20261121);
  for (int depth = 3; depth <= 7; ++depth) {
    for (int trial = 0; trial < 12; ++trial) {
      const DenseGrid dense = randomShape(depth, rng);
      const WorldGrid grid = gridOfDepth(depth);
      const Octree tree = dense.toTree(grid);
      std::string why;
      ASSERT_TRUE(tree.checkInvariants(&why)) << why;
      EXPECT_EQ(DenseGrid::fromTree(tree), dense);
      EXPECT_EQ(tree.blackVoxelCount(), dense.count());
      EXPECT_DOUBLE_EQ(tree.volume(), static_cast<double>(dense.count()) * 0.05 * 0.05 * 0.05);
      // Point queries, including at voxel centres in world coordinates.
      std::uniform_int_distribution<std::uint32_t> coord(0, dense.side() - 1);
      for (int q = 0; q < 200; ++q) {
        const Voxel v{coord(rng), coord(rng), coord(rng)};
        ASSERT_EQ(tree.occupied(v), dense.get(v));
        ASSERT_EQ(tree.occupiedAt(grid.voxelCenter(v)), dense.get(v));
      }
      // Bounds are the tight integer box of the black voxels.
      if (dense.count() > 0) {
        const auto b = tree.bounds();
        ASSERT_TRUE(b.has_value());
        const auto voxels = dense.voxels();
        Voxel lo = voxels.front(), hi = voxels.front();
        for (const Voxel& v : voxels) {
          lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
          hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
        }
        EXPECT_EQ(b->min, lo);
        EXPECT_EQ(b->max, hi);
      }
      // Round trip through the builder keeps the tree, and I = (T - 1) / 8 (Weng & Ahuja §5).
      EXPECT_EQ(OctreeBuilder(tree).build(), tree);
      std::size_t white = 0;
      for (const OctreeNode& n : tree.nodes()) white += 8 - __builtin_popcount(n.occupied());
      const std::size_t total = tree.internalNodeCount() + tree.blackLeafCount() + white;
      if (tree.rootColor() == Color::kGray) {
        EXPECT_EQ(tree.internalNodeCount(), (total - 1) / 8);
      }
    }
  }
}

TEST(Octree, PaintingWhiteCarvesAndCondenses) {
  std::mt19937_64 rng(7);
  const int depth = 5;
  const WorldGrid grid = gridOfDepth(depth);
  DenseGrid dense = randomShape(depth, rng, 4, 50);
  OctreeBuilder b(dense.toTree(grid));
  std::uniform_int_distribution<std::uint32_t> coord(0, dense.side() - 1);
  for (int i = 0; i < 300; ++i) {
    const Voxel v{coord(rng), coord(rng), coord(rng)};
    const bool black = rng() & 1;
    b.setVoxel(v, black);
    dense.set(v, black);
  }
  // A whole level-2 cube at once.
  b.paint(Cube{2, {4, 8, 12}}, false);
  for (std::uint32_t z = 12; z < 16; ++z)
    for (std::uint32_t y = 8; y < 12; ++y)
      for (std::uint32_t x = 4; x < 8; ++x) dense.set(x, y, z, false);
  const Octree t = b.build();
  std::string why;
  ASSERT_TRUE(t.checkInvariants(&why)) << why;
  EXPECT_EQ(DenseGrid::fromTree(t), dense);
  EXPECT_LE(t.internalNodeCount(), b.liveNodeCount());
}

TEST(Octree, SetOperationsAndIntersectsAgreeWithOracle) {
  std::mt19937_64 rng(42);
  for (int depth = 3; depth <= 7; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    for (int trial = 0; trial < 15; ++trial) {
      // Sparse shapes so that some pairs are disjoint.
      const DenseGrid da = randomShape(depth, rng, trial % 3, trial % 4 == 0 ? 0 : 10);
      const DenseGrid db = randomShape(depth, rng, trial % 2, 8);
      const Octree a = da.toTree(grid), b = db.toTree(grid);
      DenseGrid both(depth), either(depth);
      for (std::uint32_t z = 0; z < da.side(); ++z)
        for (std::uint32_t y = 0; y < da.side(); ++y)
          for (std::uint32_t x = 0; x < da.side(); ++x) {
            both.set(x, y, z, da.get(x, y, z) && db.get(x, y, z));
            either.set(x, y, z, da.get(x, y, z) || db.get(x, y, z));
          }
      const Octree i = intersect(a, b), u = unite(a, b);
      std::string why;
      ASSERT_TRUE(i.checkInvariants(&why)) << why;
      ASSERT_TRUE(u.checkInvariants(&why)) << why;
      EXPECT_EQ(DenseGrid::fromTree(i), both);
      EXPECT_EQ(DenseGrid::fromTree(u), either);
      EXPECT_EQ(i, both.toTree(grid));
      EXPECT_EQ(u, either.toTree(grid));
      EXPECT_EQ(intersects(a, b), both.count() > 0);
      EXPECT_EQ(intersects(b, a), both.count() > 0);
      // The overlap cubes are exactly the leaves of the intersection tree.
      const std::vector<Cube> cubes = overlappingCubes(a, b);
      EXPECT_EQ(cubes, i.blackLeaves());
    }
  }
}

TEST(Octree, EqualityIsOccupancy) {
  const WorldGrid grid = gridOfDepth(4);
  const Octree a = Octree::fromVoxels(grid, {{1, 2, 3}, {4, 5, 6}});
  const Octree b = Octree::fromVoxels(grid, {{4, 5, 6}, {1, 2, 3}});
  const Octree c = Octree::fromVoxels(grid, {{4, 5, 6}});
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  const Octree other_grid = Octree::fromVoxels(gridOfDepth(5), {{1, 2, 3}, {4, 5, 6}});
  EXPECT_NE(a, other_grid);
  EXPECT_THROW(intersects(a, other_grid), InvalidArgument);
}

TEST(Octree, RejectsMalformedNodeArrays) {
  const WorldGrid grid = gridOfDepth(3);
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {}), Error);
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{0, 0xff, 0}}), Error);  // not compact
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{0, 0, 0}}), Error);     // all white
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{1, 0, 1}}), Error);     // out of range
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{0, 1, 1}}), Error);     // both masks
  // A cycle: child index 0 points back at the root.
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{0, 0, 1}}), Error);
  // Too deep: root -> level 2 -> level 1 -> gray child below voxels.
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{1, 0, 1}, {2, 0, 1}, {3, 0, 1}, {0, 1, 0}}),
               Error);
  // Unreachable node.
  EXPECT_THROW(Octree::fromNodes(grid, Color::kGray, {{0, 1, 0}, {0, 1, 0}}), Error);
  const Octree ok = Octree::fromNodes(grid, Color::kGray, {{1, 0, 1}, {0, 3, 0}});
  EXPECT_EQ(ok.blackVoxelCount(), 2u * 8u);
  EXPECT_THROW(OctreeBuilder(grid).paint(Cube{1, {1, 0, 0}}, true), InvalidArgument);
  EXPECT_THROW(Octree::fromVoxels(grid, {{8, 0, 0}}), InvalidArgument);
}

TEST(WorldGrid, RejectsBadParameters) {
  EXPECT_THROW(WorldGrid(Eigen::Vector3d::Zero(), 0.0, 5), InvalidArgument);
  EXPECT_THROW(WorldGrid(Eigen::Vector3d::Zero(), -1.0, 5), InvalidArgument);
  EXPECT_THROW(WorldGrid(Eigen::Vector3d::Zero(), std::nan(""), 5), InvalidArgument);
  EXPECT_THROW(WorldGrid(Eigen::Vector3d::Zero(), 0.01, 0), InvalidArgument);
  EXPECT_THROW(WorldGrid(Eigen::Vector3d::Zero(), 0.01, kMaxDepth + 1), InvalidArgument);
  EXPECT_THROW(WorldGrid(Eigen::Vector3d(0, std::nan(""), 0), 0.01, 5), InvalidArgument);
  // Depth 20 with 1 mm voxels: a kilometre universe, coordinates exact in 32 bits.
  const WorldGrid big(Eigen::Vector3d(-524.288, -524.288, -524.288), 0.001, 20);
  Voxel v;
  ASSERT_TRUE(big.voxelAt(Eigen::Vector3d(524.2875, 0.0, -524.288), &v));
  EXPECT_EQ(v.x, (1u << 20) - 1);
  EXPECT_EQ(v.z, 0u);
  EXPECT_FALSE(big.voxelAt(Eigen::Vector3d(524.2885, 0, 0), &v));
  EXPECT_FALSE(big.voxelAt(Eigen::Vector3d(std::nan(""), 0, 0), &v));
  const Octree deep = Octree::fromVoxels(big, {{(1u << 20) - 1, 12345, 0}});
  EXPECT_TRUE(deep.occupied({(1u << 20) - 1, 12345, 0}));
  EXPECT_EQ(deep.internalNodeCount(), 20u);
}

}  // namespace
}  // namespace octomotion
