#include "octomotion/planner/trade_study.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <random>
#include <sstream>

#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include "octomotion/octree/mesh.h"
#include "octomotion/planner/ompl/octree_validity_checker.h"
#include "octomotion/planner/reference/fcl_checker.h"
#include "octomotion/planner/reference/fcl_octomap_checker.h"

namespace octomotion {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

namespace {

double micros(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// The scene's robot, environment and region, loaded the way loadPlanningScene does (without
// building any collision model: the study builds one per setting).
struct StudyScene {
  SceneSpec spec;
  std::optional<RobotModel> robot;
  std::optional<EnvironmentGeometry> environment;
  double robot_diagonal = 0;
  std::optional<Eigen::AlignedBox3d> bounds;  // free-flying: SE(3) position bounds
  double resolution = 0;                      // the scene's own (or auto) resolution
};

StudyScene loadStudyScene(const TradeStudyOptions& options, const WarningSink& warnings) {
  StudyScene s;
  s.spec = loadScene(options.scene_path);
  SceneSpec& spec = s.spec;
  if (options.overrides.self_pair_tables) {
    spec.octree.self_pair_tables = *options.overrides.self_pair_tables;
  }
  if (options.overrides.exact_primitives) {
    spec.octree.exact_primitives = *options.overrides.exact_primitives;
  }
  if (options.overrides.max_surface_voxels) {
    spec.octree.max_surface_voxels = *options.overrides.max_surface_voxels;
  }
  if (!spec.robot.urdf.empty()) {
    RobotModelOptions ro;
    ro.package_paths = spec.robot.package_paths;
    ro.package_paths.insert(ro.package_paths.end(), options.overrides.package_paths.begin(),
                            options.overrides.package_paths.end());
    ro.warnings = warnings;
    s.robot = RobotModel::fromUrdfFile(spec.robot.urdf, ro);
    if (s.robot->variableCount() == 0) {
      ro.base = BaseMotion::kFreeFlying;
      s.robot = RobotModel::fromUrdfFile(spec.robot.urdf, ro);
    }
    if (!spec.robot.srdf.empty()) s.robot->loadSrdfFile(spec.robot.srdf);
    s.robot_diagonal = robotGeometryBox(*s.robot).diagonal().norm();
  } else {
    s.robot = RobotModel::fromMesh(spec.robot.mesh);
    MeshLoadOptions mo;
    mo.keep_root_transform = spec.robot.keep_mesh_root_transform;
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& v : loadMesh(spec.robot.mesh, mo).vertices) box.extend(v);
    s.robot_diagonal = box.diagonal().norm();
  }
  try {
    s.environment = EnvironmentGeometry::load(spec.environment, warnings);
  } catch (const Error& e) {
    throw FileError(spec.path, e.what());
  }
  Eigen::AlignedBox3d scene_box;
  if (const auto b = s.environment->bounds()) scene_box = *b;
  if (s.robot->isFreeFlying()) {
    if (!spec.problem.bounds) {
      if (scene_box.isEmpty()) {
        throw FileError(spec.path, "problem.bounds: missing, and there is no environment");
      }
      spec.problem.bounds = scene_box;
    }
    s.bounds = spec.problem.bounds;
  }
  if (spec.problem.bounds) scene_box.extend(*spec.problem.bounds);
  s.resolution = spec.octree.resolution ? *spec.octree.resolution
                                        : autoResolution(*s.robot, scene_box, s.robot_diagonal);
  return s;
}

// The state set: uniform over the joint limits (fixed base) or over the position bounds and
// SO(3) (free-flying; Shoemake's uniform quaternions).
struct States {
  std::size_t count = 0, dof = 0;
  std::vector<double> q;  // count x dof
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> X_WB;
  const double* at(std::size_t i) const { return dof ? &q[i * dof] : nullptr; }
};

States sampleStates(const StudyScene& scene, std::size_t count, std::uint64_t seed) {
  States s;
  s.count = count;
  const RobotModel& robot = *scene.robot;
  s.dof = static_cast<std::size_t>(robot.variableCount());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  s.q.resize(count * s.dof);
  s.X_WB.assign(count, Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t k = 0; k < s.dof; ++k) {
      const Variable& v = robot.variables()[k];
      s.q[i * s.dof + k] = v.lower + (v.upper - v.lower) * unit(rng);
    }
    if (robot.isFreeFlying()) {
      const Eigen::AlignedBox3d& b = *scene.bounds;
      Eigen::Vector3d t;
      for (int k = 0; k < 3; ++k) t[k] = b.min()[k] + (b.max()[k] - b.min()[k]) * unit(rng);
      const double u1 = unit(rng), u2 = 2 * M_PI * unit(rng), u3 = 2 * M_PI * unit(rng);
      const double a = std::sqrt(1 - u1), c = std::sqrt(u1);
      const Eigen::Quaterniond r(c * std::cos(u3), a * std::sin(u2), a * std::cos(u2),
                                 c * std::sin(u3));
      s.X_WB[i].linear() = r.normalized().toRotationMatrix();
      s.X_WB[i].translation() = t;
    }
  }
  return s;
}

// Thread CPU time in microseconds: the means are taken over whole passes in CPU time, so the
// shared machine's preemptions (which wall-clock means would absorb) do not inflate them.
double threadCpuMicros() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

// A check of state i, for timing passes that pair a setting with the reference.
using CheckFn = std::function<bool(std::size_t)>;

// Timed passes, one after the other, kTimedRounds times (the median kept) so that a burst of
// load on the shared machine moves one round, not the result.
constexpr int kTimedRounds = 5;

// The passes over the states: each check timed alone (wall clock, for the medians and the
// 90th percentiles; includes the clock reads), then kTimedRounds rounds of whole
// passes in thread CPU time (the means): each round times the reference's full check (when
// given) right before this checker's, so their ratio is taken on the same machine state, then
// the environment-only pass likewise after `env_reference`'s (when given). mean_us and
// env_mean_us are the medians of the rounds' means, speedup and env_speedup the medians of the
// rounds' ratios (reference / this).
struct Measurement {
  std::vector<double> full_us;
  std::vector<bool> answers, env_answers;
  double mean_us = 0, env_mean_us = 0;
  double speedup = 1, env_speedup = -1;
};

template <class Full, class Env>
Measurement measure(std::size_t count, const Full& full, const Env& env,
                    const CheckFn& reference = {}, const CheckFn& env_reference = {}) {
  Measurement m;
  m.full_us.resize(count);
  m.answers.resize(count);
  m.env_answers.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto t0 = Clock::now();
    const bool hit = full(i);
    const auto t1 = Clock::now();
    m.full_us[i] = micros(t0, t1);
    m.answers[i] = hit;
  }
  const auto expected =
      static_cast<std::size_t>(std::count(m.answers.begin(), m.answers.end(), true));
  auto pass = [&](const auto& check) {
    std::size_t hits = 0;
    const double c0 = threadCpuMicros();
    for (std::size_t i = 0; i < count; ++i) hits += check(i) ? 1 : 0;
    const double us = (threadCpuMicros() - c0) / static_cast<double>(count);
    return std::make_pair(us, hits);
  };
  for (std::size_t i = 0; i < count; ++i) m.env_answers[i] = env(i);
  const auto env_expected =
      static_cast<std::size_t>(std::count(m.env_answers.begin(), m.env_answers.end(), true));
  std::vector<double> means, ratios, env_means, env_ratios;
  for (int round = 0; round < kTimedRounds; ++round) {
    const double reference_us = reference ? pass(reference).first : 0.0;
    const auto [us, hits] = pass(full);
    const double env_reference_us = env_reference ? pass(env_reference).first : 0.0;
    const auto [env_us, env_hits] = pass(env);
    if (hits != expected || env_hits != env_expected) {
      throw Error("trade study: a checker answered differently on the same states");
    }
    means.push_back(us);
    env_means.push_back(env_us);
    if (reference) ratios.push_back(reference_us / us);
    if (env_reference) env_ratios.push_back(env_reference_us / env_us);
  }
  m.mean_us = percentile(means, 0.5);
  m.env_mean_us = percentile(env_means, 0.5);
  if (reference) m.speedup = percentile(ratios, 0.5);
  if (env_reference) m.env_speedup = percentile(env_ratios, 0.5);
  return m;
}

