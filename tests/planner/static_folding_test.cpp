// CollisionModelOptions::fold_static: links no joint moves are tested against the environment
// once, and self pairs with no joint between them once, at build time. The answers must equal
// those of the model without folding in every state (both halves, both checker paths), the
// report must list exactly the links and pairs a brute-force look at the kinematics finds
// constant, and a folded contact must make every state collide.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/held_joints.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {
namespace {

using ::testing::HasSubstr;

const std::string kUrdfDir = std::string(OCTOMOTION_TEST_DATA_DIR) + "/urdf";
const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

// A base and a column bolted together (overlapping by 2 cm), an arm turning on the column, a
// clamp bolted to the arm's end, a lamp bolted above the arm (base-lamp: a constant pair).
const char* kPostBot = R"(<?xml version="1.0"?>
<robot name="post_bot">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="mount" type="fixed"><parent link="base"/><child link="column"/>
    <origin xyz="0 0 0.28"/></joint>
  <link name="column"><collision><geometry><cylinder radius="0.05" length="0.4"/></geometry>
  </collision></link>
  <joint name="turn" type="revolute"><parent link="column"/><child link="arm"/>
    <origin xyz="0 0 0.25"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="arm"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.6 0.05 0.05"/>
  </geometry></collision></link>
  <joint name="clamp" type="fixed"><parent link="arm"/><child link="clamp_link"/>
    <origin xyz="0.6 0 0"/></joint>
  <link name="clamp_link"><collision><geometry><box size="0.1 0.1 0.1"/></geometry>
  </collision></link>
  <joint name="lamp_mount" type="fixed"><parent link="column"/><child link="lamp"/>
    <origin xyz="0 0 0.42"/></joint>
  <link name="lamp"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
</robot>)";

EnvironmentObject box(const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
  EnvironmentObject o;
  o.primitive = Box{size / 2};
  o.X_WO.translation() = centre;
  o.name = "box";
  return o;
}

struct Models {
  OctreeCollisionModel folded, unfolded;
};

Models build(const RobotModel& robot, const std::vector<EnvironmentObject>& objects,
             std::vector<std::string>* warnings = nullptr) {
  const EnvironmentGeometry environment = EnvironmentGeometry::load(objects);
  CollisionModelOptions options;
  options.resolution = 0.02;
  options.refine = RefineMode::kNone;  // the voxels' answers
  options.warnings = [warnings](const std::string& m) {
    if (warnings) warnings->push_back(m);
  };
  CollisionModelOptions off = options;
  off.fold_static = false;
  off.warnings = [](const std::string&) {};
  return {OctreeCollisionModel(robot, environment, options),
          OctreeCollisionModel(robot, environment, off)};
}

// Both halves on both paths, state by state; returns how many states collide.
std::size_t expectSameAnswers(const Models& m, int states, std::uint64_t seed) {
  CheckScratch a = m.folded.makeScratch(), b = m.unfolded.makeScratch();
  const RobotModel& robot = m.folded.robot();
  std::size_t colliding = 0;
  for (const std::vector<double>& q : test::uniformJointStates(robot, states, seed)) {
    robot.forwardKinematics(q.data(), q.size(), a.robot);
    robot.forwardKinematics(q.data(), q.size(), b.robot);
    for (CheckerPath path : {CheckerPath::kMoveTree, CheckerPath::kFused}) {
      const bool env = m.unfolded.environmentInCollision(path, b);
      const bool self = m.unfolded.selfInCollision(path, b);
      EXPECT_EQ(m.folded.environmentInCollision(path, a), env);
      EXPECT_EQ(m.folded.selfInCollision(path, a), self);
      colliding += (env || self) && path == CheckerPath::kFused;
    }
  }
  return colliding;
}

// Brute force: poses at random states, compared with the first.
void expectReportMatchesKinematics(const Models& m) {
  const RobotModel& robot = m.folded.robot();
  const std::vector<std::vector<double>> states = test::uniformJointStates(robot, 30, 5);
  std::vector<RobotData> poses;
  for (const std::vector<double>& q : states) {
    poses.push_back(robot.makeData());
    robot.forwardKinematics(q.data(), q.size(), poses.back());
  }
  auto constant = [&](auto pose_of) {
    for (const RobotData& d : poses) {
      if (!(pose_of(d).matrix() - pose_of(poses.front()).matrix()).isZero(1e-12)) return false;
    }
    return true;
  };
  const CollisionModelReport& on = m.folded.report();
  const CollisionModelReport& off = m.unfolded.report();
  std::vector<std::string> static_links, still_tested;
  for (const std::string& name : off.environment_order) {
    const int l = robot.linkIndex(name);
    const bool fixed =
        !robot.isFreeFlying() && constant([&](const RobotData& d) { return d.linkPose(l); });
    (fixed ? static_links : still_tested).push_back(name);
  }
  EXPECT_EQ(std::set<std::string>(on.static_links.begin(), on.static_links.end()),
            std::set<std::string>(static_links.begin(), static_links.end()));
  EXPECT_EQ(std::set<std::string>(on.environment_order.begin(), on.environment_order.end()),
            std::set<std::string>(still_tested.begin(), still_tested.end()));
  std::set<std::pair<std::string, std::string>> pairs;  // brute force
  for (const auto& [a, b] : robot.checkedPairs()) {
    if (!off.links[static_cast<std::size_t>(a)].modelled ||
        !off.links[static_cast<std::size_t>(b)].modelled) {
      continue;
    }
    if (constant([&](const RobotData& d) { return d.linkPose(a).inverse() * d.linkPose(b); })) {
      pairs.emplace(robot.link(a).name, robot.link(b).name);
    }
  }
  using Pairs = std::set<std::pair<std::string, std::string>>;
  EXPECT_EQ(Pairs(on.constant_pairs.begin(), on.constant_pairs.end()), pairs);
  EXPECT_EQ(on.self_pairs + on.constant_pairs.size(), off.self_pairs);
}

