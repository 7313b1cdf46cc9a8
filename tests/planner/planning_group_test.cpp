// SRDF groups and group states, holding joints (holdJoints: the reduced model's kinematics
// against the full model's) and the scene keys problem.group / fixed / named starts and goals
// (resolvePlanningGroup). Expected values come from the files' definitions
// (tests/data/urdf/arm.urdf, arm_groups.srdf), not from a run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "joint_states.h"
#include "octomotion/error.h"
#include "octomotion/planner/robot/held_joints.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/planning_group.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const std::string kUrdfDir = std::string(OCTOMOTION_TEST_DATA_DIR) + "/urdf";
const std::string kArm = kUrdfDir + "/arm.urdf";
const std::string kArmGroups = kUrdfDir + "/arm_groups.srdf";
const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

template <typename F>
void expectError(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << fragments.front();
  } catch (const Error& e) {
    for (const std::string& fragment : fragments) EXPECT_THAT(e.what(), HasSubstr(fragment));
  }
}

std::vector<std::string> jointNames(const RobotModel& robot, const std::vector<int>& joints) {
  std::vector<std::string> names;
  for (int j : joints) names.push_back(robot.joint(j).name);
  return names;
}

std::vector<std::string> linkNames(const RobotModel& robot, const std::vector<int>& links) {
  std::vector<std::string> names;
  for (int l : links) names.push_back(robot.link(l).name);
  return names;
}

std::vector<std::string> variableNames(const RobotModel& robot) {
  std::vector<std::string> names;
  for (const Variable& v : robot.variables()) names.push_back(v.name);
  return names;
}

RobotModel armWithGroups() {
  RobotModel arm = RobotModel::fromUrdfFile(kArm);
  arm.loadSrdfFile(kArmGroups);
  return arm;
}

// --- SRDF groups ---

TEST(SrdfGroups, ChainJointsLinksSubgroupsAndStates) {
  const RobotModel arm = armWithGroups();
  ASSERT_EQ(arm.groups().size(), 4u);
  // A chain: the joints from the tip up to the base (the fixed tool_mount included).
  const JointGroup* chain = arm.findGroup("arm");
  ASSERT_NE(chain, nullptr);
  EXPECT_THAT(jointNames(arm, chain->joints), ElementsAre("shoulder", "elbow", "tool_mount"));
  EXPECT_THAT(linkNames(arm, chain->links), ElementsAre("upper", "fore", "tool"));
  EXPECT_THAT(arm.groupVariables(*chain),
              ElementsAre(arm.variableIndex("shoulder"), arm.variableIndex("elbow")));
  // Links: their parent joints; the mimic joint is in the group but has no variable.
  const JointGroup* gripper = arm.findGroup("gripper");
  ASSERT_NE(gripper, nullptr);
  EXPECT_THAT(jointNames(arm, gripper->joints), ElementsAre("slider", "finger_mirror"));
  EXPECT_THAT(arm.groupVariables(*gripper), ElementsAre(arm.variableIndex("slider")));
  // A subgroup defined after the group that names it.
  const JointGroup* both = arm.findGroup("arm_wrist");
  ASSERT_NE(both, nullptr);
  EXPECT_THAT(jointNames(arm, both->joints),
              ElementsAre("shoulder", "elbow", "tool_mount", "wrist"));
  EXPECT_EQ(arm.findGroup("nope"), nullptr);
  // Group states, values by joint index in file order.
  ASSERT_EQ(arm.groupStates().size(), 2u);
  const GroupState& folded = arm.groupStates()[0];
  EXPECT_EQ(folded.name, "folded");
  EXPECT_EQ(folded.group, "arm");
  ASSERT_EQ(folded.values.size(), 2u);
  EXPECT_EQ(folded.values[0].first, arm.jointIndex("shoulder"));
  EXPECT_DOUBLE_EQ(folded.values[0].second, 0.5);
  EXPECT_EQ(folded.values[1].first, arm.jointIndex("elbow"));
  EXPECT_DOUBLE_EQ(folded.values[1].second, -2.0);
}

