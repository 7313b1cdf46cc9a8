// Where an arm's octree check spends its time, split by what the answers are (docs/trade-off.md,
// "Reading the results"): uniform states are sorted into free / false positive (environment or
// self) / colliding with the environment / colliding with itself only, by FCL's and the fused
// octree checker's answers, and each class gets its mean forward-kinematics, environment-half
// and self-half time next to FCL's full check of the same states. A plain program (like
// tradeoff_bench): the numbers are per-class means, each phase timed with steady_clock (~20 ns
// of clock reads per phase), the states checked twice and the second pass kept. Usage:
//   build/bench/planner_check_breakdown_bench SCENE RESOLUTION [SELF_RATIO] [STATES]
//   e.g. robots/scenes/bookshelf.yaml 0.005 0.125 20000
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "joint_states.h"
#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace {

using namespace octomotion;
using Clock = std::chrono::steady_clock;

double us(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE RESOLUTION [SELF_RATIO] [STATES]\n", argv[0]);
    return 2;
  }
  const double resolution = std::atof(argv[2]);
  const double self_ratio = argc > 3 ? std::atof(argv[3]) : 1.0;
  const int count = argc > 4 ? std::atoi(argv[4]) : 20000;
  if (!(resolution > 0) || !(self_ratio > 0) || count < 1) {
    throw InvalidArgument("RESOLUTION and SELF_RATIO must be > 0, STATES >= 1");
  }
  SceneOverrides overrides;
  overrides.resolution = resolution;
  overrides.refine = RefineMode::kNone;  // the voxels' check, false positives included
  if (self_ratio != 1.0) overrides.self_link_resolution = resolution * self_ratio;
  overrides.require_free_start_goal = false;  // uniform states, not the problem
  const PlanningScene scene = loadPlanningScene(argv[1], overrides);
  const OctreeCollisionModel& octree = *scene.model;
  const RobotModel& robot = octree.robot();
  if (robot.isFreeFlying()) throw InvalidArgument("an arm scene is needed (joint states)");
  const auto fcl = scene.fclModel();
  const auto states = test::uniformJointStates(robot, count, 7);

  enum { kFree, kEnvFp, kSelfFp, kEnvHit, kSelfHit, kClasses };
  const char* names[kClasses] = {"free", "env false positive", "self false positive",
                                 "environment contact", "self contact only"};
  double fk[kClasses] = {}, env[kClasses] = {}, self[kClasses] = {}, ref[kClasses] = {};
  int n[kClasses] = {}, missed = 0;
  CheckScratch scratch = octree.makeScratch();
  auto exact = fcl->makeScratch();
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& q : states) {
      const auto t0 = Clock::now();
      robot.forwardKinematics(q.data(), q.size(), scratch.robot, octree.baseMount());
      const auto t1 = Clock::now();
      const bool e = octree.environmentInCollision(CheckerPath::kFused, scratch);
      const auto t2 = Clock::now();
      const bool s = !e && octree.selfInCollision(CheckerPath::kFused, scratch);
      const auto t3 = Clock::now();
      fcl->setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
      const bool f = fcl->inCollision(*exact);
      const auto t4 = Clock::now();
      if (pass == 0) continue;
      if (f && !e && !s) {
        ++missed;
        continue;
      }
      const int k = !f ? (e ? kEnvFp : s ? kSelfFp : kFree) : (e ? kEnvHit : kSelfHit);
      ++n[k];
      fk[k] += us(t0, t1);
      env[k] += us(t1, t2);
      self[k] += us(t2, t3);
      ref[k] += us(t3, t4);
    }
  }
  std::printf("%s at %g m, self trees %g m: %d states (%d missed contacts)\n", argv[1], resolution,
              octree.report().self_link_resolution, count, missed);
  std::printf("%-22s %6s %8s %8s %8s %8s   (per-state means, us)\n", "class", "states", "FK", "env",
              "self", "FCL");
  double total = 0, total_fcl = 0;
  for (int k = 0; k < kClasses; ++k) {
    const double d = n[k] > 0 ? n[k] : 1;
    std::printf("%-22s %6d %8.3f %8.3f %8.3f %8.3f\n", names[k], n[k], fk[k] / d, env[k] / d,
                self[k] / d, ref[k] / d);
    total += fk[k] + env[k] + self[k];
    total_fcl += ref[k];
  }
  std::printf("mean: octree %.3f us, FCL %.3f us, FCL / octree %.2f\n", total / count,
              total_fcl / count, total_fcl / total);
  return missed == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const octomotion::Error& e) {
    std::fprintf(stderr, "planner_check_breakdown_bench: %s\n", e.what());
    return 2;
  }
}
