// Point octree vs nanoflann's KD-tree (v1.4.3) on 1M uniform random points: build time and
// k-nearest-neighbour queries (k = 1, 10) over 10,000 random query points per iteration. Run
// with --benchmark_repetitions=5 --benchmark_report_aggregates_only=true for medians.
// Both trees store float coordinates and return squared float distances; a checksum over the
// query results confirms both answer the same (reported as the counter "d2sum").
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include <nanoflann.hpp>

#include "octomotion/pointcloud/point_octree.h"

namespace {

using octomotion::pointcloud::Neighbour;
using octomotion::pointcloud::PointOctree;

constexpr std::size_t kPoints = 1000000;
constexpr std::size_t kQueries = 10000;

const std::vector<Eigen::Vector3f>& cloud() {
  static const std::vector<Eigen::Vector3f> points = [] {
    std::mt19937_64 rng(1234);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f);
    std::vector<Eigen::Vector3f> p(kPoints);
    for (auto& x : p) x = Eigen::Vector3f(u(rng), u(rng), u(rng));
    return p;
  }();
  return points;
}

const std::vector<Eigen::Vector3f>& queries() {
  static const std::vector<Eigen::Vector3f> q = [] {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<float> u(-10.5f, 10.5f);
    std::vector<Eigen::Vector3f> out(kQueries);
    for (auto& x : out) x = Eigen::Vector3f(u(rng), u(rng), u(rng));
    return out;
  }();
  return q;
}

struct CloudAdaptor {
  const std::vector<Eigen::Vector3f>* pts;
  std::size_t kdtree_get_point_count() const { return pts->size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*pts)[i][static_cast<int>(dim)];
  }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>,
                                        CloudAdaptor, 3, std::uint32_t>;

PointOctree::Options octreeOptions(benchmark::State& state) {
  PointOctree::Options opt;
  opt.bucket_size = static_cast<std::uint32_t>(state.range(0));
  return opt;
}

void BM_OctreeBuild(benchmark::State& state) {
  const auto& pts = cloud();
  const PointOctree::Options opt = octreeOptions(state);
  std::size_t bytes = 0;
  for (auto _ : state) {
    PointOctree tree = PointOctree::build(pts, opt);
    bytes = tree.bytes();
    benchmark::DoNotOptimize(tree);
  }
  state.counters["points"] = static_cast<double>(pts.size());
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
}

void BM_NanoflannBuild(benchmark::State& state) {
  CloudAdaptor adaptor{&cloud()};
  for (auto _ : state) {
    KdTree tree(3, adaptor,
                nanoflann::KDTreeSingleIndexAdaptorParams(
                    static_cast<std::size_t>(state.range(0))));  // builds the index
    KdTree* built = &tree;
    benchmark::DoNotOptimize(built);
  }
  state.counters["points"] = static_cast<double>(cloud().size());
}

void BM_OctreeKnn(benchmark::State& state) {
  const std::size_t k = static_cast<std::size_t>(state.range(1));
  const PointOctree tree = PointOctree::build(cloud(), octreeOptions(state));
  std::vector<Neighbour> result;
  result.reserve(k);
  double checksum = 0;
  for (auto _ : state) {
    checksum = 0;
    for (const Eigen::Vector3f& q : queries()) {
      tree.kNearest(q, k, &result);
      checksum += result.back().distance2;
    }
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kQueries));
  state.counters["d2sum"] = checksum;
}

void BM_NanoflannKnn(benchmark::State& state) {
  const std::size_t k = static_cast<std::size_t>(state.range(1));
  CloudAdaptor adaptor{&cloud()};
  KdTree tree(3, adaptor,
              nanoflann::KDTreeSingleIndexAdaptorParams(static_cast<std::size_t>(state.range(0))));
  std::vector<std::uint32_t> ids(k);
  std::vector<float> d2(k);
  double checksum = 0;
  for (auto _ : state) {
    checksum = 0;
    for (const Eigen::Vector3f& q : queries()) {
      const std::size_t found = tree.knnSearch(q.data(), k, ids.data(), d2.data());
      checksum += d2[found - 1];
    }
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kQueries));
  state.counters["d2sum"] = checksum;
}

// Args: {bucket size / leaf max size, k}.
BENCHMARK(BM_OctreeBuild)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NanoflannBuild)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OctreeKnn)
    ->Args({16, 1})
    ->Args({16, 10})
    ->Args({32, 10})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NanoflannKnn)->Args({10, 1})->Args({10, 10})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