TEST(SrdfGroups, ChainThroughTheCommonAncestor) {
  // From the right finger to the left one: up to the hand, then down.
  RobotModel arm = RobotModel::fromUrdfFile(kArm);
  arm.loadSrdfString(
      "<robot name='arm'><group name='fingers'><chain base_link='finger_right' "
      "tip_link='finger_left'/></group></robot>",
      "fingers.srdf");
  EXPECT_THAT(jointNames(arm, arm.findGroup("fingers")->joints),
              ElementsAre("slider", "finger_mirror"));
}

TEST(SrdfGroups, MergeAddsAndReplaceReplaces) {
  RobotModel arm = armWithGroups();
  arm.loadSrdfString(
      "<robot name='arm'><group name='shoulder_only'><joint name='shoulder'/></group>"
      "<group name='both'><group name='shoulder_only'/><group name='wrist'/></group></robot>",
      "more.srdf", SrdfMode::kMerge);
  EXPECT_EQ(arm.groups().size(), 6u);
  EXPECT_THAT(jointNames(arm, arm.findGroup("both")->joints), ElementsAre("shoulder", "wrist"));
  arm.loadSrdfString("<robot name='arm'/>", "empty.srdf");
  EXPECT_TRUE(arm.groups().empty());
  EXPECT_TRUE(arm.groupStates().empty());
}

TEST(SrdfGroups, ErrorsNameFileLineAndTheUnknownName) {
  RobotModel arm = armWithGroups();
  auto load = [&](const std::string& body) {
    arm.loadSrdfString("<robot name='arm'>\n" + body + "\n</robot>", "bad.srdf");
  };
  expectError([&] { load("<group name='g'><joint name='ghost'/></group>"); },
              {"bad.srdf", "line 2", "ghost", "group 'g'"});
  expectError([&] { load("<group name='g'><link name='phantom'/></group>"); },
              {"bad.srdf", "line 2", "phantom"});
  expectError([&] { load("<group name='g'><chain base_link='base' tip_link='nowhere'/></group>"); },
              {"bad.srdf", "tip_link", "nowhere"});
  expectError([&] { load("<group name='g'><group name='missing'/></group>"); },
              {"bad.srdf", "subgroup 'missing'"});
  expectError(
      [&] {
        load(
            "<group name='a'><group name='b'/></group><group name='b'><group "
            "name='a'/></group>");
      },
      {"bad.srdf", "cycle"});
  expectError([&] { load("<group name='g'/>\n<group name='g'/>"); },
              {"bad.srdf", "line 3", "defined twice"});
  expectError([&] { load("<group_state name='s' group='none'/>"); }, {"bad.srdf", "group 'none'"});
  expectError(
      [&] {
        load(
            "<group name='arm'/><group_state name='s' group='arm'><joint name='wraith' "
            "value='1'/></group_state>");
      },
      {"bad.srdf", "wraith", "group_state 's'"});
  expectError(
      [&] {
        load(
            "<group name='arm'/><group_state name='s' group='arm'><joint name='elbow' "
            "value='x'/></group_state>");
      },
      {"bad.srdf", "'x'", "elbow"});
  // A bad file leaves the groups as they were.
  EXPECT_EQ(arm.groups().size(), 4u);
  EXPECT_EQ(arm.groupStates().size(), 2u);
}

// --- holdJoints ---

// FK of the reduced model at q equals FK of the full model at the expanded q, link by link.
void expectSameKinematics(const RobotModel& full, const RobotModel& reduced, int states,
                          std::uint64_t seed) {
  RobotData full_data = full.makeData();
  RobotData reduced_data = reduced.makeData();
  for (const std::vector<double>& q : test::uniformJointStates(reduced, states, seed)) {
    const std::vector<double> q_full = expandConfiguration(full, reduced, q);
    full.forwardKinematics(q_full.data(), q_full.size(), full_data);
    reduced.forwardKinematics(q.data(), q.size(), reduced_data);
    for (int l = 0; l < full.linkCount(); ++l) {
      const Eigen::Matrix4d diff =
          full_data.linkPose(l).matrix() - reduced_data.linkPose(l).matrix();
      ASSERT_LT(diff.norm(), 1e-12) << "link " << full.link(l).name;
    }
  }
}

