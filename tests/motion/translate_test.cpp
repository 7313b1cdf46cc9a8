// Integral translation by label-path arithmetic (Ahuja & Nash 1984 §3): the paper's tables and
// worked examples, then property tests against a dense brute-force shift (depths 3-7).
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "dense_grid.h"
#include "octomotion/error.h"
#include "octomotion/motion/translate.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {
namespace {

using test::DenseGrid;
using test::randomShape;
using Displacement = Eigen::Matrix<std::int64_t, 3, 1>;

WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d(0.5, -1, 2), 0.1, depth);
}

Octree treeOf(const WorldGrid& grid, const std::vector<std::string>& paths) {
  OctreeBuilder b(grid);
  for (const std::string& p : paths) b.paint(LabelPath::parse(p).cube(grid.depth()), true);
  return b.build();
}

// Brute force: every black voxel moved by d, the ones leaving the universe dropped.
DenseGrid shifted(const DenseGrid& g, const Displacement& d, bool* clipped) {
  DenseGrid out(g.depth());
  const std::int64_t side = g.side();
  *clipped = false;
  for (int a = 0; a < 3; ++a) {
    if (d[a] >= side || d[a] <= -side) {  // (and v + d could overflow)
      *clipped = g.count() > 0;
      return out;
    }
  }
  for (const Voxel& v : g.voxels()) {
    const std::int64_t x = v.x + d.x(), y = v.y + d.y(), z = v.z + d.z();
    if (x < 0 || y < 0 || z < 0 || x >= side || y >= side || z >= side) {
      *clipped = true;
      continue;
    }
    out.set(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
            static_cast<std::uint32_t>(z));
  }
  return out;
}

// Table 2 exactly as the paper prints it (carry digit, then label), rows +x, +y, +z.
TEST(LabelArithmetic, TransitionTableIsAhujaNashTable2) {
  const char* table2[3][8] = {{"1", "10", "3", "12", "5", "14", "7", "16"},
                              {"2", "3", "10", "11", "6", "7", "14", "15"},
                              {"4", "5", "6", "7", "10", "11", "12", "13"}};
  for (int axis = 0; axis < 3; ++axis) {
    for (int label = 0; label < 8; ++label) {
      const int printed = std::stoi(table2[axis][label], nullptr, 8);
      EXPECT_EQ(kLabelTransition[axis][label], printed) << "axis " << axis << " label " << label;
      // Table 1: the new label is the old one plus the increment, mod 8, and the carry is set
      // exactly when the octant was already on the + side of the axis.
      const LabelStep step = stepLabel(label, axis);
      EXPECT_EQ(step.label, (label + kLabelIncrement[axis][label]) % 8);
      EXPECT_EQ(step.carry, ((label >> axis) & 1) == 1);
      EXPECT_EQ(step.label, label ^ (1 << axis));
    }
  }
  static_assert(stepLabel(7, 1).label == 5 && stepLabel(7, 1).carry, "Table 2: 7 +y -> 15");
}

