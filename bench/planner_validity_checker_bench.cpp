// The OMPL checker's isValid as a planner calls it, per scene and checker: the scene's own
// checker (loadPlanningScene) on 1024 uniform states from a fixed seed (joint limits; SE(3):
// position bounds, uniform orientation), one state per iteration. Bounds check, state
// conversion, thread scratch and the collision check are all in the time.
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"

namespace {

using namespace octomotion;
namespace ob = ompl::base;

const char* const kScenes[] = {"bookshelf", "cage", "rooms"};
const CheckerKind kCheckers[] = {CheckerKind::kOctreeFused, CheckerKind::kOctree, CheckerKind::kFcl,
                                 CheckerKind::kFclOctomap};

void BM_IsValid(benchmark::State& state) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string scene_name = kScenes[state.range(0)];
  SceneOverrides overrides;
  overrides.checker = kCheckers[state.range(1)];
  overrides.require_free_start_goal = false;  // uniform states, not the problem
  const PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + scene_name + ".yaml", overrides);
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const RobotModel& robot = scene.model->robot();
  // Not OMPL's sampler: its seed is fixed once per process, and every benchmark must see the
  // same states whatever ran before it.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ob::State*> states(1024);
  for (ob::State*& s : states) {
    std::vector<double> q;
    for (const Variable& v : robot.variables())
      q.push_back(v.lower + (v.upper - v.lower) * unit(rng));
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    if (robot.isFreeFlying()) {
      const Eigen::AlignedBox3d& bounds = *scene.spec.problem.bounds;
      const Eigen::Vector3d u(unit(rng), unit(rng), unit(rng));
      X_WB.translation() = bounds.min() + bounds.sizes().cwiseProduct(u);
      const double a = unit(rng), b = 2 * M_PI * unit(rng), c = 2 * M_PI * unit(rng);
      X_WB.linear() = Eigen::Quaterniond(std::sqrt(a) * std::cos(c), std::sqrt(1 - a) * std::sin(b),
                                         std::sqrt(1 - a) * std::cos(b), std::sqrt(a) * std::sin(c))
                          .normalized()
                          .toRotationMatrix();
    }
    s = si->allocState();
    configurationToState(robot, q, X_WB, s);
  }
  const ob::StateValidityChecker& checker = *si->getStateValidityChecker();
  std::size_t i = 0, valid = 0;
  for (auto _ : state) {
    valid += checker.isValid(states[i]);
    i = (i + 1) % states.size();
  }
  benchmark::DoNotOptimize(valid);
  state.SetLabel(scene_name + " " + checkerKindName(kCheckers[state.range(1)]));
  for (ob::State* s : states) si->freeState(s);
}
BENCHMARK(BM_IsValid)
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2, 3}})
    ->ArgNames({"scene", "checker"})
    ->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