// The reduction keeps the links, the joints' names, the geometry and the filter.
void expectSameStructure(const RobotModel& full, const RobotModel& reduced) {
  ASSERT_EQ(reduced.linkCount(), full.linkCount());
  ASSERT_EQ(reduced.jointCount(), full.jointCount());
  for (int l = 0; l < full.linkCount(); ++l) {
    EXPECT_EQ(reduced.link(l).name, full.link(l).name);
    EXPECT_EQ(reduced.link(l).collision.size(), full.link(l).collision.size());
  }
  for (int j = 0; j < full.jointCount(); ++j) EXPECT_EQ(reduced.joint(j).name, full.joint(j).name);
  EXPECT_EQ(reduced.checkedPairs(), full.checkedPairs());
  EXPECT_EQ(reduced.disabledPairs(), full.disabledPairs());
  EXPECT_EQ(reduced.groups().size(), full.groups().size());
}

TEST(HoldJoints, ArmWithMimicMatchesTheFullModel) {
  const RobotModel arm = armWithGroups();
  const int shoulder = arm.variableIndex("shoulder"), elbow = arm.variableIndex("elbow");
  const int wrist = arm.variableIndex("wrist"), slider = arm.variableIndex("slider");
  std::vector<double> values(static_cast<std::size_t>(arm.variableCount()), 0.0);
  values[static_cast<std::size_t>(wrist)] = 0.7;
  values[static_cast<std::size_t>(slider)] = 0.03;
  // The master held: its mimic is held too.
  {
    std::vector<std::string> warnings;
    const RobotModel reduced = holdJoints(arm, {shoulder, elbow}, values,
                                          [&](const std::string& m) { warnings.push_back(m); });
    EXPECT_TRUE(warnings.empty());
    EXPECT_THAT(variableNames(reduced), ElementsAre("shoulder", "elbow"));
    expectSameStructure(arm, reduced);
    ASSERT_EQ(reduced.heldJoints().size(), 3u);
    EXPECT_EQ(reduced.heldJoints()[2].joint, arm.jointIndex("finger_mirror"));
    EXPECT_TRUE(reduced.heldJoints()[2].mimic);
    EXPECT_DOUBLE_EQ(reduced.heldJoints()[2].value, -0.03);  // multiplier -1
    EXPECT_FALSE(reduced.joint(arm.jointIndex("finger_mirror")).movable());
    expectSameKinematics(arm, reduced, 200, 1);
    const std::vector<double> full_q = expandConfiguration(arm, reduced, {0.1, 0.2});
    EXPECT_THAT(full_q, ElementsAre(0.1, 0.2, 0.7, 0.03));
  }
  // The master planned: the mimic joint still follows it.
  {
    const RobotModel reduced = holdJoints(arm, {slider, elbow}, values);
    EXPECT_THAT(variableNames(reduced), ElementsAre("elbow", "slider"));
    EXPECT_TRUE(reduced.joint(arm.jointIndex("finger_mirror")).isMimic());
    expectSameKinematics(arm, reduced, 200, 2);
  }
  // Every variable planned: the same model.
  const RobotModel same = holdJoints(arm, {0, 1, 2, 3}, values);
  EXPECT_EQ(variableNames(same), variableNames(arm));
  EXPECT_TRUE(same.heldJoints().empty());
  expectSameKinematics(arm, same, 50, 3);
}

TEST(HoldJoints, RandomSubsetsOfThePanda) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  RobotModel panda = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  panda.loadSrdfFile(kPanda + "/panda.srdf");
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<int> planned;
    std::vector<double> values;
    for (const Variable& v : panda.variables()) {
      if (std::bernoulli_distribution(0.5)(rng)) planned.push_back(static_cast<int>(values.size()));
      values.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    const RobotModel reduced = holdJoints(panda, planned, values);
    ASSERT_EQ(reduced.variableCount(), static_cast<int>(planned.size()));
    expectSameStructure(panda, reduced);
    expectSameKinematics(panda, reduced, 50, static_cast<std::uint64_t>(trial));
  }
}