// FCL and FCL+OctoMap share the scratch API.
template <class Model>
Measurement measureFclLike(const Model& model, const States& states, std::size_t count,
                           const CheckFn& reference = {}) {
  auto scratch = model.makeScratch();
  return measure(
      count,
      [&](std::size_t i) {
        model.setConfiguration(states.at(i), states.dof, states.X_WB[i], *scratch);
        return model.inCollision(*scratch);
      },
      [&](std::size_t i) {
        model.setConfiguration(states.at(i), states.dof, states.X_WB[i], *scratch);
        return model.environmentInCollision(*scratch);
      },
      reference);
}

Measurement measureOctree(const OctreeCollisionModel& model, CheckerPath path, const States& states,
                          std::size_t count, const CheckFn& reference,
                          const CheckFn& env_reference) {
  CheckScratch scratch = model.makeScratch();
  const RobotModel& robot = model.robot();
  const bool free_flying = robot.isFreeFlying();
  return measure(
      count,
      [&](std::size_t i) {
        return model.inCollision(states.at(i), states.dof, states.X_WB[i], path, scratch);
      },
      [&](std::size_t i) {
        robot.forwardKinematics(states.at(i), states.dof, scratch.robot,
                                free_flying ? states.X_WB[i] : model.baseMount());
        return model.environmentInCollision(path, scratch);
      },
      reference, env_reference);
}

