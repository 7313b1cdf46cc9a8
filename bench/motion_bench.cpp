// Weng & Ahuja 1987 moveTree cost against K n (Theorem 3), and the fused collision query
// (collides) against moveTree + intersects for a link-sized mesh in a cluttered room.
//
// Per-pose times are wall-clock (steady_clock) around each single query; the counters give
// their median / 90th percentile over the pose set, which is robust to the shared machine's
// preemptions. Run:
//   build-move/bench/motion_bench --benchmark_filter='Fused|MoveTreeThen'
//   build-move/bench/motion_bench --benchmark_filter=MoveTreeKn
// moveTree + intersects are timed per pose in thread CPU time (milliseconds: wall time on the
// shared machine is inflated by preemptions); speedup_vs_fused = its median / the fused median.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "octomotion/motion/black_cell_grid.h"
#include "octomotion/motion/clearance_grid.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

// Thread CPU time in microseconds: for the millisecond-scale operations, which wall-clock
// timing on the shared machine would inflate with preemptions (~1 us resolution).
double threadCpuMicros() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

// A closed capsule mesh along z: body of length `body`, hemispherical caps of `radius`,
// `seg` vertices per ring, `cap_rings` latitude rings per cap, `body_rings` rings on the body.
TriangleMesh capsuleMesh(double radius, double body, int seg, int cap_rings, int body_rings) {
  TriangleMesh m;
  std::vector<double> ring_z, ring_r;
  for (int i = 1; i <= cap_rings; ++i) {  // bottom cap, from the pole up
    const double a = -M_PI / 2 + M_PI / 2 * i / cap_rings;
    ring_z.push_back(-body / 2 + radius * std::sin(a));
    ring_r.push_back(radius * std::cos(a));
  }
  for (int i = 1; i < body_rings; ++i) {
    ring_z.push_back(-body / 2 + body * i / body_rings);
    ring_r.push_back(radius);
  }
  for (int i = 0; i < cap_rings; ++i) {  // top cap, from the equator up
    const double a = M_PI / 2 * i / cap_rings;
    ring_z.push_back(body / 2 + radius * std::sin(a));
    ring_r.push_back(radius * std::cos(a));
  }
  m.vertices.push_back(Eigen::Vector3d(0, 0, -body / 2 - radius));
  for (std::size_t r = 0; r < ring_z.size(); ++r) {
    for (int s = 0; s < seg; ++s) {
      const double t = 2 * M_PI * s / seg;
      m.vertices.push_back(
          Eigen::Vector3d(ring_r[r] * std::cos(t), ring_r[r] * std::sin(t), ring_z[r]));
    }
  }
  m.vertices.push_back(Eigen::Vector3d(0, 0, body / 2 + radius));
  const std::uint32_t top = static_cast<std::uint32_t>(m.vertices.size() - 1);
  auto at = [&](std::size_t r, int s) {
    return static_cast<std::uint32_t>(1 + r * seg + (s % seg));
  };
  for (int s = 0; s < seg; ++s) m.triangles.push_back({0, at(0, s + 1), at(0, s)});
  for (std::size_t r = 0; r + 1 < ring_z.size(); ++r) {
    for (int s = 0; s < seg; ++s) {
      m.triangles.push_back({at(r, s), at(r, s + 1), at(r + 1, s + 1)});
      m.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    }
  }
  const std::size_t last = ring_z.size() - 1;
  for (int s = 0; s < seg; ++s) m.triangles.push_back({at(last, s), at(last, s + 1), top});
  return m;
}

// The link: a 26 cm capsule of radius 4 cm, ~3.5k triangles, in a frame centred on it.
const TriangleMesh& linkMesh() {
  static const TriangleMesh mesh = capsuleMesh(0.04, 0.18, 48, 12, 14);
  return mesh;
}

