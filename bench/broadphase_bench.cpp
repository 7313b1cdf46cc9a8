// The N-objects octree report's timing experiment (§3.1, Table 1), reproduced and extended:
// two parallel planes of cubes — a central cube with concentric square rings, the second plane's
// rings offset — move toward each other, bounce off each other (exact cube overlap reverses an
// approaching cube) and off two walls, for 200 steps. Sets t0..t10 have 2..882 cubes as in the
// report; t15..t50 go up to 20,402. Methods: the N-objects octree for N = 5, 10, 30, 50, the
// exhaustive all-pairs test (N = infinity) and FCL 0.7's DynamicAABBTreeCollisionManager, all
// feeding the same exact narrow phase (oriented-cube separating axes).
//
// Google Benchmark mode (default): one iteration = 200 steps from the initial scene; CPU time
// (the machine is shared, wall time measures its load); counters give CPU time per step and
// candidate pairs / collisions per step. Use --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true for medians and spread.
// CSV mode: `broadphase_bench --csv [--max-rings R] [--reps K] [--exhaustive-max-rings E]`
// prints median thread-CPU microseconds per step per method and cube count (plot with
// scripts/plot_broadphase.gp).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include "octomotion/broadphase/aabb.h"
#include "octomotion/broadphase/n_objects_octree.h"

namespace {

using octomotion::broadphase::Aabb;
using octomotion::broadphase::NObjectsOctree;
using octomotion::broadphase::OrientedBox;

constexpr int kSteps = 200;
constexpr double kSpeed = 0.15;   // per step, cube side 1 (the report's fidelity constraint)
constexpr double kSpacing = 2.0;  // centre distance within a plane
constexpr double kOffset = 0.4;   // second plane's rings shifted in y and z
constexpr double kPlaneX = 6.0;   // planes start at x = -6 and +6
constexpr double kWallX = 9.0;    // and bounce off walls at |x| = 9

struct Scene {
  std::vector<OrientedBox> cubes;
  std::vector<double> vx;
};

// 2 (2r+1)^2 cubes: t0 = 2, t1 = 18, ..., t10 = 882.
Scene makeScene(int rings) {
  Scene s;
  std::mt19937_64 rng(1993);
  std::uniform_real_distribution<double> tilt(-0.25, 0.25);  // radians, fixed per cube
  for (int plane = 0; plane < 2; ++plane) {
    const double x = plane == 0 ? -kPlaneX : kPlaneX;
    const double shift = plane == 0 ? 0.0 : kOffset;
    for (int i = -rings; i <= rings; ++i) {
      for (int j = -rings; j <= rings; ++j) {
        OrientedBox c;
        c.center = Eigen::Vector3d(x, kSpacing * i + shift, kSpacing * j + shift);
        c.R_WB = (Eigen::AngleAxisd(tilt(rng), Eigen::Vector3d::UnitX()) *
                  Eigen::AngleAxisd(tilt(rng), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(tilt(rng), Eigen::Vector3d::UnitZ()))
                     .toRotationMatrix();
        c.half = Eigen::Vector3d::Constant(0.5);
        s.cubes.push_back(c);
        s.vx.push_back(plane == 0 ? kSpeed : -kSpeed);
      }
    }
  }
  return s;
}

int cubesFor(int rings) {
  return 2 * (2 * rings + 1) * (2 * rings + 1);
}

// The report's dynamics (§1.2): move, then reverse every cube that collided while approaching
// its partner; walls keep the planes in the arena.
struct Dynamics {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> collisions;
  std::vector<char> flip;
  void advance(Scene& s) {
    for (std::size_t i = 0; i < s.cubes.size(); ++i) s.cubes[i].center.x() += s.vx[i];
  }
  void respond(Scene& s) {
    flip.assign(s.cubes.size(), 0);
    for (auto [a, b] : collisions) {
      const double dx = s.cubes[b].center.x() - s.cubes[a].center.x();
      if (dx * s.vx[a] > 0) flip[a] = 1;
      if (-dx * s.vx[b] > 0) flip[b] = 1;
    }
    for (std::size_t i = 0; i < s.cubes.size(); ++i) {
      const double x = s.cubes[i].center.x();
      if ((x > kWallX && s.vx[i] > 0) || (x < -kWallX && s.vx[i] < 0)) flip[i] = 1;
      if (flip[i]) s.vx[i] = -s.vx[i];
    }
    collisions.clear();
  }
};

struct RunStats {
  std::uint64_t candidates = 0;
  std::uint64_t collisions = 0;
  std::uint64_t pair_tests = 0;  // AABB tests the broad phase made (octree: co-resident pairs)
  std::uint64_t splits_merges = 0, neighbour_queries = 0;  // octree maintenance work
};

// N-objects octree (capacity = kUnlimited: exhaustive). Builds the tree from the initial scene
// (§2.2's 150 % root), then times nothing itself: the caller times the whole call.
class OctreeRun {
 public:
  OctreeRun(const Scene& initial, std::uint32_t capacity) : scene_(initial) {
    std::vector<Aabb> boxes;
    for (const OrientedBox& c : scene_.cubes) boxes.push_back(c.aabb());
    NObjectsOctree::Options opt;
    opt.leaf_capacity = capacity;
    opt.max_depth = 12;
    tree_ = std::make_unique<NObjectsOctree>(NObjectsOctree::forBoxes(boxes, opt));
  }
  RunStats run() {
    RunStats stats;
    for (int step = 0; step < kSteps; ++step) {
      dyn_.advance(scene_);
      for (std::uint32_t i = 0; i < scene_.cubes.size(); ++i)
        tree_->move(i, scene_.cubes[i].aabb());
      tree_->forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) {
        ++stats.candidates;
        if (octomotion::broadphase::overlaps(scene_.cubes[a], scene_.cubes[b]))
          dyn_.collisions.emplace_back(a, b);
      });
      stats.collisions += dyn_.collisions.size();
      stats.pair_tests += tree_->counters().coresident_pairs;
      dyn_.respond(scene_);
    }
    stats.splits_merges = tree_->counters().splits + tree_->counters().merges;
    stats.neighbour_queries = tree_->counters().neighbour_queries;
    return stats;
  }

