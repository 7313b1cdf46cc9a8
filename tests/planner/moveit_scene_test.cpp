// MoveIt input: a PlanningScene's collision objects give the same environment as the equivalent
// hand-written scene (link frames and the mount included), a MotionPlanRequest fills the problem,
// and all 700 MotionBenchMaker problems for the Panda are read (their starts collision-free for
// FCL, as the data's README says).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "mbm_problems.h"
#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/scene/moveit_scene.h"
#include "octomotion/planner/scene/scene_frames.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kPanda = kSource + "/../shared/data/panda";
const std::string kMbm = kSource + "/../shared/data/mbm_panda/problems.tar.bz2";

class TempDir {
 public:
  explicit TempDir(const std::string& stem)
      : path_(fs::temp_directory_path() / (stem + "_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = (path_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// octo7 mounted away from the origin, held at a start that moves link3 off its zero pose.
std::string octo7Robot() {
  return "robot:\n  urdf: " + kSource + "/robots/octo7/octo7.urdf\n  package_path: [" + kSource +
         "]\n  pose: {xyz: [0.3, -0.2, 0.1], rpy: [0.1, -0.2, 0.7]}\n";
}
const char* kStart = "problem:\n  start: [0.4, -0.3, 0.2, -1.1, 0.3, 0.9, -0.5, 0.01]\n";

// A table in the model frame (no frame_id), a tool on link3 with an object pose (two shapes), an
// inline mesh on link3, and quaternions in both spellings.
const char* kPlanningScene = R"(
name: made_up
robot_state: {joint_state: {name: [], position: []}}
world:
  collision_objects:
    - id: table
      header: {frame_id: ""}
      primitives: [{type: box, dimensions: [0.6, 0.4, 0.05]}]
      primitive_poses: [{position: [0.5, 0, -0.1], orientation: [0, 0, 0.3826834323650898, 0.9238795325112867]}]
    - id: tool
      header: {frame_id: link3}
      pose: {position: {x: 0.01, y: 0.02, z: 0.03}, orientation: {x: 0, y: 0.6, z: 0, w: 0.8}}
      primitives:
        - {type: cylinder, dimensions: [0.2, 0.03]}
        - {type: 2, dimensions: [0.04]}
      primitive_poses:
        - {position: [0, 0, 0.1], orientation: [0, 0, 0, 1]}
        - {position: {x: 0.05, y: 0, z: 0}, orientation: {x: 0.6, y: 0, z: 0, w: 0.8}}
    - id: wedge
      header: {frame_id: link3}
      meshes:
        - vertices: [{x: 0, y: 0, z: 0}, {x: 0.25, y: 0, z: 0}, {x: 0, y: 0.25, z: 0}, {x: 0, y: 0, z: 0.5}]
          triangles: [{vertex_indices: [0, 2, 1]}, {vertex_indices: [0, 1, 3]}, {vertex_indices: [0, 3, 2]}, {vertex_indices: [1, 2, 3]}]
      mesh_poses: [{position: [0.1, 0.1, 0], orientation: [0, 0, 0, 1]}]
)";

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// A pose as a hand-written scene writes it.
std::string yamlPose(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d t = X.translation();
  return "{xyz: [" + number(t.x()) + ", " + number(t.y()) + ", " + number(t.z()) + "], quat: [" +
         number(q.x()) + ", " + number(q.y()) + ", " + number(q.z()) + ", " + number(q.w()) + "]}";
}

Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

double maxDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

TEST(MoveItScene, GivesTheObjectsOfTheEquivalentHandWrittenScene) {
  TempDir dir("octomotion_moveit_scene_test");
  dir.file("planning_scene.yaml", kPlanningScene);
  const std::string moveit =
      dir.file("moveit.yaml",
               octo7Robot() + "environment:\n  - moveit_scene: planning_scene.yaml\n" + kStart);
  // The same objects by hand: frames named, the object pose composed with each shape's.
  const Eigen::Isometry3d table =
      pose({0.5, 0, -0.1}, Eigen::Quaterniond(0.9238795325112867, 0, 0, 0.3826834323650898));
  const Eigen::Isometry3d tool = pose({0.01, 0.02, 0.03}, Eigen::Quaterniond(0.8, 0, 0.6, 0));
  const Eigen::Isometry3d cylinder = tool * pose({0, 0, 0.1}, Eigen::Quaterniond::Identity());
  const Eigen::Isometry3d sphere = tool * pose({0.05, 0, 0}, Eigen::Quaterniond(0.8, 0.6, 0, 0));
  const Eigen::Isometry3d wedge = pose({0.1, 0.1, 0}, Eigen::Quaterniond::Identity());
  dir.file("wedge.obj",
           "v 0 0 0\nv 0.25 0 0\nv 0 0.25 0\nv 0 0 0.5\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const std::string hand = dir.file(
      "hand.yaml",
      octo7Robot() + "environment:\n" +
          "  - {name: table, frame: link0, box: {size: [0.6, 0.4, 0.05]}, pose: " +
          yamlPose(table) + "}\n" +
          "  - {name: tool/0, frame: link3, cylinder: {radius: 0.03, length: 0.2}, pose: " +
          yamlPose(cylinder) + "}\n" +
          "  - {name: tool/1, frame: link3, sphere: {radius: 0.04}, pose: " + yamlPose(sphere) +
          "}\n" + "  - {name: wedge, frame: link3, mesh: {file: wedge.obj}, pose: " +
          yamlPose(wedge) + "}\n" + kStart);

  const SceneInputs a = loadSceneInputs(moveit);
  const SceneInputs b = loadSceneInputs(hand);
  ASSERT_EQ(a.spec.environment.size(), 4u);
  ASSERT_EQ(b.spec.environment.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const EnvironmentObject& x = a.spec.environment[i];
    const EnvironmentObject& y = b.spec.environment[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kind, y.kind) << x.name;
    EXPECT_LT(maxDifference(x.X_WO, y.X_WO), 1e-12) << x.name;
    EXPECT_TRUE(x.frame.empty() && !x.robot_root_frame) << x.name << ": frame left unresolved";
    if (x.kind == EnvironmentObject::Kind::kPrimitive) {
      EXPECT_EQ(x.primitive.index(), y.primitive.index()) << x.name;
      EXPECT_TRUE(boundingBox(x.primitive, Eigen::Isometry3d::Identity())
                      .isApprox(boundingBox(y.primitive, Eigen::Isometry3d::Identity()), 1e-12))
          << x.name;
    }
  }
  const TriangleMesh& inline_mesh = a.environment->items()[3].mesh;
  const TriangleMesh& file_mesh = b.environment->items()[3].mesh;
  ASSERT_EQ(inline_mesh.vertices.size(), file_mesh.vertices.size());
  EXPECT_EQ(inline_mesh.triangles.size(), file_mesh.triangles.size());
  Eigen::AlignedBox3d box_a, box_b;
  for (const auto& v : inline_mesh.vertices) box_a.extend(v);
  for (const auto& v : file_mesh.vertices) box_b.extend(v);
  EXPECT_TRUE(box_a.isApprox(box_b, 1e-12));

  // Independently: the objects sit where the mounted robot's links are at the start.
  RobotModelOptions options;
  options.package_paths = {kSource};
  const RobotModel robot = RobotModel::fromUrdfFile(kSource + "/robots/octo7/octo7.urdf", options);
  const Eigen::Isometry3d X_WB = *a.spec.robot.pose;
  const std::vector<double> q = {0.4, -0.3, 0.2, -1.1, 0.3, 0.9, -0.5, 0.01};
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data, X_WB);
  const Eigen::Isometry3d& X_W3 = data.linkPose(robot.linkIndex("link3"));
  EXPECT_LT(maxDifference(a.spec.environment[0].X_WO, X_WB * table), 1e-12);
  EXPECT_LT(maxDifference(a.spec.environment[1].X_WO, X_W3 * cylinder), 1e-12);
  EXPECT_LT(maxDifference(a.spec.environment[2].X_WO, X_W3 * sphere), 1e-12);
  EXPECT_LT(maxDifference(a.spec.environment[3].X_WO, X_W3 * wedge), 1e-12);
  // Not vacuous: link3 is neither at the mount nor at the origin.
  EXPECT_GT(maxDifference(X_W3, X_WB), 0.05);
}

TEST(MoveItScene, ShapesWithoutAnObjectPoseAreAbsoluteAndAppendRemoveApply) {
  const std::vector<EnvironmentObject> objects = parseMoveItScene(R"(
world:
  collision_objects:
    - id: a
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [1, 2, 3], orientation: [0, 0, 0, 1]}]
    - id: b
      primitives: [{type: box, dimensions: [1, 2, 3]}]
      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]
    - id: a
      operation: 2
      primitives: [{type: cylinder, dimensions: [0.5, 0.25]}]
      primitive_poses: [{position: [0, 0, 1], orientation: [0, 0, 0, 1]}]
    - {id: b, operation: REMOVE}
    - id: c
      pose: {position: [0, 0, 0], orientation: [0, 0, 0, 0]}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [0, 1, 0], orientation: {x: 0, y: 0, z: 0, w: 0}}]
)",
                                                                  "mem.yaml");
  ASSERT_EQ(objects.size(), 3u);
  // An orientation never filled in (all zeros) is the identity, as MoveIt reads it.
  EXPECT_EQ(objects[2].name, "c");
  EXPECT_TRUE(objects[2].X_WO.linear().isIdentity(0));
  EXPECT_EQ(objects[2].X_WO.translation(), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(objects[0].name, "a/0");
  EXPECT_EQ(objects[1].name, "a/1");
  EXPECT_TRUE(objects[0].robot_root_frame);
  EXPECT_EQ(objects[0].X_WO.translation(), Eigen::Vector3d(1, 2, 3));
  ASSERT_TRUE(std::holds_alternative<Cylinder>(objects[1].primitive));
  EXPECT_EQ(std::get<Cylinder>(objects[1].primitive).length, 0.5);  // [height, radius]
  EXPECT_EQ(std::get<Cylinder>(objects[1].primitive).radius, 0.25);
}

