// convexHullTriangles and ConvexPoints::hullOf against brute force: every hull passes its own
// check and holds every point; every triangle of it is a face of the hull (no point beyond its
// plane); a climb along its edges finds the highest of all the points, on random clouds,
// clouds with many points on a few planes (box corners and face grids), duplicates and nearly
// flat sets, and far from the origin; the check refuses open, doubled and non-convex surfaces; sets
// with no volume get no hull, and so do sets of more than kMaxHullPoints.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "octomotion/motion/convex_gap.h"
#include "octomotion/motion/convex_hull.h"

namespace octomotion {
namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

double highestAlong(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& d) {
  double highest = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) highest = std::max(highest, d.dot(p));
  return highest;
}

// Clouds of several kinds, fixed by the seed.
std::vector<Eigen::Vector3d> cloud(std::mt19937_64& rng, int kind, double away = 3) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  const int count = 4 + static_cast<int>(300 * (u(rng) + 1) / 2);
  const Eigen::Vector3d offset(away * u(rng), away * u(rng), away * u(rng));
  const double scale = std::pow(10.0, 2 * u(rng));  // 0.01 to 100
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    switch (kind) {
      case 0:  // inside a ball
        p = Eigen::Vector3d(u(rng), u(rng), u(rng));
        break;
      case 1:  // on a sphere: every point a vertex
        p = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
        break;
      case 2:  // a box's corners and a grid on its faces: many points on each plane
        p = Eigen::Vector3d(std::round(2 * u(rng)) / 2, std::round(2 * u(rng)) / 2,
                            std::round(2 * u(rng)) / 2);
        p[static_cast<int>(3 * (u(rng) + 1) / 2) % 3] = u(rng) < 0 ? -1 : 1;
        break;
      default:  // a thin slab: nearly flat
        p = Eigen::Vector3d(u(rng), u(rng), 1e-3 * u(rng));
        break;
    }
    points.push_back(offset + scale * p);
    if (u(rng) > 0.8) points.push_back(points.back());  // duplicates
  }
  return points;
}

TEST(ConvexHull, EveryTriangleIsAFaceAndEveryPointIsInside) {
  std::mt19937_64 rng(0x4011);
  int made = 0;
  for (int set = 0; set < 200; ++set) {
    const std::vector<Eigen::Vector3d> points = cloud(rng, set % 4);
    const auto triangles = convexHullTriangles(points);
    if (!triangles) continue;
    ++made;
    double extent = 0;
    for (const Eigen::Vector3d& p : points) extent = std::max(extent, p.norm());
    EXPECT_TRUE(isClosedConvexSurface(points, *triangles, 1e-9 * extent));
    for (const auto& t : *triangles) {
      const Eigen::Vector3d& a = points[t[0]];
      const Eigen::Vector3d n = (points[t[1]] - a).cross(points[t[2]] - a).normalized();
      double beyond = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : points) beyond = std::max(beyond, n.dot(p - a));
      // A face: no point beyond its plane, and its own points on it.
      EXPECT_LE(beyond, 1e-9 * extent);
      EXPECT_GE(beyond, -1e-9 * extent);
    }
  }
  EXPECT_GE(made, 150);  // only flat or tiny sets may fail
}

