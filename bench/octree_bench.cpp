// Speed of the compact octree's queries: the parallel traversal `intersects` and
// `overlappingCubes` (Ahuja & Nash 1984 §5) on large trees, `occupied` point queries, and
// writing/reading the octomotion file format.
// Counters: "nodes/s" = internal nodes of both trees / time per call (how fast the traversal
// would go if it had to touch every node), "voxels" etc. describe the inputs.
// Run: build-*/bench/octree_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <sstream>

#include "octomotion/octree/io.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/octree_builder.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

constexpr double kVoxel = 0.01;

WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d::Zero(), kVoxel, depth);
}

// A ball of `radius_voxels` about the universe centre shifted by `dx_voxels` along x. The pairs
// below meet around x = centre + 37 voxels, off every large cube boundary, so the traversal
// cannot separate them at the root.
Octree ball(int depth, double radius_voxels, double dx_voxels) {
  const WorldGrid grid = gridOfDepth(depth);
  const double half = grid.sideMetres() / 2;
  const Eigen::Isometry3d X_WS(Eigen::Translation3d(half + dx_voxels * kVoxel, half, half));
  return voxelize(grid, Sphere{radius_voxels * kVoxel}, X_WS, Rounding::kCenter);
}

// An upright box of half-size `half_voxels` about the universe centre shifted along x.
Octree box(int depth, double half_voxels, double dx_voxels) {
  const WorldGrid grid = gridOfDepth(depth);
  const double half = grid.sideMetres() / 2;
  const Eigen::Isometry3d X_WS(Eigen::Translation3d(half + dx_voxels * kVoxel, half, half));
  return voxelize(grid, Box{Eigen::Vector3d::Constant(half_voxels * kVoxel)}, X_WS,
                  Rounding::kCenter);
}

// Two noisy clouds filling the same ball-shaped region, one on the even voxels (x+y+z even), one
// on the odd: disjoint, but interleaved everywhere, so no subtree pair can be skipped early.
std::pair<Octree, Octree> interleavedNoise(int depth, double radius_voxels, double density) {
  const WorldGrid grid = gridOfDepth(depth);
  OctreeBuilder even(grid), odd(grid);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(0, 1);
  const double c = grid.sideVoxels() / 2.0;
  const std::uint32_t lo = static_cast<std::uint32_t>(c - radius_voxels);
  const std::uint32_t hi = static_cast<std::uint32_t>(c + radius_voxels);
  for (std::uint32_t z = lo; z < hi; ++z)
    for (std::uint32_t y = lo; y < hi; ++y)
      for (std::uint32_t x = lo; x < hi; ++x) {
        const double dx = x + 0.5 - c, dy = y + 0.5 - c, dz = z + 0.5 - c;
        if (dx * dx + dy * dy + dz * dz > radius_voxels * radius_voxels) continue;
        if (unit(rng) >= density) continue;
        ((x + y + z) % 2 ? odd : even).setVoxel({x, y, z});
      }
  return {even.build(), odd.build()};
}

struct Pair {
  Octree a, b;
};

// Built once per process (voxelizing depth-10 balls takes a moment).
const Pair& overlappingBalls() {
  static const Pair p{ball(10, 200, 37 - 100), ball(10, 200, 37 + 100)};
  return p;
}
const Pair& nearMissBalls() {
  // Centres 402 voxels apart, radii 200: a gap of about two voxels where they face each other.
  static const Pair p{ball(10, 200, 37 - 201), ball(10, 200, 37 + 201)};
  return p;
}
const Pair& nearMissBoxes() {
  // Two 401-voxel cubes face to face across a one-voxel gap (x = centre + 37): the traversal
  // must follow the whole 401 x 401 facing plane down to level 0 to prove them apart.
  static const Pair p{box(10, 200.5, 37 - 201), box(10, 200.5, 37 + 201)};
  return p;
}
const Pair& noise() {
  static const Pair p = [] {
    auto [a, b] = interleavedNoise(8, 60, 0.3);
    return Pair{std::move(a), std::move(b)};
  }();
  return p;
}

