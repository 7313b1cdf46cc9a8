// Clearance: time per OctreeCollisionModel::clearanceLowerBound of the environment-tree method
// (ClearanceMethod::kEnvironmentTree: branch and bound over the black leaves, exact box
// distances) and the point-octree method (ClearanceMethod::kPointOctree: nearest black-leaf
// centre per leaf level). Robot: a 6-link snake (8 x 4 x 4 cm box links, 10 cm pitch), 512
// random collision-free states. Scenes: "cloud" = a point cloud (a noisy wall and a cluster,
// 20,000 points in an XYZ file) + 4 boxes; "boxes" = 24 random boxes (large black leaves).
// Counter "gap_mm": mean of (tree bound - point bound), the extra looseness of the point method.
//
//   build/bench/planner_clearance_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "octomotion/planner/model/collision_model.h"
#include "snake_robot.h"

namespace {

using namespace octomotion;

using test::snakeUrdf;

std::vector<EnvironmentObject> scene(bool cloud) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<EnvironmentObject> objects;
  if (cloud) {
    const std::string path = "/tmp/octomotion_clearance_bench_cloud.xyz";
    std::ofstream out(path);
    for (int i = 0; i < 16000; ++i) {
      out << 0.55 + 0.01 * u(rng) << " " << 0.5 * u(rng) << " " << 0.4 * u(rng) << "\n";
    }
    for (int i = 0; i < 4000; ++i) {
      out << 0.2 + 0.08 * u(rng) << " " << 0.08 * u(rng) << " " << 0.35 + 0.05 * u(rng) << "\n";
    }
    EnvironmentObject o;
    o.name = "cloud";
    o.kind = EnvironmentObject::Kind::kPointCloud;
    o.file = path;
    objects.push_back(o);
  }
  const int boxes = cloud ? 4 : 24;
  for (int i = 0; i < boxes; ++i) {
    EnvironmentObject box;
    box.name = "box" + std::to_string(i);
    box.primitive =
        Box{Eigen::Vector3d(0.03 + 0.05 * std::abs(u(rng)), 0.03 + 0.05 * std::abs(u(rng)), 0.05)};
    // Boxes around the robot, not on its base.
    Eigen::Vector3d p(u(rng), u(rng), 0.5 * u(rng));
    p.head<2>() = p.head<2>().normalized() * (0.3 + 0.3 * std::abs(u(rng)));
    box.X_WO.translation() = p;
    objects.push_back(box);
  }
  return objects;
}

void BM_Clearance(benchmark::State& state) {
  const bool cloud = state.range(0) == 0;
  const auto method =
      state.range(1) == 0 ? ClearanceMethod::kEnvironmentTree : ClearanceMethod::kPointOctree;
  const RobotModel robot = RobotModel::fromUrdfString(snakeUrdf(6, 1.5), "snake.urdf", ".");
  const EnvironmentGeometry env = EnvironmentGeometry::load(scene(cloud));
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the octree's own bound
  o.clearance = method;
  const OctreeCollisionModel model(robot, env, o);
  // Free states, FK done up front; each iteration swaps one into the scratch.
  CheckScratch scratch = model.makeScratch();
  std::mt19937_64 rng(7);
  std::vector<RobotData> poses;
  double gap = 0;
  while (poses.size() < 512) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    if (model.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(), CheckerPath::kFused,
                          scratch)) {
      continue;
    }
    gap += model.clearanceLowerBoundTree(scratch) - model.clearanceLowerBoundPoints(scratch);
    poses.push_back(scratch.robot);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    std::swap(scratch.robot, poses[i]);
    benchmark::DoNotOptimize(model.clearanceLowerBound(scratch));
    std::swap(scratch.robot, poses[i]);
    i = (i + 1) % poses.size();
  }
  state.counters["env_leaves"] = static_cast<double>(model.environment().blackLeafCount());
  state.counters["gap_mm"] = 1000 * gap / static_cast<double>(poses.size());
  state.SetLabel(std::string(cloud ? "cloud" : "boxes") +
                 (method == ClearanceMethod::kPointOctree ? " point octree" : " environment tree"));
}

BENCHMARK(BM_Clearance)->ArgsProduct({{0, 1}, {0, 1}})->ArgNames({"boxes", "points"});

}  // namespace

BENCHMARK_MAIN();
