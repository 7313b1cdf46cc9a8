// OMPL's own multi-threaded planners on one shared OctreeValidityChecker: ompl::tools::ParallelPlan
// (several RRTConnect instances solving together) and AnytimePathShortening (planners run in
// parallel, their paths shortened and hybridized) call isValid concurrently from their threads.
// Their solutions must be valid under a fresh, single-threaded checker and under FCL, and many
// threads checking one fixed-seed state set must get exactly the single-threaded answers. CI runs
// this test under ThreadSanitizer too (a data race in the checker is then a failure).
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/AnytimePathShortening.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/multiplan/ParallelPlan.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"

namespace octomotion {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

PlanningScene load(const char* scene_file, std::uint64_t seed) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  SceneOverrides overrides;
  overrides.checker = CheckerKind::kOctreeFused;
  overrides.seed = seed;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + scene_file, overrides);
  scene.setup->setup();
  return scene;
}

// The path is valid for a checker made for this check only (so nothing the planner threads did
// is involved): every state; every segment through the scene's own motion validator (the
// certified one, which keeps no state between calls; a discrete validator would check other
// states than the ones it proved the segment by). FCL (exact; octree rounding is conservative)
// finds no collision even at ten times the density. The path joins the scene's start to its goal.
void expectPathValid(const PlanningScene& scene, const og::PathGeometric& path) {
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  auto fresh_si = std::make_shared<ob::SpaceInformation>(si->getStateSpace());
  fresh_si->setStateValidityChecker(
      std::make_shared<OctreeValidityChecker>(fresh_si, scene.model, CheckerPath::kFused));
  fresh_si->setup();
  std::size_t invalid_states = 0, invalid_motions = 0;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    const ob::State* s = path.getState(static_cast<unsigned>(i));
    invalid_states += fresh_si->isValid(s) ? 0 : 1;
    if (i > 0) {
      invalid_motions += si->checkMotion(path.getState(static_cast<unsigned>(i - 1)), s) ? 0 : 1;
    }
  }
  EXPECT_EQ(invalid_states, 0u) << "of " << path.getStateCount() << " states";
  EXPECT_EQ(invalid_motions, 0u) << "of " << path.getStateCount() - 1 << " segments";

  og::PathGeometric dense(path);
  dense.interpolate(static_cast<unsigned>(10 * (path.getStateCount() - 1) + 1));
  const RobotModel& robot = scene.fcl_model->robot();
  auto fcl = scene.fcl_model->makeScratch();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t fcl_colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X_WB));
    scene.fcl_model->setConfiguration(q.data(), q.size(), X_WB, *fcl);
    fcl_colliding += scene.fcl_model->inCollision(*fcl) ? 1 : 0;
  }
  EXPECT_EQ(fcl_colliding, 0u) << "of " << dense.getStateCount() << " states";
  const auto& pdef = scene.setup->getProblemDefinition();
  EXPECT_LT(si->distance(path.getState(0), pdef->getStartState(0)), 1e-9);
  EXPECT_TRUE(
      pdef->getGoal()->isSatisfied(path.getState(static_cast<unsigned>(path.getStateCount() - 1))));
}

class MultiThreadedPlanners : public ::testing::TestWithParam<const char*> {};

// The planners run on the arm in the bookshelf, which RRTConnect solves in well under a second
// (the narrow passage takes tens of seconds, too long for a sanitizer build); the many-threads
// check below runs on both scenes.
TEST(MultiThreadedPlanning, ParallelPlanRrtConnectOnOneChecker) {
  PlanningScene scene = load("bookshelf.yaml", 11);
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const ob::ProblemDefinitionPtr& pdef = scene.setup->getProblemDefinition();
  ompl::tools::ParallelPlan parallel(pdef);
  for (int i = 0; i < 3; ++i) parallel.addPlanner(std::make_shared<og::RRTConnect>(si));
  // With hybridize, every planner runs until it has a solution (or the cap, for sanitizer
  // builds), then the paths are hybridized: many concurrent checks.
  const ob::PlannerStatus status = parallel.solve(300.0, /*hybridize=*/true);
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  const auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
  ASSERT_NE(path, nullptr);
  expectPathValid(scene, *path);
}

