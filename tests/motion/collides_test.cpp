// The fused query must answer exactly intersects(moveTree(...), env), in both rounding modes,
// and its witness must be black in both trees.
#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "dense_grid.h"
#include "motion_oracle.h"
#include "octomotion/error.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

using test::DenseGrid;

const Rounding kModes[] = {Rounding::kCenter, Rounding::kConservative};

// A cluttered environment: random boxes and balls plus scattered voxels, or voxelized
// primitives.
Octree clutter(const WorldGrid& grid, std::mt19937_64& rng, int kind) {
  if (kind == 0) return test::randomShape(grid.depth(), rng, 6, 60).toTree(grid);
  Octree env(grid);
  std::uniform_real_distribution<double> pos(0.0, grid.sideMetres());
  std::uniform_real_distribution<double> size(0.03, 0.2);
  for (int i = 0; i < 8; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = test::randomRotation(rng).toRotationMatrix();
    X.translation() = grid.origin() + Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
    Primitive p;
    switch (i % 3) {
      case 0:
        p = Box{Eigen::Vector3d(size(rng), size(rng), size(rng))};
        break;
      case 1:
        p = Sphere{size(rng)};
        break;
      default:
        p = Cylinder{0.5 * size(rng), 3 * size(rng)};
        break;
    }
    env = unite(env, voxelize(grid, p, X, Rounding::kConservative));
  }
  return env;
}

struct Source {
  Octree tree;
  MovableSource prepared;
  explicit Source(Octree t) : tree(std::move(t)), prepared(tree) {}
};

std::vector<Source> sources(std::mt19937_64& rng) {
  std::vector<Source> out;
  const WorldGrid g1(Eigen::Vector3d(0.1, 0.2, -0.3), 0.02, 4);
  const WorldGrid g2(Eigen::Vector3d(-1.0, 0.0, 0.5), 0.03, 4);  // coarser than the target
  const WorldGrid g3(Eigen::Vector3d(0.0, 0.0, 0.0), 0.015, 3);  // finer than the target
  out.emplace_back(test::randomShape(4, rng, 2, 4).toTree(g1));
  out.emplace_back(test::randomShape(4, rng, 3, 10).toTree(g2));
  out.emplace_back(test::randomShape(3, rng, 1, 3).toTree(g3));
  out.emplace_back(voxelize(g2, Cylinder{0.05, 0.25},
                            Eigen::Isometry3d(Eigen::Translation3d(test::gridCentre(g2))),
                            Rounding::kConservative));
  out.emplace_back(Octree::full(g1));
  return out;
}

TEST(Collides, EqualsMoveTreeThenIntersects) {
  std::mt19937_64 rng(42);
  auto srcs = sources(rng);
  CollisionScratch scratch;
  int compared = 0, hits = 0;
  for (int depth = 5; depth <= 6; ++depth) {
    const WorldGrid grid(Eigen::Vector3d(-0.7, -0.2, 0.1), 0.02, depth);
    for (int kind = 0; kind < 2; ++kind) {
      const Octree env = clutter(grid, rng, kind);
      std::uniform_real_distribution<double> pos(-0.1, 1.1);
      for (const Source& s : srcs) {
        const int poses = 1000;
        for (int p = 0; p < poses; ++p) {
          const Eigen::Vector3d c_W =
              grid.origin() + grid.sideMetres() * Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
          const Eigen::Isometry3d X =
              test::randomPoseAbout(rng, test::gridCentre(s.tree.grid()), c_W);
          for (Rounding mode : kModes) {
            const Octree moved = moveTree(s.tree, X, grid, mode);
            const bool expect = intersects(moved, env);
            Cube w{-1, {}};
            const bool got = collides(s.prepared, X, env, mode, scratch, &w);
            ASSERT_EQ(got, expect) << "depth " << depth << " kind " << kind << " pose " << p
                                   << " mode " << toString(mode);
            if (got) {
              ASSERT_EQ(w.level, 0);
              EXPECT_TRUE(moved.occupied(w.origin));
              EXPECT_TRUE(env.occupied(w.origin));
              ++hits;
            }
            ++compared;
          }
        }
      }
    }
  }
  std::printf("compared %d poses x modes, %d colliding\n", compared, hits);
  EXPECT_GE(compared, 2 * 20000);
  EXPECT_GT(hits, compared / 10);
  EXPECT_LT(hits, compared * 9 / 10);
}

