// Exact refine mode's shortcuts past FCL. Certain self contacts
// (planner/src/model/refine_self_contact.cpp): a checked pair of closed-mesh links with a vertex
// of one deep inside the other and another deep outside is called in contact without voxels or
// FCL; so is a pair where one element is a primitive (a solid for FCL) that a vertex, a closed
// mesh or a primitive of the other reaches into. Property: on the real Panda and the shipped octo6
// and octo7 (no environment, so every contact is a self contact) at uniform random states (fixed
// seed), every check that called a self contact certain is one FCL finds in self collision, and the
// refined answer is FCL's on every state. Link-object pairs cleared by hulls (objectHull,
// refine_hulls.cpp): among boxes, balls and cylinders around the Panda, the refined environment
// answer is FCL's on every state while the hulls clear pairs FCL would otherwise test. Not vacuous:
// each shortcut fires. Skipped without
// ../shared/data/panda.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "exact_and_fcl.h"
#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {
namespace {

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

// Checks `robot` alone at uniform states: every certain self contact is an FCL contact, the
// refined answer is FCL's everywhere, and most of FCL's self contacts are called certain.
void expectCertainSelfContactsAreFcl(const RobotModel& robot, std::uint64_t seed) {
  test::ExactAndFcl setup(robot);
  const OctreeCollisionModel& model = setup.model;
  const FclCollisionModel& fcl = setup.fcl;
  FclCollisionModel::ScratchPtr& exact = setup.exact;
  CheckScratch& scratch = setup.scratch;
  std::size_t certain_states = 0, fcl_contacts = 0, wrong = 0, disagreements = 0, state = 0;
  for (const std::vector<double>& q : test::uniformJointStates(robot, 3000, seed)) {
    ++state;
    fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
    const bool truth = fcl.selfInCollision(*exact);
    fcl_contacts += truth;
    const std::uint64_t before = model.refineCounts(scratch).certain_self_contacts;
    const bool hit = model.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(),
                                       CheckerPath::kFused, scratch);
    const bool certain = model.refineCounts(scratch).certain_self_contacts > before;
    certain_states += certain;
    if (certain && !truth) {
      ADD_FAILURE() << "certain self contact FCL does not find, state " << state - 1;
      ++wrong;
    }
    disagreements += hit != truth;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(disagreements, 0u);
  // Most of FCL's self contacts are called certain; the rest went to FCL.
  EXPECT_GT(certain_states, fcl_contacts / 2);
  EXPECT_GT(fcl_contacts, 50u);
  EXPECT_LT(model.refineCounts(scratch).fcl_pairs, fcl_contacts);
}

TEST(RefineSelfContact, EveryCertainSelfContactIsAnFclContact) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda";
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  expectCertainSelfContactsAreFcl(robot, 0x5e1f);
}

// The shipped arms mix closed meshes with boxes and cylinders in one link (octo6's forearm and
// wrist, octo7's): contacts with a primitive element are certain through its solid.
TEST(RefineSelfContact, CertainContactsWithPrimitiveElementsAreFclContacts) {
  const std::string source = OCTOMOTION_SOURCE_DIR;
  for (const std::string name : {"octo6", "octo7"}) {
    SCOPED_TRACE(name);
    RobotModelOptions options;
    options.package_paths = {source};
    RobotModel robot =
        RobotModel::fromUrdfFile(source + "/robots/" + name + "/" + name + ".urdf", options);
    robot.loadSrdfFile(source + "/robots/" + name + "/" + name + ".srdf");
    bool primitive_element = false, mesh_element = false;
    for (int l = 0; l < robot.linkCount(); ++l) {
      for (const CollisionElement& e : robot.link(l).collision) {
        primitive_element |= std::holds_alternative<Primitive>(e.geometry);
        mesh_element |= std::holds_alternative<MeshRef>(e.geometry);
      }
    }
    ASSERT_TRUE(primitive_element && mesh_element) << "the arm no longer mixes element kinds";
    expectCertainSelfContactsAreFcl(robot, 0x0c70);
  }
}

