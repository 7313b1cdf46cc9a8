// Where a planner's time goes, per checker (docs/trade-off.md, "Reading the results"): the scene's
// problem is solved RUNS times with the fused octree checker and with FCL, and each solve is
// split into the time spent in the state validity checker and the rest (sampling,
// nearest-neighbour queries, interpolation, the motion validator's bookkeeping). Then what
// ompl::tools::Benchmark adds to every run's "time REAL" is measured with a planner that spins
// for each checker's solve times in turn: Benchmark solves through Planner::solve(fn, 0.1), whose
// termination condition is evaluated by a thread that sleeps in 1 ms steps and is joined when
// the solve returns. The solves here use a thread-free condition. A plain program (like
// planner_check_breakdown_bench): per-solve wall times with steady_clock; each check is timed
// by a wrapper whose own clock reads (calibrated, subtracted) are the only overhead.
// Usage:
//   build/bench/planner_plan_split_bench SCENE RESOLUTION [RUNS] [PLANNER] [ROUNDING]
//   e.g. robots/scenes/bookshelf.yaml 0.01 200 RRTConnect center
// (the motion step is bound at RESOLUTION, so plan at the scene's own resolution to compare
// with the trade study, which keeps the scene's step at every setting).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace {

using namespace octomotion;
namespace ob = ompl::base;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Counts and times every check of the checker it wraps. Single-threaded use only (the planners
// measured here are).
class TimedChecker : public ob::StateValidityChecker {
 public:
  TimedChecker(const ob::SpaceInformationPtr& si, ob::StateValidityCheckerPtr inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* state) const override {
    const auto t0 = Clock::now();
    const bool valid = inner_->isValid(state);
    seconds_ += seconds(t0, Clock::now());
    ++checks_;
    return valid;
  }
  void reset() {
    checks_ = 0;
    seconds_ = 0;
  }
  long checks() const { return checks_; }
  double checkSeconds() const { return seconds_; }

 private:
  ob::StateValidityCheckerPtr inner_;
  mutable long checks_ = 0;
  mutable double seconds_ = 0;
};

// A planner that spins and gives up, run r for durations[r % n]: Benchmark's time of its runs
// minus the spin is what Benchmark adds to every run. (A planner that returned at once would hide
// most of it: the termination-condition thread would be joined before its first 1 ms sleep.)
class SpinFor : public ob::Planner {
 public:
  SpinFor(const ob::SpaceInformationPtr& si, std::vector<double> durations)
      : ob::Planner(si, "SpinFor"), durations_(std::move(durations)) {}
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    const double spin = durations_[next_++ % durations_.size()];
    const auto start = Clock::now();
    while (seconds(start, Clock::now()) < spin && !ptc()) {
    }
    return ob::PlannerStatus::TIMEOUT;
  }

 private:
  std::vector<double> durations_;
  std::size_t next_ = 0;
};

// The cost of the two clock reads around each check (subtracted from the check time).
double clockPairSeconds() {
  constexpr int kPairs = 200000;
  const auto t0 = Clock::now();
  for (int i = 0; i < kPairs; ++i) {
    Clock::now();
    Clock::now();
  }
  return seconds(t0, Clock::now()) / kPairs;
}

struct Split {
  int solved = 0;
  std::vector<double> solve, checks, check_s, rest;
  double benchmark_added = 0;  // what Benchmark's "time REAL" adds to runs of these lengths
};

// What Benchmark's "time REAL" adds to runs that spin for the given solve times (the join waits
// out the thread's current 1 ms sleep, so it depends on each run's length): the median over as
// many runs as there are times. Runs on the scene's own set-up (the planner never checks).
double benchmarkAddedTime(ompl::geometric::SimpleSetup& ss, const std::vector<double>& solves) {
  ompl::tools::Benchmark benchmark(ss, "added time");
  benchmark.addPlanner(std::make_shared<SpinFor>(ss.getSpaceInformation(), solves));
  const ompl::tools::Benchmark::Request request(
      1.0 + *std::max_element(solves.begin(), solves.end()), 4096.0,
      static_cast<unsigned>(solves.size()), 0.05, /*displayProgress=*/false,
      /*saveConsoleOutput=*/false, /*simplify=*/false);
  benchmark.benchmark(request);
  std::vector<double> extra;
  const auto& runs = benchmark.getRecordedExperimentData().planners.front().runs;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const auto it = runs[r].find("time REAL");
    if (it != runs[r].end()) extra.push_back(std::atof(it->second.c_str()) - solves[r]);
  }
  return median(extra);
}