// A 2.56 m room: floor, table-like boxes, shelves, cylinders (poles, bottles) and balls.
Octree clutteredRoom(const WorldGrid& grid) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> xy(-1.2, 1.2), z(0.0, 2.4), u(0.0, 1.0);
  auto place = [&](const Primitive& p, bool tilt) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (tilt) {
      X.linear() =
          Eigen::AngleAxisd(2 * M_PI * u(rng),
                            Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized())
              .toRotationMatrix();
    }
    X.translation() = Eigen::Vector3d(xy(rng), xy(rng), z(rng));
    return voxelize(grid, p, X, Rounding::kConservative);
  };
  Octree env =
      voxelize(grid, Box{Eigen::Vector3d(1.28, 1.28, 0.02)},
               Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.0)), Rounding::kConservative);
  for (int i = 0; i < 10; ++i)
    env = unite(
        env,
        place(Box{Eigen::Vector3d(0.1 + 0.25 * u(rng), 0.1 + 0.2 * u(rng), 0.02 + 0.05 * u(rng))},
              i % 2));
  for (int i = 0; i < 14; ++i)
    env = unite(env, place(Cylinder{0.015 + 0.05 * u(rng), 0.2 + 0.8 * u(rng)}, true));
  for (int i = 0; i < 14; ++i) env = unite(env, place(Sphere{0.03 + 0.1 * u(rng)}, false));
  return env;
}

struct Setup {
  double voxel;
  WorldGrid env_grid;
  Octree env;
  Octree link;
  std::unique_ptr<MovableSource> prepared;
  std::vector<Eigen::Isometry3d> free_poses, colliding_poses;
  std::unique_ptr<BlackCellGrid> cells;  // the environment's, for BM_FusedWithCellGrid
  std::unique_ptr<ClearanceGrid> clear;  // the environment's, for BM_FusedWithClearanceGrid
};

int depthFor(double voxel, double metres) {
  int d = 1;
  while (voxel * std::ldexp(1.0, d) < metres - 1e-9) ++d;
  return d;
}

// Environment, link and 1000 + 1000 poses classified free/colliding (centre-mode result used
// for classification of both modes would bias them, so each mode has its own sets).
Setup& setup(int res, Rounding mode) {
  static std::map<std::pair<int, int>, std::unique_ptr<Setup>> cache;
  auto& slot = cache[{res, static_cast<int>(mode)}];
  if (slot) return *slot;
  const double voxel = res == 0 ? 0.005 : (res == 1 ? 0.01 : 0.02);
  const WorldGrid env_grid(Eigen::Vector3d(-1.28, -1.28, 0.0), voxel, depthFor(voxel, 2.56));
  const int sdepth = depthFor(voxel, 0.32);
  const double sside = voxel * std::ldexp(1.0, sdepth);
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-sside / 2), voxel, sdepth);
  static std::map<int, Octree> envs;
  if (!envs.count(res)) envs.emplace(res, clutteredRoom(env_grid));
  auto s = std::make_unique<Setup>(Setup{
      voxel,
      env_grid,
      envs.at(res),
      voxelizeMesh(link_grid, linkMesh(), Eigen::Isometry3d::Identity(), Rounding::kConservative),
      nullptr,
      {},
      {},
      nullptr,
      nullptr});
  s->prepared = std::make_unique<MovableSource>(s->link);
  s->cells = std::make_unique<BlackCellGrid>(s->env);
  s->clear = std::make_unique<ClearanceGrid>(s->env);
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> xy(-1.15, 1.15), z(0.1, 2.45);
  std::normal_distribution<double> n(0, 1);
  CollisionScratch scratch;
  while (s->free_poses.size() < 1000 || s->colliding_poses.size() < 1000) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(xy(rng), xy(rng), z(rng));
    auto& set =
        collides(*s->prepared, X, s->env, mode, scratch) ? s->colliding_poses : s->free_poses;
    if (set.size() < 1000) set.push_back(X);
  }
  slot = std::move(s);
  return *slot;
}

struct Summary {
  double median, p90, mean;
};
Summary summarize(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  double sum = 0;
  for (double x : t) sum += x;
  return {t[t.size() / 2], t[t.size() * 9 / 10], sum / t.size()};
}

std::map<std::tuple<int, int, int>, double> fused_median;  // for the speed-up counter