TEST(ConvexHull, ClimbFindsTheHighestOfEveryPoint) {
  std::mt19937_64 rng(0x4012);
  std::normal_distribution<double> g(0.0, 1.0);
  int exact = 0;
  for (int set = 0; set < 160; ++set) {
    const std::vector<Eigen::Vector3d> points = cloud(rng, set % 4);
    const ConvexPoints hull = ConvexPoints::hullOf(points, 0.25);
    if (!hull.hasEdges()) continue;  // no hull: every point is searched
    EXPECT_TRUE(hull.exactClimb());
    ++exact;
    double extent = 0;
    for (const Eigen::Vector3d& p : points) extent = std::max(extent, p.norm());
    // The radius grows only by rounding.
    EXPECT_GE(hull.radius(), 0.25);
    EXPECT_LE(hull.radius(), 0.25 + 1e-9 * extent);
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d d(g(rng), g(rng), g(rng));
      const double climbed = d.dot(hull.point(hull.climbSupport(d))) + d.norm() * hull.radius();
      const double highest = highestAlong(points, d) + d.norm() * 0.25;
      // Never below the highest point (the certificate's side), and no higher than rounding.
      EXPECT_GE(climbed, highest - 1e-12 * (1 + std::abs(highest)));
      EXPECT_LE(climbed, highest + 1e-9 * extent * d.norm());
      EXPECT_EQ(hull.exactSupport(d), hull.climbSupport(d));
    }
  }
  EXPECT_GE(exact, 120);
}

// Climbs start at the support point of the cell of the cube of directions that d crosses: the
// directions that pick the cell are checked where they are awkward: on the cells' and faces'
// borders, along the axes, with zero and negative zero components, at scales from 1e-290 to
// 1e290 and beyond the start table's range (1e-305, 1e305), and with a NaN component (no
// crash; any answer). The climb must still find the highest point.
TEST(ConvexHull, ClimbFindsTheHighestFromEveryStartCell) {
  std::mt19937_64 rng(0x4016);
  const std::vector<double> coordinates = {-1.0,  -0.75, -0.5, -0.25, -0.0, 0.0,
                                           0.125, 0.25,  0.5,  0.75,  1.0,  0.3};
  const std::vector<double> scales = {1e-305, 1e-290, 1e-3, 1.0, 7.0, 1e290, 1e305};
  for (int set = 0; set < 8; ++set) {
    const std::vector<Eigen::Vector3d> points = cloud(rng, set % 4);
    const ConvexPoints hull = ConvexPoints::hullOf(points);
    if (!hull.hasEdges()) continue;
    for (double x : coordinates) {
      for (double y : coordinates) {
        for (double z : coordinates) {
          for (double scale : scales) {
            const Eigen::Vector3d d = Eigen::Vector3d(x, y, z) * scale;
            if (d.isZero(0)) continue;
            // The comparison on the unit direction: the scaled products may under- or overflow.
            const Eigen::Vector3d unit = Eigen::Vector3d(x, y, z).normalized();
            const double climbed = unit.dot(hull.point(hull.climbSupport(d)));
            const double highest = highestAlong(points, unit);
            EXPECT_GE(climbed, highest - 1e-12 * (1 + std::abs(highest)))
                << "set " << set << " d " << d.transpose();
          }
        }
      }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Eigen::Vector3d& d :
         {Eigen::Vector3d(nan, 1, 0), Eigen::Vector3d(1, nan, 0.5), Eigen::Vector3d(0, 0.2, nan),
          Eigen::Vector3d(nan, nan, nan), Eigen::Vector3d(0, 0, 0)}) {
      EXPECT_LT(hull.climbSupport(d), hull.size());
    }
  }
}

TEST(ConvexHull, FarFromTheOriginTheClimbStillHoldsEveryPoint) {
  // Small sets a hundred kilometres out: rounding in the planes is then far above the sets'
  // own scale. A hull may not be made; one that is must still hold every point.
  std::mt19937_64 rng(0x4015);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int set = 0; set < 80; ++set) {
    const std::vector<Eigen::Vector3d> points = cloud(rng, set % 4, 1e5);
    const ConvexPoints hull = ConvexPoints::hullOf(points);
    for (int k = 0; k < 100; ++k) {
      const Eigen::Vector3d d(g(rng), g(rng), g(rng));
      const double support = d.dot(hull.point(hull.exactSupport(d))) + d.norm() * hull.radius();
      const double highest = highestAlong(points, d);
      EXPECT_GE(support, highest - 1e-9 * d.norm()) << "set " << set;
    }
  }
}

