// Moving a voxelized object: Ahuja & Nash's path-arithmetic translation, its top-down variant,
// and Jackins & Tanimoto 90-degree rotations of an existing tree, against voxelizing the
// primitive again at the moved pose. Trees of depth 7-10; a sphere (mostly large interior leaves)
// and a box.
//
//   build-<name>/bench/translate_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <utility>

#include "octomotion/motion/rotate90.h"
#include "octomotion/motion/translate.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

using Displacement = Eigen::Matrix<std::int64_t, 3, 1>;

constexpr double kVoxel = 0.01;

WorldGrid gridOfDepth(int depth) {
  // Centred on the world origin so the shapes sit in the middle of the universe, off the
  // octant boundaries' symmetry by a fraction of a voxel.
  const double half = 0.5 * kVoxel * static_cast<double>(1u << depth);
  return WorldGrid(Eigen::Vector3d(-half, -half, -half), kVoxel, depth);
}

Primitive shapeOf(int shape, int depth) {
  const double side = kVoxel * static_cast<double>(1u << depth);
  if (shape == 0) return Sphere{0.3 * side};
  return Box{Eigen::Vector3d(0.3 * side, 0.2 * side, 0.15 * side)};
}

Eigen::Isometry3d poseOf(const Eigen::Vector3d& shift_voxels) {
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  X_WS.translation() = Eigen::Vector3d(0.0037, -0.0021, 0.0013) + shift_voxels * kVoxel;
  return X_WS;
}

const Octree& sourceTree(int depth, int shape) {
  static std::map<std::pair<int, int>, Octree> cache;
  auto it = cache.find({depth, shape});
  if (it == cache.end()) {
    it = cache
             .emplace(std::make_pair(depth, shape),
                      voxelize(gridOfDepth(depth), shapeOf(shape, depth),
                               poseOf(Eigen::Vector3d::Zero()), Rounding::kConservative))
             .first;
  }
  return it->second;
}

// 0: one voxel along x (H = 0: every level is traversed); 1: odd in all three axes;
// 2: 16 voxels along each axis (H = 4: nodes of 16^3 voxels move whole).
Displacement displacementOf(int index) {
  switch (index) {
    case 0:
      return Displacement(1, 0, 0);
    case 1:
      return Displacement(3, -5, 7);
    default:
      return Displacement(16, -16, 16);
  }
}

const char* kShapeNames[] = {"sphere", "box"};

void setLabel(benchmark::State& state) {
  state.SetLabel(std::string(kShapeNames[state.range(1)]) +
                 " d=" + std::to_string(displacementOf(static_cast<int>(state.range(2)))[0]) + "," +
                 std::to_string(displacementOf(static_cast<int>(state.range(2)))[1]) + "," +
                 std::to_string(displacementOf(static_cast<int>(state.range(2)))[2]));
}

void BM_TranslatePathArithmetic(benchmark::State& state) {
  const Octree& source =
      sourceTree(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const Displacement d = displacementOf(static_cast<int>(state.range(2)));
  std::size_t nodes = 0;
  for (auto _ : state) {
    TranslateResult moved = translate(source, d);
    nodes = moved.tree.internalNodeCount();
    benchmark::DoNotOptimize(moved);
  }
  state.counters["source_nodes"] = static_cast<double>(source.internalNodeCount());
  state.counters["result_nodes"] = static_cast<double>(nodes);
  setLabel(state);
}

// The same translation computed top-down from the source windows (translateTopDown).
void BM_TranslateTopDown(benchmark::State& state) {
  const Octree& source =
      sourceTree(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const Displacement d = displacementOf(static_cast<int>(state.range(2)));
  std::size_t nodes = 0;
  for (auto _ : state) {
    TranslateResult moved = translateTopDown(source, d);
    nodes = moved.tree.internalNodeCount();
    benchmark::DoNotOptimize(moved);
  }
  state.counters["result_nodes"] = static_cast<double>(nodes);
  setLabel(state);
}

void BM_TranslateByRevoxelizing(benchmark::State& state) {
  const int depth = static_cast<int>(state.range(0));
  const int shape = static_cast<int>(state.range(1));
  const Displacement d = displacementOf(static_cast<int>(state.range(2)));
  const WorldGrid grid = gridOfDepth(depth);
  const Primitive primitive = shapeOf(shape, depth);
  const Eigen::Isometry3d X_WS = poseOf(d.cast<double>());
  const bool same = voxelize(grid, primitive, X_WS, Rounding::kConservative) ==
                    translate(sourceTree(depth, shape), d).tree;
  std::size_t nodes = 0;
  for (auto _ : state) {
    Octree rebuilt = voxelize(grid, primitive, X_WS, Rounding::kConservative);
    nodes = rebuilt.internalNodeCount();
    benchmark::DoNotOptimize(rebuilt);
  }
  state.counters["result_nodes"] = static_cast<double>(nodes);
  // 1 when re-voxelizing gave exactly the translated tree (it may differ by boundary voxels
  // where the shifted pose rounds differently in floating point).
  state.counters["same_tree"] = same ? 1.0 : 0.0;
  setLabel(state);
}

void BM_Rotate90(benchmark::State& state) {
  const Octree& source =
      sourceTree(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const AxisRotation R = AxisRotation::about(2, 1);
  for (auto _ : state) {
    Octree rotated = rotate90(source, R);
    benchmark::DoNotOptimize(rotated);
  }
  state.counters["nodes"] = static_cast<double>(source.internalNodeCount());
  state.SetLabel(kShapeNames[state.range(1)]);
}

void BM_Rotate90ByRevoxelizing(benchmark::State& state) {
  const int depth = static_cast<int>(state.range(0));
  const int shape = static_cast<int>(state.range(1));
  const WorldGrid grid = gridOfDepth(depth);
  const Primitive primitive = shapeOf(shape, depth);
  // The same quarter turn about z, about the universe centre (the world origin here).
  const Eigen::Isometry3d X_WS =
      Eigen::Isometry3d(Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ())) *
      poseOf(Eigen::Vector3d::Zero());
  for (auto _ : state) {
    Octree rebuilt = voxelize(grid, primitive, X_WS, Rounding::kConservative);
    benchmark::DoNotOptimize(rebuilt);
  }
  state.SetLabel(kShapeNames[state.range(1)]);
}

void translateArgs(benchmark::internal::Benchmark* b) {
  for (int depth = 7; depth <= 10; ++depth)
    for (int shape = 0; shape < 2; ++shape)
      for (int d = 0; d < 3; ++d) b->Args({depth, shape, d});
  b->ArgNames({"depth", "shape", "d"})->Unit(benchmark::kMicrosecond);
}

void rotateArgs(benchmark::internal::Benchmark* b) {
  for (int depth = 7; depth <= 10; ++depth)
    for (int shape = 0; shape < 2; ++shape) b->Args({depth, shape});
  b->ArgNames({"depth", "shape"})->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_TranslatePathArithmetic)->Apply(translateArgs);
BENCHMARK(BM_TranslateTopDown)->Apply(translateArgs);
BENCHMARK(BM_TranslateByRevoxelizing)->Apply(translateArgs);
BENCHMARK(BM_Rotate90)->Apply(rotateArgs);
BENCHMARK(BM_Rotate90ByRevoxelizing)->Apply(rotateArgs);

}  // namespace
}  // namespace octomotion

BENCHMARK_MAIN();
