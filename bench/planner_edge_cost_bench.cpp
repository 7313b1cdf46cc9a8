// Where a certified motion check's time goes while planning: the Panda MotionBenchMaker problems
// (../shared/data/mbm_panda, the first `kPerSet` problems of each of the 7 sets, each read
// straight from its MoveIt scene and request with the Panda of ../shared/data/panda) planned
// once each by the scene's defaults (RRTConnect, 1 s, seed 1), with the octree (fused) checker
// at the defaults (exact refine) and with exact FCL, with the certified validator's collision
// screen (CertifiedMotionValidator::kScreenLevels), without it (`noscreen`) and with 2 and 4
// levels. The counters,
// per plan, split the motion checks into accepted and rejected edges
// (CertifiedMotionValidator::Counts): how many, milliseconds per edge, screen and proof state
// checks per edge, states whose clearances were measured, exact pair distances, the deepest
// bisection level and the edge's bound (metres of travel), self pairs the pair table proved
// over the whole edge (`table`); `rejected_by_screen` is the share of
// rejected edges the screen rejected, `solved` the share of problems solved, and `plan_ms` the
// median planning time.
// BM_GridClearance times one of a clearance state's parts alone: the per-link grid bound
// (OctreeCollisionModel::clearanceLowerBoundGridPerLink) at 256 random collision-free states of
// the first problem of each set, every link asked for a clearance of `cap_cm` (100: as at an
// edge's ends, where the whole edge's bound is asked; 10: deep in a bisection).
//
//   build/bench/planner_edge_cost_bench --benchmark_filter=octree   (one command line)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>

#include "mbm_problems.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace {

using namespace octomotion;
namespace ob = ompl::base;

constexpr std::size_t kPerSet = 3;

std::vector<test::MbmProblem> chosen(const test::MbmProblems& set) {
  std::vector<test::MbmProblem> out;
  std::map<std::string, std::size_t> per_set;
  for (const test::MbmProblem& p : set.problems()) {
    if (per_set[p.set]++ < kPerSet) out.push_back(p);
  }
  return out;
}

// The problems, extracted once; null (the state skipped with an error) without ../shared/data.
const test::MbmProblems* problems(benchmark::State& state) {
  static const test::MbmProblems set;
  if (set.problems().empty() ||
      !std::filesystem::exists(test::MbmProblems::panda() + "/panda.urdf")) {
    state.SkipWithError("no MotionBenchMaker problems or Panda under ../shared/data");
    return nullptr;
  }
  return &set;
}

void run(benchmark::State& state, CheckerKind checker, int screen_levels) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const test::MbmProblems* problem_set = problems(state);
  if (!problem_set) return;
  const test::MbmProblems& set = *problem_set;
  const std::string panda = test::MbmProblems::panda();
  CertifiedMotionValidator::Counts total;
  std::size_t plans = 0, solved = 0;
  std::vector<double> times;
  for (auto _ : state) {
    for (const test::MbmProblem& p : chosen(set)) {
      const std::string path = set.folder() + "/" + p.set + "_" +
                               std::filesystem::path(p.request).stem().string() + "_edge_cost.yaml";
      test::MbmProblems::writeScene(path, p, ", seed: 1, time: 1");
      SceneOverrides overrides;
      overrides.checker = checker;
      PlanningScene scene = loadPlanningScene(path, overrides, [](const std::string&) {});
      const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
      scene.setup->setup();
      auto validator =
          std::dynamic_pointer_cast<CertifiedMotionValidator>(si->getMotionValidator());
      if (!validator) {
        state.SkipWithError("the scene's motion validator is not the certified one");
        return;
      }
      validator->setScreenLevels(screen_levels);
      validator->resetCounts();
      const ob::PlannerStatus status =
          scene.setup->solve(ob::timedPlannerTerminationCondition(scene.spec.problem.time));
      ++plans;
      solved += status == ob::PlannerStatus::EXACT_SOLUTION ? 1 : 0;
      times.push_back(scene.setup->getLastPlanComputationTime());
      const CertifiedMotionValidator::Counts c = validator->counts();
      for (auto [sum, add] :
           {std::pair{&total.accepted, &c.accepted}, std::pair{&total.rejected, &c.rejected}}) {
        sum->edges += add->edges;
        sum->screen_checks += add->screen_checks;
        sum->proof_checks += add->proof_checks;
        sum->clearance_states += add->clearance_states;
        sum->pair_distances += add->pair_distances;
        sum->table_pairs += add->table_pairs;
        sum->depth += add->depth;
        sum->travel += add->travel;
        sum->seconds += add->seconds;
      }
      total.rejected_by_screen += c.rejected_by_screen;
      total.remembered_ends += c.remembered_ends;
    }
  }
  const double n = plans ? static_cast<double>(plans) : 1.0;
  std::sort(times.begin(), times.end());
  state.counters["solved"] = static_cast<double>(solved) / n;
  state.counters["plan_ms"] = times.empty() ? 0.0 : 1e3 * times[times.size() / 2];
  for (auto [name, e] : {std::pair{std::string("acc_"), &total.accepted},
                         std::pair{std::string("rej_"), &total.rejected}}) {
    const double edges = e->edges ? static_cast<double>(e->edges) : 1.0;
    state.counters[name + "per_plan"] = static_cast<double>(e->edges) / n;
    state.counters[name + "ms"] = 1e3 * e->seconds / edges;
    state.counters[name + "screen"] = static_cast<double>(e->screen_checks) / edges;
    state.counters[name + "proof"] = static_cast<double>(e->proof_checks) / edges;
    state.counters[name + "clear"] = static_cast<double>(e->clearance_states) / edges;
    state.counters[name + "pairs"] = static_cast<double>(e->pair_distances) / edges;
    state.counters[name + "table"] = static_cast<double>(e->table_pairs) / edges;
    state.counters[name + "depth"] = static_cast<double>(e->depth) / edges;
    state.counters[name + "travel_m"] = e->travel / edges;
  }
  state.counters["rejected_by_screen"] =
      static_cast<double>(total.rejected_by_screen) /
      (total.rejected.edges ? static_cast<double>(total.rejected.edges) : 1.0);
  state.counters["remembered_per_edge"] =
      static_cast<double>(total.remembered_ends) /
      std::max(1.0, static_cast<double>(total.accepted.edges + total.rejected.edges));
}