TEST(MoveItRequest, FillsTheProblemAndExcludesTheScenesOwn) {
  TempDir dir("octomotion_moveit_request_test");
  dir.file("request.yaml", R"(
planner_id: RRTConnectkConfigDefault
group_name: arm
allowed_planning_time: 7.5
start_state:
  joint_state:
    name: [joint1, joint2, finger_joint1, finger_joint2]
    position: [0.1, 0.2, 0.03, 0.03]
goal_constraints:
  - joint_constraints:
      - {joint_name: joint1, position: 0.5, tolerance_above: 0.001, tolerance_below: 0.001}
      - {joint_name: joint2, position: -0.5}
)");
  const std::string scene =
      dir.file("scene.yaml", octo7Robot() + "problem:\n  moveit_request: request.yaml\n");
  const SceneSpec s = loadScene(scene);
  EXPECT_EQ(s.problem.group, "arm");
  EXPECT_EQ(s.problem.moveit_request, dir.path() + "/request.yaml");
  EXPECT_EQ(s.problem.time, 7.5);
  ASSERT_TRUE(s.problem.start && s.problem.goal);
  const std::vector<std::pair<std::string, double>> start = {
      {"joint1", 0.1}, {"joint2", 0.2}, {"finger_joint1", 0.03}, {"finger_joint2", 0.03}};
  EXPECT_EQ(s.problem.start->named, start);
  const std::vector<std::pair<std::string, double>> goal = {{"joint1", 0.5}, {"joint2", -0.5}};
  EXPECT_EQ(s.problem.goal->named, goal);

  // The scene's time wins; start/goal/group and a request exclude each other.
  EXPECT_EQ(
      loadScene(dir.file("timed.yaml", octo7Robot() + "problem:\n  moveit_request: request.yaml\n"
                                                      "  time: 2\n"))
          .problem.time,
      2.0);
  try {
    loadScene(dir.file("both.yaml", octo7Robot() + "problem:\n  moveit_request: request.yaml\n"
                                                   "  start: [0, 0, 0, 0, 0, 0, 0, 0]\n"));
    FAIL() << "a request and a start were both accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("problem.start"));
    EXPECT_THAT(e.what(), HasSubstr("moveit_request"));
  }

  // Once the robot is loaded, the mimic finger (consistent) leaves the named start.
  SceneSpec resolved = s;
  RobotModelOptions options;
  options.package_paths = {kSource};
  const RobotModel robot = RobotModel::fromUrdfFile(s.robot.urdf, options);
  resolveSceneFrames(resolved, robot);
  ASSERT_EQ(resolved.problem.start->named.size(), 3u);
  EXPECT_EQ(resolved.problem.start->named.back().first, "finger_joint1");
  const std::vector<double> q = frameConfiguration(resolved, robot);
  EXPECT_EQ(q[static_cast<std::size_t>(robot.variableIndex("joint2"))], 0.2);
  EXPECT_EQ(q[static_cast<std::size_t>(robot.variableIndex("finger_joint1"))], 0.03);
}