 private:
  Scene scene_;
  Dynamics dyn_;
  std::unique_ptr<NObjectsOctree> tree_;
};

// FCL's dynamic AABB tree; its pair callback runs the same exact narrow phase.
class FclRun {
 public:
  explicit FclRun(const Scene& initial) : scene_(initial) {
    auto box = std::make_shared<fcl::Box<double>>(1.0, 1.0, 1.0);
    for (std::size_t i = 0; i < scene_.cubes.size(); ++i) {
      auto object = std::make_unique<fcl::CollisionObject<double>>(box);
      object->setRotation(scene_.cubes[i].R_WB);
      object->setTranslation(scene_.cubes[i].center);
      object->computeAABB();
      object->setUserData(reinterpret_cast<void*>(i));
      raw_.push_back(object.get());
      objects_.push_back(std::move(object));
    }
    manager_.registerObjects(raw_);
    manager_.setup();
  }
  RunStats run() {
    RunStats stats;
    Context ctx{this, &stats};
    for (int step = 0; step < kSteps; ++step) {
      dyn_.advance(scene_);
      for (std::size_t i = 0; i < scene_.cubes.size(); ++i) {
        objects_[i]->setTranslation(scene_.cubes[i].center);
        objects_[i]->computeAABB();
      }
      manager_.update();
      manager_.collide(&ctx, &FclRun::onPair);
      stats.collisions += dyn_.collisions.size();
      dyn_.respond(scene_);
    }
    return stats;
  }

 private:
  struct Context {
    FclRun* self;
    RunStats* stats;
  };
  static bool onPair(fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2,
                     void* data) {
    auto* ctx = static_cast<Context*>(data);
    ++ctx->stats->candidates;
    auto a = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o1->getUserData()));
    auto b = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o2->getUserData()));
    if (a > b) std::swap(a, b);
    const Scene& s = ctx->self->scene_;
    if (octomotion::broadphase::overlaps(s.cubes[a], s.cubes[b]))
      ctx->self->dyn_.collisions.emplace_back(a, b);
    return false;  // keep going
  }

  Scene scene_;
  Dynamics dyn_;
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects_;
  std::vector<fcl::CollisionObject<double>*> raw_;
  fcl::DynamicAABBTreeCollisionManager<double> manager_;
};

constexpr std::uint32_t kExhaustive = NObjectsOctree::kUnlimited;

void setCounters(benchmark::State& state, int cubes, const RunStats& last) {
  state.counters["cubes"] = cubes;
  state.counters["time/step"] = benchmark::Counter(
      kSteps, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["cand/step"] = static_cast<double>(last.candidates) / kSteps;
  state.counters["coll/step"] = static_cast<double>(last.collisions) / kSteps;
  state.counters["tests/step"] = static_cast<double>(last.pair_tests) / kSteps;
  state.counters["split+merge/step"] = static_cast<double>(last.splits_merges) / kSteps;
  state.counters["nbr/step"] = static_cast<double>(last.neighbour_queries) / kSteps;
}

void BM_Octree(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(0));
  const auto capacity = static_cast<std::uint32_t>(state.range(1));
  const Scene initial = makeScene(rings);
  RunStats last;
  for (auto _ : state) {
    state.PauseTiming();
    OctreeRun run(initial, capacity);
    state.ResumeTiming();
    last = run.run();
    benchmark::DoNotOptimize(last);
  }
  setCounters(state, cubesFor(rings), last);
}

