// isValid is const and thread-safe: several threads checking the same states on one checker get
// exactly the single-threaded answers. CI also runs this test under ThreadSanitizer.
#include <gtest/gtest.h>

#include <thread>

#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

void checkConcurrently(const char* scene_file, CheckerKind checker, bool exact_primitives = false) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.checker = checker;
  overrides.exact_primitives = exact_primitives;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + scene_file, overrides);
  const auto si = scene.setup->getSpaceInformation();
  si->setup();
  auto sampler = si->allocStateSampler();
  const int n = 601;  // prime, so every stride below visits every state once
  std::vector<ompl::base::State*> states;
  for (int i = 0; i < n; ++i) {
    states.push_back(si->allocState());
    sampler->sampleUniform(states.back());
  }
  std::vector<char> expected(n);
  for (int i = 0; i < n; ++i) expected[i] = si->isValid(states[i]);
  const int valid = static_cast<int>(std::count(expected.begin(), expected.end(), 1));
  EXPECT_GT(valid, 0);
  EXPECT_LT(valid, n);  // both answers occur, so the comparison means something

  const int threads = 4;
  std::vector<std::vector<char>> got(threads, std::vector<char>(n));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      // Each thread walks the states in its own order so that they overlap in time.
      for (int k = 0; k < n; ++k) {
        const int i = (k * (2 * t + 1) + 17 * t) % n;
        got[t][i] = si->isValid(states[i]);
      }
    });
  }
  for (auto& th : pool) th.join();
  for (int t = 0; t < threads; ++t) EXPECT_EQ(got[t], expected) << "thread " << t;
  for (auto* s : states) si->freeState(s);
}

TEST(ThreadSafety, ArmFused) {
  checkConcurrently("bookshelf.yaml", CheckerKind::kOctreeFused);
}
TEST(ThreadSafety, ArmMoveTree) {
  checkConcurrently("bookshelf.yaml", CheckerKind::kOctree);
}
TEST(ThreadSafety, RigidFused) {
  checkConcurrently("narrow_passage.yaml", CheckerKind::kOctreeFused);
}
TEST(ThreadSafety, ArmFusedExactPrimitives) {
  checkConcurrently("cage.yaml", CheckerKind::kOctreeFused, true);
}
TEST(ThreadSafety, ArmFcl) {
  checkConcurrently("bookshelf.yaml", CheckerKind::kFcl);
}

}  // namespace
}  // namespace octomotion
