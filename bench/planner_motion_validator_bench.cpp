// Motion validators on the Panda MotionBenchMaker problems (../shared/data/mbm_panda, the first
// problem of each of the 7 sets, each read straight from its MoveIt scene and request with the
// Panda of ../shared/data/panda): the certified validator against OMPL's discrete one at the
// step boundMotionStep sets, over the octree (fused) checker at the defaults (exact refine) and
// with the voxels alone (refine none), and exact FCL. Each benchmark checks
// the same edges (per problem, 40 from a valid state toward a uniform one, at most RRTConnect's
// default range of 0.2 x the space's extent, ending valid) in each iteration; edges per second
// are `items_per_second`, and
// `checks_per_edge` counts state checks that test the environment (the certified validator's
// self-pair-only checks in `self_checks_per_edge`), `accepted` the share of edges found free.
// The certified validator remembers the last valid ends it checked (64 per thread): across
// iterations some of these edges' ends are remembered, as a planner's tree nodes are.
//
//   build/bench/planner_motion_validator_bench --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>

#include "mbm_problems.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"

namespace {

using namespace octomotion;
namespace ob = ompl::base;

// Counts the checks the discrete validator makes through si->isValid.
class CountingChecker : public ob::StateValidityChecker {
 public:
  CountingChecker(const ob::SpaceInformationPtr& si, ob::StateValidityCheckerPtr inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* s) const override {
    checks.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(s);
  }
  mutable std::atomic<std::size_t> checks{0};