void BM_Fcl(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(0));
  const Scene initial = makeScene(rings);
  RunStats last;
  for (auto _ : state) {
    state.PauseTiming();
    FclRun run(initial);
    state.ResumeTiming();
    last = run.run();
    benchmark::DoNotOptimize(last);
  }
  setCounters(state, cubesFor(rings), last);
}

const int kRings[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 15, 20, 30, 50};
constexpr int kExhaustiveMaxRings = 20;  // 3,362 cubes; beyond that it takes seconds per run

void registerAll() {
  for (int rings : kRings) {
    const std::string set =
        "t" + std::to_string(rings) + "/cubes:" + std::to_string(cubesFor(rings));
    for (std::uint32_t n : {5u, 10u, 30u, 50u}) {
      benchmark::RegisterBenchmark(("Octree/N" + std::to_string(n) + "/" + set).c_str(), BM_Octree)
          ->Args({rings, n})
          ->Unit(benchmark::kMillisecond);
    }
    if (rings <= kExhaustiveMaxRings) {
      benchmark::RegisterBenchmark(("Exhaustive/" + set).c_str(), BM_Octree)
          ->Args({rings, kExhaustive})
          ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark(("FclDynamicAabbTree/" + set).c_str(), BM_Fcl)
        ->Args({rings})
        ->Unit(benchmark::kMillisecond);
  }
}

// --- CSV mode -------------------------------------------------------------------------------

// Thread CPU time: the build machine is shared, and wall-clock time mostly measures the load.
double threadCpuMicros() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

template <class MakeRun>
double medianMicrosPerStep(int reps, MakeRun make, RunStats* stats) {
  std::vector<double> times;
  for (int r = 0; r < reps; ++r) {
    auto run = make();
    const double t0 = threadCpuMicros();
    *stats = run.run();
    times.push_back((threadCpuMicros() - t0) / kSteps);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

int runCsv(int max_rings, int reps, int exhaustive_max_rings) {
  std::printf(
      "rings,cubes,N5_us,N10_us,N30_us,N50_us,exhaustive_us,fcl_us,N10_cand,exhaustive_cand,"
      "fcl_cand,N10_tests,N30_tests,collisions\n");
  bool consistent = true;
  for (int rings : kRings) {
    if (rings > max_rings) break;
    const Scene initial = makeScene(rings);
    std::vector<double> us;
    RunStats stats, n10_stats, n30_stats;
    std::uint64_t collisions = 0;
    auto check = [&](const RunStats& s) {
      if (collisions == 0) collisions = s.collisions;
      if (s.collisions != collisions) consistent = false;
    };
    for (std::uint32_t n : {5u, 10u, 30u, 50u}) {
      us.push_back(medianMicrosPerStep(
          reps, [&] { return OctreeRun(initial, n); }, &stats));
      check(stats);
      if (n == 10) n10_stats = stats;
      if (n == 30) n30_stats = stats;
    }
    RunStats ex_stats;
    double ex_us = NAN;
    if (rings <= exhaustive_max_rings) {
      ex_us = medianMicrosPerStep(
          reps, [&] { return OctreeRun(initial, kExhaustive); }, &ex_stats);
      check(ex_stats);
    }
    RunStats fcl_stats;
    const double fcl_us = medianMicrosPerStep(
        reps, [&] { return FclRun(initial); }, &fcl_stats);
    check(fcl_stats);
    std::printf("%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.1f,%.1f,%.1f,%.1f,%.1f,%llu\n", rings,
                cubesFor(rings), us[0], us[1], us[2], us[3], ex_us, fcl_us,
                static_cast<double>(n10_stats.candidates) / kSteps,
                static_cast<double>(ex_stats.candidates) / kSteps,
                static_cast<double>(fcl_stats.candidates) / kSteps,
                static_cast<double>(n10_stats.pair_tests) / kSteps,
                static_cast<double>(n30_stats.pair_tests) / kSteps,
                static_cast<unsigned long long>(collisions));
    std::fflush(stdout);
  }
  if (!consistent) {
    std::fprintf(stderr, "error: methods disagree on the collisions found\n");
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--csv") == 0) {
      int max_rings = 50, reps = 5, exhaustive_max_rings = 30;
      for (int j = 1; j + 1 < argc; ++j) {
        if (std::strcmp(argv[j], "--max-rings") == 0) max_rings = std::atoi(argv[j + 1]);
        if (std::strcmp(argv[j], "--reps") == 0) reps = std::max(1, std::atoi(argv[j + 1]));
        if (std::strcmp(argv[j], "--exhaustive-max-rings") == 0)
          exhaustive_max_rings = std::atoi(argv[j + 1]);
      }
      return runCsv(max_rings, reps, exhaustive_max_rings);
    }
  }
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
