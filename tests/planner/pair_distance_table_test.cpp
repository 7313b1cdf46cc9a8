// The self pairs' distance table (robot/pair_distance_table.h) on the real Panda: it covers the
// pairs whose distance depends on at most two variables (its wrist pairs among them), and its
// bounds never exceed exact FCL's distance between the pair's two links, at random
// configurations and along random straight-line motions (FCL at dense samples), for a table built
// from FCL's distances and for the one the certified motion validator builds from exact refine's
// (a scene at the defaults). Fixed seeds; skipped without ../shared/data.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "joint_states.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/motion_bound.h"
#include "octomotion/planner/robot/pair_distance_table.h"

namespace octomotion {
namespace {

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
// FCL's own distance tolerance: the table is built from (and compared with) its answers.
constexpr double kTolerance = 1e-5;

RobotModel panda() {
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  return robot;
}

// Pair p's exact distance at q, by FCL on the two links' geometry.
double fclPairDistance(const FclCollisionModel& fcl, BackendScratch& scratch,
                       const std::pair<int, int>& pair, const std::vector<double>& q) {
  fcl.setPose(q.data(), q.size(), Eigen::Isometry3d::Identity(), scratch);
  return fcl.linkPairDistance(scratch, pair.first, pair.second,
                              std::numeric_limits<double>::infinity());
}

// The table's bounds at `states` random configurations, and along `motions` random motions
// (each at 200 states, half of them short), stay at or below FCL's distance; the bounds are
// positive at most configurations (a table of zeros would pass the rest).
void expectBelowFcl(const RobotModel& robot, const LinkMotionBound& bound,
                    const PairDistanceTable& table, int states, int motions, std::uint64_t seed) {
  const FclCollisionModel fcl(robot, EnvironmentGeometry::load({}));
  auto scratch = fcl.makeBackendScratch();
  std::mt19937_64 rng(seed);
  const std::vector<std::vector<double>> qs = test::uniformJointStates(robot, states, seed);
  const std::vector<std::vector<double>> ends =
      test::uniformJointStates(robot, 2 * motions, seed + 1);
  std::size_t compared = 0, positive = 0;
  for (std::size_t p = 0; p < bound.pairs().size(); ++p) {
    if (!table.covers(p)) continue;
    const std::pair<int, int>& pair = bound.pairs()[p];
    SCOPED_TRACE(robot.link(pair.first).name + " / " + robot.link(pair.second).name);
    for (int s = 0; s < states; ++s) {
      const std::vector<double>& q = qs[static_cast<std::size_t>(s)];
      const double lower = table.at(p, q.data());
      EXPECT_GE(lower, 0.0);
      EXPECT_LE(lower, fclPairDistance(fcl, *scratch, pair, q) + kTolerance) << "state " << s;
      positive += lower > 0 ? 1 : 0;
      ++compared;
    }
    for (int m = 0; m < motions; ++m) {
      const std::vector<double>& q1 = ends[2 * static_cast<std::size_t>(m)];
      std::vector<double> q2 = ends[2 * static_cast<std::size_t>(m) + 1];
      if (m % 2 == 1) {  // a short one, a tenth of the way
        for (std::size_t v = 0; v < q1.size(); ++v) q2[v] = q1[v] + 0.1 * (q2[v] - q1[v]);
      }
      const double a = std::uniform_real_distribution<double>(0.0, 0.5)(rng);
      const double b = std::uniform_real_distribution<double>(a, 1.0)(rng);
      const double lower = table.along(p, q1.data(), q2.data(), a, b);
      double least = std::numeric_limits<double>::infinity();
      std::vector<double> q(q1.size());
      for (int k = 0; k <= 200; ++k) {
        const double t = a + (b - a) * k / 200;
        for (std::size_t v = 0; v < q.size(); ++v) q[v] = q1[v] + (q2[v] - q1[v]) * t;
        least = std::min(least, fclPairDistance(fcl, *scratch, pair, q));
        // Any state of the motion: at most the whole motion's bound.
        if (k % 50 == 0) {
          EXPECT_LE(lower, table.at(p, q.data())) << "motion " << m;
        }
      }
      EXPECT_LE(lower, least + kTolerance) << "motion " << m;
    }
  }
  EXPECT_GT(positive, compared / 2);
}

TEST(PairDistanceTable, CoversThePandasWristPairsAndStaysBelowFcl) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  const RobotModel robot = panda();
  const LinkMotionBound bound(robot);
  const FclCollisionModel fcl(robot, EnvironmentGeometry::load({}));
  auto scratch = fcl.makeBackendScratch();
  const auto start = std::chrono::steady_clock::now();
  const PairDistanceTable table(robot, bound, [&](std::size_t p, const double* q, double cap) {
    fcl.setPose(q, static_cast<std::size_t>(robot.variableCount()), Eigen::Isometry3d::Identity(),
                *scratch);
    return fcl.linkPairDistance(*scratch, bound.pairs()[p].first, bound.pairs()[p].second, cap);
  });

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("build_seconds", std::to_string(seconds));
  RecordProperty("distance_calls", std::to_string(table.distanceCalls()));
  // Exactly the pairs with one or two variables of non-zero lever.
  for (std::size_t p = 0; p < bound.pairs().size(); ++p) {
    int moving = 0;
    for (int v = 0; v < robot.variableCount(); ++v) moving += bound.pairLever(p, v) > 0 ? 1 : 0;
    EXPECT_EQ(table.covers(p), moving == 1 || moving == 2) << p;
  }
  auto covered = [&](const std::string& a, const std::string& b) {
    for (std::size_t p = 0; p < bound.pairs().size(); ++p) {
      const std::string& first = robot.link(bound.pairs()[p].first).name;
      const std::string& second = robot.link(bound.pairs()[p].second).name;
      if ((first == a && second == b) || (first == b && second == a)) return table.covers(p);
    }
    return false;
  };
  EXPECT_TRUE(covered("panda_link5", "panda_link7"));
  EXPECT_TRUE(covered("panda_link5", "panda_hand"));
  expectBelowFcl(robot, bound, table, 1500, 60, 41);
}

// The table the validator builds at the defaults (exact refine: hull bounds, FCL near contact).
TEST(PairDistanceTable, TheValidatorsTableFromExactRefineStaysBelowFcl) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string path =
      (std::filesystem::temp_directory_path() / "octomotion_pair_distance_table.yaml").string();
  std::ofstream(path) << "robot: {urdf: " << kPanda << "/panda.urdf, srdf: " << kPanda
                      << "/panda.srdf}\n"
                      << "environment:\n"
                      << "  - {name: far, box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [5, 5, 5]}}\n"
                      << "octree: {resolution: 0.01}\n";
  PlanningScene scene = loadPlanningScene(path);
  scene.setup->setup();
  const auto* validator = dynamic_cast<const CertifiedMotionValidator*>(
      scene.setup->getSpaceInformation()->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  ASSERT_TRUE(validator->backend().exactAnswers());
  const PairDistanceTable* table = validator->pairTable();
  ASSERT_NE(table, nullptr);
  EXPECT_GE(table->tableCount(), 2u);
  const RobotModel& robot = scene.model->robot();
  expectBelowFcl(robot, LinkMotionBound(robot), *table, 1000, 40, 43);
}

}  // namespace
}  // namespace octomotion