TEST(StaticFolding, ArmWithHeldWristAndGripper) {
  RobotModel arm = RobotModel::fromUrdfFile(kUrdfDir + "/arm.urdf");
  arm.loadSrdfFile(kUrdfDir + "/arm_groups.srdf");
  // The SRDF disables these pairs because they are in contact in every state (below).
  arm.enableCollision("fore", "finger_left");
  arm.enableCollision("fore", "finger_right");
  // Wrist and slider held: the hand and fingers move with the forearm only.
  const RobotModel reduced = holdJoints(arm, {0, 1}, {0, 0, 0.4, 0.03});
  const Models m =
      build(reduced, {box({0.9, 0.9, 0.1}, {0.2, 0.2, 0.4}), box({0, 0, -0.1}, {1, 1, 0.02})});
  const CollisionModelReport& report = m.folded.report();
  EXPECT_THAT(report.static_links, ::testing::ElementsAre("base"));  // over the floor
  // The test arm's fingers sit inside its forearm's tetrahedron: the two constant pairs are in
  // contact, so every state is; exact FCL agrees.
  ASSERT_EQ(report.static_collisions.size(), 2u) << report.toString();
  EXPECT_THAT(report.static_collisions[0], HasSubstr("'fore' and 'finger_left'"));
  EXPECT_THAT(report.static_collisions[1], HasSubstr("'fore' and 'finger_right'"));
  const FclCollisionModel fcl(reduced, EnvironmentGeometry::load({}));
  auto scratch = fcl.makeScratch();
  for (const std::vector<double>& q : test::uniformJointStates(reduced, 20, 9)) {
    fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch);
    EXPECT_TRUE(fcl.selfInCollision(*scratch));
  }
  expectReportMatchesKinematics(m);
  EXPECT_EQ(expectSameAnswers(m, 300, 1), 300u);
  EXPECT_THAT(report.toString(), HasSubstr("static links"));
}

TEST(StaticFolding, UrdfWithFixedJointsAndNoGroup) {
  const RobotModel bot = RobotModel::fromUrdfString(kPostBot, "post_bot.urdf", kUrdfDir);
  const Models m =
      build(bot, {box({0.5, 0.3, 0.55}, {0.1, 0.1, 0.1}), box({0.3, 0, 0.1}, {0.2, 0.2, 0.2})});
  EXPECT_TRUE(m.folded.report().static_collisions.empty()) << m.folded.report().toString();
  EXPECT_FALSE(m.folded.report().static_links.empty());
  EXPECT_FALSE(m.folded.report().constant_pairs.empty());  // base-lamp
  expectReportMatchesKinematics(m);
  EXPECT_GT(expectSameAnswers(m, 300, 2), 0u);  // the arm reaches the small box
}

TEST(StaticFolding, AStaticContactCollidesInEveryState) {
  const RobotModel bot = RobotModel::fromUrdfString(kPostBot, "post_bot.urdf", kUrdfDir);
  std::vector<std::string> warnings;
  // A box through the column.
  const Models m = build(bot, {box({0.08, 0, 0.3}, {0.1, 0.1, 0.1})}, &warnings);
  ASSERT_EQ(m.folded.report().static_collisions.size(), 1u);
  EXPECT_THAT(m.folded.report().static_collisions[0], HasSubstr("column"));
  EXPECT_THAT(m.folded.report().toString(), HasSubstr("EVERY STATE IS IN COLLISION"));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("column"));
  EXPECT_EQ(expectSameAnswers(m, 100, 3), 100u);
}

TEST(StaticFolding, AConstantPairInContactCollidesInEveryState) {
  RobotModel bot = RobotModel::fromUrdfString(kPostBot, "post_bot.urdf", kUrdfDir);
  bot.enableCollision("base", "column");     // they overlap by 2 cm
  bot.enableCollision("arm", "clamp_link");  // the clamp sits on the arm's end
  const Models m = build(bot, {box({0.5, 0.3, 0.55}, {0.1, 0.1, 0.1})});
  ASSERT_EQ(m.folded.report().static_collisions.size(), 2u);
  EXPECT_THAT(m.folded.report().static_collisions[0], HasSubstr("'base' and 'column'"));
  EXPECT_THAT(m.folded.report().static_collisions[1], HasSubstr("'arm' and 'clamp_link'"));
  expectReportMatchesKinematics(m);
  EXPECT_EQ(expectSameAnswers(m, 100, 4), 100u);
}

TEST(StaticFolding, PandaWithHeldFingers) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  RobotModel panda = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  panda.loadSrdfFile(kPanda + "/panda.srdf");
  const RobotModel arm = holdJoints(panda, {0, 1, 2, 3, 4, 5, 6}, {0, 0, 0, -1.5, 0, 1.5, 0, 0.065},
                                    [](const std::string&) {});
  const Models m =
      build(arm, {box({0.5, 0, 0.1}, {0.6, 1.0, 0.04}), box({0, 0, -0.1}, {1, 1, 0.02}),
                  box({0.45, 0.2, 0.5}, {0.1, 0.1, 0.3})});
  EXPECT_THAT(m.folded.report().static_links, ::testing::Contains("panda_link0"));
  EXPECT_TRUE(m.folded.report().static_collisions.empty());
  expectReportMatchesKinematics(m);
  EXPECT_GT(expectSameAnswers(m, 300, 5), 0u);
}

}  // namespace
}  // namespace octomotion
