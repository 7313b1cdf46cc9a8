// BlackCellGrid against brute force (every voxel of a cell black), and the fused query with a
// grid: the grid probes only find answers sooner, so collides gives moveTree + intersects'
// answer with or without it, and its witness is black in both trees.
#include "octomotion/motion/black_cell_grid.h"

#include <gtest/gtest.h>

#include <random>

#include "dense_grid.h"
#include "motion_oracle.h"
#include "octomotion/error.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

TEST(BlackCellGrid, MarksExactlyTheEntirelyBlackCells) {
  std::mt19937_64 rng(31);
  const int depth = 5;
  const WorldGrid grid(Eigen::Vector3d(-0.3, 0.1, 0.0), 0.02, depth);
  std::uniform_real_distribution<double> coord(-2.0, 34.0);  // a little outside the universe
  int black = 0, probes = 0;
  for (int shape = 0; shape < 6; ++shape) {
    const test::DenseGrid dense = test::randomShape(depth, rng, 4, 30);
    const Octree tree = dense.toTree(grid);
    // 2^15, 2^12, 2^9, 2^6 cells: levels 0 to 3.
    for (int level = 0; level <= 3; ++level) {
      const BlackCellGrid cells(tree, std::size_t{1} << (3 * (depth - level)));
      ASSERT_EQ(cells.level(), level);
      EXPECT_EQ(cells.sideVoxels(), 32.0);
      for (int i = 0; i < 3000; ++i) {
        const double g[3] = {coord(rng), coord(rng), coord(rng)};
        bool expect = g[0] >= 0 && g[1] >= 0 && g[2] >= 0 && g[0] < 32 && g[1] < 32 && g[2] < 32;
        if (expect) {
          const std::uint32_t s = 1u << level;
          const std::uint32_t o[3] = {static_cast<std::uint32_t>(g[0]) / s * s,
                                      static_cast<std::uint32_t>(g[1]) / s * s,
                                      static_cast<std::uint32_t>(g[2]) / s * s};
          for (std::uint32_t z = 0; z < s && expect; ++z)
            for (std::uint32_t y = 0; y < s && expect; ++y)
              for (std::uint32_t x = 0; x < s && expect; ++x)
                expect = dense.get(o[0] + x, o[1] + y, o[2] + z);
        }
        ASSERT_EQ(cells.black(g), expect) << "shape " << shape << " level " << level;
        black += expect;
        ++probes;
      }
    }
  }
  EXPECT_GT(black, probes / 50);  // both answers are exercised
  // The special trees: all black, all white.
  const double centre[3] = {16.0, 16.0, 16.0};
  EXPECT_TRUE(BlackCellGrid(Octree::full(grid)).black(centre));
  EXPECT_FALSE(BlackCellGrid(Octree(grid)).black(centre));
}

TEST(BlackCellGrid, CollidesAnswersTheSameWithIt) {
  std::mt19937_64 rng(0xb1c);
  const WorldGrid grid(Eigen::Vector3d(-0.64, -0.64, -0.64), 0.02, 6);
  // Large solid boxes (so whole cells are black) and scattered voxels.
  test::DenseGrid dense = test::randomShape(6, rng, 5, 40);
  const Octree env = dense.toTree(grid);
  const BlackCellGrid cells(env);
  const BlackCellGrid coarse(env, 512);  // level 3: fewer black cells, same answers
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-0.16), 0.01, 5);
  std::vector<Octree> links;
  links.push_back(test::randomShape(5, rng, 2, 6).toTree(link_grid));
  links.push_back(voxelize(link_grid, Cylinder{0.04, 0.3}, Eigen::Isometry3d::Identity(),
                           Rounding::kConservative));
  links.push_back(Octree::full(WorldGrid(Eigen::Vector3d::Zero(), 0.03, 2)));
  std::uniform_real_distribution<double> pos(-0.6, 0.6);
  CollisionScratch scratch;
  int hits = 0, compared = 0;
  for (const Octree& link : links) {
    const MovableSource source(link);
    EXPECT_FALSE(source.gridProbes().empty());
    EXPECT_LE(source.gridProbes().size(), MovableSource::kGridProbes);
    for (int p = 0; p < 300; ++p) {
      const Eigen::Isometry3d X = test::randomPoseAbout(
          rng, test::gridCentre(link.grid()), Eigen::Vector3d(pos(rng), pos(rng), pos(rng)));
      for (const Rounding mode : {Rounding::kConservative, Rounding::kCenter}) {
        const Octree moved = moveTree(link, X, grid, mode);
        const bool expect = intersects(moved, env);
        for (const BlackCellGrid* solid : {&cells, &coarse}) {
          Cube w{-1, {}};
          ASSERT_EQ(collides(source, X, env, mode, scratch, &w, solid), expect)
              << "pose " << p << " " << toString(mode);
          if (expect) {
            ASSERT_EQ(w.level, 0);
            EXPECT_TRUE(moved.occupied(w.origin));
            EXPECT_TRUE(env.occupied(w.origin));
          }
        }
        hits += expect;
        ++compared;
      }
    }
  }
  EXPECT_GT(hits, compared / 10);
  EXPECT_LT(hits, compared * 9 / 10);
  // A grid of another universe is refused.
  const Octree other(WorldGrid(Eigen::Vector3d::Zero(), 0.02, 5));
  const BlackCellGrid wrong(other);
  EXPECT_THROW(collides(MovableSource(links[0]), Eigen::Isometry3d::Identity(), env,
                        Rounding::kConservative, scratch, nullptr, &wrong),
               InvalidArgument);
}

}  // namespace
}  // namespace octomotion
