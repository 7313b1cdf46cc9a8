// What a certified distance lower bound from convex hulls costs next to FCL's exact distance
// (docs/validation.md §7, "Exact distances from hulls"), on the real Panda's checked self pairs
// at the same 256 uniform joint states (fixed seed): convexDistanceBelow on the two links' hulls
// of their mesh vertices, uncapped (GJK to convergence) and capped at 1 cm (what the certified
// validator asks near contact), and FclCollisionModel::linkPairDistance on the meshes. Each
// includes posing the robot once per state (FK), spread over that state's pairs. Needs
// ../shared/data/panda (the benchmarks report an error without it).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "octomotion/motion/convex_gap.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace {

using namespace octomotion;

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

struct PandaPairs {
  RobotModel robot;
  std::vector<ConvexPoints> hulls_L;  // per link, its mesh vertices in L
  std::vector<std::pair<int, int>> pairs;
  std::vector<std::vector<double>> states;

  PandaPairs() : robot(RobotModel::fromUrdfFile(kPanda + "/panda.urdf")) {
    robot.loadSrdfFile(kPanda + "/panda.srdf");
    CollisionMeshes meshes(false, false);
    hulls_L.resize(static_cast<std::size_t>(robot.linkCount()));
    for (int l = 0; l < robot.linkCount(); ++l) {
      std::vector<Eigen::Vector3d> points_L;
      for (const CollisionElement& e : robot.link(l).collision) {
        const TriangleMesh& mesh = meshes.get(std::get<MeshRef>(e.geometry));
        for (const Eigen::Vector3d& v : mesh.vertices) points_L.push_back(e.X_LE * v);
      }
      if (!points_L.empty()) hulls_L[static_cast<std::size_t>(l)] = ConvexPoints(points_L);
    }
    for (const auto& [a, b] : robot.checkedPairs()) {
      if (!hulls_L[static_cast<std::size_t>(a)].empty() &&
          !hulls_L[static_cast<std::size_t>(b)].empty()) {
        pairs.emplace_back(a, b);
      }
    }
    std::mt19937_64 rng(29);
    for (int s = 0; s < 256; ++s) {
      std::vector<double> q;
      for (const Variable& v : robot.variables()) {
        q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
      }
      states.push_back(std::move(q));
    }
  }
};

const PandaPairs* panda(benchmark::State& state) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) {
    state.SkipWithError("no Panda under ../shared/data");
    return nullptr;
  }
  static const PandaPairs data;
  return &data;
}

void BM_HullPairDistance(benchmark::State& state) {
  const PandaPairs* p = panda(state);
  if (p == nullptr) return;
  const double cap = state.range(0) == 0 ? std::numeric_limits<double>::infinity() : 0.01;  // 1 cm
  RobotData data = p->robot.makeData();
  std::size_t s = 0, k = 0;
  p->robot.forwardKinematics(p->states[0].data(), p->states[0].size(), data,
                             Eigen::Isometry3d::Identity());
  for (auto _ : state) {
    if (++k == p->pairs.size()) {
      k = 0;
      s = (s + 1) % p->states.size();
      p->robot.forwardKinematics(p->states[s].data(), p->states[s].size(), data,
                                 Eigen::Isometry3d::Identity());
    }
    const auto [a, b] = p->pairs[k];
    const Eigen::Isometry3d X_AB = data.linkPose(a).inverse() * data.linkPose(b);
    benchmark::DoNotOptimize(convexDistanceBelow(p->hulls_L[static_cast<std::size_t>(a)],
                                                 p->hulls_L[static_cast<std::size_t>(b)], X_AB,
                                                 cap));
  }
}
BENCHMARK(BM_HullPairDistance)->Arg(0)->Arg(1)->ArgName("capped");

void BM_FclPairDistance(benchmark::State& state) {
  const PandaPairs* p = panda(state);
  if (p == nullptr) return;
  const FclCollisionModel fcl(p->robot, EnvironmentGeometry::load({}));
  const auto scratch = fcl.makeBackendScratch();
  const double inf = std::numeric_limits<double>::infinity();
  std::size_t s = 0, k = 0;
  fcl.environmentInCollision(p->states[0].data(), p->states[0].size(),
                             Eigen::Isometry3d::Identity(), *scratch);
  for (auto _ : state) {
    if (++k == p->pairs.size()) {
      k = 0;
      s = (s + 1) % p->states.size();
      fcl.environmentInCollision(p->states[s].data(), p->states[s].size(),
                                 Eigen::Isometry3d::Identity(), *scratch);
    }
    const auto [a, b] = p->pairs[k];
    benchmark::DoNotOptimize(fcl.linkPairDistance(*scratch, a, b, inf));
  }
}
BENCHMARK(BM_FclPairDistance);

}  // namespace

BENCHMARK_MAIN();