// A box, a cylinder and a ball around a fixed-base arm's base.
EnvironmentGeometry obstaclesAroundTheBase() {
  std::vector<EnvironmentObject> objects(3);
  objects[0].primitive = Box{Eigen::Vector3d(0.15, 0.3, 0.02)};
  objects[0].X_WO =
      Eigen::Translation3d(0.45, 0, 0.4) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  objects[1].primitive = Cylinder{0.05, 0.5};
  objects[1].X_WO =
      Eigen::Translation3d(-0.1, 0.45, 0.5) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX());
  objects[2].primitive = Sphere{0.12};
  objects[2].X_WO.translation() = Eigen::Vector3d(0.1, -0.45, 0.7);
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i].name = "o" + std::to_string(i);
  return EnvironmentGeometry::load(objects);
}

// Each thread orders a pair's two exact tests by the pair's recent verdicts (a pair mostly in
// contact tries the certain contact before the hulls), and the check's two halves by which one
// found recent contacts. Along random walks (a planner's nearby states) verdicts come in runs, so
// the orders change as pairs and links turn from free to contact and back: the answers stay
// FCL's on every state, with contacts in both halves.
void expectAdaptiveOrdersKeepFclAnswers(const RobotModel& robot, std::uint64_t seed) {
  test::ExactAndFcl setup(robot, obstaclesAroundTheBase());
  const OctreeCollisionModel& model = setup.model;
  const FclCollisionModel& fcl = setup.fcl;
  FclCollisionModel::ScratchPtr& exact = setup.exact;
  CheckScratch& scratch = setup.scratch;
  std::mt19937_64 rng(seed);
  std::size_t self_contacts = 0, environment_contacts = 0, disagreements = 0;
  for (std::vector<double> q : test::uniformJointStates(robot, 150, seed)) {
    for (int step = 0; step < 20; ++step) {
      for (std::size_t j = 0; j < q.size(); ++j) {
        const Variable& v = robot.variables()[j];
        const double range = v.upper - v.lower;
        q[j] = std::clamp(q[j] + std::normal_distribution<double>(0, 0.05 * range)(rng), v.lower,
                          v.upper);
      }
      fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
      const bool in_self = fcl.selfInCollision(*exact);
      const bool in_environment = fcl.environmentInCollision(*exact);
      self_contacts += in_self;
      environment_contacts += in_environment;
      disagreements +=
          model.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(), CheckerPath::kFused,
                            scratch) != (in_self || in_environment);
    }
  }
  EXPECT_EQ(disagreements, 0u);
  EXPECT_GT(self_contacts, 300u);
  EXPECT_GT(environment_contacts, 100u);
  EXPECT_GT(model.refineCounts(scratch).certain_self_contacts, 100u);
  EXPECT_GT(model.refineCounts(scratch).certain_contacts, 50u);
  EXPECT_GT(model.refineCounts(scratch).hull_apart_pairs, 300u);
}

TEST(RefineSelfContact, AdaptiveTestOrdersKeepFclAnswers) {
  const std::string source = OCTOMOTION_SOURCE_DIR;
  {
    SCOPED_TRACE("octo6");
    RobotModelOptions options;
    options.package_paths = {source};
    RobotModel robot = RobotModel::fromUrdfFile(source + "/robots/octo6/octo6.urdf", options);
    robot.loadSrdfFile(source + "/robots/octo6/octo6.srdf");
    expectAdaptiveOrdersKeepFclAnswers(robot, 0xada6);
  }
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda";
  SCOPED_TRACE("Panda");
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  expectAdaptiveOrdersKeepFclAnswers(robot, 0xada7);
}

