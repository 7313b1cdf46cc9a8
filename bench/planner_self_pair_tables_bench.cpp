// What the self-pair tables (CollisionModelOptions::self_pair_tables, docs/planner.md) change in
// an arm's full check: the same scene and uniform states checked by the fused octree checker
// without and with them, and by FCL, in one run. Prints per model the build time, the mean check
// time (second pass over the states), false-positive rate (of the states FCL finds free, as in
// the trade study) and misses against FCL, and FCL's mean, and per table its variables, depth,
// classifications, certified shares and build time. A plain program like tradeoff_bench.
// Usage:
//   build/bench/planner_self_pair_tables_bench SCENE RESOLUTION [STATES] [SELF_RATIO] [LINK_RATIO]
//   e.g. robots/scenes/bookshelf.yaml 0.005 20000
// SELF_RATIO and LINK_RATIO (default 1) set the self-pair and link trees' voxels as fractions of
// RESOLUTION, like tradeoff_bench's --self-link-ratio and --link-ratio.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "joint_states.h"
#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE RESOLUTION [STATES] [SELF_RATIO] [LINK_RATIO]\n",
                 argv[0]);
    return 2;
  }
  const double resolution = std::atof(argv[2]);
  const int count = argc > 3 ? std::atoi(argv[3]) : 20000;
  const double self_ratio = argc > 4 ? std::atof(argv[4]) : 1.0;
  const double link_ratio = argc > 5 ? std::atof(argv[5]) : 1.0;
  if (!(resolution > 0) || !(self_ratio > 0 && self_ratio <= 1) ||
      !(link_ratio > 0 && link_ratio <= 1) || count < 1) {
    throw InvalidArgument(
        "RESOLUTION must be > 0, SELF_RATIO and LINK_RATIO in (0, 1], STATES >= 1");
  }
  SceneOverrides overrides;
  overrides.resolution = resolution;
  overrides.self_pair_tables = false;         // the scene's model is only used for its settings
  overrides.require_free_start_goal = false;  // uniform states, not the problem
  const PlanningScene scene = loadPlanningScene(argv[1], overrides);
  const RobotModel& robot = scene.model->robot();
  if (robot.isFreeFlying()) throw InvalidArgument("an arm scene is needed (joint states)");
  const auto states = test::uniformJointStates(robot, count, 7);

  const auto fcl = scene.fclModel();
  auto exact = fcl->makeScratch();
  std::vector<char> truth(states.size());
  double fcl_seconds = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < states.size(); ++i) {
      fcl->setConfiguration(states[i].data(), states[i].size(), Eigen::Isometry3d::Identity(),
                            *exact);
      truth[i] = fcl->inCollision(*exact);
    }
    fcl_seconds = seconds(t0, Clock::now());
  }
  std::printf("%s at %g m, %d uniform states, FCL: mean %.3f us\n", argv[1], resolution, count,
              1e6 * fcl_seconds / count);
  for (const bool tables : {false, true}) {
    CollisionModelOptions options;
    options.resolution = resolution;
    options.refine = RefineMode::kNone;  // the tables against the voxels alone
    options.link_resolution = resolution * link_ratio;
    options.self_link_resolution = resolution * self_ratio;
    options.X_WB = scene.model->baseMount();
    options.self_pair_tables = tables;
    const auto b0 = Clock::now();
    const OctreeCollisionModel model(robot, *scene.environment, options);
    const double build = seconds(b0, Clock::now());
    for (const SelfPairTableReport& r : model.report().self_pair_tables) {
      std::printf(
          "    table %s-%s: %d variables, depth %d, %zu classified, free %.1f %%, "
          "colliding %.1f %%, %.2f s\n",
          r.link_a.c_str(), r.link_b.c_str(), r.variables, r.depth, r.classified,
          100 * r.free_fraction, 100 * r.colliding_fraction, r.build_seconds);
    }
    CheckScratch scratch = model.makeScratch();
    int false_positives = 0, missed = 0;
    double check_seconds = 0;
    for (int pass = 0; pass < 2; ++pass) {
      false_positives = missed = 0;
      const auto t0 = Clock::now();
      for (std::size_t i = 0; i < states.size(); ++i) {
        const bool hit = model.inCollision(states[i].data(), states[i].size(), options.X_WB,
                                           CheckerPath::kFused, scratch);
        false_positives += hit && !truth[i];
        missed += !hit && truth[i];
      }
      check_seconds = seconds(t0, Clock::now());
    }
    const double mean = 1e6 * check_seconds / count;
    int free_states = 0;
    for (const char t : truth) free_states += !t;
    std::printf(
        "  octree-fused, tables %-3s: %zu tables, build %.2f s, mean %.3f us, FP %.2f %%, "
        "missed %d, FCL / octree %.2f\n",
        tables ? "on" : "off", model.report().self_pair_tables.size(), build, mean,
        100.0 * false_positives / std::max(free_states, 1), missed,
        1e6 * fcl_seconds / count / mean);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