// A closed capsule mesh along z (the benchmark's link shape, coarser tessellation).
TriangleMesh capsule(double radius, double body, int seg, int rings) {
  TriangleMesh m;
  std::vector<double> zs, rs;
  for (int i = 1; i < 2 * rings; ++i) {
    const double a = -M_PI / 2 + M_PI * i / (2 * rings);
    zs.push_back((i < rings ? -body / 2 : body / 2) + radius * std::sin(a));
    rs.push_back(radius * std::cos(a));
    if (i == rings) {  // the body: a second ring at the bottom end
      zs.back() = -body / 2;
      zs.push_back(body / 2);
      rs.push_back(radius);
    }
  }
  m.vertices.push_back(Eigen::Vector3d(0, 0, -body / 2 - radius));
  for (std::size_t r = 0; r < zs.size(); ++r)
    for (int k = 0; k < seg; ++k)
      m.vertices.push_back(Eigen::Vector3d(rs[r] * std::cos(2 * M_PI * k / seg),
                                           rs[r] * std::sin(2 * M_PI * k / seg), zs[r]));
  m.vertices.push_back(Eigen::Vector3d(0, 0, body / 2 + radius));
  auto at = [&](std::size_t r, int k) { return static_cast<std::uint32_t>(1 + r * seg + k % seg); };
  for (int k = 0; k < seg; ++k) m.triangles.push_back({0, at(0, k + 1), at(0, k)});
  for (std::size_t r = 0; r + 1 < zs.size(); ++r)
    for (int k = 0; k < seg; ++k) {
      m.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      m.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
  const std::uint32_t top = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int k = 0; k < seg; ++k)
    m.triangles.push_back({at(zs.size() - 1, k), at(zs.size() - 1, k + 1), top});
  return m;
}

