// convexApart (GJK with a checked certificate) against what can be known without it: an answer
// "apart" is re-checked by brute force over every point pair along the direction it returns;
// sets built on two sides of a known plane must be found apart whenever the gap asked for is
// smaller than the slab between them; sets sharing a point are never apart; single points
// grown by radii are apart exactly when their distance exceeds the radii and the gap; on a
// convex mesh the climb along edges finds the support, and edges never change an answer's proof.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/motion/convex_gap.h"

namespace octomotion {
namespace {

Eigen::Isometry3d randomPose(std::mt19937_64& rng, double reach) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
  if (q.norm() < 1e-6) q = Eigen::Quaterniond::Identity();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = reach * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

Eigen::Vector3d randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector3d d(n(rng), n(rng), n(rng));
  return d.squaredNorm() > 0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitZ();
}

std::vector<Eigen::Vector3d> randomCloud(std::mt19937_64& rng, int count, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

// min over a in A, b in B of n . (a - X_AB b), n = v / |v|.
double gapAlong(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                const Eigen::Isometry3d& X_AB, const Eigen::Vector3d& v) {
  const Eigen::Vector3d n = v.normalized();
  double lo_a = 1e300, hi_b = -1e300;
  for (const auto& p : a) lo_a = std::min(lo_a, n.dot(p));
  for (const auto& p : b) hi_b = std::max(hi_b, n.dot(X_AB * p));
  return lo_a - hi_b;
}

TEST(ConvexGap, EveryApartAnswerHasASeparatingDirection) {
  std::mt19937_64 rng(0xc0417e);
  std::uniform_int_distribution<int> count(1, 60);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int apart = 0, not_apart = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const auto a = randomCloud(rng, count(rng), 0.5);
    const auto b = randomCloud(rng, count(rng), 0.5);
    const double ra = 0.1 * unit(rng), rb = 0.1 * unit(rng), gap = 0.2 * unit(rng);
    const Eigen::Isometry3d X_AB = randomPose(rng, 2.5);
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    if (convexApart(ConvexPoints(a, ra), ConvexPoints(b, rb), X_AB, gap, &v)) {
      ++apart;
      EXPECT_GT(gapAlong(a, b, X_AB, v), gap + ra + rb) << "trial " << trial;
    } else {
      ++not_apart;
    }
  }
  EXPECT_GT(apart, 100);  // both answers occur
  EXPECT_GT(not_apart, 100);
}

// Two random point sets, in their own frames A and B, on the two sides of a slab of random width
// s: in a world frame W, a in x <= -s/2 and b in x >= s/2, one point of each on the slab's faces
// at the same y and z, so their distance is exactly s.
struct SlabPair {
  double s;
  std::vector<Eigen::Vector3d> a, b;
  Eigen::Isometry3d X_WA, X_WB, X_AB;
};
SlabPair slabPair(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> count(1, 200);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double s = 1e-4 + 0.3 * unit(rng);
  auto a_W = randomCloud(rng, count(rng), 0.5), b_W = randomCloud(rng, count(rng), 0.5);
  for (auto& p : a_W) p.x() = -s / 2 - (p.x() + 0.5);
  for (auto& p : b_W) p.x() = s / 2 + (p.x() + 0.5);
  a_W[0] = Eigen::Vector3d(-s / 2, 0, 0);
  b_W[0] = Eigen::Vector3d(s / 2, 0, 0);
  const Eigen::Isometry3d X_WA = randomPose(rng, 1.0), X_WB = randomPose(rng, 1.0);
  SlabPair pair{s, {}, {}, X_WA, X_WB, X_WA.inverse() * X_WB};
  for (const auto& p : a_W) pair.a.push_back(X_WA.inverse() * p);
  for (const auto& p : b_W) pair.b.push_back(X_WB.inverse() * p);
  return pair;
}

TEST(ConvexGap, SetsOnTwoSidesOfASlabAreApart) {
  std::mt19937_64 rng(0x51ab);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto [s, a, b, X_WA, X_WB, X_AB] = slabPair(rng);
    const ConvexPoints ca(a), cb(b);
    EXPECT_TRUE(convexApart(ca, cb, X_AB, 0.99 * s)) << "trial " << trial << " slab " << s;
    EXPECT_FALSE(convexApart(ca, cb, X_AB, 1.01 * s)) << "trial " << trial << " slab " << s;
  }
}

