// A world that changes between plans (OctreeCollisionModel::addObject and the others): an
// updated model answers exactly as a model built fresh on the same objects (and holds the same
// environment tree), attached objects answer as a link of the robot carrying them, updates are
// refused with clear errors, and the exact FCL reference with the same updates agrees with the
// octree within the conservative contract (never a contact FCL finds and the octree misses).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {
namespace {

const std::string kPandaDir = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

RobotModel loadOcto7() {
  RobotModelOptions options;
  options.package_paths = {OCTOMOTION_SOURCE_DIR};
  RobotModel robot = RobotModel::fromUrdfFile(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/octo7/octo7.urdf", options);
  robot.loadSrdfFile(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/octo7/octo7.srdf");
  return robot;
}

bool havePanda() {
  return std::filesystem::exists(kPandaDir + "/panda.urdf");
}

RobotModel loadPanda() {
  RobotModel robot = RobotModel::fromUrdfFile(kPandaDir + "/panda.urdf");
  robot.loadSrdfFile(kPandaDir + "/panda.srdf");
  return robot;
}

EnvironmentObject box(const std::string& name, Eigen::Vector3d size, Eigen::Vector3d xyz,
                      double yaw = 0) {
  EnvironmentObject o;
  o.name = name;
  o.primitive = Box{size / 2};
  o.X_WO.translation() = xyz;
  o.X_WO.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return o;
}

EnvironmentObject cylinder(const std::string& name, double radius, double length,
                           Eigen::Vector3d xyz) {
  EnvironmentObject o;
  o.name = name;
  o.primitive = Cylinder{radius, length};
  o.X_WO.translation() = xyz;
  return o;
}

// A MotionBenchMaker-like table top in front of the arm: a table, a shelf board, a can.
std::vector<EnvironmentObject> tableScene() {
  return {box("table", {0.6, 1.0, 0.04}, {0.55, 0, 0.3}),
          box("board", {0.3, 0.6, 0.02}, {0.6, 0.1, 0.75}, 0.3),
          cylinder("can", 0.04, 0.15, {0.45, -0.3, 0.4})};
}

CollisionModelOptions changingWorld(double resolution) {
  CollisionModelOptions o;
  o.resolution = resolution;
  o.fit_universe_to_reach = true;
  return o;
}

Eigen::Isometry3d at(Eigen::Vector3d xyz, double yaw = 0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = xyz;
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

// Same answers state by state, both halves and both query paths; returns how many states
// collide (so callers can require the comparison to have seen contacts).
int expectSameAnswers(const OctreeCollisionModel& a, const OctreeCollisionModel& b, int count,
                      std::uint64_t seed, const std::string& step) {
  CheckScratch sa = a.makeScratch(), sb = b.makeScratch();
  int colliding = 0;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  for (const auto& q : test::uniformJointStates(a.robot(), count, seed)) {
    for (CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
      const bool in_a = a.inCollision(q.data(), q.size(), I, path, sa);
      const bool in_b = b.inCollision(q.data(), q.size(), I, path, sb);
      EXPECT_EQ(in_a, in_b) << step;
      EXPECT_EQ(a.environmentInCollision(path, sa), b.environmentInCollision(path, sb)) << step;
      EXPECT_EQ(a.selfInCollision(path, sa), b.selfInCollision(path, sb)) << step;
      colliding += in_a && path == CheckerPath::kFused;
      if (::testing::Test::HasFailure()) return colliding;
    }
  }
  return colliding;
}

// Applies the steps to `model` and after each compares it with a fresh build on its objects.
void checkSequenceAgainstFresh(const RobotModel& robot, double resolution) {
  const CollisionModelOptions options = changingWorld(resolution);
  OctreeCollisionModel model(robot, EnvironmentGeometry::load(tableScene()), options);
  const auto same_as_fresh = [&](const std::string& step) {
    const OctreeCollisionModel fresh(robot, model.objects(), options);
    EXPECT_EQ(model.grid(), fresh.grid()) << step;
    EXPECT_TRUE(model.environment() == fresh.environment())
        << step << ": " << model.environment().internalNodeCount() << " nodes against "
        << fresh.environment().internalNodeCount();
    std::string why;
    EXPECT_TRUE(model.environment().checkInvariants(&why)) << step << ": " << why;
    return expectSameAnswers(model, fresh, 150, 7, step);
  };
  std::uint64_t id = model.id();
  auto new_id = [&](const std::string& step) {
    EXPECT_NE(model.id(), id) << step;
    id = model.id();
  };
  int colliding = 0;
  model.addObject(box("crate", {0.2, 0.2, 0.2}, {0.3, 0.4, 0.5}, 0.5));
  new_id("add crate");
  colliding += same_as_fresh("add crate");
  model.moveObject("crate", at({0.1, -0.45, 0.6}, -0.2));
  new_id("move crate");
  colliding += same_as_fresh("move crate");
  model.removeObject("board");
  new_id("remove board");
  colliding += same_as_fresh("remove board");
  model.moveObject("can", at({0.5, 0.2, 0.35}));  // into the table: overlapping objects
  colliding += same_as_fresh("move can into the table");
  model.addObject(cylinder("post", 0.03, 1.2, {-0.4, 0.3, 0.6}));
  model.removeObject("table");
  colliding += same_as_fresh("add post, remove table");
  model.removeObject("crate");
  model.removeObject("can");
  model.removeObject("post");
  EXPECT_TRUE(model.environment().empty());
  colliding += same_as_fresh("remove everything");
  model.addObject(box("wall", {0.05, 1.5, 1.5}, {-0.5, 0, 0.6}));
  colliding += same_as_fresh("add a wall to an empty world");
  EXPECT_GT(colliding, 0);  // the comparisons saw contacts
}

TEST(WorldUpdates, SameAsFreshBuildOcto7) {
  checkSequenceAgainstFresh(loadOcto7(), 0.02);
}

TEST(WorldUpdates, SameAsFreshBuildPanda) {
  if (!havePanda()) GTEST_SKIP() << "no Panda in " << kPandaDir;
  checkSequenceAgainstFresh(loadPanda(), 0.02);
}

// The Panda with a box held in its hand as a URDF link of its own (frame: panda_hand's, the box
// at X_LO), the touch pairs disabled in the SRDF: the model built fresh on that robot is what
// attachObject must answer like.
RobotModel pandaHolding(const Eigen::Isometry3d& X_LO, const Eigen::Vector3d& size,
                        const std::vector<std::string>& touch_links, const std::string& dir) {
  std::ifstream urdf_in(kPandaDir + "/panda.urdf"), srdf_in(kPandaDir + "/panda.srdf");
  std::stringstream urdf, srdf;
  urdf << urdf_in.rdbuf();
  srdf << srdf_in.rdbuf();
  std::string u = urdf.str(), s = srdf.str();
  for (std::size_t p = 0; (p = u.find("filename=\"meshes/", p)) != std::string::npos;) {
    u.replace(p, 10, "filename=\"" + kPandaDir + "/");
    p += kPandaDir.size();
  }
  const Eigen::Vector3d rpy = X_LO.linear().eulerAngles(2, 1, 0).reverse();
  std::ostringstream link;
  link.precision(17);
  link << "<link name=\"held\"><collision><origin xyz=\"" << X_LO.translation().transpose()
       << "\" rpy=\"" << rpy.transpose() << "\"/><geometry><box size=\"" << size.transpose()
       << "\"/></geometry></collision></link><joint name=\"held_joint\" type=\"fixed\"><parent "
          "link=\"panda_hand\"/><child link=\"held\"/></joint></robot>";
  u.replace(u.rfind("</robot>"), 8, link.str());
  std::string disable = "<disable_collisions link1=\"held\" link2=\"panda_hand\" reason=\"x\"/>";
  for (const std::string& t : touch_links) {
    disable += "<disable_collisions link1=\"held\" link2=\"" + t + "\" reason=\"x\"/>";
  }
  s.replace(s.rfind("</robot>"), 8, disable + "</robot>");
  std::ofstream(dir + "/held.urdf") << u;
  std::ofstream(dir + "/held.srdf") << s;
  RobotModel robot = RobotModel::fromUrdfFile(dir + "/held.urdf");
  robot.loadSrdfFile(dir + "/held.srdf");
  return robot;
}

TEST(WorldUpdates, AttachAnswersAsALinkOfTheRobot) {
  if (!havePanda()) GTEST_SKIP() << "no Panda in " << kPandaDir;
  const std::string dir = ::testing::TempDir() + "/world_updates_attach";
  std::filesystem::create_directories(dir);
  // A small block held between the fingers.
  Eigen::Isometry3d X_LO = Eigen::Isometry3d::Identity();
  // Small enough not to reach beyond the fingers: the robot's reach, so the universe, stay.
  X_LO.translation() = Eigen::Vector3d(0, 0, 0.07);
  X_LO.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d size(0.02, 0.05, 0.02);
  const std::vector<std::string> touch = {"panda_leftfinger", "panda_rightfinger"};
  const CollisionModelOptions options = changingWorld(0.02);
  const EnvironmentGeometry objects = EnvironmentGeometry::load(tableScene());

  OctreeCollisionModel model(loadPanda(), objects, options);
  AttachedObject held;
  held.object.name = "bar";
  held.object.primitive = Box{size / 2};
  held.object.X_WO = X_LO;
  held.link = "panda_hand";
  held.touch_links = touch;
  model.attachObject(held);
  EXPECT_EQ(model.attachedObjects(), std::vector<std::string>{"bar"});
  const OctreeCollisionModel fresh(pandaHolding(X_LO, size, touch, dir), objects, options);
  ASSERT_EQ(model.grid(), fresh.grid());
  EXPECT_GT(expectSameAnswers(model, fresh, 300, 3, "attached"), 0);

  // The world changes while it is held, then it is put down where the hand holds it.
  model.addObject(box("crate", {0.2, 0.2, 0.2}, {0.3, 0.4, 0.5}));
  const OctreeCollisionModel fresh_crate(pandaHolding(X_LO, size, touch, dir), model.objects(),
                                         options);
  expectSameAnswers(model, fresh_crate, 150, 4, "attached, crate added");
  const std::vector<double> q(static_cast<std::size_t>(model.robot().variableCount()), 0.0);
  const Eigen::Isometry3d X_WO =
      model.attachedObjectPose("bar", q.data(), q.size(), Eigen::Isometry3d::Identity());
  model.detachObject("bar", X_WO);
  EXPECT_TRUE(model.attachedObjects().empty());
  ASSERT_NE(model.objects().find("bar"), nullptr);
  const OctreeCollisionModel fresh_left(loadPanda(), model.objects(), options);
  EXPECT_TRUE(model.environment() == fresh_left.environment());
  expectSameAnswers(model, fresh_left, 150, 5, "detached, left in the world");
  // At q the robot holds the bar where it now lies: in contact with the environment there.
  CheckScratch scratch = model.makeScratch();
  EXPECT_TRUE(model.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(),
                                CheckerPath::kFused, scratch));
  model.removeObject("bar");
  model.removeObject("crate");
  const OctreeCollisionModel plain(loadPanda(), objects, options);
  EXPECT_TRUE(model.environment() == plain.environment());
  expectSameAnswers(model, plain, 150, 6, "back to the start");
}

TEST(WorldUpdates, AttachedBoxMeetsObstaclesButNotItsTouchLinks) {
  const RobotModel robot = loadOcto7();
  const CollisionModelOptions options = changingWorld(0.02);
  OctreeCollisionModel model(robot, EnvironmentGeometry::load({}), options);
  const std::vector<double> q(static_cast<std::size_t>(robot.variableCount()), 0.0);
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data);
  const int hand = robot.linkIndex("hand");
  CheckScratch scratch = model.makeScratch();
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto collides = [&](CheckerPath path) {
    return model.inCollision(q.data(), q.size(), I, path, scratch);
  };
  // A peg 25 cm past the hand's origin, out of the robot's own reach at q...
  const Eigen::Vector3d p_W = data.linkPose(hand) * Eigen::Vector3d(0, 0, 0.25);
  model.addObject(box("peg", {0.02, 0.02, 0.02}, p_W));
  ASSERT_FALSE(collides(CheckerPath::kFused));
  // ...is hit by a block the hand carries there, on both query paths, in the environment half.
  AttachedObject held;
  held.object.name = "block";
  held.object.primitive = Box{Eigen::Vector3d(0.03, 0.03, 0.03)};
  held.object.X_WO.translation() = Eigen::Vector3d(0, 0, 0.25);
  held.link = "hand";
  model.attachObject(held);
  EXPECT_TRUE(collides(CheckerPath::kFused));
  EXPECT_TRUE(model.environmentInCollision(CheckerPath::kFused, scratch));
  EXPECT_FALSE(model.selfInCollision(CheckerPath::kFused, scratch));
  EXPECT_TRUE(collides(CheckerPath::kMoveTree));
  model.detachObject("block");
  EXPECT_FALSE(collides(CheckerPath::kFused));
  model.removeObject("peg");

  // A block about the hand's origin overlaps the links around it: a self contact, gone when
  // they are its touch links (and only then).
  held.object.X_WO = Eigen::Isometry3d::Identity();
  held.object.primitive = Box{Eigen::Vector3d(0.06, 0.06, 0.06)};
  model.attachObject(held);
  EXPECT_TRUE(collides(CheckerPath::kFused));
  EXPECT_TRUE(model.selfInCollision(CheckerPath::kFused, scratch));
  EXPECT_TRUE(collides(CheckerPath::kMoveTree));
  model.detachObject("block");
  held.touch_links = {"link7", "left_finger", "right_finger", "link6"};
  model.attachObject(held);
  EXPECT_FALSE(collides(CheckerPath::kFused));
  EXPECT_FALSE(collides(CheckerPath::kMoveTree));
  // Touch links spare the robot only: an obstacle at the block's corner still meets it.
  model.addObject(
      box("peg", {0.01, 0.01, 0.01}, data.linkPose(hand) * Eigen::Vector3d(0.055, 0.055, 0.055)));
  EXPECT_TRUE(collides(CheckerPath::kFused));
  EXPECT_TRUE(model.environmentInCollision(CheckerPath::kFused, scratch));
}

TEST(WorldUpdates, RefusedWithClearErrors) {
  const RobotModel robot = loadOcto7();
  CollisionModelOptions tight;  // the universe fitted to the environment it is built with
  tight.resolution = 0.02;
  tight.refine = RefineMode::kNone;  // updatable (the default, auto, is exact here)
  OctreeCollisionModel model(robot, EnvironmentGeometry::load(tableScene()), tight);
  const std::uint64_t id = model.id();
  const Octree before = model.environment();
  auto expectError = [&](auto&& update, const std::string& words) {
    try {
      update();
      ADD_FAILURE() << "no error; expected one saying '" << words << "'";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(model.id(), id) << words;  // unchanged
    EXPECT_TRUE(model.environment() == before) << words;
  };
  expectError([&] { model.removeObject("ghost"); }, "no object named 'ghost'");
  expectError([&] { model.moveObject("ghost", at({0, 0, 0})); }, "no object named 'ghost'");
  expectError(
      [&] {
        model.addObject(box("table", {0.1, 0.1, 0.1}, {0.5, 0, 0.5}));
      },
      "object named 'table' exists");
  expectError([&] { model.detachObject("ghost"); }, "no attached object 'ghost'");
  // Within the arm's reach, but below everything the model was built with.
  expectError(
      [&] {
        model.addObject(box("lamp", {0.1, 0.1, 0.1}, {0.3, 0, 0.1}));
      },
      "outside the model's universe");
  expectError([&] { model.moveObject("can", at({0.3, 0, 0.1})); }, "outside the model's universe");
  EXPECT_EQ(model.objects().find("can")->spec.X_WO.translation(), Eigen::Vector3d(0.45, -0.3, 0.4));
  AttachedObject held;
  held.object = box("table", {0.1, 0.1, 0.1}, {0, 0, 0});
  held.link = robot.link(robot.linkCount() - 1).name;
  expectError([&] { model.attachObject(held); }, "names an object of the world");
  held.object.name = "tray";
  held.link = "no_such_link";
  expectError([&] { model.attachObject(held); }, "no_such_link");
  // Out of the robot's reach altogether: nothing to model, accepted...
  model.addObject(box("far", {0.1, 0.1, 0.1}, {30, 0, 0}));
  EXPECT_TRUE(model.environment() == before);
  // ...until a carried object could reach it.
  const std::uint64_t with_far = model.id();
  held.object = box("pole", {62, 0.02, 0.02}, {0, 0, 0});
  held.link = "hand";
  try {
    model.attachObject(held);
    ADD_FAILURE() << "a pole reaching an unmodelled object was attached";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("can reach the part of 'far'"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(model.id(), with_far);
  EXPECT_TRUE(model.attachedObjects().empty());
  // Exact primitives are not updated in place.
  CollisionModelOptions exact = tight;
  exact.exact_primitives = true;
  OctreeCollisionModel exact_model(robot, EnvironmentGeometry::load(tableScene()), exact);
  EXPECT_THROW(exact_model.removeObject("can"), InvalidArgument);
}

// The exact reference with the same updates (and a mounted robot): every contact FCL finds, the
// conservative octree finds too; and they see contacts.
void checkAgainstFcl(const RobotModel& robot, const Eigen::Isometry3d& X_WB) {
  CollisionModelOptions options = changingWorld(0.02);
  options.X_WB = X_WB;
  std::vector<EnvironmentObject> scene = tableScene();
  for (EnvironmentObject& o : scene) o.X_WO = X_WB * o.X_WO;
  const EnvironmentGeometry objects = EnvironmentGeometry::load(scene);
  OctreeCollisionModel octree(robot, objects, options);
  FclCollisionModel fcl(robot, objects, false, false, X_WB);  // mounted like the octree
  auto both = [&](auto&& update) {
    update(octree);
    update(fcl);
  };
  int fcl_hits = 0, octree_only = 0;
  auto compare = [&](const std::string& step) {
    CheckScratch so = octree.makeScratch();
    auto sf = fcl.makeScratch();
    for (const auto& q : test::uniformJointStates(robot, 200, 9)) {
      fcl.setConfiguration(q.data(), q.size(), X_WB, *sf);
      const bool f_env = fcl.environmentInCollision(*sf), f_self = fcl.selfInCollision(*sf);
      const bool o = octree.inCollision(q.data(), q.size(), X_WB, CheckerPath::kFused, so);
      const bool o_env = octree.environmentInCollision(CheckerPath::kFused, so);
      const bool o_self = octree.selfInCollision(CheckerPath::kFused, so);
      if (f_env) {
        EXPECT_TRUE(o_env) << step;
      }
      if (f_self) {
        EXPECT_TRUE(o_self) << step;
      }
      // The clearance (rebuilt lazily after the update) stays a lower bound on FCL's distance.
      if (!o_env) {
        EXPECT_LE(octree.clearanceLowerBound(so), fcl.environmentDistance(*sf) + 1e-9) << step;
      }
      fcl_hits += f_env || f_self;
      octree_only += o && !(f_env || f_self);
      if (::testing::Test::HasFailure()) return;
    }
  };
  both([&](auto& m) {
    m.addObject(EnvironmentGeometry::loadItem(
        box("crate", {0.2, 0.2, 0.2}, X_WB * Eigen::Vector3d(0.3, 0.4, 0.5), 0.5)));
  });
  compare("add");
  both([&](auto& m) { m.moveObject("crate", X_WB * at({0.1, -0.45, 0.6}, -0.2)); });
  both([&](auto& m) { m.removeObject("table"); });
  compare("move, remove");
  AttachedObject held;
  held.object.name = "tray";
  held.object.primitive = Box{Eigen::Vector3d(0.12, 0.12, 0.01)};
  held.object.X_WO.translation() = Eigen::Vector3d(0, 0, 0.12);
  int carrier = robot.linkCount() - 1;
  while (!robot.link(carrier).hasCollision()) --carrier;
  held.link = robot.link(carrier).name;
  both([&](auto& m) { m.attachObject(held); });
  compare("attach");
  both([&](auto& m) { m.detachObject("tray", X_WB * at({0.4, 0, 0.8})); });
  compare("detach, left in the world");
  EXPECT_GT(fcl_hits, 0);
  (void)octree_only;
}

TEST(WorldUpdates, FclReferenceAgreesWithinTheConservativeContract) {
  checkAgainstFcl(loadOcto7(), Eigen::Isometry3d::Identity());
  checkAgainstFcl(loadOcto7(), at({0.2, -0.1, 0.1}, 1.57));  // a mounted robot
  if (havePanda()) checkAgainstFcl(loadPanda(), at({0, 0, 0.1}, 0.5));
}

// The planning scene's updates reach its checker: a state inside a new obstacle is invalid, and
// valid again once it is gone; the FCL reference follows.
TEST(WorldUpdates, PlanningSceneUpdatesItsChecker) {
  SceneOverrides o;
  o.resolution = 0.02;
  o.fit_universe_to_reach = true;
  PlanningScene scene =
      loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml", o);
  const RobotModel& robot = scene.model->robot();
  const std::vector<double> q = scene.spec.problem.start->joints;
  ompl::base::ScopedState<> state(scene.setup->getStateSpace());
  configurationToState(robot, q, Eigen::Isometry3d::Identity(), state.get());
  const auto& si = scene.setup->getSpaceInformation();
  ASSERT_TRUE(si->isValid(state.get()));
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data, scene.model->baseMount());
  int last = robot.linkCount() - 1;
  while (!robot.link(last).hasCollision()) --last;
  const Eigen::Vector3d p_W = data.linkPose(last).translation();
  const std::size_t objects = scene.environment->size();
  scene.addObject(box("intruder", {0.1, 0.1, 0.1}, p_W));
  EXPECT_EQ(scene.environment->size(), objects + 1);
  EXPECT_FALSE(si->isValid(state.get()));
  auto fcl_scratch = scene.fclModel()->makeScratch();
  scene.fclModel()->setConfiguration(q.data(), q.size(), scene.model->baseMount(), *fcl_scratch);
  EXPECT_TRUE(scene.fclModel()->environmentInCollision(*fcl_scratch));
  scene.moveObject("intruder", at(p_W + Eigen::Vector3d(0, 0, 3)));
  EXPECT_TRUE(si->isValid(state.get()));
  scene.removeObject("intruder");
  EXPECT_TRUE(si->isValid(state.get()));
  EXPECT_EQ(scene.environment->size(), objects);
}

}  // namespace
}  // namespace octomotion

namespace octomotion {
namespace {

// A refused update leaves the scene as it was, and usable.
TEST(WorldUpdates, PlanningSceneRefusalLeavesItUsable) {
  SceneOverrides o;
  o.resolution = 0.02;
  PlanningScene scene =
      loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml", o);
  const std::uint64_t id = scene.model->id();
  EXPECT_THROW(scene.addObject(box("lamp", {0.1, 0.1, 0.1}, {0.0, 0.0, -0.3})), InvalidArgument);
  EXPECT_THROW(scene.removeObject("ghost"), InvalidArgument);
  EXPECT_EQ(scene.model->id(), id);
  ompl::base::ScopedState<> state(scene.setup->getStateSpace());
  configurationToState(scene.model->robot(), scene.spec.problem.start->joints,
                       Eigen::Isometry3d::Identity(), state.get());
  EXPECT_TRUE(scene.setup->getSpaceInformation()->isValid(state.get()));
}

}  // namespace
}  // namespace octomotion

namespace octomotion {
namespace {

// After an update the clearance levels are rebuilt by the first clearance query, whichever
// thread asks: threads asking at once get the answers one thread gets afterwards, and they are
// lower bounds on exact FCL's distance between the robot and the updated world.
TEST(WorldUpdates, ClearanceAfterAnUpdateFromManyThreads) {
  const RobotModel robot = loadOcto7();
  const CollisionModelOptions options = changingWorld(0.02);
  OctreeCollisionModel model(robot, EnvironmentGeometry::load(tableScene()), options);
  model.addObject(box("crate", {0.2, 0.2, 0.2}, {0.3, 0.4, 0.5}));
  const auto states = test::uniformJointStates(robot, 64, 21);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto bounds = [&](const OctreeCollisionModel& m) {
    std::vector<double> out;
    CheckScratch scratch = m.makeScratch();
    for (const auto& q : states) {
      robot.forwardKinematics(q.data(), q.size(), scratch.robot, I);
      out.push_back(m.clearanceLowerBoundPoints(scratch));
    }
    return out;
  };
  std::vector<std::vector<double>> per_thread(4);
  std::vector<std::thread> threads;
  for (auto& out : per_thread) threads.emplace_back([&] { out = bounds(model); });
  for (std::thread& t : threads) t.join();
  const std::vector<double> after = bounds(model);
  for (const auto& out : per_thread) EXPECT_EQ(out, after);
  const FclCollisionModel fcl(robot, model.objects());
  auto exact = fcl.makeScratch();
  for (std::size_t i = 0; i < after.size(); ++i) {
    fcl.setConfiguration(states[i].data(), states[i].size(), I, *exact);
    if (fcl.inCollision(*exact)) continue;
    EXPECT_LE(after[i], fcl.environmentDistance(*exact) + 1e-9) << i;
  }
  EXPECT_GT(*std::max_element(after.begin(), after.end()), 0.0);
}

}  // namespace
}  // namespace octomotion
