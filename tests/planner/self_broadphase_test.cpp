// The self-collision broad phase (SelfBroadPhase::kNObjectsOctree: an N-objects octree over the
// links' world boxes, after the N-objects octree report §2) must give exactly the answers of the
// all-pairs loop (kPairs), for both checker paths, on long chain robots, including SRDF-style
// filters that disable some of the pairs the broad phase reports; and stay per-thread.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <thread>

#include "environment_answers.h"
#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "snake_robot.h"

namespace octomotion {
namespace {

using test::snakeUrdf;

RobotModel snake(int links, double limit) {
  return RobotModel::fromUrdfString(snakeUrdf(links, limit), "snake.urdf", ".");
}

std::shared_ptr<const OctreeCollisionModel> model(
    RobotModel robot, SelfBroadPhase strategy,
    std::uint32_t leaf_capacity = kSelfBroadPhaseLeafCapacity) {
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.self_broad_phase = strategy;
  o.self_broad_phase_leaf_capacity = leaf_capacity;
  static const EnvironmentGeometry empty = EnvironmentGeometry::load({});
  return std::make_shared<const OctreeCollisionModel>(std::move(robot), empty, o);
}

std::vector<char> selfAnswers(const OctreeCollisionModel& m,
                              const std::vector<std::vector<double>>& states, CheckerPath path) {
  CheckScratch scratch = m.makeScratch();
  std::vector<char> hits;
  for (const auto& q : states) {
    m.robot().forwardKinematics(q.data(), q.size(), scratch.robot);
    hits.push_back(m.selfInCollision(path, scratch));
  }
  return hits;
}

// leaf_capacity: the default (one leaf) and small N, which splits the octree into many leaves
// (pairs spanning several leaves are reported once, by the leaf owning their overlap's corner).
void expectSameAnswers(RobotModel robot, int states_count, std::uint64_t seed,
                       std::uint32_t leaf_capacity) {
  const auto pairs = model(robot, SelfBroadPhase::kPairs);
  const auto octree = model(robot, SelfBroadPhase::kNObjectsOctree, leaf_capacity);
  ASSERT_EQ(pairs->selfBroadPhase(), SelfBroadPhase::kPairs);
  ASSERT_EQ(octree->selfBroadPhase(), SelfBroadPhase::kNObjectsOctree);
  const auto states = test::uniformJointStates(robot, states_count, seed);
  for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    const std::vector<char> expected = selfAnswers(*pairs, states, path);
    const std::vector<char> got = selfAnswers(*octree, states, path);
    const auto hits = std::count(expected.begin(), expected.end(), 1);
    // Both answers must occur often, or the comparison says little.
    EXPECT_GT(hits, states_count / 10);
    EXPECT_LT(hits, states_count - states_count / 10);
    for (std::size_t i = 0; i < states.size(); ++i) {
      ASSERT_EQ(got[i], expected[i]) << "state " << i << " path " << static_cast<int>(path);
    }
  }
}

TEST(SelfBroadPhase, OctreeMatchesAllPairsOn30LinkSnake) {
  expectSameAnswers(snake(30, 2.0), 3000, 7, kSelfBroadPhaseLeafCapacity);
}

TEST(SelfBroadPhase, SubdividedOctreeMatchesAllPairsOn30LinkSnake) {
  expectSameAnswers(snake(30, 2.0), 2000, 8, 4);
  expectSameAnswers(snake(30, 2.0), 1500, 9, 16);
}

TEST(SelfBroadPhase, OctreeMatchesAllPairsWithPairsDisabled) {
  // Disabling every (i, i+2) and (i, i+3) pair: the broad phase reports such overlapping pairs
  // (they are close), and they must be skipped exactly as the all-pairs loop skips them.
  RobotModel robot = snake(26, 2.2);
  for (int i = 0; i + 3 < robot.linkCount(); ++i) {
    robot.disableCollision(i, i + 2);
    robot.disableCollision(i, i + 3);
  }
  expectSameAnswers(robot, 2000, 11, kSelfBroadPhaseLeafCapacity);
  expectSameAnswers(std::move(robot), 2000, 12, 4);
}

TEST(SelfBroadPhase, AutoFollowsTheMeasuredLinkThreshold) {
  const int at = kSelfBroadPhaseAutoLinks;
  EXPECT_EQ(model(snake(at - 1, 1.0), SelfBroadPhase::kAuto)->selfBroadPhase(),
            SelfBroadPhase::kPairs);
  const auto big = model(snake(at, 1.0), SelfBroadPhase::kAuto);
  EXPECT_EQ(big->selfBroadPhase(), SelfBroadPhase::kNObjectsOctree);
  EXPECT_EQ(big->report().self_links, static_cast<std::size_t>(at));
  EXPECT_NE(big->report().toString().find("N-objects octree"), std::string::npos);
}

TEST(SelfBroadPhase, ScratchWithoutBroadPhaseStillWorks) {
  // A default-constructed scratch (no octree yet) gets one on first use.
  const RobotModel robot = snake(24, 1.2);
  const auto octree = model(robot, SelfBroadPhase::kNObjectsOctree);
  const auto pairs = model(robot, SelfBroadPhase::kPairs);
  const auto states = test::uniformJointStates(robot, 200, 3);
  CheckScratch scratch;
  scratch.robot = robot.makeData();
  CheckScratch reference = pairs->makeScratch();
  for (const auto& q : states) {
    robot.forwardKinematics(q.data(), q.size(), scratch.robot);
    robot.forwardKinematics(q.data(), q.size(), reference.robot);
    EXPECT_EQ(octree->selfInCollision(CheckerPath::kFused, scratch),
              pairs->selfInCollision(CheckerPath::kFused, reference));
  }
  EXPECT_TRUE(scratch.self_broad_phase.has_value());
}

TEST(SelfBroadPhase, ThreadsWithTheirOwnScratchAgree) {
  const RobotModel robot = snake(40, 1.2);
  const auto octree = model(robot, SelfBroadPhase::kNObjectsOctree);
  const auto states = test::uniformJointStates(robot, 601, 5);  // prime: every stride visits all
  const std::vector<char> expected =
      selfAnswers(*model(robot, SelfBroadPhase::kPairs), states, CheckerPath::kFused);
  const int threads = 4;
  std::vector<std::vector<char>> got(threads, std::vector<char>(states.size()));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      CheckScratch scratch = octree->makeScratch();
      const std::size_t n = states.size();
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = (k * static_cast<std::size_t>(2 * t + 1) + 7) % n;
        got[static_cast<std::size_t>(t)][i] =
            octree->inCollision(states[i].data(), states[i].size(), Eigen::Isometry3d::Identity(),
                                CheckerPath::kFused, scratch);
      }
    });
  }
  for (auto& th : pool) th.join();
  for (int t = 0; t < threads; ++t) EXPECT_EQ(got[static_cast<std::size_t>(t)], expected);
}