TEST(ConvexGap, SetsSharingAPointAreNeverApart) {
  std::mt19937_64 rng(0x5a4e);
  std::uniform_int_distribution<int> count(1, 60);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto a = randomCloud(rng, count(rng), 0.5);
    auto b = randomCloud(rng, count(rng), 0.5);
    const Eigen::Isometry3d X_AB = randomPose(rng, 0.8);
    // A point of a's hull (a random convex combination), written in b's frame.
    Eigen::Vector3d shared = Eigen::Vector3d::Zero();
    double total = 0;
    for (const auto& p : a) {
      const double w = unit(rng);
      shared += w * p;
      total += w;
    }
    b.push_back(X_AB.inverse() * (shared / std::max(total, 1e-12)));
    // Placing the point in b's frame rounds it (a hull of one point is that point), so "apart"
    // is asked beyond rounding.
    EXPECT_FALSE(convexApart(ConvexPoints(a), ConvexPoints(b), X_AB, 1e-9)) << "trial " << trial;
  }
}

TEST(ConvexGap, BallsAreApartExactlyBeyondTheirRadiiAndTheGap) {
  std::mt19937_64 rng(0xba11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double ra = unit(rng), rb = unit(rng), gap = 0.1 * unit(rng);
    const double d = 3 * unit(rng);
    if (std::abs(d - (ra + rb + gap)) < 1e-9) continue;
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0);
    Eigen::Isometry3d X_WB = randomPose(rng, 1.0);
    X_WB.translation() = X_WA.translation() + d * randomPose(rng, 1.0).linear().col(0);
    const ConvexPoints a({Eigen::Vector3d::Zero()}, ra), b({Eigen::Vector3d::Zero()}, rb);
    EXPECT_EQ(convexApart(a, b, X_WA.inverse() * X_WB, gap), d > ra + rb + gap)
        << "trial " << trial;
  }
}

// An ellipsoid's latitude-longitude mesh (convex); `bump` > 0 moves every vertex in or out along
// its radius at random, which makes the mesh non-convex.
void ellipsoidMesh(std::mt19937_64& rng, double bump, std::vector<Eigen::Vector3d>& points,
                   std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector3d axes(0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng));
  const int rings = 8, sectors = 12;
  points.clear();
  triangles.clear();
  points.emplace_back(0, 0, axes.z());  // north pole: 0
  for (int i = 1; i < rings; ++i) {
    for (int j = 0; j < sectors; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / sectors;
      const double r = 1 + bump * (2 * u(rng) - 1);
      points.emplace_back(r * axes.x() * std::sin(theta) * std::cos(phi),
                          r * axes.y() * std::sin(theta) * std::sin(phi),
                          r * axes.z() * std::cos(theta));
    }
  }
  points.emplace_back(0, 0, -axes.z());  // south pole
  const auto at = [&](int i, int j) {
    return static_cast<std::uint32_t>(1 + (i - 1) * sectors + (j % sectors));
  };
  const auto south = static_cast<std::uint32_t>(points.size() - 1);
  for (int j = 0; j < sectors; ++j) {
    triangles.push_back({0, at(1, j), at(1, j + 1)});
    triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

TEST(ConvexGap, ClimbFindsTheSupportOnAConvexMesh) {
  std::mt19937_64 rng(0xc11b);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (int mesh = 0; mesh < 50; ++mesh) {
    ellipsoidMesh(rng, 0.0, points, triangles);
    const ConvexPoints hull(points, triangles);
    ASSERT_TRUE(hull.hasEdges());
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d d(n(rng), n(rng), n(rng));
      EXPECT_NEAR(d.dot(hull.point(hull.climbSupport(d))), d.dot(hull.point(hull.supportIndex(d))),
                  1e-12);
    }
  }
}