// §3.1 and Fig. 3: the unit block r057 of a depth-3 universe moved along +y.
TEST(LabelArithmetic, WorkedExamplesOfSection3_1) {
  LabelPath p = LabelPath::parse("r057");
  EXPECT_TRUE(addToPath(p, 1, 1));  // r057 + 001 = r075 (7+1 -> 5 carry, 5+1 -> 7)
  EXPECT_EQ(p.toString(), "r075");
  p = LabelPath::parse("r057");
  EXPECT_TRUE(addToPath(p, 1, 5));  // r057 + 101 = r275
  EXPECT_EQ(p.toString(), "r275");
  // r275 - 5: two's complement 011; the carry out of the root is lost and we are back home.
  EXPECT_EQ(addToPathWithCarry(p, 1, -5), 0);
  EXPECT_EQ(p.toString(), "r057");
  // The same digits as an unsigned +3 do carry out of the root: r275 + 3 leaves the universe
  // (the paper would silently keep the wrapped r057).
  p = LabelPath::parse("r275");
  EXPECT_EQ(addToPathWithCarry(p, 1, 3), 1);
  EXPECT_FALSE(addToPath(p = LabelPath::parse("r275"), 1, 3));
  EXPECT_EQ(p.toString(), "r057");
  // Fig. 3 as trees.
  const WorldGrid grid = gridOfDepth(3);
  const Octree r057 = treeOf(grid, {"r057"});
  EXPECT_EQ(r057.blackLeaves().front(), LabelPath::parse("r057").cube(3));
  TranslateResult moved = translate(r057, Displacement(0, 1, 0));
  EXPECT_FALSE(moved.clipped);
  EXPECT_EQ(moved.tree, treeOf(grid, {"r075"}));
  moved = translate(r057, Displacement(0, 5, 0));
  EXPECT_EQ(moved.tree, treeOf(grid, {"r275"}));
  moved = translate(moved.tree, Displacement(0, -5, 0));
  EXPECT_FALSE(moved.clipped);
  EXPECT_EQ(moved.tree, r057);
  // r057 is voxel (3, 1, 3): +5 in x leaves.
  moved = translate(r057, Displacement(5, 0, 0));
  EXPECT_TRUE(moved.clipped);
  EXPECT_TRUE(moved.tree.empty());
}

TEST(LabelArithmetic, PathsRoundTrip) {
  EXPECT_EQ(LabelPath::parse("r").length, 0);
  EXPECT_EQ(LabelPath::parse("r0123").toString(), "r0123");
  const Cube c{2, {4, 12, 0}};
  EXPECT_EQ(LabelPath::of(c, 5).cube(5), c);
  EXPECT_EQ(LabelPath::of(c, 5).toString(), "r023");  // x 00100, y 01100
  EXPECT_THROW(LabelPath::parse("057"), InvalidArgument);
  EXPECT_THROW(LabelPath::parse("r058"), InvalidArgument);
  EXPECT_THROW(LabelPath::parse("r" + std::string(kMaxDepth + 1, '1')), InvalidArgument);
  LabelPath p = LabelPath::parse("r01");
  EXPECT_THROW(addToPath(p, 3, 1), InvalidArgument);
  EXPECT_THROW(addToPath(p, -1, 1), InvalidArgument);
  EXPECT_THROW(addToPath(p, 0, 1, 1), InvalidArgument);  // a level-1 node moves by even amounts
  EXPECT_THROW(addToPath(p, 0, 2, -1), InvalidArgument);
  EXPECT_THROW(p.push(8), InvalidArgument);
}

// Path arithmetic against coordinate arithmetic for every level and many displacements.
TEST(LabelArithmetic, AgreesWithCoordinateAddition) {
  std::mt19937_64 rng(3141);
  for (int depth = 1; depth <= kMaxDepth; ++depth) {
    const std::int64_t side = std::int64_t{1} << depth;
    for (int trial = 0; trial < 300; ++trial) {
      const int level = static_cast<int>(rng() % static_cast<std::uint64_t>(depth + 1));
      const int axis = static_cast<int>(rng() % 3);
      std::uniform_int_distribution<std::uint32_t> coord(0, static_cast<std::uint32_t>(side - 1));
      const std::uint32_t mask = ~((std::uint32_t{1} << level) - 1u);
      const Cube cube{level, {coord(rng) & mask, coord(rng) & mask, coord(rng) & mask}};
      std::int64_t d;
      switch (trial % 4) {
        case 0:
          d = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(4 * side)) - 2 * side;
          break;
        case 1:
          d = (std::int64_t{1} << (rng() % 40)) * (rng() & 1 ? 1 : -1);
          break;
        case 2:
          d = static_cast<std::int64_t>(rng() >> 2) * (rng() & 1 ? 1 : -1);
          break;
        default:
          d = static_cast<std::int64_t>(rng() % 7) - 3;
          break;
      }
      d &= ~((std::int64_t{1} << level) - 1);  // whole node sides only
      LabelPath path = LabelPath::of(cube, depth);
      const std::int64_t carry = addToPathWithCarry(path, axis, d, level);
      const std::uint32_t origin[3] = {cube.origin.x, cube.origin.y, cube.origin.z};
      // floor((x + d) / side) without overflow: d is at most 2^62 in magnitude here.
      const std::int64_t moved = static_cast<std::int64_t>(origin[axis]) + d;
      const std::int64_t expected_carry = moved >= 0 ? moved / side : -((-moved + side - 1) / side);
      ASSERT_EQ(carry, expected_carry) << "depth " << depth << " d " << d;
      Cube expected = cube;
      const std::uint32_t wrapped = static_cast<std::uint32_t>(moved - expected_carry * side);
      (axis == 0 ? expected.origin.x : axis == 1 ? expected.origin.y : expected.origin.z) = wrapped;
      ASSERT_EQ(path.cube(depth), expected) << "depth " << depth << " d " << d;
    }
  }
}

