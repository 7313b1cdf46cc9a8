// What a convex hull costs to build (convexHullTriangles, once per link or mesh at model build)
// and what it saves per support search: ConvexPoints::hullOf's climb along the hull's edges
// against supportIndex over every point of the same set (the search GJK's certificate needed
// without a hull). Points on a unit sphere (every point a vertex) and in a ball (most inside),
// fixed seed; 256 random directions per iteration.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "octomotion/motion/convex_gap.h"
#include "octomotion/motion/convex_hull.h"

namespace {

using namespace octomotion;

std::vector<Eigen::Vector3d> points(std::size_t count, bool on_sphere) {
  std::mt19937_64 rng(0x4a11);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> result;
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    result.push_back(on_sphere ? p : p * std::cbrt(u(rng)));
  }
  return result;
}

std::vector<Eigen::Vector3d> directions() {
  std::mt19937_64 rng(0xd1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Vector3d> result;
  for (int i = 0; i < 256; ++i) result.emplace_back(g(rng), g(rng), g(rng));
  return result;
}

void BM_HullBuild(benchmark::State& state) {
  const auto cloud = points(static_cast<std::size_t>(state.range(0)), state.range(1) != 0);
  for (auto _ : state) benchmark::DoNotOptimize(convexHullTriangles(cloud));
}
BENCHMARK(BM_HullBuild)->ArgsProduct({{150, 1000, 4096}, {1, 0}})->Unit(benchmark::kMicrosecond);

// One support per direction: 0 every point (supportIndex), 1 the hull's climb.
void BM_Support(benchmark::State& state) {
  const auto cloud = points(static_cast<std::size_t>(state.range(0)), true);
  const ConvexPoints set = state.range(1) != 0 ? ConvexPoints::hullOf(cloud) : ConvexPoints(cloud);
  const auto ds = directions();
  for (auto _ : state) {
    std::size_t sum = 0;
    for (const Eigen::Vector3d& d : ds) sum += set.exactSupport(d);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(ds.size()));
}
BENCHMARK(BM_Support)->ArgsProduct({{150, 1000}, {0, 1}});

}  // namespace

BENCHMARK_MAIN();