TEST(MultiThreadedPlanning, AnytimePathShorteningOnOneChecker) {
  PlanningScene scene = load("bookshelf.yaml", 12);
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  auto aps = std::make_shared<og::AnytimePathShortening>(si);
  for (int i = 0; i < 2; ++i) {
    ob::PlannerPtr planner = std::make_shared<og::RRTConnect>(si);
    aps->addPlanner(planner);
  }
  scene.setup->setPlanner(aps);
  // Anytime: it keeps improving until the time is up, so a short time with a solve-or-retry cap.
  ob::PlannerStatus status;
  for (int attempt = 0; attempt < 10 && status != ob::PlannerStatus::EXACT_SOLUTION; ++attempt) {
    status = scene.setup->solve(1.5);
  }
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  expectPathValid(scene, scene.setup->getSolutionPath());
}

// Many threads, one checker, one fixed-seed state set: exactly the single-threaded answers, for
// isValid, clearance (README: thread-safe) and checkMotion (the motion validator's interpolated
// states are checked too).
TEST_P(MultiThreadedPlanners, ManyThreadsGetTheSingleThreadedAnswers) {
  PlanningScene scene = load(GetParam(), 13);
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  auto sampler = si->allocStateSampler();
  const int n = 101;  // prime: every stride below visits every state once
  std::vector<ob::State*> states;
  for (int i = 0; i < n; ++i) {
    states.push_back(si->allocState());
    sampler->sampleUniform(states.back());
  }
  const ob::StateValidityChecker& checker = *si->getStateValidityChecker();
  std::vector<char> valid(n), motion(n);
  // clearance costs up to ~100 isValid calls: a subset of the states keeps the test fast (and
  // its ThreadSanitizer run in CI short).
  const int clearance_states = 17;
  std::vector<double> clearance(clearance_states);
  for (int i = 0; i < n; ++i) {
    valid[i] = si->isValid(states[i]);
    if (i < clearance_states) clearance[i] = checker.clearance(states[i]);
    motion[i] = si->checkMotion(states[i], states[(i + 1) % n]);
  }
  const auto valid_count = std::count(valid.begin(), valid.end(), 1);
  EXPECT_GT(valid_count, 0);
  EXPECT_LT(valid_count, n);  // both answers occur, so the comparison means something
  EXPECT_GT(std::count_if(clearance.begin(), clearance.end(), [](double c) { return c > 0; }), 0);

  const int threads = 8;
  std::vector<std::vector<char>> got_valid(threads, std::vector<char>(n));
  std::vector<std::vector<char>> got_motion(threads, std::vector<char>(n));
  std::vector<std::vector<double>> got_clearance(threads, std::vector<double>(clearance_states));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int k = 0; k < n; ++k) {
        const int i = (k * (2 * t + 1) + 31 * t) % n;
        got_valid[t][i] = si->isValid(states[i]);
        if (i < clearance_states) got_clearance[t][i] = checker.clearance(states[i]);
        got_motion[t][i] = si->checkMotion(states[i], states[(i + 1) % n]);
      }
    });
  }
  for (auto& th : pool) th.join();
  for (int t = 0; t < threads; ++t) {
    EXPECT_EQ(got_valid[t], valid) << "thread " << t;
    EXPECT_EQ(got_motion[t], motion) << "thread " << t;
    EXPECT_EQ(got_clearance[t], clearance) << "thread " << t;
  }
  for (auto* s : states) si->freeState(s);
}

INSTANTIATE_TEST_SUITE_P(Scenes, MultiThreadedPlanners,
                         ::testing::Values("narrow_passage.yaml", "bookshelf.yaml"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace octomotion
