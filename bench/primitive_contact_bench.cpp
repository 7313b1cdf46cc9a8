// The exact-primitive test (blackLeafMeetsPrimitive) against the fused voxel query (collides,
// with the environment's BlackCellGrid and ClearanceGrid, as the planner runs it) for the case
// that made it: a 26 cm, 4 cm-radius link (a voxelized cylinder, link voxels at 1/4 of the
// environment's) beside one of the cage's 12 mm bars, at 1 cm and 5 mm. Poses are drawn with the
// link's axis within 8 cm of the bar and split by the exact test's answer into contacts and
// near misses; both queries run on the same poses, and the counters give per-pose medians
// (steady_clock around each query), the voxel query's median over the exact test's
// (`voxel_over_exact`), how many poses the voxel query alone rejects (`voxel_only`: the bar's
// voxel margin) and how many the exact test alone does (`exact_only`: a link voxel's bounding
// sphere reaching past the bar's voxels). Run: build/bench/primitive_contact_bench
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "octomotion/motion/black_cell_grid.h"
#include "octomotion/motion/clearance_grid.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/octree/voxelize.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

struct Setup {
  WorldGrid env_grid{Eigen::Vector3d::Zero(), 1.0, 1};
  Octree bar_voxels{env_grid};
  std::unique_ptr<BlackCellGrid> cells;
  std::unique_ptr<ClearanceGrid> clearance;
  Octree link{env_grid};
  std::unique_ptr<MovableSource> prepared;
  Eigen::Isometry3d X_WP;  // the bar
  std::unique_ptr<PrimitiveShape> bar;
  std::vector<Eigen::Isometry3d> contacts, near_misses;  // poses of the link's grid frame in W
};

const Cylinder kBar{0.012, 0.6};
const Cylinder kLink{0.04, 0.26};

Setup& setup(int res_index) {
  static std::unique_ptr<Setup> cache[2];
  std::unique_ptr<Setup>& s = cache[res_index];
  if (s) return *s;
  s = std::make_unique<Setup>();
  const double voxel = res_index == 0 ? 0.01 : 0.005;
  // A 64 cm (1 cm) or 64 cm (5 mm, depth 7) universe around the bar, which stands at its centre.
  s->env_grid = WorldGrid(Eigen::Vector3d::Constant(-0.32), voxel, res_index == 0 ? 6 : 7);
  s->X_WP = Eigen::Isometry3d::Identity();
  s->bar_voxels = voxelize(s->env_grid, kBar, s->X_WP, Rounding::kConservative);
  s->cells = std::make_unique<BlackCellGrid>(s->bar_voxels);
  s->clearance = std::make_unique<ClearanceGrid>(s->bar_voxels);
  s->bar = std::make_unique<PrimitiveShape>(kBar);
  // The link in its own grid (voxels at 1/4), centred in that grid.
  const WorldGrid link_grid(Eigen::Vector3d::Constant(-0.16), voxel / 4, res_index == 0 ? 7 : 8);
  s->link = voxelize(link_grid, kLink, Eigen::Isometry3d::Identity(), Rounding::kConservative);
  s->prepared = std::make_unique<MovableSource>(s->link);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  while (s->contacts.size() < 500 || s->near_misses.size() < 500) {
    Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
    X_WL.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
    X_WL.translation() = Eigen::Vector3d(0.08 * u(rng), 0.08 * u(rng), 0.2 * u(rng));
    const bool hit = blackLeafMeetsPrimitive(*s->prepared, s->X_WP.inverse() * X_WL, *s->bar);
    auto& list = hit ? s->contacts : s->near_misses;
    if (list.size() < 500) list.push_back(X_WL);
  }
  return *s;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void BM_ExactVersusVoxels(benchmark::State& state) {
  Setup& s = setup(static_cast<int>(state.range(0)));
  const auto& poses = state.range(1) ? s.contacts : s.near_misses;
  CollisionScratch scratch;
  std::vector<double> exact_us, voxel_us;
  int voxel_only = 0, exact_only = 0;
  for (auto _ : state) {
    exact_us.clear();
    voxel_us.clear();
    voxel_only = exact_only = 0;
    for (const Eigen::Isometry3d& X_WL : poses) {
      const Eigen::Isometry3d X_PL = s.X_WP.inverse() * X_WL;
      const auto t0 = Clock::now();
      const bool exact = blackLeafMeetsPrimitive(*s.prepared, X_PL, *s.bar);
      const auto t1 = Clock::now();
      const bool voxels = collides(*s.prepared, X_WL, s.bar_voxels, Rounding::kConservative,
                                   scratch, nullptr, s.cells.get(), s.clearance.get());
      const auto t2 = Clock::now();
      benchmark::DoNotOptimize(exact);
      exact_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      voxel_us.push_back(std::chrono::duration<double, std::micro>(t2 - t1).count());
      voxel_only += voxels && !exact;
      exact_only += exact && !voxels;  // a voxel's sphere reaching past the bar's voxels
    }
  }
  const double e = median(exact_us), v = median(voxel_us);
  state.counters["exact_median_us"] = e;
  state.counters["voxel_median_us"] = v;
  state.counters["voxel_over_exact"] = v / e;
  state.counters["voxel_only"] = voxel_only;
  state.counters["exact_only"] = exact_only;
  state.SetLabel(std::string(state.range(0) ? "5 mm" : "1 cm") +
                 (state.range(1) ? " contacts" : " near misses"));
}

BENCHMARK(BM_ExactVersusVoxels)
    ->Args({0, 1})
    ->Args({0, 0})
    ->Args({1, 1})
    ->Args({1, 0})
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