TEST(ConvexHull, HullDistancesMatchThePointSets) {
  // The hull's distance bound to another set equals the one over every point (the same hull).
  std::mt19937_64 rng(0x4013);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int set = 0; set < 60; ++set) {
    const std::vector<Eigen::Vector3d> a = cloud(rng, set % 3);
    const std::vector<Eigen::Vector3d> b = cloud(rng, (set + 1) % 3);
    const ConvexPoints hull_a = ConvexPoints::hullOf(a), hull_b = ConvexPoints::hullOf(b);
    const ConvexPoints all_a(a), all_b(b);
    Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
    X_AB.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
    X_AB.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 400;
    const double by_hulls = convexDistanceBelow(hull_a, hull_b, X_AB, 1e9);
    const double by_points = convexDistanceBelow(all_a, all_b, X_AB, 1e9);
    EXPECT_NEAR(by_hulls, by_points, 1e-6 * (1 + by_points)) << "set " << set;
    EXPECT_EQ(convexApart(hull_a, hull_b, X_AB, 0.5 * by_points),
              convexApart(all_a, all_b, X_AB, 0.5 * by_points));
  }
}

TEST(ConvexHull, SetsWithNoVolumeGetNone) {
  std::vector<Eigen::Vector3d> flat;
  for (int i = 0; i < 20; ++i) flat.emplace_back(i % 5, i / 5, 0.0);
  EXPECT_FALSE(convexHullTriangles(flat));
  EXPECT_FALSE(convexHullTriangles(
      {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()}));
  std::vector<Eigen::Vector3d> same(10, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(convexHullTriangles(same));
  std::vector<Eigen::Vector3d> not_finite = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                             Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                             Eigen::Vector3d::Constant(std::nan(""))};
  EXPECT_FALSE(convexHullTriangles(not_finite));
  // Too many points: none either (the build is quadratic).
  std::mt19937_64 rng(0x4014);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Vector3d> many;
  for (std::size_t i = 0; i <= kMaxHullPoints; ++i) many.emplace_back(g(rng), g(rng), g(rng));
  EXPECT_FALSE(convexHullTriangles(many));
  many.pop_back();
  EXPECT_TRUE(convexHullTriangles(many));
  // Without a hull, hullOf keeps every point and searches them all.
  const ConvexPoints kept = ConvexPoints::hullOf(flat);
  EXPECT_EQ(kept.size(), flat.size());
  EXPECT_FALSE(kept.hasEdges());
}

TEST(ConvexHull, CheckRefusesOpenDoubledAndDentedSurfaces) {
  const std::vector<Eigen::Vector3d> tetra = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                              Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const Triangles closed = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_TRUE(isClosedConvexSurface(tetra, closed, 1e-12));
  Triangles open = closed;
  open.pop_back();
  EXPECT_FALSE(isClosedConvexSurface(tetra, open, 1e-12));
  Triangles inward = closed;
  for (auto& t : inward) std::swap(t[1], t[2]);
  EXPECT_FALSE(isClosedConvexSurface(tetra, inward, 1e-12));
  Triangles doubled = closed;
  doubled.push_back(closed[0]);
  EXPECT_FALSE(isClosedConvexSurface(tetra, doubled, 1e-12));
  // A bipyramid over a triangle: convex with its apexes on both sides, dented with the lower
  // apex pushed above the base.
  std::vector<Eigen::Vector3d> bipyramid = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                            Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.2, 0.2, 1),
                                            Eigen::Vector3d(0.2, 0.2, -1)};
  const Triangles sides = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 4}, {2, 1, 4}, {1, 0, 4}};
  EXPECT_TRUE(isClosedConvexSurface(bipyramid, sides, 1e-12));
  bipyramid[4].z() = 0.5;
  EXPECT_FALSE(isClosedConvexSurface(bipyramid, sides, 1e-12));
}

}  // namespace
}  // namespace octomotion
