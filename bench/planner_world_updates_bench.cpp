// A world that changes between plans: the cost of one update of the octree model (add a box, move
// a box, remove a box; attach and detach a box) against building the whole model again, the
// Panda (../shared/data/panda) at 1 cm in a MotionBenchMaker-like table scene (a table, a shelf
// with two boards, a can, a crate), the universe fitted to the reach
// (CollisionModelOptions::fit_universe_to_reach). Each update benchmark reports
// `share_of_rebuild`: its mean time over the mean time of BM_FullRebuild's model construction
// (the target is <= 0.05).
//
//   build/bench/planner_world_updates_bench [--panda DIR] --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

std::string panda_dir = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

EnvironmentObject box(const std::string& name, Eigen::Vector3d size, Eigen::Vector3d xyz,
                      double yaw = 0) {
  EnvironmentObject o;
  o.name = name;
  o.primitive = Box{size / 2};
  o.X_WO.translation() = xyz;
  o.X_WO.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return o;
}

std::vector<EnvironmentObject> tableScene() {
  EnvironmentObject can;
  can.name = "can";
  can.primitive = Cylinder{0.04, 0.15};
  can.X_WO.translation() = Eigen::Vector3d(0.45, -0.3, 0.4);
  return {box("table", {0.8, 1.2, 0.04}, {0.6, 0, 0.3}),
          box("shelf_back", {0.02, 0.8, 0.8}, {0.95, 0, 0.7}),
          box("shelf_low", {0.3, 0.8, 0.02}, {0.8, 0, 0.6}),
          box("shelf_high", {0.3, 0.8, 0.02}, {0.8, 0, 0.9}),
          can,
          box("crate", {0.15, 0.2, 0.12}, {0.4, 0.35, 0.38}, 0.4)};
}

CollisionModelOptions options() {
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.fit_universe_to_reach = true;
  return o;
}

RobotModel panda() {
  RobotModel robot = RobotModel::fromUrdfFile(panda_dir + "/panda.urdf");
  robot.loadSrdfFile(panda_dir + "/panda.srdf");
  return robot;
}

bool havePanda(benchmark::State& state) {
  if (std::filesystem::exists(panda_dir + "/panda.urdf")) return true;
  state.SkipWithError(("no Panda in " + panda_dir + " (--panda DIR)").c_str());
  return false;
}

struct World {
  RobotModel robot = panda();
  EnvironmentGeometry objects = EnvironmentGeometry::load(tableScene());
};

World& world() {
  static World w;
  return w;
}

// Mean seconds of one model construction, measured once (3 builds) for the ratios.
double rebuildSeconds() {
  static const double seconds = [] {
    const auto t0 = Clock::now();
    for (int i = 0; i < 3; ++i) {
      const OctreeCollisionModel model(world().robot, world().objects, options());
      benchmark::DoNotOptimize(model.id());
    }
    return std::chrono::duration<double>(Clock::now() - t0).count() / 3;
  }();
  return seconds;
}

void BM_FullRebuild(benchmark::State& state) {
  if (!havePanda(state)) return;
  for (auto _ : state) {
    const OctreeCollisionModel model(world().robot, world().objects, options());
    benchmark::DoNotOptimize(model.id());
  }
}

// Times `update` alone (the undo runs with the timer paused) and reports its share of a rebuild.
template <class Update, class Undo>
void timeUpdate(benchmark::State& state, Update&& update, Undo&& undo) {
  if (!havePanda(state)) return;
  const double rebuild = rebuildSeconds();
  OctreeCollisionModel model(world().robot, world().objects, options());
  double total = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    update(model);
    total += std::chrono::duration<double>(Clock::now() - t0).count();
    state.PauseTiming();
    undo(model);
    state.ResumeTiming();
  }
  state.counters["share_of_rebuild"] = total / static_cast<double>(state.iterations()) / rebuild;
}

const EnvironmentObject kBox = box("box", {0.1, 0.1, 0.1}, {0.5, -0.2, 0.6}, 0.3);

void BM_AddBox(benchmark::State& state) {
  timeUpdate(
      state, [](OctreeCollisionModel& m) { m.addObject(kBox); },
      [](OctreeCollisionModel& m) { m.removeObject("box"); });
}

void BM_RemoveBox(benchmark::State& state) {
  timeUpdate(
      state, [](OctreeCollisionModel& m) { m.removeObject("crate"); },
      [](OctreeCollisionModel& m) { m.addObject(world().objects.items()[5].spec); });
}

void BM_MoveBox(benchmark::State& state) {
  Eigen::Isometry3d there = Eigen::Isometry3d::Identity();
  there.translation() = Eigen::Vector3d(0.3, -0.4, 0.45);
  const Eigen::Isometry3d back = world().objects.items()[5].spec.X_WO;
  timeUpdate(
      state, [&](OctreeCollisionModel& m) { m.moveObject("crate", there); },
      [&](OctreeCollisionModel& m) { m.moveObject("crate", back); });
}

void BM_AttachBox(benchmark::State& state) {
  AttachedObject held;
  held.object = box("held", {0.04, 0.06, 0.04}, {0, 0, 0.07});
  held.link = "panda_hand";
  held.touch_links = {"panda_leftfinger", "panda_rightfinger"};
  timeUpdate(
      state, [&](OctreeCollisionModel& m) { m.attachObject(held); },
      [](OctreeCollisionModel& m) { m.detachObject("held"); });
}

BENCHMARK(BM_FullRebuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AddBox)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MoveBox)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RemoveBox)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AttachBox)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--panda") == 0) {
      panda_dir = argv[i + 1];
      for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
