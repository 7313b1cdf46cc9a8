// Numerical stability of moveTree/collides: exact and floating-point rigid motions of the grid,
// ties on voxel boundaries, huge universes and far objects, invalid poses, clipping.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "dense_grid.h"
#include "motion_oracle.h"
#include "octomotion/error.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/traversal.h"

namespace octomotion {
namespace {

using test::DenseGrid;

const Rounding kModes[] = {Rounding::kCenter, Rounding::kConservative};

WorldGrid grid5() {
  return WorldGrid(Eigen::Vector3d(-0.3, 0.7, 0.05), 0.05, 5);
}

Octree shape(const WorldGrid& g, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return test::randomShape(g.depth(), rng, 3, 25).toTree(g);
}

// Rotation by `angle` about `axis` through the point c (world = source frame here).
Eigen::Isometry3d rotationAbout(double angle, const Eigen::Vector3d& axis,
                                const Eigen::Vector3d& c) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = c - X.linear() * c;
  return X;
}

template <class Map>
Octree mapped(const Octree& src, Map&& map) {
  std::vector<Voxel> out;
  const std::uint32_t side = src.grid().sideVoxels();
  for (const Voxel& v : src.blackVoxels()) {
    long p[3];
    map(v, p);
    if (p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[0] < side && p[1] < side && p[2] < side) {
      out.push_back({static_cast<std::uint32_t>(p[0]), static_cast<std::uint32_t>(p[1]),
                     static_cast<std::uint32_t>(p[2])});
    }
  }
  return Octree::fromVoxels(src.grid(), out);
}

void expectMove(const Octree& src, const Eigen::Isometry3d& X, const Octree& expect,
                const char* what) {
  const MovableSource prepared(src);
  CollisionScratch scratch;
  for (Rounding mode : kModes) {
    const Octree moved = moveTree(src, X, expect.grid(), mode);
    EXPECT_EQ(moved, expect) << what << " " << toString(mode) << ": " << moved.blackVoxelCount()
                             << " vs " << expect.blackVoxelCount();
    // The fused query agrees with it against the expected tree and its complement's probes.
    EXPECT_EQ(collides(prepared, X, expect, mode, scratch), !expect.empty()) << what;
  }
}

TEST(Stability, SmallAnglesKeepTheTree) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 1);
  const Eigen::Vector3d c = test::gridCentre(g);
  expectMove(src, Eigen::Isometry3d::Identity(), src, "identity");
  expectMove(src, rotationAbout(0.0, Eigen::Vector3d(1, 2, 3), c), src, "angle 0");
  expectMove(src, rotationAbout(1e-12, Eigen::Vector3d(1, 2, 3), c), src, "angle 1e-12");
  expectMove(src, rotationAbout(-1e-12, Eigen::Vector3d(0, 0, 1), c), src, "angle -1e-12");
}

TEST(Stability, FloatingPointQuarterAndHalfTurnsAreExact) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 2);
  const long m = static_cast<long>(g.sideVoxels()) - 1;
  const Eigen::Vector3d c = test::gridCentre(g);  // a voxel corner: the grid maps onto itself
  expectMove(src, rotationAbout(M_PI / 2, Eigen::Vector3d::UnitZ(), c),
             mapped(src, [&](const Voxel& v, long* p) { p[0] = m - v.y, p[1] = v.x, p[2] = v.z; }),
             "90 about z");
  expectMove(
      src, rotationAbout(M_PI, Eigen::Vector3d::UnitZ(), c),
      mapped(src, [&](const Voxel& v, long* p) { p[0] = m - v.x, p[1] = m - v.y, p[2] = v.z; }),
      "180 about z");
  expectMove(src, rotationAbout(M_PI / 2, Eigen::Vector3d::UnitX(), c),
             mapped(src, [&](const Voxel& v, long* p) { p[0] = v.x, p[1] = m - v.z, p[2] = v.y; }),
             "90 about x");
  expectMove(src, rotationAbout(-M_PI / 2, Eigen::Vector3d::UnitY(), c),
             mapped(src, [&](const Voxel& v, long* p) { p[0] = m - v.z, p[1] = v.y, p[2] = v.x; }),
             "-90 about y");
  // Four quarter turns composed (§3) come back to the source.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 4; ++i) X = compose(rotationAbout(M_PI / 2, Eigen::Vector3d::UnitY(), c), X);
  expectMove(src, X, src, "4 x 90 about y");
}

