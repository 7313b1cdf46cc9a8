// The trade study's runner: the scene, the state set, the timed passes of every setting.
#include "octomotion/tools/trade_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <memory>
#include <ostream>
#include <random>

#include <ompl/util/RandomNumbers.h>

#include "octomotion/octree/mesh.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/reference/fcl_octomap_collision_model.h"
#include "study_format.h"
#include "trade_study_internal.h"

namespace octomotion {

namespace ob = ompl::base;
using Clock = std::chrono::steady_clock;

using namespace trade_study_internal;

namespace {

double micros(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

StudyScene studyScene(SceneInputs inputs) {
  StudyScene s;
  s.spec = std::move(inputs.spec);
  s.robot = std::move(inputs.robot);
  s.environment = std::move(inputs.environment);
  s.resolution = *s.spec.octree.resolution;
  if (s.robot->isFreeFlying()) {
    s.robot_diagonal = inputs.robot_diagonal;
    s.bounds = s.spec.problem.bounds;
  } else {
    s.robot_diagonal = robotGeometryBox(*s.robot).diagonal().norm();
  }
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
void fillRow(const Measurement& m, const Measurement& reference_m, bool keep_answers,
             CheckRow& row) {
  if (keep_answers) row.answers = m.answers;
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

TradeStudyResult runTradeStudy(const TradeStudyOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  // By value: the models keep a copy of the sink.
  const WarningSink warnings = [progress = options.progress](const std::string& w) {
    if (progress) progress("warning: " + w);
  };
  if (options.states == 0) throw InvalidArgument("trade study: states must be > 0");
  const StudyScene scene =
      studyScene(loadSceneInputs(options.scene_path, options.overrides, warnings));
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
      robot, environment, spec.robot.keep_mesh_root_transform, spec.robot.center_mesh_vertices,
      spec.robot.pose.value_or(Eigen::Isometry3d::Identity()));
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
    row.checker = CheckerKind::kFcl;
    fillRow(fcl_m, fcl_m, options.keep_answers, row);
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
    plan_settings.push_back({CheckerKind::kFcl, "", 0, [fcl](const ob::SpaceInformationPtr& si) {
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
            spec.robot.center_mesh_vertices,
            spec.robot.pose.value_or(Eigen::Isometry3d::Identity()));
        const Measurement m = measureFclLike(*octomap, states, states.count, fcl_check);
        CheckRow row;
        row.scene = spec.name;
        row.checker = CheckerKind::kFclOctomap;
        row.resolution = resolution;
        fillRow(m, fcl_m, options.keep_answers, row);
        row.memory_bytes = octomap->octomapBytes();
        row.build_seconds = octomap->buildSeconds();
        row.speedup_vs_fcl = m.speedup;
        result.checks.push_back(row);
        octomap_scratch = octomap->makeScratch();
        octomap_env_check = [&states, &octomap, &octomap_scratch](std::size_t i) {
          octomap->setConfiguration(states.at(i), states.dof, states.X_WB[i], *octomap_scratch);
          return octomap->environmentInCollision(*octomap_scratch);
        };
        say(spec.name + ": " + settingName(CheckerKind::kFclOctomap, resolution, "") + " " +
            fmt(row.mean_us) + " us mean");
        if (planning && (options.plan_every_setting || resolution == scene_rung)) {
          plan_settings.push_back({CheckerKind::kFclOctomap, "", resolution,
                                   [octomap](const ob::SpaceInformationPtr& si) {
                                     return std::make_shared<FclOctomapValidityChecker>(si,
                                                                                        octomap);
                                   }});
        }
      } catch (const Error& e) {
        say(spec.name + ": fcl-octomap at " + resolutionLabel(resolution) +
            " skipped: " + e.what());
      }
    }
    // Each rounding as given, then (refine_exact) conservative rounding refined with FCL.
    std::vector<std::pair<Rounding, RefineMode>> modes;
    for (Rounding rounding : options.roundings) modes.emplace_back(rounding, RefineMode::kNone);
    if (options.refine_exact) modes.emplace_back(Rounding::kConservative, RefineMode::kExact);
    for (const auto& [rounding, refine] : modes) {
      CollisionModelOptions mo;
      mo.refine = refine;
      mo.resolution = resolution;
      mo.link_resolution = resolution * result.link_resolution_ratio;
      mo.self_link_resolution = resolution * result.self_link_resolution_ratio;
      mo.rounding = rounding;
      mo.self_pair_tables = spec.octree.self_pair_tables;
      mo.exact_primitives = spec.octree.exact_primitives && rounding == Rounding::kConservative;
      if (spec.octree.max_surface_voxels) mo.max_surface_voxels = *spec.octree.max_surface_voxels;
      mo.base_position_bounds = scene.bounds;
      if (spec.robot.pose) mo.X_WB = *spec.robot.pose;
      mo.keep_mesh_root_transform = spec.robot.keep_mesh_root_transform;
      mo.center_mesh_vertices = spec.robot.center_mesh_vertices;
      mo.warnings = warnings;
      std::shared_ptr<const OctreeCollisionModel> model;
      double build = 0;
      try {
        t0 = Clock::now();
        // The shared objects: no copy per setting (the model keeps them for explanations).
        model = std::make_shared<const OctreeCollisionModel>(robot, scene.environment, mo);
        build = seconds(t0, Clock::now());
        if (!free_flying) motion_reach = model->report().reach_W.sizes().maxCoeff() / 2;
      } catch (const Error& e) {
        say(spec.name + ": octree at " + resolutionLabel(resolution) + " skipped: " + e.what());
        continue;
      }
      for (CheckerKind checker : options.octree_checkers) {
        const CheckerPath path = octreeCheckerPath(checker);
        const std::size_t count = path == CheckerPath::kMoveTree && options.move_tree_states > 0
                                      ? std::min(options.move_tree_states, states.count)
                                      : states.count;
        const Measurement m =
            measureOctree(*model, path, states, count, fcl_check, octomap_env_check);
        CheckRow row;
        row.scene = spec.name;
        row.checker = checker;
        row.resolution = resolution;
        row.rounding =
            std::string(toString(rounding)) + (refine == RefineMode::kExact ? "+exact" : "");
        fillRow(m, fcl_m, options.keep_answers, row);
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
    // OMPL takes a seed before its first generator exists: a later study in the same process
    // with the same seed needs nothing, one with another seed has OMPL report that it cannot.
    const auto seed = static_cast<std::uint_fast32_t>(options.seed);
    if (ompl::RNG::getSeed() != seed) ompl::RNG::setSeed(seed);
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

}  // namespace octomotion