TEST(MoveItRequest, APositionAndOrientationGoalIsALinkPose) {
  const MoveItRequest r = parseMoveItRequest(R"(
group_name: arm
start_state: {joint_state: {name: [joint1], position: [0]}}
goal_constraints:
  - position_constraints:
      - header: {frame_id: link0}
        link_name: hand
        constraint_region:
          primitives: [{type: sphere, dimensions: [0.01]}]
          primitive_poses: [{position: [0.4, 0.1, 0.5], orientation: [0, 0, 0, 1]}]
    orientation_constraints:
      - header: {frame_id: link0}
        link_name: hand
        orientation: [1, 0, 0, 0]
        absolute_x_axis_tolerance: 0.1
        absolute_y_axis_tolerance: 0.05
        absolute_z_axis_tolerance: 0.2
)",
                                             "req.yaml");
  ASSERT_TRUE(r.goal.link_pose);
  const LinkPoseGoalSpec& g = *r.goal.link_pose;
  EXPECT_EQ(g.link, "hand");
  EXPECT_EQ(g.frame, "link0");
  EXPECT_EQ(g.position, Eigen::Vector3d(0.4, 0.1, 0.5));
  EXPECT_EQ(g.position_tolerance, 0.01);
  ASSERT_TRUE(g.orientation);
  EXPECT_EQ(g.orientation->x(), 1.0);
  EXPECT_EQ(g.orientation_tolerance, 0.05);
  EXPECT_FALSE(r.time);
}