// Large sets are searched cluster by cluster (a cluster whose bound cannot beat the best point is
// skipped): the support value is still the highest over every given point, for sets of a few to
// thousands of points, spread out or in tight clumps with repeated points, in any direction.
TEST(ConvexGap, SupportIsTheHighestOfEveryPoint) {
  std::mt19937_64 rng(0x5099);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int set = 0; set < 60; ++set) {
    const auto count = static_cast<std::size_t>(5 + 3000 * u(rng) * u(rng));
    const double clump = u(rng) < 0.5 ? 1e-6 : 1.0;
    std::vector<Eigen::Vector3d> points;
    for (std::size_t i = 0; i < count; ++i) {
      if (i > 0 && u(rng) < 0.1) {
        points.push_back(points[static_cast<std::size_t>(u(rng) * static_cast<double>(i))]);
      } else {
        points.emplace_back(Eigen::Vector3d(n(rng), n(rng), n(rng)) * clump +
                            Eigen::Vector3d(3 * std::floor(4 * u(rng)), 0, 0));
      }
    }
    const ConvexPoints hull(points);
    for (int k = 0; k < 100; ++k) {
      const Eigen::Vector3d d(n(rng), n(rng), n(rng));
      double highest = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : points) highest = std::max(highest, d.dot(p));
      EXPECT_NEAR(d.dot(hull.point(hull.supportIndex(d))), highest,
                  1e-12 * (1 + std::abs(highest)));
    }
  }
}

TEST(ConvexGap, BoxSupportIsTheHighestCorner) {
  // boxHull finds its support from the direction's signs; each corner against all eight, with
  // zero extents and zero components among the cases.
  std::mt19937_64 rng(0x50b0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    Eigen::Vector3d half(std::abs(u(rng)), std::abs(u(rng)), std::abs(u(rng)));
    if (k % 7 == 0) half[k % 3] = 0;
    Eigen::Vector3d d(u(rng), u(rng), u(rng));
    if (k % 5 == 0) d[(k / 5) % 3] = 0;
    const ConvexPoints box = boxHull(half);
    double highest = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& c : boxCorners(half)) highest = std::max(highest, d.dot(c));
    EXPECT_EQ(d.dot(box.point(box.supportIndex(d))), highest);
  }
}

// Edges only guide the search: on non-convex meshes, where a climb can stop short, every
// "apart" still has its separating direction, and convex meshes across a slab are found apart.
TEST(ConvexGap, EdgesChangeNoAnswer) {
  std::mt19937_64 rng(0xed9e);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> pa, pb;
  std::vector<std::array<std::uint32_t, 3>> ta, tb;
  int apart = 0, same = 0, trials = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double bump = trial % 2 == 0 ? 0.0 : 0.3;
    ellipsoidMesh(rng, bump, pa, ta);
    ellipsoidMesh(rng, bump, pb, tb);
    const Eigen::Isometry3d X_AB = randomPose(rng, 0.8);
    const double gap = 0.05 * unit(rng);
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    const bool with_edges = convexApart(ConvexPoints(pa, ta), ConvexPoints(pb, tb), X_AB, gap, &v);
    if (with_edges) {
      ++apart;
      EXPECT_GT(gapAlong(pa, pb, X_AB, v), gap) << "trial " << trial;
    }
    if (bump == 0.0) {
      ++trials;
      same += with_edges == convexApart(ConvexPoints(pa), ConvexPoints(pb), X_AB, gap);
    }
  }
  EXPECT_GT(apart, 300);
  // Convex meshes: the same support values, so (ties aside) the same answers.
  EXPECT_GE(same, trials - trials / 100);
}