Split measure(const std::string& scene_path, double resolution, Rounding rounding,
              CheckerKind checker, const std::string& planner_name, int runs, double clock_pair) {
  SceneOverrides overrides;
  overrides.resolution = resolution;
  overrides.rounding = rounding;
  overrides.checker = checker;
  PlanningScene scene = loadPlanningScene(scene_path, overrides);
  if (!scene.spec.problem.start || !scene.spec.problem.goal) {
    throw InvalidArgument(scene_path + ": the scene has no start and goal");
  }
  ompl::geometric::SimpleSetup& ss = *scene.setup;
  const ob::SpaceInformationPtr si = ss.getSpaceInformation();
  auto timed = std::make_shared<TimedChecker>(si, si->getStateValidityChecker());
  ss.setStateValidityChecker(timed);
  ss.setup();
  const ob::PlannerPtr planner = makePlanner(planner_name, si);
  planner->setProblemDefinition(ss.getProblemDefinition());
  planner->setup();
  const double limit = scene.spec.problem.time;
  Split split;
  for (int r = 0; r < runs; ++r) {
    planner->clear();
    ss.getProblemDefinition()->clearSolutionPaths();
    timed->reset();
    // Thread-free termination condition: the solve's own time, nothing else.
    const ob::PlannerTerminationCondition ptc = ob::timedPlannerTerminationCondition(limit);
    const auto t0 = Clock::now();
    const ob::PlannerStatus status = planner->solve(ptc);
    const double solve = seconds(t0, Clock::now());
    if (status == ob::PlannerStatus::EXACT_SOLUTION) ++split.solved;
    const double checks = static_cast<double>(timed->checks());
    const double check_s = std::max(0.0, timed->checkSeconds() - checks * clock_pair);
    const double own = solve - checks * clock_pair;  // without the wrapper's clock reads
    split.solve.push_back(own);
    split.checks.push_back(checks);
    split.check_s.push_back(check_s);
    split.rest.push_back(own - check_s);
  }
  split.benchmark_added = benchmarkAddedTime(ss, split.solve);
  return split;
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE RESOLUTION [RUNS] [PLANNER] [ROUNDING]\n", argv[0]);
    return 2;
  }
  const double resolution = std::atof(argv[2]);
  const int runs = argc > 3 ? std::atoi(argv[3]) : 60;
  const std::string planner = argc > 4 ? argv[4] : "RRTConnect";
  const Rounding rounding = argc > 5 ? roundingFromString(argv[5]) : Rounding::kConservative;
  if (!(resolution > 0) || runs < 1) throw InvalidArgument("RESOLUTION must be > 0, RUNS >= 1");
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);  // (each scene load re-seeds: a warning)
  const double clock_pair = clockPairSeconds();
  std::printf(
      "%s at %g m, %s rounding, %s, %d runs each (clock reads per check: %.0f ns, "
      "subtracted)\n",
      argv[1], resolution, toString(rounding), planner.c_str(), runs, clock_pair * 1e9);
  std::printf("%-13s %7s %9s %9s %9s %9s %9s %9s\n", "checker", "solved", "solve ms", "mean ms",
              "checks", "check ms", "us/check", "rest ms");
  const CheckerKind checkers[] = {CheckerKind::kOctreeFused, CheckerKind::kFcl};
  Split splits[2];
  for (int c = 0; c < 2; ++c) {
    const Split& s = splits[c] =
        measure(argv[1], resolution, rounding, checkers[c], planner, runs, clock_pair);
    const double per_check = mean(s.check_s) / std::max(1.0, mean(s.checks));
    std::printf("%-13s %3d/%-3d %9.3f %9.3f %9.0f %9.3f %9.3f %9.3f\n",
                checkerKindName(checkers[c]), s.solved, runs, median(s.solve) * 1e3,
                mean(s.solve) * 1e3, mean(s.checks), mean(s.check_s) * 1e3, per_check * 1e6,
                mean(s.rest) * 1e3);
  }
  auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  std::printf(
      "FCL / octree: median solve %.2f, mean solve %.2f, checks per solve %.2f, "
      "time per check %.2f\n",
      ratio(median(splits[1].solve), median(splits[0].solve)),
      ratio(mean(splits[1].solve), mean(splits[0].solve)),
      ratio(mean(splits[1].checks), mean(splits[0].checks)),
      ratio(mean(splits[1].check_s) / std::max(1.0, mean(splits[1].checks)),
            mean(splits[0].check_s) / std::max(1.0, mean(splits[0].checks))));
  const double extra_octree = splits[0].benchmark_added, extra_fcl = splits[1].benchmark_added;
  std::printf(
      "ompl::tools::Benchmark's time REAL of runs that spin for the same solve times is "
      "longer by a median %.3f ms (octree) and %.3f ms (FCL); with those added to the "
      "median solves, FCL / octree %.2f\n",
      extra_octree * 1e3, extra_fcl * 1e3,
      ratio(median(splits[1].solve) + extra_fcl, median(splits[0].solve) + extra_octree));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const octomotion::Error& e) {
    std::fprintf(stderr, "planner_plan_split_bench: %s\n", e.what());
    return 2;
  }
}