TEST(HoldJoints, WarnsOutsideLimitsAndRejectsBadInput) {
  const RobotModel arm = armWithGroups();
  std::vector<double> values(4, 0.0);
  values[3] = 0.065;  // slider, limits [0, 0.04]
  std::vector<std::string> warnings;
  const RobotModel reduced =
      holdJoints(arm, {0, 1, 2}, values, [&](const std::string& m) { warnings.push_back(m); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("slider"));
  EXPECT_THAT(warnings[0], HasSubstr("0.065"));
  EXPECT_THROW(holdJoints(arm, {0, 0}, values), InvalidArgument);
  EXPECT_THROW(holdJoints(arm, {4}, values), InvalidArgument);
  EXPECT_THROW(holdJoints(arm, {0}, {0.0}), InvalidArgument);
  values[2] = std::nan("");
  EXPECT_THROW(holdJoints(arm, {0}, values), InvalidArgument);
  EXPECT_THROW(expandConfiguration(arm, reduced, {0.0}), InvalidArgument);
}

// --- Scene keys ---

SceneSpec armScene(const std::string& problem) {
  return parseSceneYaml(
      "robot: {urdf: " + kArm + ", srdf: " + kArmGroups + "}\nproblem:\n" + problem,
      "/tmp/arm_scene.yaml");
}

TEST(PlanningGroupScene, TheShippedSceneResolves) {
  SceneSpec spec = loadScene(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/arm_group.yaml");
  EXPECT_EQ(spec.problem.group, "arm");
  ASSERT_EQ(spec.problem.fixed.size(), 1u);
  EXPECT_EQ(spec.problem.fixed[0].first, "wrist");
  ASSERT_TRUE(spec.problem.start && spec.problem.goal);
  EXPECT_EQ(spec.problem.start->group_state, "folded");
  ASSERT_EQ(spec.problem.start->named.size(), 1u);
  EXPECT_EQ(spec.problem.goal->named.size(), 2u);
  const RobotModel arm = armWithGroups();
  const RobotModel robot = resolvePlanningGroup(arm, spec);
  EXPECT_THAT(variableNames(robot), ElementsAre("shoulder", "elbow"));
  EXPECT_THAT(spec.problem.start->joints, ElementsAre(0.5, -2.0));  // group state "folded"
  EXPECT_THAT(spec.problem.goal->joints, ElementsAre(-1.0, 1.0));
  // Held: wrist from problem.fixed, slider from the start, its mimic following.
  ASSERT_EQ(robot.heldJoints().size(), 3u);
  EXPECT_EQ(robot.joint(robot.heldJoints()[0].joint).name, "wrist");
  EXPECT_DOUBLE_EQ(robot.heldJoints()[0].value, 0.5);
  EXPECT_EQ(robot.joint(robot.heldJoints()[1].joint).name, "slider");
  EXPECT_DOUBLE_EQ(robot.heldJoints()[1].value, 0.02);
  EXPECT_DOUBLE_EQ(robot.heldJoints()[2].value, -0.02);
}

TEST(PlanningGroupScene, HeldValuesInPriorityOrder) {
  const RobotModel arm = armWithGroups();
  // problem.fixed beats the start; the start's group state gives the gripper's value; nothing
  // gives the wrist one: 0 is inside its range.
  SceneSpec spec = armScene(
      "  group: arm\n  fixed: {slider: 0.01}\n  start: {group_state: open, shoulder: 1, elbow: "
      "2}\n");
  RobotModel robot = resolvePlanningGroup(arm, spec);
  ASSERT_EQ(robot.heldJoints().size(), 3u);
  EXPECT_DOUBLE_EQ(robot.heldJoints()[0].value, 0.0);   // wrist
  EXPECT_DOUBLE_EQ(robot.heldJoints()[1].value, 0.01);  // slider: fixed, not the state's 0.03
  EXPECT_THAT(spec.problem.start->joints, ElementsAre(1.0, 2.0));
  spec = armScene("  group: arm\n  start: {group_state: open, shoulder: 1, elbow: 2}\n");
  robot = resolvePlanningGroup(arm, spec);
  EXPECT_DOUBLE_EQ(robot.heldJoints()[1].value, 0.03);  // the start's group state
  spec = armScene("  group: arm_wrist\n  start: [0, 0, 0]\n");
  robot = resolvePlanningGroup(arm, spec);
  EXPECT_THAT(variableNames(robot), ElementsAre("shoulder", "elbow", "wrist"));
  EXPECT_DOUBLE_EQ(robot.heldJoints()[0].value, 0.0);  // slider: 0 is within [0, 0.04]
}

TEST(PlanningGroupScene, PandaHandGroupClampsTheHeldArm) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  RobotModel panda = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  panda.loadSrdfFile(kPanda + "/panda.srdf");
  SceneSpec spec = parseSceneYaml("robot: {urdf: " + kPanda +
                                      "/panda.urdf}\nproblem:\n"
                                      "  group: hand\n  start: open\n  goal: close\n",
                                  "/tmp/panda_hand.yaml");
  const RobotModel hand = resolvePlanningGroup(panda, spec);
  EXPECT_THAT(variableNames(hand), ElementsAre("panda_finger_joint1"));
  EXPECT_THAT(spec.problem.start->joints, ElementsAre(0.035));
  EXPECT_THAT(spec.problem.goal->joints, ElementsAre(0.0));
  // Nothing gives the arm's values: 0 clamped into each joint's limits.
  for (const HeldJoint& h : hand.heldJoints()) {
    const Joint& j = panda.joint(h.joint);
    EXPECT_DOUBLE_EQ(h.value, std::clamp(0.0, j.lower, j.upper)) << j.name;
  }
  EXPECT_EQ(hand.heldJoints().size(), 7u);
}

TEST(PlanningGroupScene, WithoutAGroupFixedJointsAreHeld) {
  const RobotModel arm = armWithGroups();
  SceneSpec spec =
      armScene("  fixed: {wrist: 1.5}\n  goal: {shoulder: 0, elbow: 0, slider: 0.01}\n");
  const RobotModel robot = resolvePlanningGroup(arm, spec);
  EXPECT_THAT(variableNames(robot), ElementsAre("shoulder", "elbow", "slider"));
  EXPECT_THAT(spec.problem.goal->joints, ElementsAre(0.0, 0.0, 0.01));
  // Nothing to hold: the robot as it is.
  spec = armScene("  start: [0, 0, 0, 0]\n");
  EXPECT_EQ(resolvePlanningGroup(arm, spec).variableCount(), 4);
}

TEST(PlanningGroupScene, ErrorsNameTheField) {
  const RobotModel arm = armWithGroups();
  auto resolve = [&](const std::string& problem) {
    SceneSpec spec = armScene(problem);
    resolvePlanningGroup(arm, spec);
  };
  expectError([&] { resolve("  group: legs\n"); },
              {"arm_scene.yaml", "problem.group", "legs", "arm, arm_wrist"});
  expectError([&] { resolve("  group: arm\n  fixed: {elbow: 0}\n"); },
              {"problem.fixed.elbow", "group 'arm'"});
  expectError([&] { resolve("  fixed: {knee: 0}\n"); }, {"problem.fixed.knee", "no joint"});
  expectError([&] { resolve("  fixed: {tool_mount: 0}\n"); },
              {"problem.fixed.tool_mount", "fixed"});
  expectError([&] { resolve("  fixed: {finger_mirror: 0}\n"); },
              {"problem.fixed.finger_mirror", "slider"});
  expectError([&] { resolve("  group: arm\n  start: {shoulder: 0}\n"); },
              {"problem.start", "'elbow'", "no value"});
  expectError(
      [&] {
        resolve(
            "  group: arm\n  start: folded\n  goal: {shoulder: 0, elbow: 0, "
            "wrist: 1}\n");
      },
      {"problem.goal.wrist", "not planned"});
  expectError(
      [&] {
        resolve(
            "  group: arm\n  start: {group_state: folded, slider: 0.01, "
            "finger_mirror: 0.01}\n");
      },
      {"problem.start.finger_mirror", "-0.01"});
  // A held master's value is its held one (problem.fixed), not the start's.
  expectError(
      [&] {
        resolve(
            "  group: arm\n  fixed: {slider: 0.01}\n  start: {group_state: folded, slider: "
            "0.03, finger_mirror: -0.03}\n");
      },
      {"problem.start.finger_mirror", "'slider' = 0.01", "gives -0.01"});
  resolve(
      "  group: arm\n  fixed: {slider: 0.01}\n  start: {group_state: folded, finger_mirror: "
      "-0.01}\n");
  expectError([&] { resolve("  group: arm\n  start: sideways\n"); },
              {"problem.start", "group_state 'sideways'", "folded (arm)"});
  expectError([&] { resolve("  group: arm\n  start: [0, 0, 0, 0]\n"); },
              {"problem.start", "expected 2 joint values", "shoulder, elbow"});
  expectError(
      [&] {
        resolve(
            "  group: arm\n  fixed: {wrist: 0, slider: 0}\n  start: {shoulder: "
            "0, knee: 1}\n");
      },
      {"problem.start.knee"});
  // Rigid bodies have no joints.
  SceneSpec body = parseSceneYaml(
      "robot: {mesh: " + kUrdfDir + "/meshes/tetra.stl}\nproblem: {group: arm}\n", "/tmp/b.yaml");
  expectError(
      [&] { resolvePlanningGroup(RobotModel::fromMesh(kUrdfDir + "/meshes/tetra.stl"), body); },
      {"problem.group", "rigid body"});
}

TEST(PlanningGroupScene, ParsingKeepsNamesAndRejectsBadValues) {
  const SceneSpec spec = armScene(
      "  group: arm\n  fixed: {wrist: 0.5, slider: 0.02}\n  start: ready\n  goal: {xyz: [0, 0, "
      "1]}\n");
  ASSERT_EQ(spec.problem.fixed.size(), 2u);
  EXPECT_EQ(spec.problem.fixed[1].first, "slider");
  EXPECT_DOUBLE_EQ(spec.problem.fixed[1].second, 0.02);
  EXPECT_EQ(spec.problem.start->group_state, "ready");
  EXPECT_TRUE(spec.problem.goal->pose.has_value());  // pose keys only: still a pose
  expectError([&] { armScene("  fixed: {wrist: high}\n"); }, {"problem.fixed.wrist", "number"});
  expectError([&] { armScene("  fixed: [1, 2]\n"); }, {"problem.fixed"});
  expectError([&] { armScene("  start: {elbow: 1, elbow: 2}\n"); },
              {"problem.start.elbow", "twice"});
  expectError([&] { armScene("  group: [a]\n"); }, {"problem.group"});
}

// --- The command line ---

using test::CliRun;

CliRun runCli(const std::string& args) {
  return test::runCli(args, "octomotion_planning_group_test");
}

TEST(PlanningGroupCli, InfoPlanAndCheckUseThePlannedJoints) {
  const std::string scene = std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/arm_group.yaml";
  const CliRun info = runCli("info " + scene + " --resolution 0.02");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("joint order: shoulder elbow\n"));
  EXPECT_THAT(info.out, HasSubstr("group: arm, 2 planned joints\n"));
  EXPECT_THAT(info.out,
              HasSubstr("held joints: wrist=0.5, slider=0.02, finger_mirror=-0.02 (mimic)\n"));
  // The path: a comment naming the planned joints, then two columns from the start's values.
  const std::string path = (std::filesystem::temp_directory_path() / "arm_group.path").string();
  const CliRun plan = runCli("plan " + scene + " --resolution 0.02 --out " + path);
  ASSERT_EQ(plan.status, 0) << plan.err;
  std::ifstream in(path);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header, "# joints: shoulder elbow");
  EXPECT_EQ(first, "0.5 -2");
  // check: columns found by name, so a file with every joint of the robot works.
  const std::string csv = (std::filesystem::temp_directory_path() / "arm_group.csv").string();
  std::ofstream(csv) << "wrist,elbow,slider,shoulder\n0,-2,0,0.5\n9,1,9,-1\n";
  const CliRun check = runCli("check " + scene + " --resolution 0.02 --states " + csv);
  ASSERT_EQ(check.status, 0) << check.err;
  EXPECT_THAT(check.err, HasSubstr("2 of 2 states valid"));
  std::filesystem::remove(path);
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace octomotion
