// N-objects octree broad phase (report §2) against brute force: the 26-direction table
// primitives against cube geometry, >=-size neighbour finding against a search over all nodes,
// candidate pairs against all-pairs overlap over random scenes and motions, and the split/merge
// and membership invariants after every step.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "octomotion/broadphase/aabb.h"
#include "octomotion/broadphase/direction.h"
#include "octomotion/broadphase/n_objects_octree.h"
#include "octomotion/error.h"

namespace octomotion::broadphase {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

int axisStep(Direction d, int a) {
  const Offset o = offset(d);
  return a == 0 ? o.dx : (a == 1 ? o.dy : o.dz);
}

TEST(Direction, NamesAndKinds) {
  EXPECT_STREQ(directionName(Direction::RUF), "RUF");
  EXPECT_EQ(kindOf(Direction::U), DirectionKind::kFace);
  EXPECT_EQ(kindOf(Direction::DB), DirectionKind::kEdge);
  EXPECT_EQ(kindOf(Direction::LDF), DirectionKind::kVertex);
  EXPECT_EQ(octantDirection(0), Direction::LDB);
  EXPECT_EQ(octantDirection(7), Direction::RUF);
  EXPECT_EQ(octantDirection(1), Direction::RDB);  // bit 0 = +x = R
  EXPECT_EQ(octantDirection(4), Direction::LDF);  // bit 2 = +z = F
  int faces = 0, edges = 0, vertices = 0;
  for (int d = 0; d < kDirectionCount; ++d) {
    const Direction dir = static_cast<Direction>(d);
    const Offset o = offset(dir);
    EXPECT_EQ(directionOf(o.dx, o.dy, o.dz), dir);
    const int n = (o.dx != 0) + (o.dy != 0) + (o.dz != 0);
    faces += n == 1;
    edges += n == 2;
    vertices += n == 3;
    EXPECT_EQ(static_cast<int>(kindOf(dir)), n - 1);
  }
  EXPECT_EQ(faces, 6);
  EXPECT_EQ(edges, 12);
  EXPECT_EQ(vertices, 8);
}

// The primitives against geometry: octant o of the parent cube [0,2)^3 is the unit cube at its
// label bits; its equal-size I-neighbour is that cube shifted by I's steps.
TEST(Direction, TablePrimitivesMatchCubeGeometry) {
  for (int d = 0; d < kDirectionCount; ++d) {
    const Direction dir = static_cast<Direction>(d);
    for (int o = 0; o < 8; ++o) {
      int outside_axes = 0;  // axes on which the neighbour leaves the parent
      int label = 0;
      for (int a = 0; a < 3; ++a) {
        const int c = ((o >> a) & 1) + axisStep(dir, a);  // in -1..2
        if (c < 0 || c > 1) outside_axes |= 1 << a;
        label |= (c & 1) << a;  // position within whichever 2x2x2 block holds the neighbour
      }
      const int stepped =
          (axisStep(dir, 0) != 0) + (axisStep(dir, 1) != 0) + (axisStep(dir, 2) != 0);
      const int outside = __builtin_popcount(static_cast<unsigned>(outside_axes));
      EXPECT_EQ(adj(dir, o), outside == stepped) << directionName(dir) << " " << o;
      EXPECT_EQ(reflect(dir, o), label) << directionName(dir) << " " << o;
      auto only = [&](int axes) {
        return directionOf(axes & 1 ? axisStep(dir, 0) : 0, axes & 2 ? axisStep(dir, 1) : 0,
                           axes & 4 ? axisStep(dir, 2) : 0);
      };
      const Direction face =
          (stepped >= 2 && outside == 1) ? only(outside_axes) : Direction::kOmega;
      const Direction edge =
          (stepped == 3 && outside == 2) ? only(outside_axes) : Direction::kOmega;
      EXPECT_EQ(commonFace(dir, o), face) << directionName(dir) << " " << o;
      EXPECT_EQ(commonEdge(dir, o), edge) << directionName(dir) << " " << o;
    }
  }
}

Aabb randomBox(std::mt19937_64& rng, double lo, double hi, double max_size) {
  std::uniform_real_distribution<double> pos(lo, hi - max_size), size(0.0, max_size);
  Aabb b;
  for (int a = 0; a < 3; ++a) {
    b.min[a] = pos(rng);
    b.max[a] = b.min[a] + size(rng);
  }
  return b;
}

// Brute-force >=-size neighbour by geometry alone: E is the cube of n's size across n's
// face/edge/vertex `dir`; the answer is the smallest live node of size >= n's containing E (so
// its cube touches that face/edge/vertex of n), or kNone when E is outside the root.
std::uint32_t bruteNeighbour(const NObjectsOctree& t, std::uint32_t n, Direction dir) {
  const Cube p = t.cube(n);
  const std::int64_t ps = p.side();
  const std::int64_t e[3] = {p.origin.x + axisStep(dir, 0) * ps, p.origin.y + axisStep(dir, 1) * ps,
                             p.origin.z + axisStep(dir, 2) * ps};
  std::uint32_t best = NObjectsOctree::kNone;
  int best_level = 1 << 20;
  for (std::uint32_t m = 0; m < t.nodeSlots(); ++m) {
    if (!t.isLive(m)) continue;
    const Cube q = t.cube(m);
    if (q.level < p.level) continue;
    const std::int64_t qmin[3] = {q.origin.x, q.origin.y, q.origin.z};
    bool contains = true;
    for (int a = 0; a < 3; ++a)
      contains = contains && qmin[a] <= e[a] && e[a] + ps <= qmin[a] + std::int64_t{q.side()};
    if (contains && q.level < best_level) {
      best = m;
      best_level = q.level;
    }
  }
  return best;
}

// n's cube and m's cube touch exactly along n's feature `dir`: closed cubes meet, interiors do
// not, and on every stepped axis m lies on the stepped side of n.
bool touchesAlong(const NObjectsOctree& t, std::uint32_t n, std::uint32_t m, Direction dir) {
  const Cube p = t.cube(n), q = t.cube(m);
  const std::int64_t pmin[3] = {p.origin.x, p.origin.y, p.origin.z};
  const std::int64_t qmin[3] = {q.origin.x, q.origin.y, q.origin.z};
  for (int a = 0; a < 3; ++a) {
    const std::int64_t pmax = pmin[a] + p.side(), qmax = qmin[a] + q.side();
    const int s = axisStep(dir, a);
    if (s > 0 && qmin[a] != pmax) return false;
    if (s < 0 && qmax != pmin[a]) return false;
    if (s == 0 && !(qmin[a] <= pmin[a] && pmax <= qmax)) return false;
  }
  return true;
}

TEST(NObjectsOctree, NeighbourFindingMatchesBruteForceEverywhere) {
  std::mt19937_64 rng(7001);
  for (int trial = 0; trial < 4; ++trial) {
    NObjectsOctree::Options opt;
    opt.leaf_capacity = 1 + static_cast<std::uint32_t>(trial);
    opt.max_depth = 6;
    NObjectsOctree tree(Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(64)}, opt);
    // Clustered small boxes give a tree with leaves at many levels.
    for (int i = 0; i < 40; ++i) tree.add(randomBox(rng, 0, 64, 6));
    for (int i = 0; i < 40; ++i) tree.add(randomBox(rng, 0, 12, 1));
    tree.rebalance();
    std::string why;
    ASSERT_TRUE(tree.checkInvariants(&why)) << why;
    std::set<int> levels;
    std::size_t checked = 0;
    for (std::uint32_t n = 0; n < tree.nodeSlots(); ++n) {
      if (!tree.isLive(n)) continue;
      levels.insert(tree.cube(n).level);
      for (int d = 0; d < kDirectionCount; ++d) {
        const Direction dir = static_cast<Direction>(d);
        const std::uint32_t found = tree.gtEqNeighbour(n, dir);
        ASSERT_EQ(found, bruteNeighbour(tree, n, dir))
            << "node " << n << " level " << tree.cube(n).level << " dir " << directionName(dir);
        if (found != NObjectsOctree::kNone) {
          // An equal-size neighbour is flush against the feature; a larger one may overhang it.
          if (tree.cube(found).level == tree.cube(n).level) {
            EXPECT_TRUE(touchesAlong(tree, n, found, dir));
          }
          EXPECT_TRUE(overlaps(tree.nodeBox(n), tree.nodeBox(found)));  // closed cubes meet
        }
        ++checked;
      }
    }
    EXPECT_GE(levels.size(), 5u);  // the tree really spans many levels
    EXPECT_GT(checked, 26u * 100u);
  }
  // The kind-checked wrappers.
  NObjectsOctree tree(Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()}, {});
  EXPECT_THROW(tree.gtEqFaceNeighbour(0, Direction::LU), InvalidArgument);
  EXPECT_THROW(tree.gtEqEdgeNeighbour(0, Direction::L), InvalidArgument);
  EXPECT_THROW(tree.gtEqVertexNeighbour(0, Direction::LU), InvalidArgument);
  EXPECT_EQ(tree.gtEqVertexNeighbour(0, Direction::LUB), NObjectsOctree::kNone);
}