TEST(ConvexGap, RefusesEmptyAndNonFiniteInput) {
  EXPECT_THROW(ConvexPoints(std::vector<Eigen::Vector3d>{}), InvalidArgument);
  EXPECT_THROW(ConvexPoints({Eigen::Vector3d(0, 0, std::nan(""))}), InvalidArgument);
  EXPECT_THROW(ConvexPoints({Eigen::Vector3d::Zero()}, -1), InvalidArgument);
  EXPECT_THROW(ConvexPoints({Eigen::Vector3d::Zero()}, {{0, 0, 1}}), InvalidArgument);
  EXPECT_FALSE(convexApart(ConvexPoints(), ConvexPoints({Eigen::Vector3d::Zero()}),
                           Eigen::Isometry3d::Identity(), 0));
}

// convexDistanceBelow: a certified lower bound. Brute force over every point: its direction
// leaves the sets at least the bound apart (so it never exceeds their distance), and it never
// exceeds the closest pair of points (less the radii). Random clouds, radii, poses and caps; each
// again from a given direction.
TEST(ConvexDistance, EveryBoundHasItsSlabAndStaysBelowEveryPointPair) {
  std::mt19937_64 rng(0xd157);
  std::uniform_int_distribution<int> count(1, 60);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> pa, pb;
  std::vector<std::array<std::uint32_t, 3>> ta, tb;
  int positive = 0, zero = 0, warm_at_cap = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const bool meshes = trial % 3 == 0;  // non-convex meshes: climbs that stop short
    if (meshes) {
      ellipsoidMesh(rng, 0.3, pa, ta);
      ellipsoidMesh(rng, 0.3, pb, tb);
    } else {
      pa = randomCloud(rng, count(rng), 0.5);
      pb = randomCloud(rng, count(rng), 0.5);
    }
    const double ra = 0.1 * unit(rng), rb = 0.1 * unit(rng);
    const double cap = trial % 2 == 0 ? std::numeric_limits<double>::infinity() : unit(rng);
    const Eigen::Isometry3d X_AB = randomPose(rng, meshes ? 0.8 : 2.5);
    const ConvexPoints a = meshes ? ConvexPoints(pa, ta, ra) : ConvexPoints(pa, ra);
    const ConvexPoints b = meshes ? ConvexPoints(pb, tb, rb) : ConvexPoints(pb, rb);
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    const double bound = convexDistanceBelow(a, b, X_AB, cap, &v);
    ASSERT_GE(bound, 0.0);
    double closest = std::numeric_limits<double>::infinity();
    for (const auto& p : pa) {
      for (const auto& q : pb) closest = std::min(closest, (p - X_AB * q).norm());
    }
    EXPECT_LE(bound, std::max(0.0, closest - ra - rb)) << "trial " << trial;
    if (bound > 0) {
      ++positive;
      EXPECT_GE(gapAlong(pa, pb, X_AB, v) - ra - rb, bound) << "trial " << trial;
    } else {
      ++zero;
    }
    // A given direction (the answer's, or a stale one) is tried first: the bound stays below
    // every point pair, equals the first where that did not reach the cap, and reaches the cap
    // where the first did.
    Eigen::Vector3d given = trial % 4 == 0 ? v : randomDirection(rng) * (0.1 + unit(rng));
    const double warm = convexDistanceBelow(a, b, X_AB, cap, &given);
    EXPECT_LE(warm, std::max(0.0, closest - ra - rb)) << "trial " << trial;
    if (bound < cap) {
      EXPECT_EQ(warm, bound) << "trial " << trial;
    } else {
      EXPECT_GE(warm, cap) << "trial " << trial;
      ++warm_at_cap;
    }
  }
  EXPECT_GT(positive, 300);  // both answers occur
  EXPECT_GT(zero, 300);
  EXPECT_GT(warm_at_cap, 100);
}