std::vector<std::int64_t> interestingOffsets(int depth) {
  const std::int64_t side = std::int64_t{1} << depth;
  std::vector<std::int64_t> out{0, 1, 2, 3, 4, 6, side / 2, side - 1, side, side + 3};
  for (int k = 2; k < depth; ++k) out.push_back((std::int64_t{1} << k) - 1);
  const std::size_t n = out.size();
  for (std::size_t i = 1; i < n; ++i) out.push_back(-out[i]);
  out.push_back(std::numeric_limits<std::int64_t>::max());
  out.push_back(std::numeric_limits<std::int64_t>::min());
  return out;
}

TEST(Translate, AgreesWithDenseShift) {
  std::mt19937_64 rng(20261121);
  for (int depth = 3; depth <= 7; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    const std::vector<std::int64_t> offsets = interestingOffsets(depth);
    const std::int64_t side = grid.sideVoxels();
    const int trials = depth <= 5 ? 60 : (depth == 6 ? 24 : 12);
    for (int trial = 0; trial < trials; ++trial) {
      const DenseGrid dense = randomShape(depth, rng, 1 + trial % 3, trial % 5 == 0 ? 0 : 15);
      const Octree tree = dense.toTree(grid);
      for (int rep = 0; rep < 4; ++rep) {
        Displacement d;
        for (int a = 0; a < 3; ++a) {
          if (rng() % 3 == 0) {
            d[a] = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(2 * side)) - side;
          } else {
            d[a] = offsets[rng() % offsets.size()];
          }
        }
        if (rep == 0) d = Displacement(0, 0, 0);
        if (rep == 1) d[rng() % 3] = 0, d[rng() % 3] = 0;  // often a single axis
        bool clipped;
        const DenseGrid expected = shifted(dense, d, &clipped);
        const TranslateResult moved = translate(tree, d);
        std::string why;
        ASSERT_TRUE(moved.tree.checkInvariants(&why)) << why;
        ASSERT_TRUE(DenseGrid::fromTree(moved.tree) == expected)
            << "depth " << depth << " d " << d.transpose();
        EXPECT_EQ(moved.clipped, clipped) << "depth " << depth << " d " << d.transpose();
        EXPECT_EQ(moved.tree.grid(), grid);
        // The top-down variant gives the same compact tree.
        const TranslateResult pulled = translateTopDown(tree, d);
        ASSERT_TRUE(pulled.tree.checkInvariants(&why)) << why;
        EXPECT_EQ(pulled.tree, moved.tree) << "depth " << depth << " d " << d.transpose();
        EXPECT_EQ(pulled.clipped, clipped) << "depth " << depth << " d " << d.transpose();
      }
    }
  }
}

