// Rotations by multiples of 90 degrees (Jackins & Tanimoto 1980, via Ahuja & Nash 1984 §5):
// all 24 against a brute-force voxel rotation on random trees of depths 3-6.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "dense_grid.h"
#include "octomotion/error.h"
#include "octomotion/motion/rotate90.h"

namespace octomotion {
namespace {

using test::DenseGrid;
using test::randomShape;

WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d(-2, 0, 1), 0.02, depth);
}

// Brute force, independent of AxisRotation::apply: voxel centres in doubled coordinates about
// the universe centre (2v + 1 - side, all integers), multiplied by the matrix.
DenseGrid rotatedDense(const DenseGrid& g, const Eigen::Matrix3i& R) {
  DenseGrid out(g.depth());
  const int side = static_cast<int>(g.side());
  for (const Voxel& v : g.voxels()) {
    const Eigen::Vector3i c(2 * static_cast<int>(v.x) + 1 - side,
                            2 * static_cast<int>(v.y) + 1 - side,
                            2 * static_cast<int>(v.z) + 1 - side);
    const Eigen::Vector3i r = R * c;
    out.set(static_cast<std::uint32_t>((r.x() + side - 1) / 2),
            static_cast<std::uint32_t>((r.y() + side - 1) / 2),
            static_cast<std::uint32_t>((r.z() + side - 1) / 2));
  }
  return out;
}

TEST(AxisRotation, TheTwentyFourRotations) {
  const auto& all = AxisRotation::all();
  EXPECT_EQ(all[0], AxisRotation());
  EXPECT_EQ(all[0].matrix(), Eigen::Matrix3i::Identity());
  std::set<std::vector<int>> distinct;
  for (const AxisRotation& R : all) {
    const Eigen::Matrix3i m = R.matrix();
    EXPECT_EQ(m.determinant(), 1);
    EXPECT_EQ(m * m.transpose(), Eigen::Matrix3i::Identity());
    distinct.insert(std::vector<int>(m.data(), m.data() + 9));
    EXPECT_EQ(AxisRotation::fromMatrix(m), R);
    EXPECT_EQ(R * R.inverse(), AxisRotation());
    EXPECT_EQ(R.inverse().matrix(), m.transpose());
    // The label map is a bijection of 0..7 and mask maps follow it bit by bit.
    int seen = 0;
    for (int k = 0; k < 8; ++k) {
      seen |= 1 << R.mapLabel(k);
      EXPECT_EQ(R.mapMask(static_cast<std::uint8_t>(1u << k)), 1 << R.mapLabel(k));
    }
    EXPECT_EQ(seen, 0xff);
    for (const AxisRotation& S : all) {
      EXPECT_EQ((R * S).matrix(), m * S.matrix());
    }
  }
  EXPECT_EQ(distinct.size(), 24u);
  // Quarter turns, right-handed: about z, +x goes to +y.
  const AxisRotation z90 = AxisRotation::about(2, 1);
  EXPECT_EQ(z90.matrix() * Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(0, 1, 0));
  EXPECT_EQ(AxisRotation::about(0, 1).matrix() * Eigen::Vector3i(0, 1, 0),
            Eigen::Vector3i(0, 0, 1));
  EXPECT_EQ(AxisRotation::about(1, 1).matrix() * Eigen::Vector3i(0, 0, 1),
            Eigen::Vector3i(1, 0, 0));
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(AxisRotation::about(axis, 4), AxisRotation());
    EXPECT_EQ(AxisRotation::about(axis, -1), AxisRotation::about(axis, 3));
  }
  // Labels (Fig. 1): a quarter turn about z takes the south-west lower octant 0 to the
  // south-east one, 1.
  EXPECT_EQ(z90.mapLabel(0), 1);
  EXPECT_EQ(z90.mapLabel(1), 3);
  EXPECT_EQ(z90.mapLabel(4), 5);
}