std::string label(int res, bool colliding, Rounding mode) {
  return std::string(res == 0   ? "5mm"
                     : res == 1 ? "1cm"
                                : "2cm") +
         (colliding ? " colliding" : " free") +
         (mode == Rounding::kConservative ? " conservative" : " center");
}

// The fused query over the setup's free or colliding poses (with the environment's cell grid
// and clearance grid when given), each call timed in microseconds; answers that disagree with
// the poses' class are counted in `wrong`.
std::vector<double> timeCollides(benchmark::State& state, const Setup& s, bool colliding,
                                 Rounding mode, const BlackCellGrid* cells,
                                 const ClearanceGrid* clear, std::size_t& wrong) {
  const auto& poses = colliding ? s.colliding_poses : s.free_poses;
  CollisionScratch scratch;
  std::vector<double> times;
  for (auto _ : state) {
    for (const auto& X : poses) {
      const auto t0 = Clock::now();
      const bool hit = collides(*s.prepared, X, s.env, mode, scratch, nullptr, cells, clear);
      const auto t1 = Clock::now();
      benchmark::DoNotOptimize(hit);
      wrong += hit != colliding;
      times.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
  }
  return times;
}

void BM_Fused(benchmark::State& state) {
  const int res = static_cast<int>(state.range(0));
  const bool colliding = state.range(1) != 0;
  const Rounding mode = state.range(2) ? Rounding::kConservative : Rounding::kCenter;
  Setup& s = setup(res, mode);
  std::size_t wrong = 0;
  const Summary sum = summarize(timeCollides(state, s, colliding, mode, nullptr, nullptr, wrong));
  fused_median[{res, colliding, static_cast<int>(mode)}] = sum.median;
  state.counters["median_us"] = sum.median;
  state.counters["p90_us"] = sum.p90;
  state.counters["mean_us"] = sum.mean;
  state.counters["link_leaves"] = static_cast<double>(s.link.blackLeafCount());
  state.counters["env_nodes"] = static_cast<double>(s.env.internalNodeCount());
  state.counters["wrong"] = static_cast<double>(wrong);
  state.SetLabel(label(res, colliding, mode));
}

void BM_MoveTreeThenIntersects(benchmark::State& state) {
  const int res = static_cast<int>(state.range(0));
  const bool colliding = state.range(1) != 0;
  const Rounding mode = state.range(2) ? Rounding::kConservative : Rounding::kCenter;
  Setup& s = setup(res, mode);
  const auto& poses = colliding ? s.colliding_poses : s.free_poses;
  const std::size_t count = res == 0 ? 60 : 150;
  std::vector<double> times;
  for (auto _ : state) {
    for (std::size_t i = 0; i < count; ++i) {
      const double t0 = threadCpuMicros();
      const bool hit = intersects(moveTree(s.link, poses[i], s.env_grid, mode), s.env);
      const double t1 = threadCpuMicros();
      benchmark::DoNotOptimize(hit);
      times.push_back(t1 - t0);
    }
  }
  const Summary sum = summarize(times);
  state.counters["median_us"] = sum.median;
  state.counters["p90_us"] = sum.p90;
  const auto it = fused_median.find({res, colliding, static_cast<int>(mode)});
  if (it != fused_median.end()) state.counters["speedup_vs_fused"] = sum.median / it->second;
  state.SetLabel(label(res, colliding, mode));
}

// The same poses with the environment's BlackCellGrid (either rounding): speedup_vs_plain is
// BM_Fused's median over this one, same run.
void BM_FusedWithCellGrid(benchmark::State& state) {
  const int res = static_cast<int>(state.range(0));
  const bool colliding = state.range(1) != 0;
  const Rounding mode = state.range(2) ? Rounding::kConservative : Rounding::kCenter;
  Setup& s = setup(res, mode);
  std::size_t wrong = 0;
  const Summary sum =
      summarize(timeCollides(state, s, colliding, mode, s.cells.get(), nullptr, wrong));
  state.counters["median_us"] = sum.median;
  state.counters["mean_us"] = sum.mean;
  state.counters["grid_level"] = s.cells->level();
  state.counters["wrong"] = static_cast<double>(wrong);
  const auto it = fused_median.find({res, colliding, static_cast<int>(mode)});
  if (it != fused_median.end()) state.counters["speedup_vs_plain"] = it->second / sum.median;
  state.SetLabel(label(res, colliding, mode));
}

// The same poses with the environment's ClearanceGrid (either rounding): speedup_vs_plain is
// BM_Fused's median over this one, same run.
void BM_FusedWithClearanceGrid(benchmark::State& state) {
  const int res = static_cast<int>(state.range(0));
  const bool colliding = state.range(1) != 0;
  const Rounding mode = state.range(2) ? Rounding::kConservative : Rounding::kCenter;
  Setup& s = setup(res, mode);
  std::size_t wrong = 0;
  const Summary sum =
      summarize(timeCollides(state, s, colliding, mode, nullptr, s.clear.get(), wrong));
  state.counters["median_us"] = sum.median;
  state.counters["mean_us"] = sum.mean;
  state.counters["grid_level"] = s.clear->level();
  state.counters["wrong"] = static_cast<double>(wrong);
  const auto it = fused_median.find({res, colliding, static_cast<int>(mode)});
  if (it != fused_median.end()) state.counters["speedup_vs_plain"] = it->second / sum.median;
  state.SetLabel(label(res, colliding, mode));
}

void fusedArgs(benchmark::internal::Benchmark* b) {
  for (int mode = 0; mode < 2; ++mode)
    for (int res = 0; res < 3; ++res)
      for (int cls = 0; cls < 2; ++cls) b->Args({res, cls, mode});
}
BENCHMARK(BM_Fused)->Apply(fusedArgs)->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FusedWithCellGrid)->Apply(fusedArgs)->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FusedWithClearanceGrid)
    ->Apply(fusedArgs)
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MoveTreeThenIntersects)
    ->Apply(fusedArgs)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// Theorem 3: moveTree time / (K n), K = source nodes (internal + leaves), n = target depth.
