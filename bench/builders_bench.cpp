// Build time of the top-down builders (Weng & Ahuja 1987 §4 descent) for an analytic sphere and
// for ~10k-triangle meshes (a UV sphere and a torus), depths 8-10, both rounding modes.
// Counters: internal nodes of the result, and nodes built per second. Also the core boxes of a
// link-like cylinder (innerBoxes, built once per link by the planner), depths 6-8.
//
//   build-<name>/bench/builders_bench --benchmark_filter=.
#include <benchmark/benchmark.h>

#include "octomotion/octree/inner_boxes.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

// The unit cube as universe, 2^depth voxels per side.
WorldGrid unitGrid(int depth) {
  return WorldGrid(Eigen::Vector3d::Zero(), 1.0 / static_cast<double>(1 << depth), depth);
}

Eigen::Isometry3d centredPose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.5, 0.5, 0.5);
  return X;
}

Rounding roundingArg(std::int64_t r) {
  return r == 0 ? Rounding::kConservative : Rounding::kCenter;
}

void report(benchmark::State& state, const Octree& tree) {
  const double nodes = static_cast<double>(tree.internalNodeCount());
  state.counters["nodes"] = nodes;
  state.counters["nodes/s"] = benchmark::Counter(nodes * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
  state.SetLabel(toString(roundingArg(state.range(1))));
}

void BM_Sphere(benchmark::State& state) {
  const WorldGrid grid = unitGrid(static_cast<int>(state.range(0)));
  const Rounding rounding = roundingArg(state.range(1));
  const Eigen::Isometry3d X = centredPose();
  Octree tree(grid);
  for (auto _ : state) {
    tree = voxelize(grid, Sphere{0.4}, X, rounding);
    benchmark::DoNotOptimize(tree.nodes().data());
  }
  report(state, tree);
}

void meshBenchmark(benchmark::State& state, const TriangleMesh& mesh) {
  const WorldGrid grid = unitGrid(static_cast<int>(state.range(0)));
  const Rounding rounding = roundingArg(state.range(1));
  const Eigen::Isometry3d X = centredPose();
  Octree tree(grid);
  for (auto _ : state) {
    tree = voxelizeMesh(grid, mesh, X, rounding);
    benchmark::DoNotOptimize(tree.nodes().data());
  }
  report(state, tree);
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}

void BM_SphereMesh10k(benchmark::State& state) {
  static const TriangleMesh mesh = sphereMesh(0.4, 100, 51);  // 10,000 triangles
  meshBenchmark(state, mesh);
}

void BM_TorusMesh10k(benchmark::State& state) {
  static const TriangleMesh mesh = torusMesh(0.3, 0.12, 100, 50);  // 10,000 triangles
  meshBenchmark(state, mesh);
}

void buildArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"depth", "center"});
  for (int depth = 8; depth <= 10; ++depth) {
    for (int rounding = 0; rounding <= 1; ++rounding) b->Args({depth, rounding});
  }
  b->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
}

// A link-like cylinder, tilted in its grid (the hard case for axis-aligned boxes: a link's
// cylinder usually lies along an axis of its frame). Counters: boxes found and the share of the
// black volume the first box holds.
void BM_InnerBoxesCylinder(benchmark::State& state) {
  const WorldGrid grid = unitGrid(static_cast<int>(state.range(0)));
  const Octree link = voxelize(grid, Cylinder{0.2, 0.8}, centredPose(), Rounding::kConservative);
  std::vector<Eigen::AlignedBox3d> boxes;
  for (auto _ : state) {
    boxes = innerBoxes(link);
    benchmark::DoNotOptimize(boxes.data());
  }
  state.counters["boxes"] = static_cast<double>(boxes.size());
  state.counters["first box share"] = boxes.empty() ? 0.0 : boxes[0].volume() / link.volume();
}
BENCHMARK(BM_InnerBoxesCylinder)
    ->ArgName("depth")
    ->DenseRange(6, 8)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

BENCHMARK(BM_Sphere)->Apply(buildArgs);
BENCHMARK(BM_SphereMesh10k)->Apply(buildArgs);
BENCHMARK(BM_TorusMesh10k)->Apply(buildArgs);

}  // namespace
}  // namespace octomotion

BENCHMARK_MAIN();
