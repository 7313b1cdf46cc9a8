// Exact refine mode (CollisionModelOptions::refine, docs/planner.md "Exact refine mode") on the
// real Panda in MotionBenchMaker scenes: per scene, the same uniform joint states checked by
// exact FCL, by the fused octree checker with conservative rounding, and by the same checker
// refined with FCL, in one run. Prints per checker the mean check time (the thread's CPU time,
// fastest of kPasses passes over the states), the share of FCL-free states it rejects (false
// positives), the contacts it misses, and FCL's mean over its own. A plain program like
// planner_self_pair_tables_bench; needs
// ../shared/data (MotionBenchMaker problems and the Panda).
// For the refined rows also, per check: the contacts certain without FCL, the links (against
// the environment) and link pairs FCL decided, the link pairs cleared by their hulls, and the
// self contacts certain without FCL (closed meshes whose surfaces cross).
// SETTINGS picks rows (digits 0-3, e.g. 01 for a quick profile without the self-pair tables'
// build); LINK_RATIO, when given, sets the refined rows' link trees to RESOLUTION x LINK_RATIO
// (and their self trees with them), to choose that resolution by measurement.
// SCENE files, when given, are measured after the MotionBenchMaker scenes (SETS 0: instead of
// them): scene YAML files such as robots/scenes/*.yaml, each with its own robot.
// Usage: build/bench/planner_refine_bench [STATES] [SETS] [RESOLUTION] [SETTINGS] [LINK_RATIO]
//        [SCENE ...]   (default 5000 4 0.01 0123, the library's link trees)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ompl/util/Console.h>

#include "joint_states.h"
#include "mbm_problems.h"
#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

// Each checker's time is its fastest pass over the states: on a shared machine the other
// passes only add other programs' load.
constexpr int kPasses = 4;

// The checking thread's CPU time: on a shared machine, wall time also counts the time the
// thread waits for a core, which differs between the rows of one run.
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

