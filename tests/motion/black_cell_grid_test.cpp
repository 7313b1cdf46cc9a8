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
  // Leaves a quarter of the environment's voxel (the finer link trees): under centre rounding
  // most leaves hold no voxel centre, so probes in black cells go through the source lookup.
  links.push_back(voxelize(WorldGrid(Eigen::Vector3d::Constant(-0.16), 0.005, 6),
                           Cylinder{0.04, 0.3}, Eigen::Isometry3d::Identity(),
                           Rounding::kConservative));
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

// The grid probes alone, against moveTree's colours: with a grid that calls every cell black
// and an environment the link never reaches, collides() answers true exactly when a probe
// lands in a voxel black in the moved tree. Conservative: always (the voxel holding a moved
// leaf's centre is black). Centre: only when that voxel's centre lies in a moved black leaf,
// which the query looks up in the source tree — never for a voxel moveTree leaves white.
TEST(BlackCellGrid, GridProbesAnswerOnlyForVoxelsBlackInTheMovedTree) {
  std::mt19937_64 rng(0x9b0);
  const WorldGrid grid(Eigen::Vector3d(-0.64, -0.64, -0.64), 0.02, 6);
  const BlackCellGrid all_black(Octree::full(grid));
  const Octree far = Octree::fromVoxels(grid, {Voxel{0, 0, 0}});  // out of the links' reach
  std::vector<Octree> links;
  links.push_back(
      test::randomShape(5, rng, 2, 6).toTree(WorldGrid(Eigen::Vector3d::Constant(-0.16), 0.01, 5)));
  // Sources of one to three leaves (one to three probes), so that under centre rounding a pose
  // often has no probe in a black voxel: a voxel as large as the target's, a 2 x 2 x 2 block
  // that is one leaf, three scattered voxels a quarter of the target's.
  links.push_back(
      Octree::fromVoxels(WorldGrid(Eigen::Vector3d::Zero(), 0.02, 2), {Voxel{1, 2, 1}}));
  links.push_back(
      Octree::fromVoxels(WorldGrid(Eigen::Vector3d::Zero(), 0.01, 3),
                         {Voxel{2, 2, 2}, Voxel{3, 2, 2}, Voxel{2, 3, 2}, Voxel{3, 3, 2},
                          Voxel{2, 2, 3}, Voxel{3, 2, 3}, Voxel{2, 3, 3}, Voxel{3, 3, 3}}));
  links.push_back(Octree::fromVoxels(WorldGrid(Eigen::Vector3d::Zero(), 0.005, 4),
                                     {Voxel{1, 1, 1}, Voxel{9, 4, 13}, Voxel{14, 10, 2}}));
  for (const double voxel : {0.02, 0.005}) {  // leaves as large as the target's, and a quarter
    const int depth = voxel > 0.01 ? 4 : 6;
    links.push_back(voxelize(WorldGrid(Eigen::Vector3d::Constant(-0.16), voxel, depth),
                             Cylinder{0.05, 0.28}, Eigen::Isometry3d::Identity(),
                             Rounding::kConservative));
  }
  std::uniform_real_distribution<double> pos(-0.3, 0.3);
  CollisionScratch scratch;
  int probe_hits[2] = {0, 0}, compared[2] = {0, 0};
  for (const Octree& link : links) {
    const MovableSource source(link);
    for (int p = 0; p < 300; ++p) {
      const Eigen::Isometry3d X = test::randomPoseAbout(
          rng, test::gridCentre(link.grid()), Eigen::Vector3d(pos(rng), pos(rng), pos(rng)));
      for (const Rounding mode : {Rounding::kConservative, Rounding::kCenter}) {
        const Octree moved = moveTree(link, X, grid, mode);
        ASSERT_FALSE(intersects(moved, far));
        bool expect = false, ambiguous = false;
        for (const auto& u : source.gridProbes()) {
          const Eigen::Vector3d g =
              grid.toGrid(X * link.grid().toWorld(Eigen::Vector3d(u[0], u[1], u[2])));
          for (int a = 0; a < 3; ++a) {
            ambiguous |= std::abs(g[a] - std::round(g[a])) < 1e-6;  // floor() could go either way
          }
          const Voxel v{static_cast<std::uint32_t>(g.x()), static_cast<std::uint32_t>(g.y()),
                        static_cast<std::uint32_t>(g.z())};
          expect |= moved.occupied(v);
        }
        if (ambiguous) continue;
        Cube w{-1, {}};
        const bool got = collides(source, X, far, mode, scratch, &w, &all_black);
        ASSERT_EQ(got, expect) << "pose " << p << " " << toString(mode);
        if (got) {
          EXPECT_TRUE(moved.occupied(w.origin));
        }
        const int m = mode == Rounding::kCenter;
        probe_hits[m] += got;
        ++compared[m];
      }
    }
  }
  std::printf("probe hits: conservative %d / %d, centre %d / %d\n", probe_hits[0], compared[0],
              probe_hits[1], compared[1]);
  EXPECT_EQ(probe_hits[0], compared[0]);      // conservative: every probe's voxel is black
  EXPECT_GT(probe_hits[1], compared[1] / 2);  // centre: exercised (both answers)
  EXPECT_LT(probe_hits[1], compared[1]);
}

}  // namespace
}  // namespace octomotion