 private:
  ob::StateValidityCheckerPtr inner_;
};

struct Edge {
  std::shared_ptr<ob::ScopedState<>> s1, s2;
};

struct Problem {
  std::shared_ptr<PlanningScene> scene;
  std::vector<Edge> edges;
};

// One scene per problem and checker: the validators are swapped on its SpaceInformation.
std::vector<Problem> loadProblems(const test::MbmProblems& set, CheckerKind checker,
                                  RefineMode refine) {
  std::vector<Problem> out;
  const std::string panda = test::MbmProblems::panda();
  std::mt19937_64 rng(1);
  for (const test::MbmProblem& p : set.firstOfEachSet()) {
    const std::string path = set.folder() + "/" + p.set + "_bench.yaml";
    test::MbmProblems::writeScene(path, p, ", seed: 1");
    SceneOverrides overrides;
    overrides.checker = checker;
    overrides.refine = refine;
    Problem problem;
    problem.scene = std::make_shared<PlanningScene>(
        loadPlanningScene(path, overrides, [](const std::string&) {}));
    const ob::SpaceInformationPtr& si = problem.scene->setup->getSpaceInformation();
    problem.scene->setup->setup();
    const RobotModel& robot = problem.scene->model->robot();
    const double range = 0.2 * si->getMaximumExtent();
    auto uniform = [&](ob::State* s) {
      std::vector<double> q;
      for (const Variable& v : robot.variables()) {
        q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
      }
      configurationToState(robot, q, Eigen::Isometry3d::Identity(), s);
    };
    while (problem.edges.size() < 40) {
      Edge e{std::make_shared<ob::ScopedState<>>(si), std::make_shared<ob::ScopedState<>>(si)};
      uniform(e.s1->get());
      if (!si->isValid(e.s1->get())) continue;
      uniform(e.s2->get());
      const double d = si->distance(e.s1->get(), e.s2->get());
      if (d > range)
        si->getStateSpace()->interpolate(e.s1->get(), e.s2->get(), range / d, e.s2->get());
      if (!si->isValid(e.s2->get())) continue;
      problem.edges.push_back(e);
    }
    out.push_back(std::move(problem));
  }
  return out;
}

// Per checker, built once: the problems, the counting checker on each and both validators.
struct Setup {
  std::vector<Problem> problems;
  std::vector<std::shared_ptr<CountingChecker>> counters;
  std::vector<std::shared_ptr<CertifiedMotionValidator>> certified;
  std::vector<std::shared_ptr<ob::DiscreteMotionValidator>> discrete;
};

const Setup& setupFor(const test::MbmProblems& set, CheckerKind checker, RefineMode refine) {
  static std::map<std::pair<CheckerKind, RefineMode>, Setup> setups;
  auto it = setups.find({checker, refine});
  if (it != setups.end()) return it->second;
  Setup s;
  s.problems = loadProblems(set, checker, refine);
  for (Problem& p : s.problems) {
    const ob::SpaceInformationPtr& si = p.scene->setup->getSpaceInformation();
    const std::shared_ptr<const CollisionBackend> backend = checkerBackend(*p.scene);
    auto counting = std::make_shared<CountingChecker>(si, si->getStateValidityChecker());
    si->setStateValidityChecker(counting);
    s.counters.push_back(counting);
    s.certified.push_back(std::make_shared<CertifiedMotionValidator>(
        si, backend,
        makeLinkMotionBound(backend->robot(), p.scene->spec.robot.keep_mesh_root_transform,
                            p.scene->spec.robot.center_mesh_vertices),
        *p.scene->spec.octree.resolution));
    s.discrete.push_back(std::make_shared<ob::DiscreteMotionValidator>(si));
  }
  return setups.emplace(std::make_pair(checker, refine), std::move(s)).first->second;
}

void run(benchmark::State& state, CheckerKind checker, MotionValidatorKind kind,
         RefineMode refine = RefineMode::kAuto) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  static const test::MbmProblems set;
  if (set.problems().empty() ||
      !std::filesystem::exists(test::MbmProblems::panda() + "/panda.urdf")) {
    state.SkipWithError("no MotionBenchMaker problems or Panda under ../shared/data");
    return;
  }
  const Setup& s = setupFor(set, checker, refine);
  for (std::size_t i = 0; i < s.problems.size(); ++i) {
    s.counters[i]->checks = 0;
    s.certified[i]->resetCounts();
  }
  auto validator = [&](std::size_t i) -> const ob::MotionValidator& {
    if (kind == MotionValidatorKind::kDiscrete) return *s.discrete[i];
    return *s.certified[i];
  };
  std::size_t edges = 0, accepted = 0;
  for (auto _ : state) {
    // Every edge of every problem, so that each row checks the same edges.
    for (std::size_t p = 0; p < s.problems.size(); ++p) {
      for (const Edge& edge : s.problems[p].edges) {
        const bool free = validator(p).checkMotion(edge.s1->get(), edge.s2->get());
        benchmark::DoNotOptimize(free);
        accepted += free ? 1 : 0;
        ++edges;
      }
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(edges));
  std::size_t checks = 0, self_checks = 0;
  for (std::size_t i = 0; i < s.problems.size(); ++i) {
    if (kind == MotionValidatorKind::kDiscrete) {
      checks += s.counters[i]->checks.load();
    } else {
      checks += s.certified[i]->stateChecks();
      self_checks += s.certified[i]->selfChecks();
    }
  }
  const double n = edges ? static_cast<double>(edges) : 1.0;
  state.counters["checks_per_edge"] = static_cast<double>(checks) / n;
  state.counters["self_checks_per_edge"] = static_cast<double>(self_checks) / n;
  state.counters["accepted"] = static_cast<double>(accepted) / n;
}

BENCHMARK_CAPTURE(run, octree_certified, CheckerKind::kOctreeFused, MotionValidatorKind::kCertified)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(run, octree_discrete, CheckerKind::kOctreeFused, MotionValidatorKind::kDiscrete)
    ->Unit(benchmark::kMicrosecond);
// The voxels alone (refine none), whose answers the validator decides at a voxel of travel.
BENCHMARK_CAPTURE(run, octree_none_certified, CheckerKind::kOctreeFused,
                  MotionValidatorKind::kCertified, RefineMode::kNone)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(run, fcl_certified, CheckerKind::kFcl, MotionValidatorKind::kCertified)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(run, fcl_discrete, CheckerKind::kFcl, MotionValidatorKind::kDiscrete)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