int run(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 5000;
  const int sets = argc > 2 ? std::atoi(argv[2]) : 4;
  const double resolution = argc > 3 ? std::atof(argv[3]) : 0.01;
  const std::string settings = argc > 4 ? argv[4] : "0123";
  const double exact_link_ratio = argc > 5 ? std::atof(argv[5]) : 0;
  if (count < 1 || sets < 0 || !(resolution > 0)) {
    throw InvalidArgument("STATES must be >= 1, SETS >= 0, RESOLUTION > 0");
  }
  // (name, scene file): the first problem of each MotionBenchMaker set, then the SCENE files.
  std::vector<std::pair<std::string, std::string>> scenes;
  std::optional<test::MbmProblems> extracted;  // its folder lives until the end
  if (sets > 0) {
    const test::MbmProblems& problems = extracted.emplace();
    const std::string panda = test::MbmProblems::panda();
    if (problems.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
      throw InvalidArgument("no MotionBenchMaker problems or Panda under ../shared/data");
    }
    std::vector<test::MbmProblem> first = problems.firstOfEachSet();
    first.resize(std::min<std::size_t>(first.size(), static_cast<std::size_t>(sets)));
    for (const test::MbmProblem& p : first) {
      const std::string scene_path = problems.folder() + "/" + p.set + "_bench.yaml";
      test::MbmProblems::writeScene(scene_path, p);
      scenes.emplace_back(p.set, scene_path);
    }
  }
  for (int i = 6; i < argc; ++i) {
    scenes.emplace_back(std::filesystem::path(argv[i]).stem().string(), argv[i]);
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  std::printf("%s at %g m, %d uniform states per scene; mean check time\n",
              sets > 0 ? "Panda (7 planned joints)" : "Each scene's robot", resolution, count);
  for (const auto& [name, scene_path] : scenes) {
    SceneOverrides overrides;
    overrides.resolution = resolution;
    overrides.require_free_start_goal = false;
    const PlanningScene scene = loadPlanningScene(scene_path, overrides, [](const std::string&) {});
    const RobotModel& robot = scene.model->robot();
    if (robot.isFreeFlying()) throw InvalidArgument(scene_path + ": not a fixed-base arm");
    const auto states = test::uniformJointStates(robot, count, 7);
    const auto fcl = scene.fclModel();
    auto exact = fcl->makeScratch();
    std::vector<char> truth(states.size());
    double fcl_seconds = std::numeric_limits<double>::infinity();
    for (int pass = 0; pass < kPasses; ++pass) {
      const double t0 = cpuSeconds();
      for (std::size_t i = 0; i < states.size(); ++i) {
        fcl->setConfiguration(states[i].data(), states[i].size(), Eigen::Isometry3d::Identity(),
                              *exact);
        truth[i] = fcl->inCollision(*exact);
      }
      fcl_seconds = std::min(fcl_seconds, cpuSeconds() - t0);
    }
    int free_states = 0;
    for (const char t : truth) free_states += !t;
    const double fcl_mean = 1e6 * fcl_seconds / count;
    std::printf("%s: %.1f %% of the states free for FCL\n", name.c_str(),
                100.0 * free_states / count);
    std::printf("  %-22s mean %8.3f us\n", "fcl", fcl_mean);
    // The library's default trees, then refined; then refined with the self pairs' trees at the
    // link trees' voxel (a narrower self margin leaves fewer pairs to FCL); then refined with
    // self-pair tables (cells certified by FCL at build time skip the pair's tests).
    for (int setting = 0; setting < 4; ++setting) {
      if (settings.find(static_cast<char>('0' + setting)) == std::string::npos) continue;
      const RefineMode refine = setting == 0 ? RefineMode::kNone : RefineMode::kExact;
      CollisionModelOptions options;
      options.resolution = resolution;
      options.X_WB = scene.model->baseMount();
      options.refine = refine;
      if (refine == RefineMode::kExact && exact_link_ratio > 0) {
        options.link_resolution = resolution * exact_link_ratio;
      }
      if (setting == 2) options.self_link_resolution = resolution * kDefaultLinkResolutionRatio;
      options.self_pair_tables = setting == 3;
      const auto b0 = Clock::now();
      const OctreeCollisionModel model(robot, *scene.environment, options);
      const double build = seconds(b0, Clock::now());
      CheckScratch scratch = model.makeScratch();
      int false_positives = 0, missed = 0;
      double check_seconds = std::numeric_limits<double>::infinity();
      RefineCounts counts;
      for (int pass = 0; pass < kPasses; ++pass) {
        const RefineCounts start = model.refineCounts(scratch);
        false_positives = missed = 0;
        const double t0 = cpuSeconds();
        for (std::size_t i = 0; i < states.size(); ++i) {
          const bool hit = model.inCollision(states[i].data(), states[i].size(), options.X_WB,
                                             CheckerPath::kFused, scratch);
          false_positives += hit && !truth[i];
          missed += !hit && truth[i];
        }
        check_seconds = std::min(check_seconds, cpuSeconds() - t0);
        const RefineCounts end = model.refineCounts(scratch);
        counts = {end.certain_contacts - start.certain_contacts,
                  end.fcl_links - start.fcl_links,
                  end.fcl_pairs - start.fcl_pairs,
                  end.hull_apart_pairs - start.hull_apart_pairs,
                  end.certain_self_contacts - start.certain_self_contacts,
                  end.hull_apart_objects - start.hull_apart_objects,
                  end.hull_apart_links - start.hull_apart_links,
                  end.grid_clear_links - start.grid_clear_links};
      }
      const double mean = 1e6 * check_seconds / count;
      std::printf("  %-22s mean %8.3f us, FP %5.2f %%, missed %d, FCL / this %5.2f, build %.2f s\n",
                  setting == 0   ? "octree-fused none"
                  : setting == 1 ? "octree-fused exact"
                  : setting == 2 ? "exact, self at r/4"
                                 : "exact, self tables",
                  mean, 100.0 * false_positives / std::max(free_states, 1), missed, fcl_mean / mean,
                  build);
      if (refine == RefineMode::kExact) {
        std::printf(
            "  %-22s per check: certain contacts %.3f, FCL links %.3f, FCL pairs %.3f, "
            "hull-apart pairs %.3f, certain self contacts %.3f, hull-apart objects %.3f, "
            "hull-apart links %.3f, grid-clear links %.3f\n",
            "", static_cast<double>(counts.certain_contacts) / count,
            static_cast<double>(counts.fcl_links) / count,
            static_cast<double>(counts.fcl_pairs) / count,
            static_cast<double>(counts.hull_apart_pairs) / count,
            static_cast<double>(counts.certain_self_contacts) / count,
            static_cast<double>(counts.hull_apart_objects) / count,
            static_cast<double>(counts.hull_apart_links) / count,
            static_cast<double>(counts.grid_clear_links) / count);
      }
    }
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