// Convex sets at a known distance s (two sides of a slab, one point of each on its faces):
// without a cap the bound is s up to GJK's tolerance (the default's, and a looser one); with one,
// it reaches a cap below s and stays below a cap above it; sets sharing a point get 0.
TEST(ConvexDistance, FindsTheDistanceOfSetsAcrossASlab) {
  std::mt19937_64 rng(0xd51a);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto [s, a, b, X_WA, X_WB, X_AB] = slabPair(rng);
    const ConvexPoints ca(a), cb(b);
    const double inf = std::numeric_limits<double>::infinity();
    // GJK stops when |v|^2 - v.w <= 1e-9 |v|^2: |v| - s <= 1e-9 |v|, and the bound along v is
    // within that of s; the nanometre taken for rounding, and rounding in the poses.
    const double bound = convexDistanceBelow(ca, cb, X_AB, inf);
    EXPECT_LE(bound, s) << "trial " << trial;
    EXPECT_GE(bound, s - 1e-8 - 1e-6 * s) << "trial " << trial;
    EXPECT_GE(convexDistanceBelow(ca, cb, X_AB, 0.99 * s), 0.99 * s) << "trial " << trial;
    EXPECT_LT(convexDistanceBelow(ca, cb, X_AB, 1.01 * s), 1.01 * s) << "trial " << trial;
    // A looser tolerance: v . w >= (1 - tolerance) |v|^2 at the stop, so the bound along v is at
    // least (1 - tolerance) |v| >= (1 - tolerance) s, and never above s.
    constexpr double kLoose = 1e-2;
    const double loose = convexDistanceBelow(ca, cb, X_AB, inf, nullptr, kLoose);
    EXPECT_LE(loose, s) << "trial " << trial;
    EXPECT_GE(loose, (1 - kLoose) * s - 1e-8) << "trial " << trial;
    // Shift b by s along the slab's normal (x in W): the sets now share a point.
    Eigen::Isometry3d X_WB_touching = X_WB;
    X_WB_touching.translation() -= Eigen::Vector3d(s, 0, 0);
    EXPECT_EQ(convexDistanceBelow(ca, cb, X_WA.inverse() * X_WB_touching, inf), 0.0)
        << "trial " << trial;
  }
}

// The distance from p to the box |x| <= h (brute force needs no search for a box).
double pointBoxDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& h) {
  return (p.cwiseAbs() - h).cwiseMax(0.0).norm();
}

// The distance from p to the solid cylinder of radius r and length l along z.
double pointCylinderDistance(const Eigen::Vector3d& p, double r, double l) {
  const double radial = std::max(0.0, p.head<2>().norm() - r);
  const double axial = std::max(0.0, std::abs(p.z()) - l / 2);
  return std::hypot(radial, axial);
}

// The distance between segments p0-p1 and q0-q1 (Ericson, Real-Time Collision Detection
// §5.1.9).
double segmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > 1e-12 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p0 + d1 * s) - (q0 + d2 * t)).norm();
}