constexpr int kDefault = CertifiedMotionValidator::kScreenLevels;
BENCHMARK_CAPTURE(run, octree, CheckerKind::kOctreeFused, kDefault)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, octree_noscreen, CheckerKind::kOctreeFused, 0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
// The screen's depth (kScreenLevels): shallower and deeper.
BENCHMARK_CAPTURE(run, octree_screen2, CheckerKind::kOctreeFused, 2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, octree_screen4, CheckerKind::kOctreeFused, 4)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, fcl, CheckerKind::kFcl, kDefault)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, fcl_noscreen, CheckerKind::kFcl, 0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_GridClearance(benchmark::State& state) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const test::MbmProblems* problem_set = problems(state);
  if (!problem_set) return;
  const test::MbmProblems& set = *problem_set;
  struct Posed {
    std::shared_ptr<const OctreeCollisionModel> model;
    std::vector<RobotData> poses;
  };
  std::vector<Posed> scenes;
  std::map<std::string, bool> seen;
  std::mt19937_64 rng(11);
  for (const test::MbmProblem& p : set.problems()) {
    if (seen[p.set]) continue;
    seen[p.set] = true;
    const std::string path = set.folder() + "/" + p.set + "_grid_clearance.yaml";
    test::MbmProblems::writeScene(path, p);
    const PlanningScene scene = loadPlanningScene(path, {}, [](const std::string&) {});
    Posed posed{scene.model, {}};
    const RobotModel& robot = scene.model->robot();
    CheckScratch scratch = scene.model->makeScratch();
    std::vector<double> q;
    while (posed.poses.size() < 256) {
      q.clear();
      for (const Variable& v : robot.variables()) {
        q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
      }
      if (!scene.model->inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(),
                                    CheckerPath::kFused, scratch)) {
        posed.poses.push_back(scratch.robot);
      }
    }
    scenes.push_back(std::move(posed));
  }
  // The links the validator asks about: those a joint moves.
  const RobotModel& robot = scenes.front().model->robot();
  const std::size_t links = static_cast<std::size_t>(robot.linkCount());
  const auto bound = makeLinkMotionBound(robot, false, false);
  std::vector<double> caps(links, 0.0);
  for (int l : bound->geometryLinks()) {
    for (int v = 0; v < robot.variableCount(); ++v) {
      if (bound->lever(l, v) > 0) caps[static_cast<std::size_t>(l)] = 0.01 * state.range(0);
    }
  }
  std::vector<double> per_link(links);
  std::vector<CheckScratch> scratches;
  for (const Posed& s : scenes) scratches.push_back(s.model->makeScratch());
  std::size_t calls = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      for (RobotData& pose : scenes[k].poses) {
        std::swap(scratches[k].robot, pose);
        scenes[k].model->clearanceLowerBoundGridPerLink(scratches[k], caps.data(), 0.0,
                                                        per_link.data());
        benchmark::DoNotOptimize(per_link.data());
        std::swap(scratches[k].robot, pose);
        ++calls;
      }
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(calls));  // states per second
}
BENCHMARK(BM_GridClearance)->Arg(100)->Arg(10)->ArgName("cap_cm")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
