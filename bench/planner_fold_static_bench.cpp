// Folding what no joint moves (CollisionModelOptions::fold_static): time per check
// (linksInCollision, FK excluded) with and without it, on the Panda planning its panda_arm group
// with the fingers held at 0.065 m (tests/data/scenes/panda_arm_group.yaml: the base is tested
// once; needs ../shared/data/panda) and on octo7 in the bookshelf (robots/scenes/bookshelf.yaml,
// every joint planned: nothing folds, so it shows the option's own cost). 1024 uniform random
// states of the planned joints, 1 cm voxels, fused path. The "hit" counter is the fraction of
// states in collision (equal with and without folding: tests/planner/static_folding_test.cpp).
//
//   build/bench/planner_fold_static_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace {

using namespace octomotion;

constexpr int kStates = 1024;

const char* const kScenes[] = {"tests/data/scenes/panda_arm_group.yaml",
                               "robots/scenes/bookshelf.yaml"};

void BM_Check(benchmark::State& state) {
  const std::string scene = std::string(OCTOMOTION_SOURCE_DIR) + "/" + kScenes[state.range(0)];
  const bool fold = state.range(1) != 0;
  SceneOverrides overrides;
  overrides.resolution = 0.01;
  SceneInputs inputs;
  try {
    inputs = loadSceneInputs(scene, overrides, [](const std::string&) {});
  } catch (const Error& e) {
    state.SkipWithError(e.what());  // the Panda is not there
    return;
  }
  const RobotModel& robot = *inputs.robot;
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // exact refine turns folding off
  o.fold_static = fold;
  o.warnings = [](const std::string&) {};
  const OctreeCollisionModel model(robot, *inputs.environment, o);
  CheckScratch scratch = model.makeScratch();
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
    const bool hit = model.linksInCollision(CheckerPath::kFused, scratch);
    std::swap(scratch.robot, poses[i]);
    hits += hit;
    benchmark::DoNotOptimize(hit);
    i = (i + 1) % poses.size();
  }
  state.counters["static_links"] = static_cast<double>(model.report().static_links.size());
  state.counters["constant_pairs"] = static_cast<double>(model.report().constant_pairs.size());
  state.counters["hit"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.SetLabel(std::filesystem::path(kScenes[state.range(0)]).stem().string() +
                 (fold ? " folded" : " unfolded"));
}

BENCHMARK(BM_Check)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