TEST(AxisRotation, RejectsWhatIsNotAProperAxisRotation) {
  Eigen::Matrix3i mirror = Eigen::Matrix3i::Identity();
  mirror(0, 0) = -1;
  EXPECT_THROW(AxisRotation::fromMatrix(mirror), InvalidArgument);
  Eigen::Matrix3i scaled = Eigen::Matrix3i::Identity() * 2;
  EXPECT_THROW(AxisRotation::fromMatrix(scaled), InvalidArgument);
  Eigen::Matrix3i repeated = Eigen::Matrix3i::Zero();
  repeated(0, 0) = repeated(1, 0) = repeated(2, 2) = 1;
  EXPECT_THROW(AxisRotation::fromMatrix(repeated), InvalidArgument);
  EXPECT_THROW(AxisRotation::fromMatrix(Eigen::Matrix3i::Zero()), InvalidArgument);
  EXPECT_THROW(AxisRotation::about(3, 1), InvalidArgument);
}

TEST(Rotate90, AllTwentyFourAgreeWithBruteForce) {
  std::mt19937_64 rng(1980);
  for (int depth = 3; depth <= 6; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    for (int trial = 0; trial < (depth <= 4 ? 6 : 3); ++trial) {
      const DenseGrid dense = randomShape(depth, rng, 1 + trial % 3, 12);
      const Octree tree = dense.toTree(grid);
      for (const AxisRotation& R : AxisRotation::all()) {
        const Octree rotated = rotate90(tree, R);
        std::string why;
        ASSERT_TRUE(rotated.checkInvariants(&why)) << why;
        ASSERT_TRUE(DenseGrid::fromTree(rotated) == rotatedDense(dense, R.matrix()))
            << "depth " << depth << "\n"
            << R.matrix();
        EXPECT_EQ(rotated.internalNodeCount(), tree.internalNodeCount());
        EXPECT_EQ(rotated.blackLeafCount(), tree.blackLeafCount());
        EXPECT_EQ(rotated.grid(), grid);
        // Cube and voxel images agree with the tree.
        for (const Cube& c : tree.blackLeaves()) {
          ASSERT_TRUE(rotated.occupied(R.apply(c, depth).origin));
          ASSERT_TRUE(rotated.occupied(R.apply(c.origin, depth)));
        }
      }
    }
  }
}

TEST(Rotate90, CompositionIdentityAndInverse) {
  std::mt19937_64 rng(1984);
  const int depth = 5;
  const WorldGrid grid = gridOfDepth(depth);
  const auto& all = AxisRotation::all();
  for (int trial = 0; trial < 4; ++trial) {
    const DenseGrid dense = randomShape(depth, rng, 2, 10);
    const Octree tree = dense.toTree(grid);
    EXPECT_EQ(rotate90(tree, AxisRotation()), tree);
    EXPECT_EQ(rotate90(tree, AxisRotation()).nodes(), tree.nodes());  // same layout too
    for (std::size_t i = 0; i < all.size(); ++i) {
      const AxisRotation& A = all[i];
      const AxisRotation& B = all[(i * 7 + static_cast<std::size_t>(trial) * 5 + 3) % all.size()];
      const Octree twice = rotate90(rotate90(tree, A), B);
      EXPECT_EQ(twice, rotate90(tree, B * A));
      EXPECT_TRUE(DenseGrid::fromTree(twice) ==
                  rotatedDense(rotatedDense(dense, A.matrix()), B.matrix()));
      EXPECT_EQ(rotate90(rotate90(tree, A), A.inverse()), tree);
    }
    // Four quarter turns about any axis come back.
    for (int axis = 0; axis < 3; ++axis) {
      Octree t = tree;
      for (int q = 0; q < 4; ++q) t = rotate90(t, AxisRotation::about(axis, 1));
      EXPECT_EQ(t, tree);
    }
  }
  // Uniform universes are their own rotations.
  EXPECT_EQ(rotate90(Octree::full(grid), all[5]), Octree::full(grid));
  EXPECT_TRUE(rotate90(Octree(grid), all[7]).empty());
}

}  // namespace
}  // namespace octomotion