std::vector<Pair> candidatePairs(NObjectsOctree& tree) {
  std::vector<Pair> pairs;
  tree.forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) { pairs.emplace_back(a, b); });
  return pairs;
}

std::vector<Pair> brutePairs(const std::vector<Aabb>& boxes) {
  std::vector<Pair> pairs;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
      if (overlaps(boxes[i], boxes[j])) pairs.emplace_back(i, j);
  return pairs;
}

// Random scene in [0,16]^3 whose coordinates are often snapped to 1/4 so boxes touch each other
// and node faces exactly (the root [0,16]^3 at depth 6 has faces on multiples of 1/4).
struct Scene {
  std::vector<Aabb> boxes;
  std::vector<Eigen::Vector3d> velocity;
};

Aabb snapped(const Aabb& b, bool snap) {
  if (!snap) return b;
  Aabb s;
  s.min = (b.min * 4).array().round() / 4;
  s.max = (b.max * 4).array().round() / 4;
  s.max = s.max.cwiseMax(s.min);
  return s;
}

TEST(NObjectsOctree, CandidatesAreExactlyTheOverlappingPairsOverRandomMotion) {
  const std::uint32_t capacities[] = {1, 2, 5, 10, NObjectsOctree::kUnlimited};
  std::mt19937_64 rng(424242);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uint64_t total_pairs = 0, total_merges = 0, total_splits = 0, total_reroots = 0;
  for (std::uint32_t capacity : capacities) {
    for (int scene_kind = 0; scene_kind < 2; ++scene_kind) {
      const bool snap = scene_kind == 0;
      Scene s;
      const int count = 120;
      for (int i = 0; i < count; ++i) {
        s.boxes.push_back(snapped(randomBox(rng, 1, 15, 1.5), snap));
        s.velocity.push_back(Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) *
                             0.5);
      }
      NObjectsOctree::Options opt;
      opt.leaf_capacity = capacity;
      opt.max_depth = 6;
      NObjectsOctree tree =
          snap ? NObjectsOctree(Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(16)}, opt)
               : NObjectsOctree::forBoxes(s.boxes, opt);
      if (snap)
        for (const Aabb& b : s.boxes) tree.add(b);
      for (int step = 0; step < 50; ++step) {
        for (int i = 0; i < count; ++i) {
          Aabb& b = s.boxes[static_cast<std::size_t>(i)];
          Eigen::Vector3d v = s.velocity[static_cast<std::size_t>(i)];
          const double r = unit(rng);
          if (r < 0.01) v *= 40;  // an occasional long jump (no shared leaf with the old box)
          // Bounce inside [0.5, 15.5], except the odd excursion that forces a re-root.
          Aabb moved{b.min + v, b.max + v};
          if (r > 0.002 && ((moved.min.array() < 0.5).any() || (moved.max.array() > 15.5).any())) {
            s.velocity[static_cast<std::size_t>(i)] = -s.velocity[static_cast<std::size_t>(i)];
            moved = b;
          }
          b = snapped(moved, snap);
          tree.move(static_cast<std::uint32_t>(i), b);
        }
        std::vector<Pair> got = candidatePairs(tree);
        std::string why;
        ASSERT_TRUE(tree.checkInvariants(&why)) << why << " N=" << capacity << " step " << step;
        std::sort(got.begin(), got.end());
        ASSERT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end())
            << "duplicate candidate pair, N=" << capacity << " step " << step;
        const std::vector<Pair> want = brutePairs(s.boxes);
        ASSERT_EQ(got, want) << "N=" << capacity << " step " << step;
        EXPECT_EQ(tree.counters().candidate_pairs, want.size());
        total_pairs += want.size();
      }
      if (capacity == NObjectsOctree::kUnlimited) {
        EXPECT_EQ(tree.leafCount(), 1u);
        EXPECT_EQ(tree.counters().coresident_pairs, std::uint64_t{count} * (count - 1) / 2);
      }
      total_merges += tree.counters().merges;
      total_splits += tree.counters().splits;
      total_reroots += tree.counters().reroots;
    }
  }
  EXPECT_GT(total_pairs, 1000u);  // the scenes really collide
  EXPECT_GT(total_merges, 100u);  // motion exercised merges...
  EXPECT_GT(total_splits, 100u);  // ... and splits
  EXPECT_GT(total_reroots, 0u);   // and the root grew at least once
}