// The source is a voxelized ball of fixed size at depths 4..7 (K grows ~4x per level); the
// target keeps the voxel size and grows the universe (n = source depth + 1 .. + 6).
void BM_MoveTreeKn(benchmark::State& state) {
  const int sdepth = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const double voxel = 0.32 / std::ldexp(1.0, sdepth);
  const WorldGrid sgrid(Eigen::Vector3d::Constant(-0.16), voxel, sdepth);
  const Octree ball =
      voxelize(sgrid, Sphere{0.14}, Eigen::Isometry3d::Identity(), Rounding::kCenter);
  const WorldGrid tgrid(Eigen::Vector3d::Zero(), voxel, n);
  const double K = 8.0 * static_cast<double>(ball.internalNodeCount()) + 1.0;  // Lemma: T = 8I + 1
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 16; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d::Constant(0.5 * tgrid.sideMetres()) +
                      Eigen::Vector3d(0.3 * voxel, 0.1 * voxel, 0);
    poses.push_back(X);
  }
  std::size_t i = 0;
  MoveStats st;
  double inodes = 0, cpu_us = 0;
  for (auto _ : state) {
    const double t0 = threadCpuMicros();
    const Octree t = moveTree(ball, poses[i++ % poses.size()], tgrid, Rounding::kCenter, &st);
    cpu_us += threadCpuMicros() - t0;
    inodes += static_cast<double>(st.internal_nodes);
    benchmark::DoNotOptimize(t);
  }
  state.counters["K"] = K;
  state.counters["n"] = n;
  // Thread CPU nanoseconds per source node per level: flat in K and n means O(K n).
  state.counters["cpu_ns_per_Kn"] =
      1e3 * cpu_us / static_cast<double>(state.iterations()) / (K * n);
  state.counters["target_I"] = inodes / static_cast<double>(state.iterations());
  state.counters["M_over_I"] = static_cast<double>(st.peak_nodes) /
                               static_cast<double>(std::max<std::size_t>(1, st.internal_nodes));
}
BENCHMARK(BM_MoveTreeKn)
    ->ArgsProduct({{4, 5, 6, 7}, {8, 10, 12, 14}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