// Uniform universes: the black root is one leaf of level n (split by the slabs), white stays.
TEST(Translate, UniformUniverses) {
  for (int depth = 1; depth <= 5; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    const std::int64_t side = grid.sideVoxels();
    const Octree full = Octree::full(grid);
    for (std::int64_t dx = -side - 1; dx <= side + 1; ++dx) {
      const Displacement d(dx, depth == 3 ? -1 : 0, 0);
      const TranslateResult moved = translate(full, d);
      bool clipped;
      const DenseGrid expected = shifted(DenseGrid::fromTree(full), d, &clipped);
      ASSERT_TRUE(moved.tree.checkInvariants());
      ASSERT_TRUE(DenseGrid::fromTree(moved.tree) == expected) << d.transpose();
      EXPECT_EQ(moved.clipped, clipped);
      const TranslateResult pulled = translateTopDown(full, d);
      ASSERT_TRUE(pulled.tree.checkInvariants());
      EXPECT_EQ(pulled.tree, moved.tree);
      EXPECT_EQ(pulled.clipped, clipped);
      EXPECT_TRUE(translateTopDown(Octree(grid), d).tree.empty());
      const TranslateResult empty = translate(Octree(grid), d);
      EXPECT_TRUE(empty.tree.empty());
      EXPECT_FALSE(empty.clipped);
    }
  }
}

// Translations compose when nothing leaves in between, and a move there and back is exact.
TEST(Translate, ComposesWithoutClipping) {
  std::mt19937_64 rng(99);
  const int depth = 6;
  const WorldGrid grid = gridOfDepth(depth);
  for (int trial = 0; trial < 30; ++trial) {
    // A shape in the middle half, so moves of up to a quarter side never clip.
    DenseGrid small = randomShape(depth - 1, rng, 2, 10);
    DenseGrid dense(depth);
    for (const Voxel& v : small.voxels()) dense.set(v.x + 16, v.y + 16, v.z + 16);
    const Octree tree = dense.toTree(grid);
    std::uniform_int_distribution<std::int64_t> step(-8, 8);
    const Displacement a(step(rng), step(rng), step(rng)), b(step(rng), step(rng), step(rng));
    const TranslateResult ab = translate(translate(tree, a).tree, b);
    const TranslateResult sum = translate(tree, a + b);
    EXPECT_FALSE(ab.clipped);
    EXPECT_FALSE(sum.clipped);
    EXPECT_EQ(ab.tree, sum.tree);
    EXPECT_EQ(translate(sum.tree, -(a + b)).tree, tree);
  }
}

// A big solid block moved by one voxel: §3.2 would split it into voxels; the result must still be
// exact, with the work bounded by the faces (a 256^3 block would be 16M voxels).
TEST(Translate, LargeBlackLeavesMoveByTheirFaces) {
  const WorldGrid grid = gridOfDepth(10);
  OctreeBuilder b(grid);
  b.paint(Cube{8, {256, 512, 0}}, true);
  const Octree block = b.build();
  const TranslateResult moved = translate(block, Displacement(1, -3, 5));
  EXPECT_FALSE(moved.clipped);
  ASSERT_TRUE(moved.tree.checkInvariants());
  EXPECT_EQ(moved.tree.blackVoxelCount(), block.blackVoxelCount());
  const auto bounds = moved.tree.bounds();
  ASSERT_TRUE(bounds.has_value());
  EXPECT_EQ(bounds->min, (Voxel{257, 509, 5}));
  EXPECT_EQ(bounds->max, (Voxel{257 + 255, 509 + 255, 5 + 255}));
  EXPECT_TRUE(moved.tree.occupied({257, 509, 5}));
  EXPECT_FALSE(moved.tree.occupied({256, 512, 4}));
  EXPECT_EQ(translateTopDown(block, Displacement(1, -3, 5)).tree, moved.tree);
}

}  // namespace
}  // namespace octomotion