// Boxes that also grow, shrink and slide diagonally: the neighbour flood must follow growth on
// both sides of an axis at once.
TEST(NObjectsOctree, CandidatesStayExactWhenBoxesChangeSize) {
  std::mt19937_64 rng(8080);
  std::uniform_real_distribution<double> unit(0, 1);
  for (std::uint32_t capacity : {1u, 3u, 8u}) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 90; ++i) boxes.push_back(randomBox(rng, 2, 14, 1.0));
    NObjectsOctree::Options opt;
    opt.leaf_capacity = capacity;
    opt.max_depth = 7;
    NObjectsOctree tree(Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(16)}, opt);
    for (const Aabb& b : boxes) tree.add(b);
    for (int step = 0; step < 40; ++step) {
      for (std::uint32_t i = 0; i < boxes.size(); ++i) {
        Aabb b = boxes[i];
        const Eigen::Vector3d centre = 0.5 * (b.min + b.max);
        Eigen::Vector3d half = 0.5 * (b.max - b.min);
        half *= 0.7 + 0.6 * unit(rng);  // grow or shrink by up to 30 %
        half = half.cwiseMin(2.0).cwiseMax(0.01);
        const Eigen::Vector3d shift(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        const Eigen::Vector3d c = (centre + 0.3 * shift).cwiseMax(2.5).cwiseMin(13.5);
        boxes[i] = {c - half, c + half};
        tree.move(i, boxes[i]);
      }
      std::vector<Pair> got = candidatePairs(tree);
      std::string why;
      ASSERT_TRUE(tree.checkInvariants(&why)) << why << " N=" << capacity << " step " << step;
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, brutePairs(boxes)) << "N=" << capacity << " step " << step;
    }
  }
}