// The 700 problems extracted once into a temporary folder (skipped without the data).
class MbmProblems : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    set_ = new test::MbmProblems();
    dir_ = new TempDir("octomotion_mbm_test");
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete set_;
    dir_ = nullptr;
    set_ = nullptr;
  }
  void SetUp() override {
    if (set_->problems().empty()) GTEST_SKIP() << "no MotionBenchMaker problems at " << kMbm;
  }
  using Problem = test::MbmProblem;
  static inline test::MbmProblems* set_ = nullptr;
  static inline TempDir* dir_ = nullptr;
  static const std::vector<Problem>& problems() { return set_->problems(); }
};

TEST_F(MbmProblems, EveryProblemIsRead) {
  EXPECT_EQ(problems().size(), 700u);
  for (const Problem& p : problems()) {
    const std::vector<EnvironmentObject> objects = loadMoveItScene(p.scene);
    EXPECT_GE(objects.size(), 1u) << p.scene;
    for (const EnvironmentObject& o : objects) {
      EXPECT_TRUE(o.X_WO.matrix().allFinite()) << p.scene << " " << o.name;
      EXPECT_TRUE(o.robot_root_frame) << p.scene << " " << o.name;  // no frame_id
    }
    const MoveItRequest r = loadMoveItRequest(p.request);
    EXPECT_EQ(r.group, "panda_arm") << p.request;
    EXPECT_EQ(r.start.named.size(), 9u) << p.request;
    EXPECT_EQ(r.goal.named.size(), 7u) << p.request;
    EXPECT_FALSE(r.goal.link_pose) << p.request;
  }
}

