// Point-region octree against brute force on random clouds (fixed seeds): insert, exact search,
// remove, k-NN and radius search, bulk build, structure invariants; environmentFromPoints and
// the clearance query against direct computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/pointcloud/environment.h"
#include "octomotion/pointcloud/point_octree.h"

namespace octomotion::pointcloud {
namespace {

float dist2(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  // Same float formula as the tree so distances compare exactly.
  const float dx = a.x() - b.x(), dy = a.y() - b.y(), dz = a.z() - b.z();
  return dx * dx + dy * dy + dz * dz;
}

std::vector<Eigen::Vector3f> randomCloud(std::mt19937_64& rng, std::size_t n, bool clustered) {
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::normal_distribution<float> g(0.0f, 0.3f);
  std::vector<Eigen::Vector3f> pts;
  for (std::size_t i = 0; i < n; ++i) {
    if (clustered && i % 3 != 0) {
      // Tight clusters and exact duplicates exercise deep splits and max-depth chains.
      const Eigen::Vector3f c(static_cast<float>(i % 5), 1.0f, -2.0f);
      pts.push_back(i % 7 == 0 ? c
                               : Eigen::Vector3f(c.x() + g(rng), c.y() + g(rng), c.z() + g(rng)));
    } else {
      pts.emplace_back(u(rng), u(rng), u(rng));
    }
  }
  return pts;
}

std::vector<float> bruteKnn(const std::vector<Eigen::Vector3f>& pts, const std::vector<bool>& alive,
                            const Eigen::Vector3f& q, std::size_t k) {
  std::vector<float> d;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (alive[i]) d.push_back(dist2(pts[i], q));
  std::sort(d.begin(), d.end());
  if (d.size() > k) d.resize(k);
  return d;
}

void expectMatchesBruteForce(const PointOctree& tree, const std::vector<Eigen::Vector3f>& pts,
                             const std::vector<bool>& alive, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(-6.0f, 6.0f);
  std::vector<Neighbour> got;
  for (int t = 0; t < 40; ++t) {
    const Eigen::Vector3f q =
        t % 4 == 0 ? pts[rng() % pts.size()] : Eigen::Vector3f(u(rng), u(rng), u(rng));
    for (std::size_t k : {1u, 5u, 17u}) {
      tree.kNearest(q, k, &got);
      const std::vector<float> want = bruteKnn(pts, alive, q, k);
      ASSERT_EQ(got.size(), want.size());
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].distance2, want[i]) << "k=" << k << " rank " << i;
        // The id really names a live point at that distance.
        ASSERT_LT(got[i].id, pts.size());
        ASSERT_TRUE(alive[got[i].id]);
        ASSERT_EQ(dist2(pts[got[i].id], q), got[i].distance2);
      }
    }
    const double nearest = tree.nearestDistance(q);
    const std::vector<float> one = bruteKnn(pts, alive, q, 1);
    if (one.empty()) {
      EXPECT_TRUE(std::isinf(nearest));
    } else {
      EXPECT_EQ(nearest, std::sqrt(static_cast<double>(one[0])));
    }
    const float radius = 0.2f + 1.5f * static_cast<float>(t % 5);
    tree.radiusSearch(q, radius, &got);
    std::vector<std::uint32_t> got_ids, want_ids;
    for (const Neighbour& n : got) got_ids.push_back(n.id);
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (alive[i] && dist2(pts[i], q) <= radius * radius)
        want_ids.push_back(static_cast<std::uint32_t>(i));
    std::sort(got_ids.begin(), got_ids.end());
    ASSERT_EQ(got_ids, want_ids) << "radius " << radius;
  }
}

TEST(PointOctree, BulkBuildAgreesWithBruteForce) {
  std::mt19937_64 rng(31337);
  for (bool clustered : {false, true}) {
    for (std::uint32_t bucket : {1u, 4u, 16u}) {
      const std::vector<Eigen::Vector3f> pts = randomCloud(rng, 3000, clustered);
      PointOctree::Options opt;
      opt.bucket_size = bucket;
      opt.max_depth = 12;
      const PointOctree tree = PointOctree::build(pts, opt);
      std::string why;
      ASSERT_TRUE(tree.checkInvariants(&why)) << why;
      EXPECT_EQ(tree.size(), pts.size());
      for (std::size_t i = 0; i < pts.size(); i += 7) EXPECT_TRUE(tree.contains(pts[i]));
      EXPECT_FALSE(tree.contains(Eigen::Vector3f(100, 0, 0)));
      EXPECT_FALSE(tree.contains(Eigen::Vector3f(0.123456f, 4.5f, -3.25f)));
      std::size_t seen = 0;
      tree.forEachPoint([&](const Eigen::Vector3f& p, std::uint32_t id) {
        ASSERT_LT(id, pts.size());
        EXPECT_EQ(p, pts[id]);
        ++seen;
      });
      EXPECT_EQ(seen, pts.size());
      expectMatchesBruteForce(tree, pts, std::vector<bool>(pts.size(), true), rng);
    }
  }
}

