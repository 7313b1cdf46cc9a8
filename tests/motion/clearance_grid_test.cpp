// ClearanceGrid against brute force (the box-to-box distance from each cell to the nearest cell
// holding a black voxel, in quarter cells), and the fused query with a clearance grid: dropping
// the clear pieces of the moved source never changes collides' answer (moveTree + intersects).
#include "octomotion/motion/clearance_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

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

TEST(ClearanceGrid, StoresTheCellDistanceRoundedDownToQuarters) {
  std::mt19937_64 rng(37);
  const int depth = 5;
  const std::uint32_t side = 1u << depth;
  const WorldGrid grid(Eigen::Vector3d(0.1, -0.2, 0.3), 0.05, depth);
  int far = 0, near = 0;
  for (int shape = 0; shape < 5; ++shape) {
    // Few boxes and dots: distances of several cells occur.
    const test::DenseGrid dense = test::randomShape(depth, rng, 1, 3);
    const Octree tree = dense.toTree(grid);
    for (int level = 0; level <= 2; ++level) {
      const ClearanceGrid clear(tree, std::size_t{1} << (3 * (depth - level)));
      ASSERT_EQ(clear.level(), level);
      const std::uint32_t s = 1u << level, n = side / s;
      EXPECT_EQ(clear.cellVoxels(), static_cast<double>(s));
      // Cells holding a black voxel, by brute force over the voxels.
      std::vector<std::array<std::uint32_t, 3>> occupied;
      for (std::uint32_t z = 0; z < n; ++z)
        for (std::uint32_t y = 0; y < n; ++y)
          for (std::uint32_t x = 0; x < n; ++x) {
            bool any = false;
            for (std::uint32_t k = 0; k < s * s * s && !any; ++k)
              any = dense.get(x * s + k % s, y * s + k / s % s, z * s + k / (s * s));
            if (any) occupied.push_back({x, y, z});
          }
      for (std::uint32_t z = 0; z < n; ++z)
        for (std::uint32_t y = 0; y < n; ++y)
          for (std::uint32_t x = 0; x < n; ++x) {
            double best = 1e300;  // squared cells, box to box
            for (const auto& o : occupied) {
              const std::uint32_t c[3] = {x, y, z};
              double d2 = 0;
              for (int a = 0; a < 3; ++a) {
                const double gap = std::max(
                    0.0, std::fabs(double(c[a]) - double(o[static_cast<std::size_t>(a)])) - 1);
                d2 += gap * gap;
              }
              best = std::min(best, d2);
            }
            const double steps =
                std::min(255.0, std::floor(ClearanceGrid::kStepsPerCell * std::sqrt(best)));
            const double expect = steps * s / ClearanceGrid::kStepsPerCell;
            // Any point of the cell gives the cell's value.
            const double g[3] = {x * s + 0.37 * s, y * s + 0.99 * s, double(z * s)};
            ASSERT_EQ(clear.clearance(g), expect)
                << "shape " << shape << " level " << level << " cell " << x << "," << y << "," << z;
            far += expect >= 2.0 * s;
            near += expect == 0.0;
          }
    }
  }
  EXPECT_GT(far, 100);  // both kinds of cells are exercised
  EXPECT_GT(near, 100);
  // Outside the universe: no bound.
  const ClearanceGrid empty{Octree(grid)};
  const double outside[3] = {-0.5, 3.0, 3.0};
  EXPECT_EQ(empty.clearance(outside), 0.0);
  const double centre[3] = {16.0, 16.0, 16.0};
  EXPECT_EQ(empty.clearance(centre), 255.0 / ClearanceGrid::kStepsPerCell);  // nothing anywhere
  EXPECT_EQ(ClearanceGrid(Octree::full(grid)).clearance(centre), 0.0);
}

TEST(ClearanceGrid, CollidesAnswersTheSameWithIt) {
  std::mt19937_64 rng(0xc1e);
  const WorldGrid grid(Eigen::Vector3d(-0.64, -0.64, -0.64), 0.02, 6);
  // A few boxes and scattered voxels: much free space, with near misses around every object.
  const Octree env = test::randomShape(6, rng, 3, 25).toTree(grid);
  const ClearanceGrid fine(env);              // level 0
  const ClearanceGrid coarse(env, 1u << 12);  // level 2: looser bounds, same answers
  const BlackCellGrid cells(env);
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
    for (int p = 0; p < 300; ++p) {
      const Eigen::Isometry3d X = test::randomPoseAbout(
          rng, test::gridCentre(link.grid()), Eigen::Vector3d(pos(rng), pos(rng), pos(rng)));
      for (const Rounding mode : {Rounding::kConservative, Rounding::kCenter}) {
        const Octree moved = moveTree(link, X, grid, mode);
        const bool expect = intersects(moved, env);
        for (const ClearanceGrid* clear : {&fine, &coarse}) {
          for (const BlackCellGrid* solid : {static_cast<const BlackCellGrid*>(nullptr), &cells}) {
            if (solid && mode != Rounding::kConservative) continue;
            Cube w{-1, {}};
            ASSERT_EQ(collides(source, X, env, mode, scratch, &w, solid, clear), expect)
                << "pose " << p << " " << toString(mode) << " level " << clear->level();
            if (expect) {
              ASSERT_EQ(w.level, 0);
              EXPECT_TRUE(moved.occupied(w.origin));
              EXPECT_TRUE(env.occupied(w.origin));
            }
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
  const ClearanceGrid wrong{Octree(WorldGrid(Eigen::Vector3d::Zero(), 0.02, 5))};
  EXPECT_THROW(collides(MovableSource(links[0]), Eigen::Isometry3d::Identity(), env,
                        Rounding::kConservative, scratch, nullptr, nullptr, &wrong),
               InvalidArgument);
}

}  // namespace
}  // namespace octomotion