TEST(NObjectsOctree, SplitAndMergeFollowTheNObjectsRule) {
  NObjectsOctree::Options opt;
  opt.leaf_capacity = 2;
  opt.max_depth = 4;
  NObjectsOctree tree(Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(16)}, opt);
  auto cell = [](double x, double y, double z) {
    return Aabb{Eigen::Vector3d(x, y, z), Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5)};
  };
  // Two objects: one leaf. The third splits the root (§2.2).
  tree.add(cell(1, 1, 1));
  tree.add(cell(13, 13, 13));
  tree.rebalance();
  EXPECT_EQ(tree.leafCount(), 1u);
  tree.add(cell(13, 1, 1));
  tree.rebalance();
  EXPECT_EQ(tree.leafCount(), 8u);
  EXPECT_EQ(tree.leavesOf(0).size(), 1u);
  EXPECT_EQ(tree.cube(tree.leavesOf(0)[0]).level, 3);
  // An object straddling the centre lives in all eight children.
  tree.add(cell(7.75, 7.75, 7.75));
  tree.rebalance();
  EXPECT_EQ(tree.leavesOf(3).size(), 8u);
  std::string why;
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  // Moving two objects next to each other forces splits down to where at most 2 share a leaf.
  tree.move(1, cell(1.6, 1.6, 1.6));
  tree.move(2, cell(1.2, 1.2, 1.2));
  tree.rebalance();
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  EXPECT_GT(tree.leafCount(), 8u);
  // Moving them away again merges everything back into one leaf... except the straddler keeps
  // the root holding 3 objects, so the root stays split with 8 leaves.
  tree.move(1, cell(13, 13, 13));
  tree.move(2, cell(13, 1, 1));
  tree.rebalance();
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  EXPECT_EQ(tree.leafCount(), 8u);
  // Crowding the +x+y+z child splits it again; the root keeps 4 distinct objects, so stays split.
  tree.move(2, cell(13.5, 13.5, 13.5));
  tree.move(3, cell(13.2, 13.2, 13.2));
  tree.rebalance();
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  EXPECT_GT(tree.counters().merges, 0u);
  // Four objects all touching one point cannot be separated: splitting stops at the finest level.
  for (std::uint32_t id = 0; id < 4; ++id) tree.move(id, cell(4.0, 4.0, 4.0));
  tree.rebalance();
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  EXPECT_EQ(candidatePairs(tree).size(), 6u);
}