// Two capsules crossing like a plus sign at their middles: no vertex of either lies inside the
// other (a capsule's side has vertices at its ends only), but points of their long side edges
// do, so the crossing is certain without FCL; at every angle of the cross, FCL agrees.
TEST(RefineSelfContact, CapsulesCrossingAtTheirSidesAreCertainContacts) {
  const std::string urdf = R"(<robot name="cross">
  <link name="root"/>
  <link name="upright"><collision><origin xyz="0 0 -0.2125"/>
    <geometry><mesh filename="upper_arm.stl"/></geometry></collision></link>
  <link name="hub"/>
  <link name="bar"><collision><origin xyz="-0.196 0 0" rpy="0 1.5707963267948966 0"/>
    <geometry><mesh filename="forearm.stl"/></geometry></collision></link>
  <joint name="fix" type="fixed"><parent link="root"/><child link="upright"/></joint>
  <joint name="turn" type="revolute"><parent link="root"/><child link="hub"/>
    <axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="hold" type="fixed"><parent link="hub"/><child link="bar"/></joint>
</robot>)";
  const RobotModel robot = RobotModel::fromUrdfString(
      urdf, "cross.urdf", std::string(OCTOMOTION_SOURCE_DIR) + "/robots/meshes/octo6");
  test::ExactAndFcl setup(robot);
  const OctreeCollisionModel& model = setup.model;
  const FclCollisionModel& fcl = setup.fcl;
  FclCollisionModel::ScratchPtr& exact = setup.exact;
  CheckScratch& scratch = setup.scratch;
  for (int k = 0; k < 24; ++k) {
    const double q = -3.1 + 6.2 * k / 23;
    SCOPED_TRACE(q);
    fcl.setConfiguration(&q, 1, Eigen::Isometry3d::Identity(), *exact);
    ASSERT_TRUE(fcl.selfInCollision(*exact));
    const RefineCounts before = model.refineCounts(scratch);
    EXPECT_TRUE(
        model.inCollision(&q, 1, Eigen::Isometry3d::Identity(), CheckerPath::kFused, scratch));
    EXPECT_EQ(model.refineCounts(scratch).certain_self_contacts, before.certain_self_contacts + 1);
    EXPECT_EQ(model.refineCounts(scratch).fcl_pairs, before.fcl_pairs);
  }
}

// Links are cleared of the environment by the clearance grid (their bounding sphere within the
// grid's bound), then by their hulls apart from the objects', before their voxels: the answers
// stay FCL's, also on states where the grid cleared a link and another touched an obstacle.
TEST(RefineSelfContact, LinksClearedByTheGridOrByHullsAreFreeForFcl) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda";
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  test::ExactAndFcl setup(robot, obstaclesAroundTheBase());
  const OctreeCollisionModel& model = setup.model;
  const FclCollisionModel& fcl = setup.fcl;
  FclCollisionModel::ScratchPtr& exact = setup.exact;
  CheckScratch& scratch = setup.scratch;
  std::size_t contacts = 0, disagreements = 0, grid_states = 0, grid_contacts = 0;
  for (const std::vector<double>& q : test::uniformJointStates(robot, 3000, 0x0b1e)) {
    fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
    const bool truth = fcl.environmentInCollision(*exact);
    contacts += truth;
    model.robot().forwardKinematics(q.data(), q.size(), scratch.robot,
                                    Eigen::Isometry3d::Identity());
    const std::uint64_t grid_before = model.refineCounts(scratch).grid_clear_links;
    disagreements += model.environmentInCollision(CheckerPath::kFused, scratch) != truth;
    if (model.refineCounts(scratch).grid_clear_links > grid_before) {
      ++grid_states;
      grid_contacts += truth;
    }
  }
  EXPECT_EQ(disagreements, 0u);
  EXPECT_GT(contacts, 50u);
  EXPECT_GT(grid_states, 300u);
  EXPECT_GT(grid_contacts, 20u) << "no state with a link the grid cleared touched an obstacle";
  EXPECT_GT(model.refineCounts(scratch).hull_apart_links, 0u);
}

}  // namespace
}  // namespace octomotion