std::vector<bool> prefix(const std::vector<bool>& v, std::size_t n) {
  return std::vector<bool>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
}

// Times, and the answers scored against the reference's (full and environment-only), on the
// first m.full_us.size() states.
void fillRow(const Measurement& m, const Measurement& reference_m, CheckRow& row) {
  const std::size_t n = m.answers.size();
  const std::vector<bool> reference = prefix(reference_m.answers, n);
  scoreAgainstReference(m.answers, reference, row);
  CheckRow env;
  scoreAgainstReference(m.env_answers, prefix(reference_m.env_answers, n), env);
  row.env_fp_rate = env.fp_rate;
  row.env_fn_rate = env.fn_rate;
  std::vector<double> free_us, colliding_us;
  for (std::size_t i = 0; i < n; ++i) {
    (reference[i] ? colliding_us : free_us).push_back(m.full_us[i]);
  }
  row.states = n;
  row.mean_us = m.mean_us;
  row.median_free_us = percentile(free_us, 0.5);
  row.p90_free_us = percentile(free_us, 0.9);
  row.median_colliding_us = percentile(colliding_us, 0.5);
  row.p90_colliding_us = percentile(colliding_us, 0.9);
  row.env_mean_us = m.env_mean_us;
}

std::string fmt(double v, int precision = 3) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

std::string resolutionLabel(double r) {
  return r >= 0.01 ? fmt(r * 100, 3) + " cm" : fmt(r * 1000, 3) + " mm";
}

std::string settingName(const std::string& checker, double resolution,
                        const std::string& rounding) {
  std::string s = checker;
  if (resolution > 0) s += " " + resolutionLabel(resolution);
  if (!rounding.empty()) s += " " + rounding;
  return s;
}

std::string fileSafe(std::string s) {
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  }
  return s;
}

// One planning setting: the checker to install and what to call it.
struct PlanSetting {
  std::string checker, rounding;
  double resolution = 0;
  std::function<ob::StateValidityCheckerPtr(const ob::SpaceInformationPtr&)> make;
};

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
  ss.setStartAndGoalStates(toState(*scene.spec.problem.start), toState(*scene.spec.problem.goal));
  PlanRow row;
  row.scene = scene.spec.name;
  row.planner = planner.name;
  row.checker = setting.checker;
  row.resolution = setting.resolution;
  row.rounding = setting.rounding;
  row.time_limit = planner.time > 0 ? planner.time : scene.spec.problem.time;
  if (options.overrides.time && !(planner.time > 0)) row.time_limit = *options.overrides.time;
  row.runs = options.runs;

  const std::string experiment =
      scene.spec.name + " " + settingName(setting.checker, setting.resolution, setting.rounding);
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

std::size_t octreeBytes(const OctreeCollisionModel& model) {
  const CollisionModelReport& r = model.report();
  std::size_t bytes =
      r.environment.bytes + r.environment_cell_grid_bytes + r.environment_clearance_grid_bytes;
  for (const LinkReport& l : r.links) bytes += l.source_bytes + l.self_source_bytes;
  for (const SelfPairTableReport& t : r.self_pair_tables) bytes += t.bytes;
  return bytes;
}

}  // namespace

std::vector<double> defaultResolutions(bool free_flying, double scene_resolution) {
  if (!free_flying) return {0.08, 0.04, 0.02, 0.01, 0.005};
  std::vector<double> r;
  for (double k : {16.0, 8.0, 4.0, 2.0, 1.0}) r.push_back(scene_resolution * k);
  return r;
}