TEST(Collides, LinkMeshInClutter) {
  std::mt19937_64 rng(77);
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-0.16), 0.02, 4);
  const TriangleMesh mesh = capsule(0.04, 0.18, 24, 6);
  ASSERT_TRUE(isClosedManifold(mesh));
  const Octree link =
      voxelizeMesh(link_grid, mesh, Eigen::Isometry3d::Identity(), Rounding::kConservative);
  ASSERT_GT(link.blackVoxelCount(), 20u);
  const MovableSource prepared(link);
  CollisionScratch scratch;
  const WorldGrid grid(Eigen::Vector3d(-0.64, -0.64, 0.0), 0.02, 6);
  const Octree env = clutter(grid, rng, 1);
  std::uniform_real_distribution<double> pos(-0.6, 0.6), z(0.0, 1.28);
  int hits = 0;
  for (int p = 0; p < 1500; ++p) {
    const Eigen::Isometry3d X = test::randomPoseAbout(rng, Eigen::Vector3d::Zero(),
                                                      Eigen::Vector3d(pos(rng), pos(rng), z(rng)));
    for (Rounding mode : kModes) {
      const Octree moved = moveTree(link, X, grid, mode);
      Cube w;
      const bool got = collides(prepared, X, env, mode, scratch, &w);
      ASSERT_EQ(got, intersects(moved, env)) << "pose " << p << " " << toString(mode);
      if (got) {
        EXPECT_TRUE(moved.occupied(w.origin) && env.occupied(w.origin));
        ++hits;
      }
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_LT(hits, 2900);
}

// The expand factor (when a gray source piece is split) only changes the traversal's cost: every
// factor must give moveTree + intersects' answer, against clutter and against another solid link
// (the self-pair case kExpandFactorDeepPairs is for), with a source 6 levels deep.
TEST(Collides, AnswerDoesNotDependOnExpandFactor) {
  std::mt19937_64 rng(0xe8f);
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-0.16), 0.005, 6);
  const Octree link = voxelizeMesh(link_grid, capsule(0.04, 0.18, 24, 6),
                                   Eigen::Isometry3d::Identity(), Rounding::kConservative);
  std::vector<std::unique_ptr<MovableSource>> prepared;
  for (const double factor : {1.0, MovableSource::kExpandFactorDeepPairs,
                              MovableSource::kExpandFactorDefault, 64.0, 1e9}) {
    prepared.push_back(std::make_unique<MovableSource>(link, factor));
    EXPECT_EQ(prepared.back()->expandFactor(), factor);
  }
  EXPECT_THROW(MovableSource(link, 0.5), InvalidArgument);
  const WorldGrid grid(Eigen::Vector3d(-0.32, -0.32, 0.0), 0.01, 6);
  const Octree clutter_env = clutter(grid, rng, 1);
  const Octree other_link = voxelize(link_grid, Cylinder{0.05, 0.25}, Eigen::Isometry3d::Identity(),
                                     Rounding::kConservative);
  CollisionScratch scratch;
  int hits = 0, compared = 0;
  for (const Octree* target : {&clutter_env, &other_link}) {
    const Eigen::Vector3d centre = test::gridCentre(target->grid());
    const double spread = target == &clutter_env ? 0.3 : 0.12;
    std::uniform_real_distribution<double> pos(-spread, spread);
    for (int p = 0; p < 400; ++p) {
      const Eigen::Isometry3d X = test::randomPoseAbout(
          rng, Eigen::Vector3d::Zero(), centre + Eigen::Vector3d(pos(rng), pos(rng), pos(rng)));
      for (Rounding mode : kModes) {
        const bool expect = intersects(moveTree(link, X, target->grid(), mode), *target);
        for (const auto& source : prepared) {
          ASSERT_EQ(collides(*source, X, *target, mode, scratch), expect)
              << "pose " << p << " factor " << source->expandFactor() << " " << toString(mode);
        }
        hits += expect;
        ++compared;
      }
    }
  }
  EXPECT_GT(hits, compared / 10);
  EXPECT_LT(hits, compared * 9 / 10);
}

// A node whose black voxels fill less than kSparseFill of its box (an L of two thin bars) is
// split at kExpandFactorSparse; a solid one keeps the source's factor. Either way the answer is
// moveTree + intersects'.
TEST(Collides, SparseNodesSplitSooner) {
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-0.32), 0.01, 6);
  auto bar = [&](const Eigen::Vector3d& size, const Eigen::Vector3d& at) {
    return voxelize(link_grid, Box{size}, Eigen::Isometry3d(Eigen::Translation3d(at)),
                    Rounding::kConservative);
  };
  const Octree l_bar =
      unite(bar({0.4, 0.04, 0.04}, {0.0, -0.18, 0.0}), bar({0.04, 0.4, 0.04}, {-0.18, 0.0, 0.0}));
  const Octree block = bar({0.3, 0.2, 0.1}, Eigen::Vector3d::Zero());
  auto maxHalf = [](const MovableSource::Node& n) {
    return std::max(n.half[0], std::max(n.half[1], n.half[2]));
  };
  const MovableSource sparse(l_bar), solid(block);
  EXPECT_DOUBLE_EQ(sparse.nodes()[0].split_half,
                   maxHalf(sparse.nodes()[0]) / MovableSource::kExpandFactorSparse);
  EXPECT_DOUBLE_EQ(solid.nodes()[0].split_half,
                   maxHalf(solid.nodes()[0]) / MovableSource::kExpandFactorDefault);
  // A source factor below the sparse one is kept.
  const MovableSource eager(l_bar, 1.0);
  EXPECT_DOUBLE_EQ(eager.nodes()[0].split_half, maxHalf(eager.nodes()[0]));

  std::mt19937_64 rng(0x15a);
  const WorldGrid grid(Eigen::Vector3d(-0.64, -0.64, -0.64), 0.01, 7);
  const Octree env = clutter(grid, rng, 1);
  std::uniform_real_distribution<double> pos(-0.4, 0.4);
  CollisionScratch scratch;
  int hits = 0, compared = 0;
  for (int p = 0; p < 200; ++p) {
    const Eigen::Isometry3d X = test::randomPoseAbout(
        rng, Eigen::Vector3d::Zero(), Eigen::Vector3d(pos(rng), pos(rng), pos(rng)));
    for (Rounding mode : kModes) {
      const bool expect = intersects(moveTree(l_bar, X, grid, mode), env);
      ASSERT_EQ(collides(sparse, X, env, mode, scratch), expect) << "pose " << p;
      hits += expect;
      ++compared;
    }
  }
  EXPECT_GT(hits, compared / 20);
  EXPECT_LT(hits, compared * 19 / 20);
}