TEST(Stability, FortyFiveDegreesMatchBruteForce) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 3);
  const Eigen::Vector3d c = test::gridCentre(g);
  const Eigen::Vector3d voxel_centre = g.voxelCenter({16, 16, 16});
  for (const Eigen::Vector3d& pivot : {c, voxel_centre}) {
    for (const Eigen::Vector3d& axis :
         {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0)}) {
      const Eigen::Isometry3d X = rotationAbout(M_PI / 4, axis, pivot);
      for (Rounding mode : kModes) {
        EXPECT_TRUE(DenseGrid::fromTree(moveTree(src, X, g, mode)) ==
                    test::bruteForceMove(src, X, g, mode));
      }
    }
  }
}

TEST(Stability, TinyAndHugeTranslations) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 4);
  const double h = g.voxelSize();
  const Eigen::Vector3d tiny(1e-9 * h, -1e-9 * h, 1e-9 * h);
  expectMove(src, Eigen::Isometry3d(Eigen::Translation3d(tiny)), src, "1e-9 voxel");
  const long k = static_cast<long>(g.sideVoxels()) - 1;  // 2^n - 1 voxels
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    t[axis] = k * h;
    const Octree expect = mapped(
        src, [&](const Voxel& v, long* p) { p[0] = v.x, p[1] = v.y, p[2] = v.z, p[axis] += k; });
    expectMove(src, Eigen::Isometry3d(Eigen::Translation3d(t)), expect, "2^n - 1 voxels");
    t[axis] = -k * h;
    const Octree back = mapped(
        src, [&](const Voxel& v, long* p) { p[0] = v.x, p[1] = v.y, p[2] = v.z, p[axis] -= k; });
    MoveStats st;
    EXPECT_EQ(moveTree(src, Eigen::Isometry3d(Eigen::Translation3d(t)), g, Rounding::kCenter, &st),
              back);
    EXPECT_TRUE(st.clipped);
  }
}

TEST(Stability, VoxelBoundaryTiesCountAsInside) {
  // Half-voxel shifts put voxel centres exactly on moved faces (centre mode: on counts as
  // inside) and give half-voxel overlaps (conservative): each black voxel covers two voxels
  // per shifted axis.
  const WorldGrid g = grid5();
  const Octree src = shape(g, 5);
  const double h = g.voxelSize();
  const Eigen::Vector3d c = test::gridCentre(g);
  for (int mask = 1; mask < 8; ++mask) {
    const Eigen::Vector3d t(mask & 1 ? 0.5 * h : 0, mask & 2 ? 0.5 * h : 0, mask & 4 ? 0.5 * h : 0);
    std::vector<Voxel> voxels;
    const std::uint32_t side = g.sideVoxels();
    for (const Voxel& v : src.blackVoxels()) {
      for (int d = 0; d < 8; ++d) {
        if (d & ~mask) continue;
        const Voxel w{v.x + (d & 1), v.y + ((d >> 1) & 1), v.z + ((d >> 2) & 1)};
        if (w.x < side && w.y < side && w.z < side) voxels.push_back(w);
      }
    }
    const Octree expect = Octree::fromVoxels(g, voxels);
    expectMove(src, Eigen::Isometry3d(Eigen::Translation3d(t)), expect, "half-voxel shift");
    // The same tie after a floating-point quarter turn.
    const Eigen::Isometry3d R = rotationAbout(M_PI / 2, Eigen::Vector3d::UnitZ(), c);
    const Eigen::Isometry3d X = compose(Eigen::Isometry3d(Eigen::Translation3d(t)), R);
    for (Rounding mode : kModes) {
      EXPECT_EQ(
          moveTree(src, X, g, mode),
          moveTree(moveTree(src, R, g, mode), Eigen::Isometry3d(Eigen::Translation3d(t)), g, mode));
    }
  }
}