void reportInputs(benchmark::State& state, const Pair& p) {
  const double nodes = static_cast<double>(p.a.internalNodeCount() + p.b.internalNodeCount());
  state.counters["nodes"] = nodes;
  state.counters["nodes/s"] = benchmark::Counter(nodes * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

void intersectsBench(benchmark::State& state, const Pair& p, bool expected) {
  for (auto _ : state) {
    const bool hit = intersects(p.a, p.b);
    benchmark::DoNotOptimize(hit);
    if (hit != expected) state.SkipWithError("wrong answer");
  }
  reportInputs(state, p);
}

void BM_IntersectsOverlappingBalls(benchmark::State& state) {
  intersectsBench(state, overlappingBalls(), true);
}
void BM_IntersectsNearMissBalls(benchmark::State& state) {
  intersectsBench(state, nearMissBalls(), false);
}
void BM_IntersectsNearMissBoxes(benchmark::State& state) {
  intersectsBench(state, nearMissBoxes(), false);
}
void BM_IntersectsInterleavedNoise(benchmark::State& state) {
  intersectsBench(state, noise(), false);
}

void BM_OverlappingCubesBalls(benchmark::State& state) {
  const Pair& p = overlappingBalls();
  std::size_t cubes = 0;
  for (auto _ : state) {
    const std::vector<Cube> out = overlappingCubes(p.a, p.b);
    cubes = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  reportInputs(state, p);
  state.counters["cubes"] = static_cast<double>(cubes);
}
void BM_OverlappingCubesNearMiss(benchmark::State& state) {
  const Pair& p = nearMissBalls();
  for (auto _ : state) {
    const std::vector<Cube> out = overlappingCubes(p.a, p.b);
    if (!out.empty()) state.SkipWithError("wrong answer");
    benchmark::DoNotOptimize(out.data());
  }
  reportInputs(state, p);
}

// Random voxels of the universe (mostly white, walking only a few levels) and random voxels of
// the ball's bounding box (about half black, walking down to the surface).
void occupiedBench(benchmark::State& state, bool near_surface) {
  const Octree& t = overlappingBalls().a;
  const auto bounds = *t.bounds();
  std::mt19937_64 rng(7);
  std::vector<Voxel> queries(4096);
  const std::uint32_t side = t.grid().sideVoxels();
  for (Voxel& v : queries) {
    if (near_surface) {
      v = {std::uniform_int_distribution<std::uint32_t>(bounds.min.x, bounds.max.x)(rng),
           std::uniform_int_distribution<std::uint32_t>(bounds.min.y, bounds.max.y)(rng),
           std::uniform_int_distribution<std::uint32_t>(bounds.min.z, bounds.max.z)(rng)};
    } else {
      std::uniform_int_distribution<std::uint32_t> coord(0, side - 1);
      v = {coord(rng), coord(rng), coord(rng)};
    }
  }
  std::size_t i = 0, black = 0;
  for (auto _ : state) {
    black += t.occupied(queries[i]);
    i = (i + 1) & (queries.size() - 1);
  }
  benchmark::DoNotOptimize(black);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.counters["nodes"] = static_cast<double>(t.internalNodeCount());
}
void BM_OccupiedUniform(benchmark::State& state) {
  occupiedBench(state, false);
}
void BM_OccupiedInBallBounds(benchmark::State& state) {
  occupiedBench(state, true);
}

// The file format (io.h) in memory: serialise / validate-and-load one ball tree.
void BM_WriteOctree(benchmark::State& state) {
  const Octree& t = overlappingBalls().a;
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::ostringstream out;
    writeOctree(t, out);
    bytes = out.str().size();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes * state.iterations()));
}
void BM_ReadOctree(benchmark::State& state) {
  const Octree& t = overlappingBalls().a;
  std::ostringstream out;
  writeOctree(t, out);
  const std::string bytes = out.str();
  for (auto _ : state) {
    std::istringstream in(bytes);
    const Octree back = readOctree(in, "<memory>");
    benchmark::DoNotOptimize(back.nodes().data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes.size() * state.iterations()));
}

BENCHMARK(BM_IntersectsOverlappingBalls);
BENCHMARK(BM_IntersectsNearMissBalls)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntersectsNearMissBoxes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IntersectsInterleavedNoise)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OverlappingCubesBalls)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlappingCubesNearMiss)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OccupiedUniform);
BENCHMARK(BM_OccupiedInBallBounds);
BENCHMARK(BM_WriteOctree)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadOctree)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace octomotion

BENCHMARK_MAIN();