TEST(NObjectsOctree, RejectsBadInput) {
  const Aabb root{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  NObjectsOctree::Options opt;
  opt.leaf_capacity = 0;
  EXPECT_THROW(NObjectsOctree(root, opt), InvalidArgument);
  opt.leaf_capacity = 4;
  opt.max_depth = 40;
  EXPECT_THROW(NObjectsOctree(root, opt), InvalidArgument);
  NObjectsOctree tree(root, {});
  Aabb nan_box = root;
  nan_box.min.x() = std::nan("");
  EXPECT_THROW(tree.add(nan_box), InvalidArgument);
  Aabb inverted{Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()};
  EXPECT_THROW(tree.add(inverted), InvalidArgument);
  tree.add(root);
  EXPECT_THROW(tree.move(0, nan_box), InvalidArgument);
  EXPECT_THROW(tree.move(5, root), InvalidArgument);
}

Eigen::Matrix3d rotation(const Eigen::Vector3d& axis_angle) {
  const double angle = axis_angle.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d k = axis_angle / angle;
  Eigen::Matrix3d K;
  K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
  return Eigen::Matrix3d::Identity() + std::sin(angle) * K + (1 - std::cos(angle)) * K * K;
}

// Separation by dense sampling: if some sample point of a lies inside b, they overlap.
bool sampledOverlap(const OrientedBox& a, const OrientedBox& b) {
  const int n = 12;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const Eigen::Vector3d u(2.0 * i / n - 1, 2.0 * j / n - 1, 2.0 * k / n - 1);
        const Eigen::Vector3d p = a.center + a.R_WB * a.half.cwiseProduct(u);
        const Eigen::Vector3d q = b.R_WB.transpose() * (p - b.center);
        if ((q.cwiseAbs().array() <= b.half.array()).all()) return true;
      }
  return false;
}

TEST(NarrowPhase, OrientedBoxesAgreeWithAabbsAndSampling) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  int overlapping = 0;
  for (int trial = 0; trial < 400; ++trial) {
    OrientedBox a, b;
    a.center = Eigen::Vector3d(u(rng), u(rng), u(rng));
    b.center = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5;
    a.half = Eigen::Vector3d(0.2 + 0.3 * std::abs(u(rng)), 0.2 + 0.3 * std::abs(u(rng)), 0.3);
    b.half = Eigen::Vector3d::Constant(0.4);
    // Axis-aligned: the exact test is the AABB test.
    EXPECT_EQ(overlaps(a, b), overlaps(a.aabb(), b.aabb()));
    a.R_WB = rotation(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5);
    b.R_WB = rotation(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5);
    const bool exact = overlaps(a, b);
    EXPECT_EQ(exact, overlaps(b, a));
    if (exact) ++overlapping;
    // The exact test implies the AABB test, and a sampled witness implies the exact test.
    if (exact) {
      EXPECT_TRUE(overlaps(a.aabb(), b.aabb()));
    }
    if (sampledOverlap(a, b) || sampledOverlap(b, a)) {
      EXPECT_TRUE(exact);
    }
  }
  EXPECT_GT(overlapping, 50);
  // Two unit cubes, one turned 45 degrees about z: corners reach 0.5*sqrt(2) from the centre.
  OrientedBox a, b;
  b.R_WB = rotation(Eigen::Vector3d(0, 0, M_PI / 4));
  b.center = Eigen::Vector3d(0.5 + 0.5 * std::sqrt(2.0) - 1e-6, 0, 0);
  EXPECT_TRUE(overlaps(a, b));
  b.center.x() += 2e-6;
  EXPECT_FALSE(overlaps(a, b));
  // Along the diagonal a's corner meets b's face at d*sqrt(2) = 0.5*sqrt(2) + 0.5, while the
  // AABBs overlap until d = 0.5 + 0.5*sqrt(2).
  const double d = (0.5 * std::sqrt(2.0) + 0.5) / std::sqrt(2.0);
  b.center = Eigen::Vector3d(d - 1e-6, d - 1e-6, 0);
  EXPECT_TRUE(overlaps(a, b));
  b.center = Eigen::Vector3d(d + 1e-6, d + 1e-6, 0);
  EXPECT_FALSE(overlaps(a, b));
  EXPECT_TRUE(overlaps(a.aabb(), b.aabb()));
}

}  // namespace
}  // namespace octomotion::broadphase