TEST(Stability, NonNormalisedQuaternions) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 6);
  std::mt19937_64 rng(6);
  const Eigen::Vector3d t(0.1, -0.05, 0.02);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Quaterniond q = test::randomRotation(rng);
    const Eigen::Isometry3d unit = poseFromQuaternion(q, t);
    for (double scale : {1e-6, 0.37, 3.7, 1e8}) {
      const Eigen::Isometry3d X = poseFromQuaternion(Eigen::Quaterniond(q.coeffs() * scale), t);
      // Equal to a few units in the last place (the normalisation's rounding, which fused
      // multiply-adds in x86-64-v3 builds change); unnormalised, they would differ by the scale.
      EXPECT_LT((X.linear() - unit.linear()).cwiseAbs().maxCoeff(), 4e-15);
      for (Rounding mode : kModes)
        EXPECT_EQ(moveTree(src, X, g, mode), moveTree(src, unit, g, mode));
    }
  }
  EXPECT_THROW(poseFromQuaternion(Eigen::Quaterniond(0, 0, 0, 0), t), InvalidArgument);
  EXPECT_THROW(poseFromQuaternion(Eigen::Quaterniond(1e-300, 0, 0, 0), t), InvalidArgument);
  EXPECT_THROW(poseFromQuaternion(Eigen::Quaterniond(std::nan(""), 0, 0, 1), t), InvalidArgument);
  EXPECT_THROW(poseFromQuaternion(Eigen::Quaterniond(1, 0, 0, 0), Eigen::Vector3d(0, INFINITY, 0)),
               InvalidArgument);
}

TEST(Stability, MillimetreVoxelsInADepth20Universe) {
  // 2^20 mm = 1 km universe; a 16 mm object near the far corner (1e6 voxels from the origin).
  const WorldGrid target(Eigen::Vector3d(-500.0, -20.0, 3.0), 0.001, 20);
  const WorldGrid source_grid(Eigen::Vector3d(0.25, -0.125, 0.0), 0.001, 4);
  std::mt19937_64 rng(20);
  const Octree src = test::randomShape(4, rng, 2, 6).toTree(source_grid);
  // Exact quarter turn about z with an integer voxel offset: (x, y, z) -> (X0 + 15 - y, Y0 + x, Z0
  // + z).
  const long X0 = 1000000, Y0 = 999990, Z0 = 1048000;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = target.origin() - X.linear() * source_grid.origin() +
                    0.001 * Eigen::Vector3d(X0 + 16, Y0, Z0);
  std::vector<Voxel> expect;
  for (const Voxel& v : src.blackVoxels()) {
    expect.push_back({static_cast<std::uint32_t>(X0 + 15 - v.y),
                      static_cast<std::uint32_t>(Y0 + v.x), static_cast<std::uint32_t>(Z0 + v.z)});
  }
  const Octree expect_tree = Octree::fromVoxels(target, expect);
  for (Rounding mode : kModes) {
    MoveStats st;
    EXPECT_EQ(moveTree(src, X, target, mode, &st), expect_tree) << toString(mode);
    EXPECT_FALSE(st.clipped);
    EXPECT_TRUE(collides(src, X, expect_tree, mode));
  }
  // Random rotations there agree with the brute force.
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector3d c_W =
        target.origin() + 0.001 * Eigen::Vector3d(1040000.3, 7.7, 1048500.1);
    const Eigen::Isometry3d Y = test::randomPoseAbout(rng, test::gridCentre(source_grid), c_W);
    for (Rounding mode : kModes) {
      const Octree moved = moveTree(src, Y, target, mode);
      EXPECT_EQ(moved, test::bruteForceMoveTree(src, Y, target, mode));
      EXPECT_TRUE(collides(src, Y, moved, mode) == !moved.empty());
    }
  }
}

