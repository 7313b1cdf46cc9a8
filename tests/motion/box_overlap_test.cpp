// boxesOverlap (separating axes) against an exact oracle: two convex boxes overlap iff an edge
// of one meets the other as a solid (either one holds the other, and then all its edges are
// inside, or their boundaries cross, and then some edge pierces a face).
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "octomotion/motion/box_overlap.h"

namespace octomotion {
namespace {

struct Box {
  Eigen::Vector3d c, h;  // centre and half-extents along the columns of R
  Eigen::Matrix3d R;
  std::array<Eigen::Vector3d, 8> corners() const {
    std::array<Eigen::Vector3d, 8> v;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d s((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
      v[static_cast<std::size_t>(k)] = c + R * s.cwiseProduct(h);
    }
    return v;
  }
};

// Slab clipping of segment p0-p1 against the solid box.
bool segmentMeetsBox(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Box& b) {
  const Eigen::Vector3d q0 = b.R.transpose() * (p0 - b.c), q1 = b.R.transpose() * (p1 - b.c);
  double lo = 0, hi = 1;
  for (int a = 0; a < 3; ++a) {
    const double d = q1[a] - q0[a];
    if (std::fabs(d) < 1e-300) {
      if (std::fabs(q0[a]) > b.h[a]) return false;
      continue;
    }
    double t0 = (-b.h[a] - q0[a]) / d, t1 = (b.h[a] - q0[a]) / d;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

bool edgesMeet(const Box& a, const Box& b) {
  const auto v = a.corners();
  for (int i = 0; i < 8; ++i) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((i & bit) == 0 && segmentMeetsBox(v[static_cast<std::size_t>(i)],
                                            v[static_cast<std::size_t>(i | bit)], b)) {
        return true;
      }
    }
  }
  return false;
}

bool oracle(const Box& a, const Box& b) {
  return edgesMeet(a, b) || edgesMeet(b, a);
}

bool sat(const Box& a, const Box& b, double margin = 0) {
  return boxesOverlap(a.c, a.h, b.R, b.c, b.h, margin);
}

Eigen::Matrix3d randomRotation(std::mt19937_64& rng, int kind) {
  std::normal_distribution<double> n(0, 1);
  if (kind == 0) return Eigen::Matrix3d::Identity();
  if (kind == 1) {  // about one axis only: parallel edges, degenerate cross products
    return Eigen::AngleAxisd(n(rng), Eigen::Vector3d::Unit(static_cast<int>(rng() % 3)))
        .toRotationMatrix();
  }
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

TEST(BoxOverlap, AgreesWithTheEdgeOracleOnRandomBoxes) {
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), size(0.01, 1.0);
  int overlapping = 0, separated = 0, ties = 0;
  for (int i = 0; i < 60000; ++i) {
    const Box a{Eigen::Vector3d(pos(rng), pos(rng), pos(rng)) * 0.3,
                Eigen::Vector3d(size(rng), size(rng), size(rng)), Eigen::Matrix3d::Identity()};
    const Box b{Eigen::Vector3d(pos(rng), pos(rng), pos(rng)),
                Eigen::Vector3d(size(rng), size(rng), size(rng)), randomRotation(rng, i % 3)};
    const bool exact = oracle(a, b);
    // Skip near-ties: the answer flips when the boxes grow or shrink by 1e-9.
    Box a_grown = a, a_shrunk = a;
    a_grown.h.array() += 1e-9;
    a_shrunk.h.array() -= 1e-9;
    if (oracle(a_grown, b) != oracle(a_shrunk, b)) {
      ++ties;
      continue;
    }
    ASSERT_EQ(sat(a, b), exact) << "case " << i;
    (exact ? overlapping : separated) += 1;
  }
  // Both answers are well represented, ties are rare.
  EXPECT_GT(overlapping, 10000);
  EXPECT_GT(separated, 10000);
  EXPECT_LT(ties, 100);
}

TEST(BoxOverlap, MarginCountsNearlyTouchingBoxesAsOverlapping) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 1000; ++i) {
    // Any rotation for the separated half; for the overlapping half b turns about x only, so
    // its +x-most part is a face centred on a's +x face and the distance is exactly the gap.
    const Eigen::Matrix3d R =
        i % 2 ? randomRotation(rng, 2)
              : Eigen::AngleAxisd(std::uniform_real_distribution<double>(-3, 3)(rng),
                                  Eigen::Vector3d::UnitX())
                    .toRotationMatrix();
    const Box a{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, 0.2, 0.1),
                Eigen::Matrix3d::Identity()};
    Box b{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.05, 0.1, 0.2), R};
    // Push b along +x until it just leaves a, then 1 mm further.
    const double reach = (R.cwiseAbs() * b.h)[0];
    b.c.x() = a.h.x() + reach + 1e-3;
    EXPECT_FALSE(sat(a, b)) << i;
    EXPECT_FALSE(sat(a, b, 0.9e-3)) << i;
    if (i % 2 == 0) {
      EXPECT_TRUE(sat(a, b, 1.1e-3)) << i;
    }
  }
}

}  // namespace
}  // namespace octomotion
