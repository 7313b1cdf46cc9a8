// The exact-primitive test (primitive_contact.h) against brute force: the squared distance to a
// box, ball and cylinder against dense samples of each solid, and blackLeafMeetsPrimitive
// against the voxel rule applied to every black voxel of random source trees (a dense array:
// large leaves must answer as their voxels do), with points inside the voxels as the
// conservative oracle (a voxel that overlaps the shape must be found).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "dense_grid.h"
#include "motion_oracle.h"
#include "octomotion/error.h"
#include "octomotion/motion/box_overlap.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

Primitive randomPrimitive(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> size(0.01, 0.12);
  switch (kind % 3) {
    case 0:
      return Box{Eigen::Vector3d(size(rng), size(rng), size(rng))};
    case 1:
      return Sphere{size(rng)};
    default:
      return Cylinder{0.5 * size(rng), 4 * size(rng)};
  }
}

// Distance to the solid by sampling its surface densely (parametrically, not by the formula under
// test); `step` bounds the sampling error.
double sampledDistance(const Primitive& p, const Eigen::Vector3d& x, double* step) {
  if (containsPoint(p, x)) {
    *step = 0;
    return 0;
  }
  double best = 1e300;
  const int n = 120;
  if (const auto* b = std::get_if<Box>(&p)) {
    const Eigen::Vector3d& h = b->half_extents;
    for (int face = 0; face < 6; ++face) {
      const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          Eigen::Vector3d q;
          q[a] = face % 2 ? h[a] : -h[a];
          q[u] = -h[u] + 2 * h[u] * i / n;
          q[v] = -h[v] + 2 * h[v] * j / n;
          best = std::min(best, (q - x).norm());
        }
    }
    *step = 2 * h.maxCoeff() / n * std::sqrt(2.0);
    return best;
  }
  if (const auto* s = std::get_if<Sphere>(&p)) {
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j < 2 * n; ++j) {
        const double th = M_PI * i / n, ph = M_PI * j / n;
        const Eigen::Vector3d q =
            s->radius *
            Eigen::Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        best = std::min(best, (q - x).norm());
      }
    *step = 2 * M_PI * s->radius / n;
    return best;
  }
  const auto& c = std::get<Cylinder>(p);
  const double hl = 0.5 * c.length;
  for (int j = 0; j < 2 * n; ++j) {
    const double ph = M_PI * j / n;
    for (int i = 0; i <= n; ++i) {
      // The side, and the two caps (rings of radius r i / n).
      const Eigen::Vector3d side(c.radius * std::cos(ph), c.radius * std::sin(ph),
                                 -hl + 2 * hl * i / n);
      best = std::min(best, (side - x).norm());
      for (double z : {-hl, hl}) {
        const double r = c.radius * i / n;
        best = std::min(best, (Eigen::Vector3d(r * std::cos(ph), r * std::sin(ph), z) - x).norm());
      }
    }
  }
  *step = std::max(2 * hl / n, M_PI * c.radius / n) * std::sqrt(2.0);
  return best;
}

TEST(PrimitiveShape, SquaredDistanceMatchesDenseSamplesOfTheSolid) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-0.3, 0.3);
  int outside = 0;
  for (int i = 0; i < 600; ++i) {
    const Primitive p = randomPrimitive(rng, i);
    const PrimitiveShape shape(p);
    const Eigen::Vector3d x(coord(rng), coord(rng), i % 4 == 0 ? 0.0 : coord(rng));
    double step = 0;
    const double expected = sampledDistance(p, x, &step);
    const double got = std::sqrt(shape.squaredDistance(x.data()));
    outside += expected > 0;
    // The formula is exact; the samples overestimate by at most half a sampling step.
    EXPECT_LE(got, expected + 1e-12) << "primitive " << i;
    EXPECT_GE(got, expected - step) << "primitive " << i;
  }
  EXPECT_GT(outside, 400);
}

TEST(PrimitiveShape, RejectsInvalidSizes) {
  EXPECT_THROW(PrimitiveShape(Sphere{-1.0}), InvalidArgument);
  EXPECT_THROW(PrimitiveShape(Cylinder{0.1, std::nan("")}), InvalidArgument);
  EXPECT_THROW(PrimitiveShape(Box{Eigen::Vector3d(0.1, 0, 0.1)}), InvalidArgument);
}

// The rule for one black voxel (its cube, placed in P), written with Eigen: the voxel's bounding
// sphere meets the shape, and for a box the voxel and the box overlap.
bool leafRule(const Primitive& p, const PrimitiveShape& shape, const Eigen::Vector3d& centre_P,
              const Eigen::Matrix3d& R_PS, double half) {
  const double reach = std::sqrt(3.0) * half * (1 + 1e-9);
  if (shape.squaredDistance(centre_P.data()) > reach * reach) return false;
  if (const auto* b = std::get_if<Box>(&p)) {
    return boxesOverlap(Eigen::Vector3d::Zero(), b->half_extents, R_PS, centre_P,
                        Eigen::Vector3d::Constant(half), 1e-9 * half);
  }
  return true;
}

struct LeafQuery {
  bool oracle = false;        // some black voxel satisfies the rule
  bool point_inside = false;  // a sampled point of a black voxel lies inside the shape
};