// Two disjoint convex polyhedra are closest at a vertex of one and the other's solid, or at two
// edges: the least of those, for boxes (zero when a corner is inside the other or edges cross
// faces: callers keep the boxes apart).
double boxBoxDistance(const Eigen::Vector3d& ha, const Eigen::Vector3d& hb,
                      const Eigen::Isometry3d& X_AB) {
  std::array<Eigen::Vector3d, 8> ca, cb_A;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d sign((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    ca[static_cast<std::size_t>(k)] = ha.cwiseProduct(sign);
    cb_A[static_cast<std::size_t>(k)] = X_AB * Eigen::Vector3d(hb.cwiseProduct(sign));
  }
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  for (int k = 0; k < 8; ++k) {
    best = std::min(best, pointBoxDistance(cb_A[static_cast<std::size_t>(k)], ha));
    best = std::min(best, pointBoxDistance(X_BA * ca[static_cast<std::size_t>(k)], hb));
  }
  // Edges: corners differing in one bit.
  for (int i = 0; i < 8; ++i) {
    for (int bi = 1; bi < 8; bi <<= 1) {
      if (i & bi) continue;
      for (int j = 0; j < 8; ++j) {
        for (int bj = 1; bj < 8; bj <<= 1) {
          if (j & bj) continue;
          best = std::min(best, segmentDistance(ca[static_cast<std::size_t>(i)],
                                                ca[static_cast<std::size_t>(i | bi)],
                                                cb_A[static_cast<std::size_t>(j)],
                                                cb_A[static_cast<std::size_t>(j | bj)]));
        }
      }
    }
  }
  return best;
}

// The primitives' hulls against closed-form distances: a ball to a ball, a box or a cylinder,
// and a box to a box (brute force over corners and edges). Boxes and balls are exact hulls, so
// the bound is the distance up to GJK's tolerance; a cylinder's is an outer 32-gon prism, so the
// bound may fall short by radius * (1 / cos(pi / 32) - 1), never more, and never exceeds it.
TEST(ConvexDistance, PrimitiveHullsMatchClosedFormDistances) {
  std::mt19937_64 rng(0x9e1e);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Eigen::Isometry3d X_AB = randomPose(rng, 1.5);
    const double rb = 0.2 * unit(rng);
    const ConvexPoints ball = ballHull(rb);
    const Eigen::Vector3d p_A = X_AB.translation();  // the ball's centre in A
    const Eigen::Vector3d h(0.05 + 0.4 * unit(rng), 0.05 + 0.4 * unit(rng), 0.05 + 0.4 * unit(rng));
    // Ball to ball.
    const double ra = 0.2 * unit(rng);
    EXPECT_NEAR(convexDistanceBelow(ballHull(ra), ball, X_AB, inf),
                std::max(0.0, p_A.norm() - ra - rb), 1e-8)
        << "trial " << trial;
    // Ball to box.
    const double to_box = std::max(0.0, pointBoxDistance(p_A, h) - rb);
    const double box_bound = convexDistanceBelow(boxHull(h), ball, X_AB, inf);
    EXPECT_LE(box_bound, to_box) << "trial " << trial;
    EXPECT_GE(box_bound, to_box - 1e-8 - 1e-6 * to_box) << "trial " << trial;
    // Ball to cylinder.
    const double radius = h.x(), length = 2 * h.z();
    const double to_cylinder = std::max(0.0, pointCylinderDistance(p_A, radius, length) - rb);
    const double cylinder_bound =
        convexDistanceBelow(cylinderHull(radius, length), ball, X_AB, inf);
    EXPECT_LE(cylinder_bound, to_cylinder) << "trial " << trial;
    EXPECT_GE(cylinder_bound, to_cylinder - radius * (1 / std::cos(M_PI / 32) - 1) - 1e-8)
        << "trial " << trial;
    // Box to box, when apart (the brute force needs disjoint boxes).
    const Eigen::Vector3d hb(0.05 + 0.4 * unit(rng), 0.05 + 0.4 * unit(rng),
                             0.05 + 0.4 * unit(rng));
    if (convexApart(boxHull(h), boxHull(hb), X_AB, 1e-6)) {
      ++compared;
      const double exact = boxBoxDistance(h, hb, X_AB);
      const double bound = convexDistanceBelow(boxHull(h), boxHull(hb), X_AB, inf);
      EXPECT_LE(bound, exact + 1e-12) << "trial " << trial;
      EXPECT_GE(bound, exact - 1e-8 - 1e-6 * exact) << "trial " << trial;
    }
  }
  EXPECT_GT(compared, 500);
}

TEST(ConvexDistance, PrimitiveHullsRefuseBadSizes) {
  EXPECT_THROW(boxHull(Eigen::Vector3d(1, -1, 1)), InvalidArgument);
  EXPECT_THROW(boxHull(Eigen::Vector3d(1, std::nan(""), 1)), InvalidArgument);
  EXPECT_THROW(ballHull(-1), InvalidArgument);
  EXPECT_THROW(cylinderHull(1, -1), InvalidArgument);
  EXPECT_THROW(cylinderHull(1, 1, 2), InvalidArgument);
  EXPECT_EQ(convexDistanceBelow(ConvexPoints(), ballHull(1), Eigen::Isometry3d::Identity(), 1),
            0.0);
}

}  // namespace
}  // namespace octomotion