// A scene file of one problem, as docs/examples/moveit_box.yaml writes it: the objects, the
// request's problem with the mimic finger dropped, and a mount that carries the objects along.
TEST_F(MbmProblems, ASceneFileReadsAProblem) {
  if (!fs::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  const Problem& p = problems().front();
  const std::string robot =
      "robot:\n  urdf: " + kPanda + "/panda.urdf\n  srdf: " + kPanda + "/panda.srdf\n";
  const std::string rest = "environment:\n  - moveit_scene: " + p.scene +
                           "\nproblem:\n  moveit_request: " + p.request + "\n";
  const SceneInputs plain = loadSceneInputs(dir_->file("plain.yaml", robot + rest));
  const SceneInputs mounted = loadSceneInputs(dir_->file(
      "mounted.yaml", robot + "  pose: {xyz: [0.5, -1, 0.75], rpy: [0.1, 0, 2]}\n" + rest));
  EXPECT_EQ(plain.spec.problem.group, "panda_arm");
  EXPECT_EQ(plain.spec.problem.start->named.size(), 9u);  // as the request gives them
  EXPECT_EQ(plain.spec.problem.goal->named.size(), 7u);
  // The planned joints are the group's: the start and goal vectors have its 7 values.
  EXPECT_EQ(plain.robot->variableCount(), 7);
  EXPECT_EQ(plain.spec.problem.start->joints.size(), 7u);
  EXPECT_EQ(plain.spec.problem.goal->joints.size(), 7u);
  ASSERT_EQ(plain.spec.environment.size(), loadMoveItScene(p.scene).size());
  ASSERT_EQ(mounted.spec.environment.size(), plain.spec.environment.size());
  const Eigen::Isometry3d& M = *mounted.spec.robot.pose;
  for (std::size_t i = 0; i < plain.spec.environment.size(); ++i) {
    EXPECT_LT(maxDifference(mounted.spec.environment[i].X_WO, M * plain.spec.environment[i].X_WO),
              1e-12);
  }
  EXPECT_EQ(plain.environment->size(), plain.spec.environment.size());
}

// The data's README: at fingers 0.065 none of 105 problems checked had a start in collision
// (VAMP counts 699 of the 700 valid). Fifteen problems of each set, with exact FCL.
TEST_F(MbmProblems, StartsAreCollisionFreeForFcl) {
  if (!fs::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  std::map<std::string, int> taken;
  int checked = 0, free = 0, colliding_objects = 0;
  for (const Problem& p : problems()) {
    if (taken[p.set]++ >= 15) continue;
    SceneSpec spec;
    spec.path = p.scene;
    spec.environment = loadMoveItScene(p.scene);
    spec.problem.start = loadMoveItRequest(p.request).start;
    resolveSceneFrames(spec, robot);
    ASSERT_EQ(spec.problem.start->named.size(), 8u) << p.request;  // the mimic finger dropped
    const std::vector<double> q = frameConfiguration(spec, robot);
    const FclCollisionModel fcl(robot, EnvironmentGeometry::load(spec.environment));
    auto scratch = fcl.makeScratch();
    fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch);
    ++checked;
    const bool hit = fcl.inCollision(*scratch);
    free += !hit;
    // Not vacuous: the same scene with a ball on the hand collides.
    if (checked <= 7) {
      RobotData data = robot.makeData();
      robot.forwardKinematics(q.data(), q.size(), data);
      EnvironmentObject ball;
      ball.primitive = Sphere{0.05};
      ball.X_WO = data.linkPose(robot.linkIndex("panda_hand"));
      spec.environment.push_back(ball);
      const FclCollisionModel with_ball(robot, EnvironmentGeometry::load(spec.environment));
      auto s = with_ball.makeScratch();
      with_ball.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *s);
      colliding_objects += with_ball.environmentInCollision(*s);
    }
  }
  EXPECT_EQ(checked, 105);
  EXPECT_GE(free, checked - 1);
  EXPECT_EQ(colliding_objects, 7);
}

}  // namespace
}  // namespace octomotion
