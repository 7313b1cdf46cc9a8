// Self-collision broad phase: time per self check (selfInCollision, FK excluded) of the
// all-pairs loop (SelfBroadPhase::kPairs: every checked pair, bounding-sphere pre-test first)
// against the N-objects octree broad phase over the links' world boxes
// (SelfBroadPhase::kNObjectsOctree, leaf capacity N = 8 ... 64, and N = infinity: one leaf,
// i.e. the octree's SIMD all-pairs box kernel), on synthetic snake robots of
// 6 ... 100 box links (8 x 4 x 4 cm links on a 10 cm pitch, joints alternating about z and y,
// +-1 rad), 1024 uniform random states, 1 cm voxels, fused checker path. The "hit" counter is
// the fraction of states in self-collision (the all-pairs loop stops at the first contact).
// Decides kSelfBroadPhaseAutoLinks (collision_model.h); see docs/planner.md.
//
//   build/bench/planner_selfcollision_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "octomotion/broadphase/n_objects_octree.h"
#include "octomotion/planner/model/collision_model.h"
#include "snake_robot.h"

namespace {

using namespace octomotion;

constexpr double kJointLimit = 1.0;  // radians
constexpr int kStates = 1024;

using test::snakeUrdf;

// strategy: 0 = all pairs, else the octree with leaf capacity N = strategy.
void BM_SelfCheck(benchmark::State& state) {
  const int links = static_cast<int>(state.range(0));
  const auto n = static_cast<std::uint32_t>(state.range(1));
  RobotModel robot = RobotModel::fromUrdfString(snakeUrdf(links, kJointLimit), "snake.urdf", ".");
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the voxels' self half
  o.self_broad_phase = n == 0 ? SelfBroadPhase::kPairs : SelfBroadPhase::kNObjectsOctree;
  if (n) o.self_broad_phase_leaf_capacity = n;
  const OctreeCollisionModel model(robot, EnvironmentGeometry::load({}), o);
  CheckScratch scratch = model.makeScratch();
  // FK once per state up front; each iteration swaps a state's link poses into the scratch.
  std::mt19937_64 rng(2024);
  std::vector<RobotData> poses;
  for (int k = 0; k < kStates; ++k) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    RobotData d = robot.makeData();
    robot.forwardKinematics(q.data(), q.size(), d);
    poses.push_back(std::move(d));
  }
  std::size_t i = 0;
  std::int64_t hits = 0;
  for (auto _ : state) {
    std::swap(scratch.robot, poses[i]);
    const bool hit = model.selfInCollision(CheckerPath::kFused, scratch);
    std::swap(scratch.robot, poses[i]);
    hits += hit;
    benchmark::DoNotOptimize(hit);
    i = (i + 1) % poses.size();
  }
  state.counters["links"] = static_cast<double>(links);
  state.counters["pairs"] = static_cast<double>(model.report().self_pairs);
  state.counters["hit"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.SetLabel(n == 0                                        ? "all pairs"
                 : n == broadphase::NObjectsOctree::kUnlimited ? "one leaf (N = inf)"
                                                               : "octree N=" + std::to_string(n));
}

BENCHMARK(BM_SelfCheck)
    ->ArgsProduct({{6, 12, 16, 20, 24, 32, 40, 48, 64, 100}, {0, 8, 16, 64, 4294967295}})
    ->ArgNames({"links", "N"});

}  // namespace

BENCHMARK_MAIN();
