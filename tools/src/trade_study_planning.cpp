// The trade study's planning runs: one ompl::tools::Benchmark per planner and setting.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/link_pose_goal.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/tools/experiment_name.h"
#include "trade_study_internal.h"

namespace octomotion::trade_study_internal {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

std::string fileSafe(std::string s) {
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  }
  return s;
}

double medianOf(std::vector<double> v) {
  return percentile(v, 0.5);
}

double property(const std::map<std::string, std::string>& run, const std::string& key,
                double fallback) {
  const auto it = run.find(key);
  if (it == run.end() || it->second.empty()) return fallback;
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    return fallback;
  }
}

// The planner under study, timed from inside: Benchmark's "time REAL" also holds its own
// machinery of each run (it solves through Planner::solve(fn, 0.1), whose termination condition
// is evaluated by a thread that sleeps in 1 ms steps and is joined when the solve returns, so
// every run pays up to a millisecond; bench/planner_plan_split_bench measures it), which weighs
// on solves of a few milliseconds. The post-run event writes the wrapped planner's own solve
// time next to it ("solve time REAL").
// Everything else is the wrapped planner's: name, specs, parameters and progress properties (the
// latter two hold callbacks bound to it), problem definition, set-up and planner data.
constexpr const char* kSolveTimeProperty = "solve time REAL";  // written per run, read back below

class TimedPlanner : public ob::Planner {
 public:
  explicit TimedPlanner(ob::PlannerPtr inner)
      : ob::Planner(inner->getSpaceInformation(), inner->getName()), inner_(std::move(inner)) {
    specs_ = inner_->getSpecs();
    params_ = inner_->params();
    plannerProgressProperties_ = inner_->getPlannerProgressProperties();
  }
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    const auto start = std::chrono::steady_clock::now();
    const ob::PlannerStatus status = inner_->solve(ptc);
    last_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return status;
  }
  void setProblemDefinition(const ob::ProblemDefinitionPtr& pdef) override {
    ob::Planner::setProblemDefinition(pdef);
    inner_->setProblemDefinition(pdef);
  }
  void setup() override {
    ob::Planner::setup();
    inner_->setup();
  }
  void clear() override {
    ob::Planner::clear();
    inner_->clear();
  }
  void checkValidity() override { inner_->checkValidity(); }
  void getPlannerData(ob::PlannerData& data) const override { inner_->getPlannerData(data); }
  double lastSolveSeconds() const { return last_seconds_; }

 private:
  ob::PlannerPtr inner_;
  double last_seconds_ = 0;
};

}  // namespace