TEST(Collides, ConvenienceFormAndSpecialTrees) {
  std::mt19937_64 rng(5);
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.05, 5);
  const Octree env = test::randomShape(5, rng).toTree(grid);
  const Octree src = test::randomShape(3, rng).toTree(WorldGrid(Eigen::Vector3d::Zero(), 0.05, 3));
  for (Rounding mode : kModes) {
    for (int t = 0; t < 50; ++t) {
      const Eigen::Isometry3d X = test::randomPoseAbout(rng, Eigen::Vector3d::Constant(0.2),
                                                        Eigen::Vector3d::Constant(0.8));
      EXPECT_EQ(collides(src, X, env, mode), intersects(moveTree(src, X, grid, mode), env));
      EXPECT_FALSE(collides(src, X, Octree(grid), mode));
      EXPECT_FALSE(collides(Octree(src.grid()), X, env, mode));
      EXPECT_EQ(collides(src, X, Octree::full(grid), mode), !moveTree(src, X, grid, mode).empty());
    }
  }
  // Entirely outside the universe: no collision, no throw.
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(100, 0, 0);
  EXPECT_FALSE(collides(src, far, Octree::full(grid), Rounding::kConservative));
}

TEST(Collides, RejectsBadPoses) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.05, 4);
  const Octree t = Octree::full(grid);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().x() = std::nan("");
  EXPECT_THROW(collides(t, X, t, Rounding::kCenter), InvalidArgument);
  X = Eigen::Isometry3d::Identity();
  X.linear()(0, 0) = 1.1;
  EXPECT_THROW(collides(t, X, t, Rounding::kCenter), InvalidArgument);
}

TEST(Collides, ThreadsShareOnePreparedSource) {
  std::mt19937_64 rng(9);
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.05, 6);
  const Octree env = test::randomShape(6, rng, 5, 40).toTree(grid);
  const Octree src = test::randomShape(4, rng).toTree(WorldGrid(Eigen::Vector3d::Zero(), 0.05, 4));
  const MovableSource prepared(src);
  std::vector<Eigen::Isometry3d> poses;
  std::vector<char> expect;
  for (int i = 0; i < 400; ++i) {
    poses.push_back(
        test::randomPoseAbout(rng, Eigen::Vector3d::Constant(0.4), Eigen::Vector3d::Constant(1.6)));
    expect.push_back(intersects(moveTree(src, poses.back(), grid, Rounding::kCenter), env));
  }
  std::vector<int> wrong(2, 0);
  auto work = [&](int id) {
    CollisionScratch scratch;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (collides(prepared, poses[i], env, Rounding::kCenter, scratch) != (expect[i] != 0)) {
        ++wrong[id];
      }
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  EXPECT_EQ(wrong[0] + wrong[1], 0);
}

}  // namespace
}  // namespace octomotion