TEST(Stability, ObjectsFarFromTheOrigin) {
  // The source grid sits 20 km from the origin of S; the pose brings it back into the target.
  const WorldGrid source_grid(Eigen::Vector3d(1e4, -2e4, 5e3), 0.05, 4);
  const WorldGrid target(Eigen::Vector3d(-3e3, 4e3, 1e3), 0.05, 7);
  std::mt19937_64 rng(21);
  const Octree src = test::randomShape(4, rng, 2, 6).toTree(source_grid);
  for (int i = 0; i < 40; ++i) {
    const Eigen::Isometry3d X =
        test::randomPoseAbout(rng, test::gridCentre(source_grid), test::gridCentre(target));
    for (Rounding mode : kModes) {
      const Octree moved = moveTree(src, X, target, mode);
      EXPECT_TRUE(DenseGrid::fromTree(moved) == test::bruteForceMove(src, X, target, mode));
    }
  }
  // An exact integer translation from far away lands exactly.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = target.origin() - source_grid.origin() + 0.05 * Eigen::Vector3d(40, 50, 60);
  const Octree expect = [&] {
    std::vector<Voxel> v;
    for (const Voxel& s : src.blackVoxels()) v.push_back({s.x + 40, s.y + 50, s.z + 60});
    return Octree::fromVoxels(target, v);
  }();
  for (Rounding mode : kModes) EXPECT_EQ(moveTree(src, T, target, mode), expect);
}

TEST(Stability, InvalidPosesAreRejected) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 7);
  const MovableSource prepared(src);
  CollisionScratch scratch;
  std::vector<Eigen::Isometry3d> bad;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().y() = nan;
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.translation().z() = -inf;
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.linear()(1, 2) = nan;
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.linear()(0, 0) = inf;
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.linear() *= 1.001;  // scaled
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.linear()(0, 1) = 0.01;  // sheared
  bad.push_back(X);
  X = Eigen::Isometry3d::Identity();
  X.linear()(2, 2) = -1;  // reflection
  bad.push_back(X);
  for (const Eigen::Isometry3d& B : bad) {
    for (Rounding mode : kModes) {
      EXPECT_THROW(moveTree(src, B, g, mode), InvalidArgument);
      EXPECT_THROW(collides(prepared, B, src, mode, scratch), InvalidArgument);
    }
    EXPECT_THROW(compose(B, Eigen::Isometry3d::Identity()), InvalidArgument);
  }
  // Within the tolerance: a rotation off by 1e-8 is accepted (and snapped).
  X = Eigen::Isometry3d::Identity();
  X.linear()(0, 1) = 1e-8;
  for (Rounding mode : kModes) EXPECT_EQ(moveTree(src, X, g, mode), src);
}

TEST(Stability, MovingOutOfTheUniverseClips) {
  const WorldGrid g = grid5();
  const Octree src = shape(g, 8);
  std::mt19937_64 rng(9);
  for (int i = 0; i < 30; ++i) {
    // Centre near a face or a corner of the universe: part of the object is outside.
    const Eigen::Vector3d c_W =
        g.origin() + g.sideMetres() * Eigen::Vector3d(i % 2, 0.5, (i / 2) % 2);
    const Eigen::Isometry3d X = test::randomPoseAbout(rng, test::gridCentre(g), c_W);
    for (Rounding mode : kModes) {
      MoveStats st;
      Octree moved(g);
      ASSERT_NO_THROW(moved = moveTree(src, X, g, mode, &st));
      EXPECT_TRUE(st.clipped);
      EXPECT_TRUE(DenseGrid::fromTree(moved) == test::bruteForceMove(src, X, g, mode));
      EXPECT_EQ(collides(src, X, Octree::full(g), mode), !moved.empty());
    }
  }
  // Entirely outside, even absurdly far: an empty tree, flagged, no throw.
  for (double d : {50.0, 1e12, 1e300}) {
    for (Rounding mode : kModes) {
      MoveStats st;
      const Octree moved =
          moveTree(src, Eigen::Isometry3d(Eigen::Translation3d(d, -d, 0)), g, mode, &st);
      EXPECT_TRUE(moved.empty());
      EXPECT_TRUE(st.clipped);
      EXPECT_FALSE(
          collides(src, Eigen::Isometry3d(Eigen::Translation3d(d, -d, 0)), Octree::full(g), mode));
    }
  }
  // Inside: not flagged.
  MoveStats st;
  moveTree(src, Eigen::Isometry3d::Identity(), g, Rounding::kCenter, &st);
  EXPECT_FALSE(st.clipped);
}

}  // namespace
}  // namespace octomotion
