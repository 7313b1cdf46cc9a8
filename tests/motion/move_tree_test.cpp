// moveTree (Weng & Ahuja 1987 §4) against a dense brute-force voxelization of the moved black
// cubes, Theorems 1 and 2 on moved single cubes, Table 2's M close to I, and §3's rule of always
// moving the source tree.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dense_grid.h"
#include "motion_oracle.h"
#include "octomotion/error.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {
namespace {

using test::DenseGrid;

const Rounding kModes[] = {Rounding::kCenter, Rounding::kConservative};

// Random source tree on its own grid (origin expressed in frame S), voxel size s * target's.
struct Scenario {
  WorldGrid source_grid;
  Octree source;
  WorldGrid target_grid;
};

Scenario randomScenario(std::mt19937_64& rng, int target_depth, double s) {
  const WorldGrid target(Eigen::Vector3d(-0.4, 0.25, -1.0), 0.05, target_depth);
  const int sdepth = std::max(2, std::min(5, target_depth - 2 - (s > 1.2 ? 1 : 0)));
  const WorldGrid source(Eigen::Vector3d(0.3, -0.2, 0.1), 0.05 * s, sdepth);
  const DenseGrid shape = test::randomShape(sdepth, rng, 2, 6);
  return {source, shape.toTree(source), target};
}

TEST(MoveTree, MatchesBruteForceAtRandomPoses) {
  std::mt19937_64 rng(1987);
  const double scales[] = {1.0, 1.5, 2.0, 0.75};
  int compared = 0;
  for (int depth = 4; depth <= 8; ++depth) {
    const int shapes = depth <= 6 ? 40 : (depth == 7 ? 10 : 4);
    const int poses = depth <= 6 ? 25 : (depth == 7 ? 10 : 5);
    for (int shape = 0; shape < shapes; ++shape) {
      const Scenario sc = randomScenario(rng, depth, scales[shape % 4]);
      std::uniform_real_distribution<double> jitter(-0.35, 0.35);
      for (int p = 0; p < poses; ++p) {
        // Mostly inside the universe, sometimes partly outside.
        const Eigen::Vector3d c_W =
            test::gridCentre(sc.target_grid) +
            sc.target_grid.sideMetres() * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        const Eigen::Isometry3d X =
            test::randomPoseAbout(rng, test::gridCentre(sc.source_grid), c_W);
        for (Rounding mode : kModes) {
          MoveStats stats;
          const Octree moved = moveTree(sc.source, X, sc.target_grid, mode, &stats);
          std::string why;
          ASSERT_TRUE(moved.checkInvariants(&why)) << why;
          if (depth <= 6) {
            const DenseGrid expect = test::bruteForceMove(sc.source, X, sc.target_grid, mode);
            ASSERT_TRUE(DenseGrid::fromTree(moved) == expect)
                << "depth " << depth << " shape " << shape << " pose " << p << " mode "
                << toString(mode) << ": " << moved.blackVoxelCount() << " vs " << expect.count();
          } else {  // dense arrays of 2^21+ cells are slow under the sanitizers: compare trees
            const Octree expect = test::bruteForceMoveTree(sc.source, X, sc.target_grid, mode);
            ASSERT_EQ(moved, expect)
                << "depth " << depth << " shape " << shape << " pose " << p << " mode "
                << toString(mode) << ": " << moved.blackVoxelCount() << " vs "
                << expect.blackVoxelCount();
          }
          EXPECT_EQ(stats.black_leaves, moved.blackLeafCount());
          EXPECT_EQ(stats.internal_nodes, moved.internalNodeCount());
          EXPECT_GE(stats.peak_nodes, stats.internal_nodes);
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 2000);
}

TEST(MoveTree, CenterIsInsideConservative) {
  // The centre rule's voxels are a subset of the conservative rule's.
  std::mt19937_64 rng(7);
  for (int t = 0; t < 60; ++t) {
    const Scenario sc = randomScenario(rng, 6, 1.0);
    const Eigen::Isometry3d X = test::randomPoseAbout(rng, test::gridCentre(sc.source_grid),
                                                      test::gridCentre(sc.target_grid));
    const Octree c = moveTree(sc.source, X, sc.target_grid, Rounding::kCenter);
    const Octree k = moveTree(sc.source, X, sc.target_grid, Rounding::kConservative);
    const DenseGrid dc = DenseGrid::fromTree(c), dk = DenseGrid::fromTree(k);
    for (const Voxel& v : dc.voxels()) ASSERT_TRUE(dk.get(v));
  }
}

// Theorem 2's bound on internal nodes of a moved m-cube in a 2^n universe.
double theorem2Bound(int m, int n) {
  if (m == 0) return 8.0 * n - 7;
  if (m == 1) return 8.0 * n + 12;
  if (m == 2) return 8.0 * n + 101;
  return 5.76 * std::pow(4.0, m) + 17 * std::pow(2.0, m) + 8.0 * n + 76.0 * m - 277;
}

TEST(MoveTree, SingleCubesSatisfyTheorems1And2) {
  // A single black m-cube at random orientations and positions inside universes up to n = 12
  // (Appendix B/C). M <= I + n: with one cube, the only live nodes not in the final tree are
  // the split-but-not-yet-condensed cells on the current recursion path (levels n-1..1) plus a
  // root that ends uniform, since every finished cell is condensed at once.
  std::mt19937_64 rng(12);
  std::size_t worst_b[7] = {}, worst_i[7] = {};
  for (int m = 0; m <= 6; ++m) {
    const WorldGrid source_grid(Eigen::Vector3d::Zero(), 1.0, m + 1);
    OctreeBuilder b(source_grid);
    b.paint(source_grid.universe().child(0), true);
    const Octree cube = b.build();
    const Eigen::Vector3d c_S = Eigen::Vector3d::Constant(std::ldexp(0.5, m));
    for (int n = std::max(m + 2, 4); n <= 12; n += (n < 8 ? 1 : 2)) {
      const WorldGrid target(Eigen::Vector3d(-3, 5, 0), 1.0, n);
      const double side = target.sideMetres();
      const double margin = std::ldexp(1.0, m) + 1.0;  // keep the whole cube inside
      std::uniform_real_distribution<double> pos(margin, side - margin);
      const int trials = m >= 5 ? 15 : 40;
      for (int t = 0; t < trials; ++t) {
        const Eigen::Vector3d c_W = target.origin() + Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
        const Eigen::Isometry3d X = test::randomPoseAbout(rng, c_S, c_W);
        MoveStats st;
        const Octree moved = moveTree(cube, X, target, Rounding::kCenter, &st);
        ASSERT_FALSE(st.clipped);
        const double bound_b = 24.25 * std::pow(4.0, m) - 200 * std::pow(2.0, m) + 1454;
        EXPECT_LE(static_cast<double>(st.black_leaves), bound_b) << "m=" << m << " n=" << n;
        EXPECT_LE(static_cast<double>(st.internal_nodes), theorem2Bound(m, n))
            << "m=" << m << " n=" << n;
        EXPECT_LE(st.peak_nodes, st.internal_nodes + static_cast<std::size_t>(n));
        worst_b[m] = std::max(worst_b[m], st.black_leaves);
        worst_i[m] = std::max(worst_i[m], st.internal_nodes);
      }
    }
  }
  for (int m = 0; m <= 6; ++m) {
    std::printf("m=%d  max B=%zu  max I=%zu\n", m, worst_b[m], worst_i[m]);
  }
}

TEST(MoveTree, PeakNodesStayCloseToTreeSize) {
  // Table 2: M is always close to I. For general sources the intermediate tree can hold nodes a
  // later cube fills in; we check M <= 1.25 I + n (Table 2's worst is M = 1.2 I at n = 4).
  std::mt19937_64 rng(2);
  double worst = 0;
  for (int t = 0; t < 80; ++t) {
    const Scenario sc = randomScenario(rng, 7, 1.0);
    const Eigen::Isometry3d X = test::randomPoseAbout(rng, test::gridCentre(sc.source_grid),
                                                      test::gridCentre(sc.target_grid));
    for (Rounding mode : kModes) {
      MoveStats st;
      moveTree(sc.source, X, sc.target_grid, mode, &st);
      if (st.internal_nodes == 0) continue;
      EXPECT_LE(static_cast<double>(st.peak_nodes), 1.25 * st.internal_nodes + 7);
      worst = std::max(worst, static_cast<double>(st.peak_nodes) / st.internal_nodes);
    }
  }
  std::printf("worst M/I = %.3f\n", worst);
}

TEST(MoveTree, RotateThenRotateBackGivesTheSource) {
  // §3: both motions applied to the source; composing phi and -phi returns the source exactly.
  std::mt19937_64 rng(3);
  for (int t = 0; t < 100; ++t) {
    const Scenario sc = randomScenario(rng, 6, 1.0);
    const WorldGrid& grid = sc.source_grid;  // move onto the source's own grid
    std::uniform_real_distribution<double> angle(-M_PI, M_PI);
    const double phi = angle(rng);
    const Eigen::Vector3d axis = test::randomRotation(rng) * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d pivot = test::gridCentre(grid) + Eigen::Vector3d(0.013, -0.02, 0.007);
    Eigen::Isometry3d Rphi = Eigen::Isometry3d::Identity(), Rback = Eigen::Isometry3d::Identity();
    Rphi.linear() = Eigen::AngleAxisd(phi, axis).toRotationMatrix();
    Rphi.translation() = pivot - Rphi.linear() * pivot;
    Rback.linear() = Eigen::AngleAxisd(-phi, axis).toRotationMatrix();
    Rback.translation() = pivot - Rback.linear() * pivot;
    const Eigen::Isometry3d X = compose(Rback, Rphi);
    for (Rounding mode : kModes) {
      EXPECT_EQ(moveTree(sc.source, X, grid, mode), sc.source) << "phi " << phi;
    }
    // Whereas moving the moved tree back generally does not (quantization accumulates).
  }
}

TEST(MoveTree, ComposeFollowsSection3) {
  std::mt19937_64 rng(4);
  for (int t = 0; t < 20; ++t) {
    Eigen::Isometry3d X1 = Eigen::Isometry3d::Identity(), X2 = Eigen::Isometry3d::Identity();
    X1.linear() = test::randomRotation(rng).toRotationMatrix();
    X2.linear() = test::randomRotation(rng).toRotationMatrix();
    X1.translation() = Eigen::Vector3d(1, -2, 3);
    X2.translation() = Eigen::Vector3d(-0.5, 0.25, 4);
    const Eigen::Isometry3d X = compose(X2, X1);
    const Eigen::Vector3d p(0.3, 0.7, -1.1);
    EXPECT_LT((X * p - X2 * (X1 * p)).norm(), 1e-12);
    EXPECT_LT((X.linear() - X2.linear() * X1.linear()).norm(), 1e-15);
    EXPECT_LT((X.translation() - (X2.linear() * X1.translation() + X2.translation())).norm(),
              1e-15);
  }
}

TEST(MoveTree, EmptyAndFullSources) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.1, 4);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  for (Rounding mode : kModes) {
    EXPECT_TRUE(moveTree(Octree(grid), I, grid, mode).empty());
    EXPECT_EQ(moveTree(Octree::full(grid), I, grid, mode), Octree::full(grid));
    // A full source rotated by 45° about the universe centre: clipped, corners dropped.
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d c = test::gridCentre(grid);
    X.translation() = c - X.linear() * c;
    MoveStats st;
    const Octree moved = moveTree(Octree::full(grid), X, grid, mode, &st);
    EXPECT_TRUE(st.clipped);
    EXPECT_TRUE(DenseGrid::fromTree(moved) ==
                test::bruteForceMove(Octree::full(grid), X, grid, mode));
  }
}

}  // namespace
}  // namespace octomotion