TEST(PointOctree, InsertSearchRemoveAgreeWithBruteForce) {
  std::mt19937_64 rng(2718);
  for (std::uint32_t bucket : {1u, 3u, 8u}) {
    PointOctree::Options opt;
    opt.bucket_size = bucket;
    opt.max_depth = 10;
    PointOctree tree(Eigen::Vector3d::Constant(-8), 16.0, opt);
    std::vector<Eigen::Vector3f> pts;
    std::vector<bool> alive;
    const std::vector<Eigen::Vector3f> source = randomCloud(rng, 2000, true);
    for (const Eigen::Vector3f& p : source) {
      const std::uint32_t id = tree.insert(p);
      ASSERT_EQ(id, pts.size());
      pts.push_back(p);
      alive.push_back(true);
    }
    std::string why;
    ASSERT_TRUE(tree.checkInvariants(&why)) << why;
    const std::size_t nodes_full = tree.nodeCount();
    expectMatchesBruteForce(tree, pts, alive, rng);
    // Remove two thirds in random order; every removal hits exactly one stored copy.
    std::vector<std::size_t> order(pts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::size_t live = pts.size();
    for (std::size_t n = 0; n < order.size() * 2 / 3; ++n) {
      const std::size_t i = order[n];
      ASSERT_TRUE(tree.remove(pts[i]));
      // Which copy went is unspecified for duplicates: retire any live copy with those coordinates.
      for (std::size_t j = 0; j < pts.size(); ++j) {
        if (alive[j] && pts[j] == pts[i]) {
          alive[j] = false;
          break;
        }
      }
      --live;
      if (n % 97 == 0) {
        ASSERT_TRUE(tree.checkInvariants(&why)) << why;
        ASSERT_EQ(tree.size(), live);
      }
    }
    ASSERT_TRUE(tree.checkInvariants(&why)) << why;
    EXPECT_LT(tree.nodeCount(), nodes_full);  // siblings collapsed
    // Exact search agrees with the live set; removing an absent point fails.
    for (std::size_t i = 0; i < pts.size(); ++i) {
      bool any = false;
      for (std::size_t j = 0; j < pts.size() && !any; ++j) any = alive[j] && pts[j] == pts[i];
      ASSERT_EQ(tree.contains(pts[i]), any);
    }
    EXPECT_FALSE(tree.remove(Eigen::Vector3f(7.5f, 7.5f, 7.5f)));
    EXPECT_FALSE(tree.remove(Eigen::Vector3f(100, 0, 0)));
    // Removed ids never come back from a query. (Ids of removed duplicates may differ from
    // the ones retired above, so compare distances via a fresh alive mask of coordinates.)
    std::vector<Neighbour> got;
    tree.kNearest(Eigen::Vector3f(0, 0, 0), 25, &got);
    EXPECT_EQ(got.size(), std::min<std::size_t>(25, live));
    // Remove everything: the tree is empty again and queries say so.
    for (std::size_t j = 0; j < pts.size(); ++j) {
      if (alive[j]) {
        ASSERT_TRUE(tree.remove(pts[j]));
      }
    }
    EXPECT_TRUE(tree.empty());
    EXPECT_EQ(tree.nodeCount(), 1u);
    EXPECT_TRUE(std::isinf(tree.nearestDistance(Eigen::Vector3f::Zero())));
    tree.kNearest(Eigen::Vector3f::Zero(), 3, &got);
    EXPECT_TRUE(got.empty());
  }
}

TEST(PointOctree, RejectsBadInput) {
  EXPECT_THROW(PointOctree(Eigen::Vector3d::Zero(), 0.0), InvalidArgument);
  EXPECT_THROW(PointOctree(Eigen::Vector3d::Constant(NAN), 1.0), InvalidArgument);
  PointOctree::Options opt;
  opt.bucket_size = 0;
  EXPECT_THROW(PointOctree(Eigen::Vector3d::Zero(), 1.0, opt), InvalidArgument);
  PointOctree tree(Eigen::Vector3d::Zero(), 1.0);
  EXPECT_THROW(tree.insert(Eigen::Vector3f(2, 0, 0)), InvalidArgument);
  EXPECT_THROW(tree.insert(Eigen::Vector3f(NAN, 0, 0)), InvalidArgument);
  EXPECT_THROW(PointOctree::build({Eigen::Vector3f(0, INFINITY, 0)}), InvalidArgument);
  EXPECT_FALSE(tree.contains(Eigen::Vector3f(NAN, 0, 0)));
}

TEST(PointOctree, ManyIdenticalPointsStopAtMaxDepth) {
  PointOctree::Options opt;
  opt.bucket_size = 4;
  opt.max_depth = 6;
  PointOctree tree(Eigen::Vector3d::Zero(), 1.0, opt);
  for (int i = 0; i < 100; ++i) tree.insert(Eigen::Vector3f(0.3f, 0.3f, 0.3f));
  std::string why;
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
  EXPECT_EQ(tree.height(), 6);
  std::vector<Neighbour> got;
  tree.radiusSearch(Eigen::Vector3f(0.3f, 0.3f, 0.3f), 0.0f, &got);
  EXPECT_EQ(got.size(), 100u);
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(tree.remove(Eigen::Vector3f(0.3f, 0.3f, 0.3f)));
  EXPECT_TRUE(tree.empty());
  ASSERT_TRUE(tree.checkInvariants(&why)) << why;
}

TEST(Environment, OccupancyAndClearanceFromPoints) {
  std::mt19937_64 rng(4242);
  const WorldGrid grid(Eigen::Vector3d(-1, -1, -1), 0.125, 4);  // 2 m cube, 16^3 voxels
  std::vector<Eigen::Vector3f> pts = randomCloud(rng, 800, false);
  for (Eigen::Vector3f& p : pts) p *= 0.25f;  // mostly inside [-1.25, 1.25]^3
  pts.emplace_back(NAN, 0, 0);
  EnvironmentStats stats;
  const Octree env = environmentFromPoints(grid, pts, {}, &stats);
  // Brute force: the set of voxels containing a point.
  std::vector<Voxel> want;
  std::size_t outside = 0;
  for (const Eigen::Vector3f& p : pts) {
    Voxel v;
    if (grid.voxelAt(p.cast<double>(), &v)) {
      want.push_back(v);
    } else {
      ++outside;
    }
  }
  EXPECT_EQ(stats.outside_universe, outside);
  EXPECT_GT(outside, 1u);
  EXPECT_EQ(stats.points_used + stats.outside_universe, pts.size());
  EXPECT_EQ(env, Octree::fromVoxels(grid, want));
  EXPECT_EQ(env.blackVoxelCount(), stats.occupied_voxels);

  // Downsampling keeps one centroid per cube; the occupancy of coarse cubes is preserved when
  // the downsampling cube equals the voxel.
  EnvironmentOptions coarse;
  coarse.downsample_voxel = 0.5;
  const std::vector<Eigen::Vector3f> thin = downsample(pts, 0.5);
  EXPECT_LT(thin.size(), pts.size());
  for (const Eigen::Vector3f& c : thin) {
    // Every centroid lies in a 0.5 m cube that holds at least one original point.
    const Eigen::Vector3f cube = (c / 0.5f).array().floor();
    bool witnessed = false;
    for (const Eigen::Vector3f& p : pts)
      witnessed =
          witnessed || (p.allFinite() && ((p / 0.5f).array().floor() == cube.array()).all());
    EXPECT_TRUE(witnessed);
  }
  const Octree env_thin = environmentFromPoints(grid, pts, coarse, &stats);
  EXPECT_EQ(stats.points_used + stats.outside_universe, thin.size());
  EXPECT_LE(env_thin.blackVoxelCount(), env.blackVoxelCount());
  EXPECT_THROW(downsample(pts, 0.0), InvalidArgument);
  EnvironmentOptions negative;
  negative.downsample_voxel = -1.0;
  EXPECT_THROW(environmentFromPoints(grid, pts, negative), InvalidArgument);

  // Clearance = distance to the nearest (finite) point.
  const ClearanceMap clearance(pts);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int t = 0; t < 50; ++t) {
    const Eigen::Vector3d q(u(rng), u(rng), u(rng));
    float best = INFINITY;
    for (const Eigen::Vector3f& p : pts)
      if (p.allFinite()) best = std::min(best, dist2(p, q.cast<float>()));
    EXPECT_EQ(clearance.clearance(q), std::sqrt(static_cast<double>(best)));
  }
  EXPECT_TRUE(std::isinf(ClearanceMap({}).clearance(Eigen::Vector3d::Zero())));
}

}  // namespace
}  // namespace octomotion::pointcloud
