// convexApart (GJK with a checked certificate) against what can be known without it: an answer
// "apart" is re-checked by brute force over every point pair along the direction it returns;
// sets built on two sides of a known plane must be found apart whenever the gap asked for is
// smaller than the slab between them; sets sharing a point are never apart; single points
// grown by radii are apart exactly when their distance exceeds the radii and the gap; on a
// convex mesh the climb along edges finds the support, and edges never change an answer's proof.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
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

TEST(ConvexGap, SetsOnTwoSidesOfASlabAreApart) {
  std::mt19937_64 rng(0x51ab);
  std::uniform_int_distribution<int> count(1, 200);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    // In a world frame W: a in x <= -s/2, b in x >= s/2, the slab between them s wide.
    const double s = 1e-4 + 0.3 * unit(rng);
    auto a_W = randomCloud(rng, count(rng), 0.5), b_W = randomCloud(rng, count(rng), 0.5);
    for (auto& p : a_W) p.x() = -s / 2 - (p.x() + 0.5);
    for (auto& p : b_W) p.x() = s / 2 + (p.x() + 0.5);
    // One point of each on the slab's faces, at the same y and z: the distance is exactly s.
    a_W[0] = Eigen::Vector3d(-s / 2, 0, 0);
    b_W[0] = Eigen::Vector3d(s / 2, 0, 0);
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0), X_WB = randomPose(rng, 1.0);
    std::vector<Eigen::Vector3d> a, b;
    for (const auto& p : a_W) a.push_back(X_WA.inverse() * p);
    for (const auto& p : b_W) b.push_back(X_WB.inverse() * p);
    const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
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

}  // namespace
}  // namespace octomotion