LeafQuery bruteForce(const Octree& source, const Eigen::Isometry3d& X_PS, const Primitive& p,
                     std::mt19937_64& rng) {
  const PrimitiveShape shape(p);
  LeafQuery out;
  const double s = source.grid().voxelSize();
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Voxel by voxel (a dense array of the tree's colours), whatever the leaves.
  const double h = 0.5 * s;
  for (const Voxel& v : test::DenseGrid::fromTree(source).voxels()) {
    const Eigen::Vector3d centre_S =
        source.grid().toWorld(Eigen::Vector3d(v.x, v.y, v.z)) + Eigen::Vector3d::Constant(h);
    out.oracle = out.oracle || leafRule(p, shape, X_PS * centre_S, X_PS.linear(), h);
    // Corners, centre and random points of the leaf.
    for (int k = 0; k < 17 && !out.point_inside; ++k) {
      Eigen::Vector3d d;
      if (k < 8) {
        d = Eigen::Vector3d((k & 1) ? h : -h, (k & 2) ? h : -h, (k & 4) ? h : -h);
      } else if (k == 8) {
        d.setZero();
      } else {
        d = h * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      }
      out.point_inside = containsPoint(p, X_PS * (centre_S + d));
    }
  }
  return out;
}

TEST(BlackLeafMeetsPrimitive, EqualsTheLeafRuleOnEveryLeafAndFindsEveryOverlap) {
  std::mt19937_64 rng(5);
  const WorldGrid grids[] = {WorldGrid(Eigen::Vector3d(0.1, -0.2, 0.05), 0.01, 4),
                             WorldGrid(Eigen::Vector3d(-0.3, 0.0, 0.2), 0.004, 5)};
  int hits = 0, misses = 0, overlaps = 0, near_only = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const WorldGrid& g = grids[trial % 2];
    const Octree source =
        trial % 7 == 0 ? voxelize(g, Cylinder{0.02, 0.05},
                                  Eigen::Isometry3d(Eigen::Translation3d(test::gridCentre(g))),
                                  Rounding::kConservative)
                       : test::randomShape(g.depth(), rng, 2, 6).toTree(g);
    const MovableSource prepared(source);
    const Primitive p = randomPrimitive(rng, trial);
    // The primitive near the source's centre, so that contacts and near misses both occur.
    std::uniform_real_distribution<double> offset(-0.12, 0.12);
    Eigen::Isometry3d X_PS = Eigen::Isometry3d::Identity();
    X_PS.linear() = test::randomRotation(rng).toRotationMatrix();
    const Eigen::Vector3d centre_S = test::gridCentre(g);
    X_PS.translation() =
        -(X_PS.linear() * centre_S) + Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    const LeafQuery expected = bruteForce(source, X_PS, p, rng);
    const bool got = blackLeafMeetsPrimitive(prepared, X_PS, PrimitiveShape(p));
    EXPECT_EQ(got, expected.oracle) << "trial " << trial;
    if (expected.point_inside) {
      ++overlaps;
      EXPECT_TRUE(got) << "trial " << trial << ": a leaf overlaps the shape";
    }
    near_only += got && !expected.point_inside;
    (got ? hits : misses)++;
  }
  // Not vacuous: both answers, real overlaps, and answers from the leaves' margin alone.
  EXPECT_GT(hits, 150);
  EXPECT_GT(misses, 150);
  EXPECT_GT(overlaps, 100);
  EXPECT_GT(near_only, 8);
}

TEST(BlackLeafMeetsPrimitive, EmptyAndFullSources) {
  const WorldGrid g(Eigen::Vector3d::Zero(), 0.01, 3);
  const MovableSource empty{Octree(g)};
  const MovableSource full{Octree::full(g)};
  const PrimitiveShape ball(Sphere{0.01});
  Eigen::Isometry3d X_PS = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(blackLeafMeetsPrimitive(empty, X_PS, ball));
  EXPECT_TRUE(blackLeafMeetsPrimitive(full, X_PS, ball));
  // The full 8 cm cube [0, 8 cm]^3 — one black leaf of 1 cm voxels — and the 1 cm ball beside
  // its face x = 0, in line with a voxel's centre (y = z = 3.5 cm). 3 mm from the face it is
  // within that voxel's sphere (1.8 - 1 < √3 x 0.5 cm): yes, the voxels' margin. 5 mm from it,
  // no voxel's sphere reaches it, though the whole leaf's sphere (√3 x 4 cm) would: no.
  X_PS.translation() = Eigen::Vector3d(0.013, -0.035, -0.035);
  EXPECT_TRUE(blackLeafMeetsPrimitive(full, X_PS, ball));
  X_PS.translation() = Eigen::Vector3d(0.015, -0.035, -0.035);
  EXPECT_FALSE(blackLeafMeetsPrimitive(full, X_PS, ball));
  X_PS.translation() = Eigen::Vector3d(-0.04, -0.04, -0.04);  // inside: the centre shortcut
  EXPECT_TRUE(blackLeafMeetsPrimitive(full, X_PS, ball));
  // A box obstacle 1 cm beyond the cube's face: the sphere reaches it, the exact test does not.
  const PrimitiveShape slab(Box{Eigen::Vector3d(0.005, 0.5, 0.5)});
  X_PS.translation() = Eigen::Vector3d(0.015, 0, 0);  // the slab spans x in [-0.02, -0.01] of S
  EXPECT_FALSE(blackLeafMeetsPrimitive(full, X_PS, slab));
  X_PS.translation() = Eigen::Vector3d(0.004, 0, 0);  // now it spans x in [-0.009, 0.001]
  EXPECT_TRUE(blackLeafMeetsPrimitive(full, X_PS, slab));
}

}  // namespace
}  // namespace octomotion