// The environment pre-test over the objects' own boxes (EnvironmentPreTest::kObjectBoxes) only
// skips links that cannot touch any object: same answers as the single environment box, with
// 12 to 70 rotated boxes (also tested in their own frames) and an upright pole reaching out of
// the universe.
TEST(EnvironmentPreTest, ObjectBoxesMatchEnvironmentBox) {
  const RobotModel robot = snake(7, 1.5);
  const auto states = test::uniformJointStates(robot, 2000, 4);
  for (const int count : {12, 30, 70}) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<EnvironmentObject> objects;
    const double size = 0.01 + 0.2 / count;
    for (int i = 0; i < count; ++i) {
      EnvironmentObject box;
      box.name = "box" + std::to_string(i);
      box.primitive = Box{
          Eigen::Vector3d(size + 0.03 * std::abs(u(rng)), size + 0.03 * std::abs(u(rng)), 0.02)};
      box.X_WO.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
      box.X_WO.translation() = 0.6 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      objects.push_back(box);
    }
    objects.back().primitive = Cylinder{0.02, 5.0};
    objects.back().X_WO = Eigen::Isometry3d(Eigen::Translation3d(0.3, -0.2, 0));
    const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
    CollisionModelOptions o;
    o.resolution = 0.01;
    o.refine = RefineMode::kNone;  // the voxels' answers
    o.link_resolution = 0.01;      // the moveTree path below materialises every link leaf
    const OctreeCollisionModel automatic(robot, env, o);
    EXPECT_EQ(automatic.report().environment_pre_test, EnvironmentPreTest::kObjectBoxes);
    EXPECT_EQ(automatic.report().environment_object_boxes, objects.size());
    o.environment_pre_test = EnvironmentPreTest::kEnvironmentBox;
    const OctreeCollisionModel merged_box(robot, env, o);
    EXPECT_EQ(merged_box.report().environment_pre_test, EnvironmentPreTest::kEnvironmentBox);
    for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
      const std::string what = std::to_string(count) + " objects";
      const int hits = test::environmentHitsIfSame(automatic, merged_box, states, path, what);
      ASSERT_GE(hits, 0);
      EXPECT_GT(hits, 100) << what;  // both answers are exercised
      EXPECT_LT(hits, 1900) << what;
    }
  }
}

// The universe's origin: the lowest corner of the environment the robot reaches, or 1-3 voxels
// below it, whichever gives the environment tree the fewest nodes (kOriginShifts). Checked
// against the four trees built here, on boxes at round coordinates (whose tree size depends on
// the shift) at two resolutions.
TEST(EnvironmentUniverse, KeepsTheShiftWithTheFewestNodes) {
  std::vector<EnvironmentObject> objects;
  const double boxes[][6] = {{0.3, 0.2, 0.25, 0.1, 0.4, 0.05},
                             {-0.4, 0.1, 0.5, 0.05, 0.3, 0.5},
                             {0.1, -0.45, 0.2, 0.35, 0.05, 0.2}};
  for (const auto& b : boxes) {
    EnvironmentObject box;
    box.name = "box" + std::to_string(objects.size());
    box.primitive = Box{Eigen::Vector3d(b[3], b[4], b[5])};
    box.X_WO.translation() = Eigen::Vector3d(b[0], b[1], b[2]);
    objects.push_back(box);
  }
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  int shifted = 0;
  for (const double res : {0.02, 0.005}) {
    CollisionModelOptions o;
    o.resolution = res;
    o.refine = RefineMode::kNone;  // the voxels' answers
    const OctreeCollisionModel m(snake(4, 1.5), env, o);
    const Eigen::AlignedBox3d region = env.bounds()->intersection(m.report().reach_W);
    std::size_t fewest = 0;
    int best = -1;
    for (int k = 0; k < kOriginShifts; ++k) {
      const WorldGrid g(region.min() - Eigen::Vector3d::Constant(k * res), res, m.grid().depth());
      const std::size_t nodes = env.voxelize(g, o.rounding).internalNodeCount();
      if (best < 0 || nodes < fewest) {
        fewest = nodes;
        best = k;
      }
    }
    EXPECT_EQ(m.environment().internalNodeCount(), fewest) << res;
    EXPECT_TRUE(m.grid().origin().isApprox(region.min() - Eigen::Vector3d::Constant(best * res)))
        << res << ": shift " << best;
    EXPECT_EQ(m.report().grid, m.grid());
    shifted += best > 0;
  }
  EXPECT_GT(shifted, 0);  // the search mattered at least once here
}

}  // namespace
}  // namespace octomotion