PlanRow runPlanning(const StudyScene& scene, const PlanSetting& setting,
                    const StudyPlanner& planner, double motion_reach,
                    const TradeStudyOptions& options) {
  const RobotModel& robot = *scene.robot;
  const bool free_flying = robot.isFreeFlying();
  og::SimpleSetup ss(makeStateSpace(robot, free_flying ? &*scene.bounds : nullptr));
  const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
  // Every checker plans with the motion step `octomotion plan` uses for the scene.
  boundMotionStep(*si, robot, motion_reach, scene.resolution);
  ss.setStateValidityChecker(setting.make(si));
  auto toState = [&](const StateSpec& s) {
    ob::ScopedState<> state(si);
    if (free_flying) {
      configurationToState(robot, {}, *s.pose, state.get());
    } else {
      configurationToState(robot, s.joints, Eigen::Isometry3d::Identity(), state.get());
    }
    return state;
  };
  if (const auto& link_pose = scene.spec.problem.goal->link_pose) {
    // The robot outlives ss: a non-owning pointer.
    const std::shared_ptr<const RobotModel> unowned(std::shared_ptr<const RobotModel>(), &robot);
    ss.setStartState(toState(*scene.spec.problem.start));
    ss.setGoal(makeLinkPoseGoal(si, unowned,
                                scene.spec.robot.pose.value_or(Eigen::Isometry3d::Identity()),
                                *link_pose, planner.name, ompl::RNG().uniformInt(0, 1 << 30)));
  } else {
    ss.setStartAndGoalStates(toState(*scene.spec.problem.start), toState(*scene.spec.problem.goal));
  }
  PlanRow row;
  row.scene = scene.spec.name;
  row.planner = planner.name;
  row.checker = setting.checker;
  row.resolution = setting.resolution;
  row.rounding = setting.rounding;
  row.time_limit = planner.time > 0 ? planner.time : scene.spec.problem.time;
  if (options.overrides.time && !(planner.time > 0)) row.time_limit = *options.overrides.time;
  row.runs = options.runs;

  // One word: Planner Arena's log import keeps only the last word of the experiment line.
  const std::string experiment = experimentName(scene.spec.name, checkerKindName(setting.checker),
                                                setting.resolution, setting.rounding);
  ompl::tools::Benchmark benchmark(ss, experiment);
  const auto timed = std::make_shared<TimedPlanner>(makePlanner(planner.name, si));
  benchmark.addPlanner(timed);
  benchmark.setPostRunEvent(
      [timed](const ob::PlannerPtr&, ompl::tools::Benchmark::RunProperties& run) {
        std::ostringstream seconds;
        seconds << std::setprecision(9) << timed->lastSolveSeconds();
        run[kSolveTimeProperty] = seconds.str();
      });
  ompl::tools::Benchmark::Request request(row.time_limit, 4096.0, options.runs, 0.05,
                                          /*displayProgress=*/false,
                                          /*saveConsoleOutput=*/false, /*simplify=*/true);
  benchmark.benchmark(request);
  if (!options.log_dir.empty()) {
    row.log_file = options.log_dir + "/" +
                   fileSafe(scene.spec.name + "_" + planner.name + "_" +
                            settingName(setting.checker, setting.resolution, setting.rounding)) +
                   ".log";
    if (!benchmark.saveResultsToFile(row.log_file.c_str())) {
      throw FileError(row.log_file, "cannot write the benchmark log");
    }
  }
  const auto& data = benchmark.getRecordedExperimentData();
  std::vector<double> times, solve_times, firsts, lengths;
  if (!data.planners.empty()) {
    const auto& experiment_data = data.planners.front();
    for (std::size_t r = 0; r < experiment_data.runs.size(); ++r) {
      const auto& run = experiment_data.runs[r];
      const double time = property(run, "time REAL", row.time_limit);
      const bool solved = property(run, "solved BOOLEAN", 0) != 0 &&
                          property(run, "approximate solution BOOLEAN", 0) == 0;
      // A failed run costs the whole limit (it may also fail early, e.g. on an invalid start).
      times.push_back(solved ? std::min(time, row.time_limit) : row.time_limit);
      const double solve = property(run, kSolveTimeProperty, time);
      solve_times.push_back(solved ? std::min(solve, row.time_limit) : row.time_limit);
      if (!solved) continue;
      ++row.solved;
      double length = property(run, "simplified solution length REAL", -1);
      if (length < 0) length = property(run, "solution length REAL", -1);
      if (length >= 0) lengths.push_back(length);
      // Asymptotically optimal planners run to the limit; their progress data says when the
      // first solution appeared (to the 0.05 s sampling interval).
      double first = time;
      if (r < experiment_data.runsProgressData.size()) {
        for (const auto& sample : experiment_data.runsProgressData[r]) {
          const auto cost = sample.find("best cost REAL");
          if (cost == sample.end()) break;
          if (std::isfinite(property(sample, "best cost REAL", INFINITY))) {
            first = std::min(first, property(sample, "time REAL", time));
            break;
          }
        }
      }
      firsts.push_back(first);
    }
  }
  row.median_time = medianOf(times);
  row.median_solve_time = medianOf(solve_times);
  row.median_first_solution = firsts.empty() ? -1.0 : medianOf(firsts);
  row.median_length = lengths.empty() ? -1.0 : medianOf(lengths);
  return row;
}

}  // namespace octomotion::trade_study_internal