double percentile(std::vector<double>& values, double p) {
  if (values.empty()) return 0.0;
  const double rank = std::ceil(p * static_cast<double>(values.size()));
  const std::size_t k =
      std::min(values.size() - 1, static_cast<std::size_t>(std::max(rank, 1.0)) - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

void scoreAgainstReference(const std::vector<bool>& answers, const std::vector<bool>& reference,
                           CheckRow& row) {
  if (answers.size() != reference.size()) {
    throw InvalidArgument("scoreAgainstReference: " + std::to_string(answers.size()) +
                          " answers for " + std::to_string(reference.size()) + " states");
  }
  row.states = reference.size();
  row.free_states = row.colliding_states = row.false_positives = row.false_negatives = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (reference[i]) {
      ++row.colliding_states;
      if (!answers[i]) ++row.false_negatives;
    } else {
      ++row.free_states;
      if (answers[i]) ++row.false_positives;
    }
  }
  row.fp_rate = row.free_states ? static_cast<double>(row.false_positives) /
                                      static_cast<double>(row.free_states)
                                : 0.0;
  row.fn_rate = row.colliding_states ? static_cast<double>(row.false_negatives) /
                                           static_cast<double>(row.colliding_states)
                                     : 0.0;
}

TradeStudyResult runTradeStudy(const TradeStudyOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  // By value: the models keep a copy of the sink.
  const WarningSink warnings = [progress = options.progress](const std::string& w) {
    if (progress) progress("warning: " + w);
  };
  if (options.states == 0) throw InvalidArgument("trade study: states must be > 0");
  const StudyScene scene = loadStudyScene(options, warnings);
  const RobotModel& robot = *scene.robot;
  const bool free_flying = robot.isFreeFlying();
  const EnvironmentGeometry& environment = *scene.environment;
  const SceneSpec& spec = scene.spec;

  TradeStudyResult result;
  result.scene = spec.name;
  result.free_flying = free_flying;
  result.scene_resolution = scene.resolution;
  const LinkTreeResolutions ratios =
      linkTreeResolutions(1.0, options.link_resolution_ratio, options.self_link_resolution_ratio);
  result.link_resolution_ratio = ratios.link;
  result.self_link_resolution_ratio = ratios.self;
  result.self_pair_tables = spec.octree.self_pair_tables;
  result.exact_primitives = spec.octree.exact_primitives;
  std::vector<double> resolutions = options.resolutions.empty()
                                        ? defaultResolutions(free_flying, scene.resolution)
                                        : options.resolutions;
  for (double r : resolutions) {
    if (!(r > 0) || !std::isfinite(r)) {
      throw InvalidArgument("resolutions: " + fmt(r) + " is not a positive size");
    }
  }
  std::sort(resolutions.begin(), resolutions.end(), std::greater<>());
  // The ladder entry closest to the scene's own resolution (in ratio).
  double scene_rung = resolutions.front();
  for (double r : resolutions) {
    if (std::abs(std::log(r / scene.resolution)) <
        std::abs(std::log(scene_rung / scene.resolution))) {
      scene_rung = r;
    }
  }

  const States states = sampleStates(scene, options.states, options.seed);
  say(spec.name + ": " + std::to_string(states.count) + " uniform states");

  // The exact reference first: its answers classify the states.
  auto t0 = Clock::now();
  auto fcl = std::make_shared<const FclCollisionModel>(
      robot, environment, spec.robot.keep_mesh_root_transform, spec.robot.center_mesh_vertices);
  const double fcl_build = seconds(t0, Clock::now());
  const Measurement fcl_m = measureFclLike(*fcl, states, states.count);
  // FCL's full check again, paired with every setting's timed passes (Measurement::speedup).
  auto fcl_scratch = fcl->makeScratch();
  const CheckFn fcl_check = [&](std::size_t i) {
    fcl->setConfiguration(states.at(i), states.dof, states.X_WB[i], *fcl_scratch);
    return fcl->inCollision(*fcl_scratch);
  };
  {
    CheckRow row;
    row.scene = spec.name;
    row.checker = "fcl";
    fillRow(fcl_m, fcl_m, row);
    row.build_seconds = fcl_build;
    result.checks.push_back(row);
    say(spec.name + ": fcl " + fmt(row.mean_us) + " us mean, " +
        std::to_string(row.colliding_states) + " colliding states");
  }

  std::vector<PlanSetting> plan_settings;
  // boundMotionStep's reach: the body's diagonal, or (arms) from the octree model's report.
  double motion_reach = scene.robot_diagonal;
  const bool planning =
      options.runs > 0 && !options.planners.empty() && spec.problem.start && spec.problem.goal;
  if (planning) {
    plan_settings.push_back({"fcl", "", 0, [fcl](const ob::SpaceInformationPtr& si) {
                               return std::make_shared<FclValidityChecker>(si, fcl);
                             }});
  }

  for (double resolution : resolutions) {
    // FCL+OctoMap's environment-only check at this resolution, paired with every octree
    // setting's environment-only passes (CheckRow::env_speedup_vs_fcl_octomap).
    std::shared_ptr<const FclOctomapCollisionModel> octomap;
    FclOctomapCollisionModel::ScratchPtr octomap_scratch;
    CheckFn octomap_env_check;
    if (options.fcl_octomap) {
      try {
        octomap = std::make_shared<const FclOctomapCollisionModel>(
            robot, environment, resolution, spec.robot.keep_mesh_root_transform,
            spec.robot.center_mesh_vertices);
        const Measurement m = measureFclLike(*octomap, states, states.count, fcl_check);
        CheckRow row;
        row.scene = spec.name;
        row.checker = "fcl-octomap";
        row.resolution = resolution;
        fillRow(m, fcl_m, row);
        row.memory_bytes = octomap->octomapBytes();
        row.build_seconds = octomap->buildSeconds();
        row.speedup_vs_fcl = m.speedup;
        result.checks.push_back(row);
        octomap_scratch = octomap->makeScratch();
        octomap_env_check = [&states, &octomap, &octomap_scratch](std::size_t i) {
          octomap->setConfiguration(states.at(i), states.dof, states.X_WB[i], *octomap_scratch);
          return octomap->environmentInCollision(*octomap_scratch);
        };
        say(spec.name + ": " + settingName("fcl-octomap", resolution, "") + " " + fmt(row.mean_us) +
            " us mean");
        if (planning && (options.plan_every_setting || resolution == scene_rung)) {
          plan_settings.push_back(
              {"fcl-octomap", "", resolution, [octomap](const ob::SpaceInformationPtr& si) {
                 return std::make_shared<FclOctomapValidityChecker>(si, octomap);
               }});
        }
      } catch (const Error& e) {
        say(spec.name + ": fcl-octomap at " + resolutionLabel(resolution) +
            " skipped: " + e.what());
      }
    }
    for (Rounding rounding : options.roundings) {
      CollisionModelOptions mo;
      mo.resolution = resolution;
      mo.link_resolution = resolution * result.link_resolution_ratio;
      mo.self_link_resolution = resolution * result.self_link_resolution_ratio;
      mo.rounding = rounding;
      mo.self_pair_tables = spec.octree.self_pair_tables;
      mo.exact_primitives = spec.octree.exact_primitives && rounding == Rounding::kConservative;
      if (spec.octree.max_surface_voxels) mo.max_surface_voxels = *spec.octree.max_surface_voxels;
      mo.base_position_bounds = scene.bounds;
      mo.keep_mesh_root_transform = spec.robot.keep_mesh_root_transform;
      mo.center_mesh_vertices = spec.robot.center_mesh_vertices;
      mo.warnings = warnings;
      std::shared_ptr<const OctreeCollisionModel> model;
      double build = 0;
      try {
        t0 = Clock::now();
        model = std::make_shared<const OctreeCollisionModel>(robot, environment, mo);
        build = seconds(t0, Clock::now());
        if (!free_flying) motion_reach = model->report().reach_W.sizes().maxCoeff() / 2;
      } catch (const Error& e) {
        say(spec.name + ": octree at " + resolutionLabel(resolution) + " skipped: " + e.what());
        continue;
      }
      for (CheckerPath path : options.paths) {
        const std::string checker = path == CheckerPath::kFused ? "octree-fused" : "octree";
        const std::size_t count = path == CheckerPath::kMoveTree && options.move_tree_states > 0
                                      ? std::min(options.move_tree_states, states.count)
                                      : states.count;
        const Measurement m =
            measureOctree(*model, path, states, count, fcl_check, octomap_env_check);
        CheckRow row;
        row.scene = spec.name;
        row.checker = checker;
        row.resolution = resolution;
        row.rounding = toString(rounding);
        fillRow(m, fcl_m, row);
        row.memory_bytes = octreeBytes(*model);
        row.build_seconds = build;
        row.speedup_vs_fcl = m.speedup;
        row.env_speedup_vs_fcl_octomap = m.env_speedup;
        result.checks.push_back(row);
        say(spec.name + ": " + settingName(checker, resolution, row.rounding) + " " +
            fmt(row.mean_us) + " us mean, FP " + fmt(100 * row.fp_rate) + " %, FN " +
            fmt(100 * row.fn_rate) + " %");
        // By default: the fused conservative octree at every resolution, the moveTree path
        // (conservative) at the scene's resolution.
        const bool conservative = rounding == Rounding::kConservative;
        if (planning &&
            (options.plan_every_setting ||
             (conservative && (path == CheckerPath::kFused || resolution == scene_rung)))) {
          plan_settings.push_back(
              {checker, row.rounding, resolution, [model, path](const ob::SpaceInformationPtr& si) {
                 return std::make_shared<OctreeValidityChecker>(si, model, path);
               }});
        }
      }
    }
  }

  if (planning) {
    static bool seeded = false;  // OMPL's seed can be set once, before its generators exist
    if (!seeded) {
      ompl::RNG::setSeed(options.overrides.seed ? *options.overrides.seed : options.seed);
      seeded = true;
    }
    for (const StudyPlanner& planner : options.planners) {
      for (const PlanSetting& setting : plan_settings) {
        PlanRow row = runPlanning(scene, setting, planner, motion_reach, options);
        say(spec.name + ": " + planner.name + " with " +
            settingName(setting.checker, setting.resolution, setting.rounding) + ": " +
            std::to_string(row.solved) + "/" + std::to_string(row.runs) + " solved, median " +
            fmt(row.median_time) + " s");
        result.planning.push_back(std::move(row));
      }
    }
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Writers.

const char* const kCheckCsvColumns =
    "scene,checker,resolution_m,rounding,states,free_states,colliding_states,mean_us,"
    "median_free_us,p90_free_us,median_colliding_us,p90_colliding_us,env_mean_us,"
    "false_positives,false_negatives,fp_rate,fn_rate,env_fp_rate,env_fn_rate,memory_bytes,"
    "build_s,speedup_vs_fcl,env_speedup_vs_fcl_octomap";
const char* const kPlanCsvColumns =
    "scene,planner,checker,resolution_m,rounding,time_limit_s,runs,solved,median_time_s,"
    "median_first_solution_s,median_length,log_file,median_solve_time_s";

void writeCheckCsv(const std::vector<CheckRow>& rows, std::ostream& out, bool header) {
  if (header) out << kCheckCsvColumns << '\n';
  out << std::setprecision(6);
  for (const CheckRow& r : rows) {
    out << r.scene << ',' << r.checker << ',' << r.resolution << ',' << r.rounding << ','
        << r.states << ',' << r.free_states << ',' << r.colliding_states << ',' << r.mean_us << ','
        << r.median_free_us << ',' << r.p90_free_us << ',' << r.median_colliding_us << ','
        << r.p90_colliding_us << ',' << r.env_mean_us << ',' << r.false_positives << ','
        << r.false_negatives << ',' << r.fp_rate << ',' << r.fn_rate << ',' << r.env_fp_rate << ','
        << r.env_fn_rate << ',' << r.memory_bytes << ',' << r.build_seconds << ','
        << r.speedup_vs_fcl << ',' << r.env_speedup_vs_fcl_octomap << '\n';
  }
}

void writePlanCsv(const std::vector<PlanRow>& rows, std::ostream& out, bool header) {
  if (header) out << kPlanCsvColumns << '\n';
  out << std::setprecision(6);
  for (const PlanRow& r : rows) {
    out << r.scene << ',' << r.planner << ',' << r.checker << ',' << r.resolution << ','
        << r.rounding << ',' << r.time_limit << ',' << r.runs << ',' << r.solved << ','
        << r.median_time << ',' << r.median_first_solution << ',' << r.median_length << ','
        << r.log_file << ',' << r.median_solve_time << '\n';
  }
}

namespace {

std::string cell(double v, int precision = 3) {
  return v < 0 ? "–" : fmt(v, precision);
}
std::string percent(double rate) {
  return fmt(100 * rate, 3);
}

const CheckRow* findRow(const TradeStudyResult& r, const std::string& checker, double resolution,
                        const std::string& rounding) {
  for (const CheckRow& row : r.checks) {
    if (row.checker == checker && row.resolution == resolution && row.rounding == rounding) {
      return &row;
    }
  }
  return nullptr;
}

const PlanRow* findPlan(const TradeStudyResult& r, const std::string& planner,
                        const std::string& checker) {
  for (const PlanRow& row : r.planning) {
    if (row.planner == planner && row.checker == checker) return &row;
  }
  return nullptr;
}

}  // namespace

void writeMarkdown(const TradeStudyResult& result, std::ostream& out) {
  out << "### " << result.scene << "\n\n";
  const CheckRow& fcl = result.checks.front();
  out << fcl.states << " uniform states (" << fcl.colliding_states << " colliding per FCL, "
      << fcl.free_states << " free); times in microseconds per check, forward kinematics "
      << "included; FP % of free states, FN % of colliding states.";
  out << " Octree link source trees at " << result.link_resolution_ratio
      << " x the environment resolution.";
  if (!result.free_flying && result.self_link_resolution_ratio != result.link_resolution_ratio) {
    out << " Self-collision trees at " << result.self_link_resolution_ratio
        << " x the environment resolution.";
  }
  if (result.self_pair_tables) {
    out << " Self-pair tables on (conservative settings; docs/planner.md, \"Self-pair tables\").";
  }
  if (result.exact_primitives) {
    out << " Exact primitives on (conservative settings; docs/planner.md, \"Exact primitives\").";
  }
  out << "\n\n";
  out << "| checker | resolution | rounding | mean | free median | free p90 | colliding median "
         "| colliding p90 | env-only mean | FP % | FN % | env FP % | env FN % | memory KiB | build "
         "s | FCL / this |\n"
      << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const CheckRow& r : result.checks) {
    out << "| " << r.checker << " | "
        << (r.resolution > 0 ? resolutionLabel(r.resolution) : "exact") << " | "
        << (r.rounding.empty() ? "–" : r.rounding) << " | " << fmt(r.mean_us) << " | "
        << fmt(r.median_free_us) << " | " << fmt(r.p90_free_us) << " | "
        << fmt(r.median_colliding_us) << " | " << fmt(r.p90_colliding_us) << " | "
        << cell(r.env_mean_us) << " | " << percent(r.fp_rate) << " | " << percent(r.fn_rate)
        << " | " << (r.env_fp_rate < 0 ? "–" : percent(r.env_fp_rate)) << " | "
        << (r.env_fn_rate < 0 ? "–" : percent(r.env_fn_rate)) << " | "
        << (r.memory_bytes ? fmt(static_cast<double>(r.memory_bytes) / 1024.0) : "–") << " | "
        << fmt(r.build_seconds) << " | " << fmt(r.speedup_vs_fcl) << " |\n";
  }
  out << "\n";
  if (!result.planning.empty()) {
    out << "| planner | checker | resolution | rounding | limit s | solved | median time s | "
           "median solve s | median first solution s | median length |\n"
        << "|---|---|---|---|--:|--:|--:|--:|--:|--:|\n";
    for (const PlanRow& r : result.planning) {
      out << "| " << r.planner << " | " << r.checker << " | "
          << (r.resolution > 0 ? resolutionLabel(r.resolution) : "exact") << " | "
          << (r.rounding.empty() ? "–" : r.rounding) << " | " << fmt(r.time_limit) << " | "
          << r.solved << "/" << r.runs << " | " << fmt(r.median_time) << " | "
          << fmt(r.median_solve_time) << " | " << cell(r.median_first_solution) << " | "
          << cell(r.median_length) << " |\n";
    }
    out << "\n";
  }
}

void writeTargets(const TradeStudyResult& result, std::ostream& out) {
  const CheckRow& fcl = result.checks.front();
  auto verdict = [](double ratio, double target) {
    return ratio >= target ? "**met** (" + fmt(ratio / target, 3) + "x the target)"
                           : "**missed** (" + fmt(ratio, 3) + "x of the " + fmt(target, 3) +
                                 "x asked; short by a factor " + fmt(target / ratio, 3) + ")";
  };
  out << "Targets for " << result.scene << " (" << fcl.states << " states; FCL mean "
      << fmt(fcl.mean_us) << " us):\n\n";
  if (!result.free_flying) {
    // The best octree setting whose false-positive rate is at most 2 %.
    const CheckRow* best = nullptr;
    auto score = [](const CheckRow& r) {
      return std::min(r.speedup_vs_fcl / 5.0, r.env_speedup_vs_fcl_octomap / 10.0);
    };
    for (const CheckRow& r : result.checks) {
      // Only settings that never miss a contact count (center rounding does miss some).
      if (r.checker.rfind("octree", 0) != 0 || r.false_negatives > 0 || r.fp_rate > 0.02) {
        continue;
      }
      if (!best || score(r) > score(*best)) best = &r;
    }
    if (!best) {
      const CheckRow* lowest = nullptr;
      for (const CheckRow& r : result.checks) {
        if (r.checker != "octree-fused" || r.false_negatives > 0) continue;
        if (!lowest || r.fp_rate < lowest->fp_rate) lowest = &r;
      }
      out << "- no octree setting without false negatives reaches a false-positive rate <= 2 %: "
             "the targets are **missed** at every resolution measured";
      if (lowest) {
        out << "; the lowest is "
            << settingName(lowest->checker, lowest->resolution, lowest->rounding) << " with FP "
            << percent(lowest->fp_rate) << " % (environment only: " << percent(lowest->env_fp_rate)
            << " %), mean " << fmt(lowest->mean_us)
            << " us, FCL / octree = " << fmt(lowest->speedup_vs_fcl)
            << ", FCL+OctoMap / octree (environment only) = "
            << cell(lowest->env_speedup_vs_fcl_octomap);
      }
      out << ".\n";
    } else {
      out << "- full check, " << settingName(best->checker, best->resolution, best->rounding)
          << " (FP " << percent(best->fp_rate) << " %): mean " << fmt(best->mean_us)
          << " us, FCL / octree = " << fmt(best->speedup_vs_fcl)
          << " — target >= 5: " << verdict(best->speedup_vs_fcl, 5) << "\n";
      if (best->env_speedup_vs_fcl_octomap > 0) {
        out << "- environment only, same setting: " << fmt(best->env_mean_us)
            << " us, FCL+OctoMap / octree = " << fmt(best->env_speedup_vs_fcl_octomap)
            << " — target >= 10: " << verdict(best->env_speedup_vs_fcl_octomap, 10) << "\n";
      }
    }
    if (fcl.states < 20000) {
      out << "- (fewer than the 20,000 states the target asks for)\n";
    }
  } else {
    for (const CheckRow& r : result.checks) {
      if (r.checker != "octree-fused" || r.rounding != "conservative") continue;
      const CheckRow* octomap = findRow(result, "fcl-octomap", r.resolution, "");
      out << "- " << settingName(r.checker, r.resolution, r.rounding) << ": mean " << fmt(r.mean_us)
          << " us, FCL / octree = " << fmt(r.speedup_vs_fcl)
          << " (target >= 3: " << verdict(r.speedup_vs_fcl, 3) << ")";
      if (octomap) {
        const double ratio = octomap->mean_us / r.mean_us;
        out << ", FCL+OctoMap / octree = " << fmt(ratio) << " (target >= 10: " << verdict(ratio, 10)
            << ")";
      }
      out << "\n";
    }
  }
  const PlanRow* fcl_plan = findPlan(result, "RRTConnect", "fcl");
  if (fcl_plan) {
    for (const PlanRow& r : result.planning) {
      if (r.planner != "RRTConnect" || r.checker != "octree-fused" ||
          r.rounding != "conservative") {
        continue;
      }
      const double ratio = r.median_time > 0 ? fcl_plan->median_time / r.median_time : 0;
      const double solve_ratio =
          r.median_solve_time > 0 ? fcl_plan->median_solve_time / r.median_solve_time : 0;
      out << "- RRTConnect, " << settingName(r.checker, r.resolution, r.rounding) << ": solved "
          << r.solved << "/" << r.runs << " vs FCL " << fcl_plan->solved << "/" << fcl_plan->runs
          << (r.solved >= fcl_plan->solved ? " (met)" : " (**missed**)")
          << "; median time FCL / octree = " << fmt(ratio)
          << " — target >= 3: " << verdict(ratio, 3)
          << "; the planners' own solve times, FCL / octree = " << fmt(solve_ratio) << " — "
          << verdict(solve_ratio, 3) << "\n";
    }
  }
  out << "\n";
}

namespace {

// gnuplot data: one block per curve (blocks two blank lines apart, each headed by the curve's
// quoted name and `columns`), curves in order of first appearance; `name(row)` picks a row's
// curve and `point(row)` writes its lines.
template <class Row, class Name, class Point>
void writeCurves(const std::vector<Row>& rows, const char* columns, Name name, Point point,
                 std::ostream& out) {
  std::vector<std::string> curves;
  for (const Row& r : rows) {
    const std::string n = name(r);
    if (std::find(curves.begin(), curves.end(), n) == curves.end()) curves.push_back(n);
  }
  out << std::setprecision(6);
  bool first = true;
  for (const std::string& curve : curves) {
    if (!first) out << "\n\n";
    first = false;
    out << '"' << curve << "\" " << columns << '\n';
    for (const Row& r : rows) {
      if (name(r) == curve) point(r);
    }
  }
  out << '\n';
}

std::string withRounding(const std::string& name, const std::string& rounding) {
  return rounding.empty() ? name : name + " " + rounding;
}

}  // namespace

void writeTradeoffPlotData(const TradeStudyResult& result, std::ostream& out) {
  // Curves: each checker x rounding across resolutions; FCL is one point at 0 %.
  writeCurves(
      result.checks, "fp_percent mean_us resolution_cm",
      [](const CheckRow& r) { return withRounding(r.checker, r.rounding); },
      [&](const CheckRow& r) {
        out << 100 * r.fp_rate << ' ' << r.mean_us << ' ' << 100 * r.resolution << '\n';
      },
      out);
}

void writePlanningPlotData(const TradeStudyResult& result, std::ostream& out) {
  double lo = INFINITY, hi = 0;
  for (const PlanRow& r : result.planning) {
    if (r.resolution > 0) {
      lo = std::min(lo, r.resolution);
      hi = std::max(hi, r.resolution);
    }
  }
  writeCurves(
      result.planning, "resolution_cm median_time_s solved",
      [](const PlanRow& r) { return withRounding(r.planner + " " + r.checker, r.rounding); },
      [&](const PlanRow& r) {
        if (r.resolution > 0) {
          out << 100 * r.resolution << ' ' << r.median_time << ' ' << r.solved << '\n';
        } else if (hi > 0) {  // the exact checker: a flat line across the range
          out << 100 * lo << ' ' << r.median_time << ' ' << r.solved << '\n'
              << 100 * hi << ' ' << r.median_time << ' ' << r.solved << '\n';
        }
      },
      out);
}

}  // namespace octomotion
