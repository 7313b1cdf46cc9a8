// Hostile input, round two (issue 25): each test holds one defect that a hostile user found —
// wrong answers first, then crashes, hangs and unbounded memory, then messages that did not
// locate the problem. Big or deep inputs are generated here in a scratch directory, never
// committed. Every test is bounded in time: a reader that blocks is a failure, not a hang.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <string>

#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/robot/package_locator.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/scene.h"
#include "octomotion/tools/gltf_export.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kSource = OCTOMOTION_SOURCE_DIR;

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("octomotion_hostile_") + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  // A free-flying 10 cm cube in a 2 m box with one small obstacle off the straight line from
  // the start to the goal, so RRTConnect solves it at once.
  std::string freeFlyingScene(const std::string& problem_extra = "",
                              const std::string& bounds = "{min: [-1, -1, -1], max: [1, 1, 1]}") {
    writeBoxObj("cube.obj", Eigen::Vector3d::Constant(-0.05), Eigen::Vector3d::Constant(0.05));
    return write("free.yaml",
                 "robot: {mesh: cube.obj}\n"
                 "environment:\n"
                 "  - {name: post, box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [0, 0.8, 0]}}\n"
                 "octree: {resolution: 0.05}\n"
                 "problem:\n"
                 "  start: {xyz: [-0.5, 0, 0]}\n"
                 "  goal: {xyz: [0.5, 0, 0]}\n"
                 "  bounds: " +
                     bounds + "\n  seed: 1\n" + problem_extra);
  }

  void writeBoxObj(const std::string& name, const Eigen::Vector3d& lo,
                   const Eigen::Vector3d& hi) const {
    std::ofstream out(dir_ / name);
    for (int i = 0; i < 8; ++i) {
      out << "v " << ((i & 1) ? hi.x() : lo.x()) << ' ' << ((i & 2) ? hi.y() : lo.y()) << ' '
          << ((i & 4) ? hi.z() : lo.z()) << '\n';
    }
    out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 2 4 8 6\nf 1 5 7 3\n";
  }

  fs::path dir_;
};

// What a call threw: the message of an octomotion::Error, or a failure for anything else.
std::string errorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an octomotion::Error: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted";
  return "";
}

// A two-link arm: a revolute joint j1 about z with `j1_limits`, then `tail` (more joints and
// links, which may refer to link "arm").
std::string armUrdf(const std::string& tail = "",
                    const std::string& j1_limits = "lower=\"-1\" upper=\"1\"") {
  return "<robot name=\"arm\">\n"
         "  <link name=\"base\"><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry>"
         "</collision></link>\n"
         "  <link name=\"arm\"><collision><origin xyz=\"0.2 0 0\"/><geometry>"
         "<box size=\"0.3 0.05 0.05\"/></geometry></collision></link>\n"
         "  <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/><limit " +
         j1_limits + " effort=\"1\" velocity=\"1\"/></joint>\n" + tail + "</robot>\n";
}

// ---------------------------------------------------------------------------------------------
// Wrong answers.

// D2: j3 = 1e200 j2, j2 = 1e200 j1 composes to an infinite multiplier: every state gave the
// links after j3 a NaN pose, which the checker called collision-free. Refused at load now.
TEST_F(HostileInput, MimicChainThatOverflowsIsRefusedAtLoad) {
  auto mimicChain = [](const char* multiplier) {
    const std::string tail = std::string() +
                             "  <link name=\"l2\"/><link name=\"l3\"><collision><geometry>"
                             "<sphere radius=\"0.05\"/></geometry></collision></link>\n"
                             "  <joint name=\"j2\" type=\"revolute\"><parent link=\"arm\"/>"
                             "<child link=\"l2\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" "
                             "upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\" "
                             "multiplier=\"" +
                             multiplier +
                             "\"/></joint>\n"
                             "  <joint name=\"j3\" type=\"prismatic\"><parent link=\"l2\"/>"
                             "<child link=\"l3\"/><axis xyz=\"1 0 0\"/><limit lower=\"-1\" "
                             "upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j2\" "
                             "multiplier=\"" +
                             multiplier + "\"/></joint>\n";
    return armUrdf(tail);
  };
  // Multipliers 2 and 2 compose to 4: a valid model.
  const RobotModel fine = RobotModel::fromUrdfString(mimicChain("2"), "mimic.urdf", ".");
  EXPECT_DOUBLE_EQ(fine.joint(fine.jointIndex("j3")).mimic_multiplier, 4.0);
  const std::string what =
      errorOf([&] { RobotModel::fromUrdfString(mimicChain("1e200"), "mimic_overflow.urdf", "."); });
  EXPECT_THAT(what, HasSubstr("mimic_overflow.urdf"));
  EXPECT_THAT(what, HasSubstr("joint 'j3'"));
  EXPECT_THAT(what, HasSubstr("not finite"));
}

// D2, downstream: finite joint values can still give a link a non-finite pose (here a prismatic
// mimic whose value overflows at the master's upper limit). No such pose reaches a collision
// query: forward kinematics refuses it, so the checkers call the state invalid.
TEST_F(HostileInput, NonFiniteLinkPoseIsNeverReportedFree) {
  const std::string tail =
      "  <link name=\"tip\"><collision><geometry><sphere radius=\"0.05\"/></geometry>"
      "</collision></link>\n"
      "  <joint name=\"slide\" type=\"prismatic\"><parent link=\"arm\"/><child link=\"tip\"/>"
      "<axis xyz=\"1 0 0\"/><limit lower=\"-1e300\" upper=\"1e300\" effort=\"1\" "
      "velocity=\"1\"/><mimic joint=\"j1\" multiplier=\"1e300\"/></joint>\n";
  const RobotModel robot = RobotModel::fromUrdfString(armUrdf(tail), "overflow.urdf", ".");
  RobotData data = robot.makeData();
  const std::vector<double> small{0.5};
  robot.forwardKinematics(small.data(), small.size(), data);
  EXPECT_TRUE(data.linkPose(robot.linkIndex("tip")).matrix().allFinite());
  // With j1 in [-1e10, 1e10] the slide's value, 1e300 * q1, overflows to infinity.
  const RobotModel wide = RobotModel::fromUrdfString(
      armUrdf(tail, "lower=\"-1e10\" upper=\"1e10\""), "overflow.urdf", ".");
  const std::vector<double> huge{1e10};
  const std::string what =
      errorOf([&] { wide.forwardKinematics(huge.data(), huge.size(), data = wide.makeData()); });
  EXPECT_THAT(what, HasSubstr("link 'tip'"));
  EXPECT_THAT(what, HasSubstr("not finite"));
}

// D3: the norm of [1e200, 1e200, 0, 0] overflowed to inf and q / inf became the identity. The
// quaternion is a half turn about (1, 1, 0).
TEST_F(HostileInput, HugeQuaternionAndAxisComponentsNormaliseWithoutOverflow) {
  const SceneSpec yaml = parseSceneYaml(
      "robot: {mesh: a.stl}\n"
      "environment:\n"
      "  - {box: {size: [1, 1, 1]}, pose: {axis: [0, 1e200, 0], theta: 0.5}}\n"
      "  - {box: {size: [1, 1, 1]}, pose: {axis: [0, 1e-200, 0], theta: 0.5}}\n"
      "problem: {start: {quat: [1e200, 1e200, 0, 0]}, goal: {quat: [0, 0, 1e-200, 1e-200]}}\n",
      "/s/huge.yaml");
  const Eigen::Matrix3d half_turn =
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  EXPECT_TRUE(yaml.problem.start->pose->linear().isApprox(half_turn, 1e-12))
      << yaml.problem.start->pose->linear();
  const Eigen::Matrix3d quarter_z =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(yaml.problem.goal->pose->linear().isApprox(quarter_z, 1e-12));
  // D4: an axis with huge (or tiny) components is still the axis.
  const Eigen::Matrix3d about_y =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (const EnvironmentObject& object : yaml.environment) {
    EXPECT_TRUE(object.X_WO.linear().isApprox(about_y, 1e-12)) << object.X_WO.linear();
  }
  // The same in an OMPL.app .cfg ...
  const SceneSpec cfg = parseOmplAppCfg(
      "[problem]\nrobot = r.obj\nworld = w.obj\n"
      "start.x = 0\nstart.y = 0\nstart.z = 0\nstart.theta = 0.5\n"
      "start.axis.x = 0\nstart.axis.y = 1e200\nstart.axis.z = 0\n"
      "goal.x = 0\ngoal.y = 0\ngoal.z = 0\n",
      "/s/huge.cfg");
  EXPECT_TRUE(cfg.problem.start->pose->linear().isApprox(about_y, 1e-12));
  // ... and in a URDF joint axis.
  std::string urdf = armUrdf();
  const std::string axis = "<axis xyz=\"0 0 1\"/>";
  urdf.replace(urdf.find(axis), axis.size(), "<axis xyz=\"0 0 1e200\"/>");
  const RobotModel robot = RobotModel::fromUrdfString(urdf, "huge_axis.urdf", ".");
  EXPECT_TRUE(robot.joint(robot.jointIndex("j1")).axis.isApprox(Eigen::Vector3d::UnitZ(), 1e-15))
      << robot.joint(robot.jointIndex("j1")).axis.transpose();
  // ... and in a path file's quaternion (x y z qx qy qz qw).
  CollisionElement ball;
  ball.geometry = Primitive{Sphere{0.1}};
  const RobotModel body = RobotModel::rigidBody("ball", {ball});
  std::istringstream path_text("1 2 3 1e200 1e200 0 0\n");
  const std::vector<RobotState> path = readPath(body, path_text, "huge.path");
  ASSERT_EQ(path.size(), 1u);
  EXPECT_TRUE(path[0].X_WB.linear().isApprox(half_turn, 1e-12)) << path[0].X_WB.linear();
}

// D1: a start or goal outside the bounds or the joint limits was accepted (`plan` printed
// OMPL's warnings and "no solution"). Now one error at load, naming the field, the value and the
// bound.
TEST_F(HostileInput, StartOrGoalOutsideBoundsOrLimitsIsRefusedAtLoad) {
  const std::string free_flying = freeFlyingScene();
  EXPECT_NO_THROW(loadPlanningScene(free_flying));
  std::string text;
  {
    std::ifstream in(free_flying);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    return write("outside.yaml", t);
  };
  std::string what =
      errorOf([&] { loadPlanningScene(replaced("start: {xyz: [-0.5,", "start: {xyz: [-1.5,")); });
  EXPECT_THAT(what, HasSubstr("outside.yaml"));
  EXPECT_THAT(what, HasSubstr("problem.start: x = -1.5 is outside problem.bounds [-1, 1]"));
  what = errorOf(
      [&] { loadPlanningScene(replaced("goal: {xyz: [0.5, 0, 0]", "goal: {xyz: [0.5, 0, 3]")); });
  EXPECT_THAT(what, HasSubstr("problem.goal: z = 3 is outside problem.bounds [-1, 1]"));

  // An OMPL.app problem names its keys.
  write("robot.obj", "");
  writeBoxObj("robot.obj", Eigen::Vector3d::Constant(-0.05), Eigen::Vector3d::Constant(0.05));
  writeBoxObj("world.obj", Eigen::Vector3d(-0.1, 0.7, -0.1), Eigen::Vector3d(0.1, 0.9, 0.1));
  const std::string cfg =
      write("outside.cfg",
            "[problem]\nrobot = robot.obj\nworld = world.obj\n"
            "start.x = -0.5\nstart.y = 0\nstart.z = 0\ngoal.x = 0.5\ngoal.y = 4\ngoal.z = 0\n"
            "volume.min.x = -1\nvolume.min.y = -1\nvolume.min.z = -1\n"
            "volume.max.x = 1\nvolume.max.y = 1\nvolume.max.z = 1\n");
  what = errorOf([&] { loadPlanningScene(cfg); });
  EXPECT_THAT(what, HasSubstr("outside.cfg"));
  EXPECT_THAT(what,
              HasSubstr("[problem] goal.y = 4 is outside [volume.min.y, volume.max.y] [-1, 1]"));

  // A fixed-base arm names the joint and its limits.
  const std::string urdf = write("arm.urdf", armUrdf());
  const std::string arm_scene = write("arm_outside.yaml",
                                      "robot: {urdf: arm.urdf}\noctree: {resolution: 0.05}\n"
                                      "problem: {start: [0.5], goal: [1.25]}\n");
  what = errorOf([&] { loadPlanningScene(arm_scene); });
  EXPECT_THAT(what, HasSubstr("arm_outside.yaml"));
  EXPECT_THAT(what, HasSubstr("problem.goal[0]: joint 'j1' = 1.25 is outside its limits [-1, 1]"));

  // The command line says it in one line before planning.
  const std::string err_path = (dir_ / "stderr").string();
  const int raw = std::system(
      (std::string(OCTOMOTION_CLI) + " plan " + arm_scene + " >/dev/null 2>" + err_path).c_str());
  EXPECT_NE(raw, 0);
  std::ifstream in(err_path);
  std::stringstream stream;
  stream << in.rdbuf();
  const std::string err = stream.str();
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_THAT(err, HasSubstr("joint 'j1' = 1.25"));
}

struct CliResult {
  int status;
  std::string out, err;
};

CliResult runCli(const fs::path& dir, const std::string& args, const std::string& stdout_to = "") {
  const std::string out_path = stdout_to.empty() ? (dir / "stdout").string() : stdout_to;
  const std::string err_path = (dir / "stderr").string();
  const int raw = std::system(
      (std::string(OCTOMOTION_CLI) + " " + args + " >" + out_path + " 2>" + err_path).c_str());
  auto slurp = [](const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, stdout_to.empty() ? slurp(out_path) : "",
          slurp(err_path)};
}

// D1, continued: a start in collision ended in "no solution" after the whole time limit. `plan`
// says so at once, naming the link and the object (CollisionBackend::explain).
TEST_F(HostileInput, StartInCollisionIsSaidAtOnce) {
  std::string text;
  {
    std::ifstream in(freeFlyingScene());
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const std::string from = "start: {xyz: [-0.5, 0, 0]}";
  const std::string into_post = "start: {xyz: [0, 0.78, 0]}";  // 8 cm deep into the post
  text.replace(text.find(from), from.size(), into_post);
  const std::string scene = write("start_in_post.yaml", text + "  time: 60\n");
  const auto t0 = std::chrono::steady_clock::now();
  const CliResult r = runCli(dir_, "plan " + scene);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("start_in_post.yaml: problem.start is in collision for the "
                               "octree-fused checker: link cube with object post"));
  EXPECT_THAT(r.err, Not(HasSubstr("margin")));
  // 1 mm from the post (whose face is at y = 0.75): free for FCL, but within the margin of
  // 20 cm voxels.
  text.replace(text.find(into_post), into_post.size(), "start: {xyz: [0, 0.699, 0]}");
  const std::string near = write("start_near_post.yaml", text);
  const CliResult margin =
      runCli(dir_, "plan " + near + " --resolution 0.2 --link-resolution 0.2 --refine none");
  EXPECT_EQ(margin.status, 1);
  EXPECT_THAT(margin.err, HasSubstr("the exact shapes do not touch: within the voxel margin of "
                                    "resolution 0.2 m, try a finer --resolution"));
}

// D17: a .cfg volume without volume.min.x dropped the five other volume keys silently.
TEST_F(HostileInput, CfgVolumeMustBeWholeOrAbsent) {
  const std::string problem =
      "[problem]\nrobot = r.obj\nworld = w.obj\n"
      "start.x = 0\nstart.y = 0\nstart.z = 0\ngoal.x = 1\ngoal.y = 0\ngoal.z = 0\n";
  EXPECT_FALSE(parseOmplAppCfg(problem, "/s/none.cfg").problem.bounds);
  const std::string what = errorOf([&] {
    parseOmplAppCfg(problem +
                        "volume.min.y = -1\nvolume.min.z = -1\n"
                        "volume.max.x = 1\nvolume.max.y = 1\nvolume.max.z = 1\n",
                    "/s/partial.cfg");
  });
  EXPECT_THAT(what, HasSubstr("partial.cfg"));
  EXPECT_THAT(what, HasSubstr("volume.min.x: missing"));
}

// D11: docs/scenes.md promises that a typo is never ignored, but yaml-cpp keeps one of two
// equal keys silently.
TEST_F(HostileInput, DuplicateYamlKeysAreRefused) {
  std::string what = errorOf([] {
    parseSceneYaml("robot: {mesh: a.stl}\noctree: {resolution: 0.01, resolution: 0.1}\n",
                   "/s/twice.yaml");
  });
  EXPECT_THAT(what, HasSubstr("twice.yaml"));
  EXPECT_THAT(what, HasSubstr("octree.resolution: key given twice"));
  what = errorOf([] {
    parseSceneYaml("robot: {mesh: a.stl}\nproblem: {time: 1}\nproblem: {time: 2}\n",
                   "/s/twice.yaml");
  });
  EXPECT_THAT(what, HasSubstr("problem: key given twice"));
  EXPECT_THAT(what, HasSubstr("line 3"));
}

// D14: --interpolation 1e-9 overflowed the state count (an unsigned cast) and wrote a 4-state
// path. A spacing that needs more than a million states is refused; a sane one still gives
// ceil(length / spacing) + 1 states.
TEST_F(HostileInput, InterpolationSpacingCannotOverflowTheStateCount) {
  PlanningScene scene = loadPlanningScene(freeFlyingScene());
  const PlanResult result = plan(scene, 0.01);
  ASSERT_TRUE(result.solved);
  const double length = result.path->length();
  EXPECT_EQ(result.path->getStateCount(), static_cast<std::size_t>(std::ceil(length / 0.01)) + 1);
  PlanningScene again = loadPlanningScene(freeFlyingScene());
  const std::string what = errorOf([&] { plan(again, 1e-9); });
  EXPECT_THAT(what, HasSubstr("free.yaml: interpolation (--interpolation): a spacing of 1e-09"));
}

// D15, D7: --seed 1e30 became seed 1 (an out-of-range cast) and --time 9e9 gave up at once
// (OMPL's deadline overflowed). Each is one error line naming the option; the scene keys too.
TEST_F(HostileInput, SeedAndTimeOutOfRangeAreRefused) {
  const std::string scene = freeFlyingScene();
  for (const auto& [args, says] : {std::pair<std::string, std::string>{"--seed 1e30", "--seed"},
                                   {"--seed 18446744073709551616", "--seed"},
                                   {"--time 9e9", "--time: 9e+09 s is more than the limit"}}) {
    const CliResult r = runCli(dir_, "info " + scene + " " + args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(says)) << args;
  }
  EXPECT_EQ(runCli(dir_, "info " + scene + " --seed 9000000000000000 --time 1e6").status, 0);
  const CliResult bench = runCli(dir_, "bench " + scene + " --planners RRTConnect:9e9");
  EXPECT_EQ(bench.status, 1);
  EXPECT_THAT(bench.err, HasSubstr("--planners: RRTConnect:9e9: 9e+09 s is more than the limit"));
  EXPECT_THAT(
      errorOf([] { parseSceneYaml("robot: {mesh: a}\nproblem: {time: 9e9}\n", "/s/t.yaml"); }),
      HasSubstr("problem.time: 9e+09 s is more than the limit"));
  EXPECT_THAT(errorOf([] {
                parseOmplAppCfg(
                    "[problem]\nrobot = r\nworld = w\nstart.x = 0\nstart.y = 0\nstart.z = 0\n"
                    "goal.x = 1\ngoal.y = 0\ngoal.z = 0\n[benchmark]\ntime_limit = 9e9\n",
                    "/s/t.cfg");
              }),
              HasSubstr("[benchmark] time_limit: 9e+09 s is more than the limit"));
}

// ---------------------------------------------------------------------------------------------
// Crashes, hangs and unbounded memory.

std::string nested(const std::string& tag, int depth, const std::string& inside = "") {
  std::string text;
  text.reserve(static_cast<std::size_t>(depth) * (2 * tag.size() + 5) + inside.size());
  for (int i = 0; i < depth; ++i) text += "<" + tag + ">";
  text += inside;
  for (int i = 0; i < depth; ++i) text += "</" + tag + ">";
  return text;
}

// Runs `call` with a time bound: a reader that blocks or takes quadratic time fails the test.
std::string errorWithin(std::chrono::seconds limit, const std::function<void()>& call,
                        const std::function<void()>& unblock = {}) {
  auto future = std::async(std::launch::async, [&] { return errorOf(call); });
  if (future.wait_for(limit) == std::future_status::ready) return future.get();
  ADD_FAILURE() << "no answer within " << limit.count() << " s";
  // A reader blocked on a FIFO may open it again after each unblocking: keep unblocking.
  while (unblock && future.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
    unblock();
  }
  return future.get();
}

// D6: 100,000 nested elements overflowed TinyXML's stack (30,000 took 43 s, its parse being
// quadratic in the depth). Every XML reader checks the depth first, in linear time.
TEST_F(HostileInput, DeeplyNestedXmlIsRefusedBeforeParsing) {
  const std::string deep =
      "<robot name=\"r\"><link name=\"a\"/>" + nested("x", 100000) + "</robot>";
  std::string what = errorWithin(std::chrono::seconds(5),
                                 [&] { RobotModel::fromUrdfFile(write("deep.urdf", deep)); });
  EXPECT_THAT(what, HasSubstr("deep.urdf"));
  EXPECT_THAT(what, HasSubstr("nest"));
  const RobotModel robot = RobotModel::fromUrdfString(armUrdf(), "arm.urdf", ".");
  what = errorWithin(std::chrono::seconds(5), [&] {
    RobotModel copy = robot;
    copy.loadSrdfFile(
        write("deep.srdf", "<robot name=\"arm\">" + nested("x", 100000) + "</robot>"));
  });
  EXPECT_THAT(what, HasSubstr("deep.srdf"));
  EXPECT_THAT(what, HasSubstr("nest"));
  // A package.xml that deep is unreadable, like any other broken manifest: the package is then
  // found by its directory's name.
  fs::create_directories(dir_ / "pkg" / "meshes");
  write("pkg/package.xml", "<package>" + nested("x", 100000, "<name>pkg</name>") + "</package>");
  write("pkg/meshes/m.stl", "");
  const PackageLocator locator({dir_.string()}, false);
  const auto resolved = std::async(std::launch::async, [&] {
    return locator.resolve("package://pkg/meshes/m.stl", dir_.string());
  });
  ASSERT_EQ(resolved.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  // Nesting up to the limit still parses (a URDF needs five levels).
  EXPECT_NO_THROW(RobotModel::fromUrdfString(
      "<robot name=\"r\"><link name=\"a\">" + nested("x", 200) + "</link></robot>", "ok.urdf",
      "."));
}

// D5: a Collada file of 10,000 nested <node>s overflowed the stack inside assimp (SIGSEGV).
TEST_F(HostileInput, DeeplyNestedColladaIsRefusedBeforeAssimp) {
  const std::string head =
      "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" "
      "version=\"1.4.1\"><library_visual_scenes><visual_scene id=\"s\">";
  const std::string tail =
      "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#s\"/></scene>"
      "</COLLADA>\n";
  const std::string path = write("deep.dae", head + nested("node", 10000) + tail);
  const std::string what = errorWithin(std::chrono::seconds(5), [&] { loadMesh(path); });
  EXPECT_THAT(what, HasSubstr("deep.dae"));
  EXPECT_THAT(what, HasSubstr("nest more than"));
}

// D12, D13: a FIFO given as the scene or as a mesh blocked forever, and a scene symlinked to
// /dev/zero read 4.2 GB before std::bad_alloc. Every reader wants a regular file first.
TEST_F(HostileInput, FifosAndDevicesAreRefusedWithoutReading) {
  const std::string fifo = (dir_ / "fifo.yaml").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Opening the FIFO for writing and closing it lets a blocked reader see the end of it.
  const auto unblock = [&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  };
  std::string what = errorWithin(
      std::chrono::seconds(5), [&] { loadPlanningScene(fifo); }, unblock);
  EXPECT_THAT(what, HasSubstr("fifo.yaml: scene file is not a regular file"));
  const std::string mesh_fifo = (dir_ / "fifo.stl").string();
  ASSERT_EQ(mkfifo(mesh_fifo.c_str(), 0600), 0);
  const auto unblock_mesh = [&] {
    const int fd = ::open(mesh_fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  };
  what = errorWithin(
      std::chrono::seconds(5), [&] { loadMesh(mesh_fifo); }, unblock_mesh);
  EXPECT_THAT(what, HasSubstr("fifo.stl: mesh file is not a regular file"));
  // As a scene's environment mesh, the error also names the scene.
  const std::string scene =
      write("fifo_world.yaml", "robot: {mesh: " + kSource +
                                   "/robots/meshes/rigid/l_piece.stl}\n"
                                   "environment: [{mesh: {file: fifo.stl}}]\n");
  what = errorWithin(
      std::chrono::seconds(5), [&] { loadPlanningScene(scene); }, unblock_mesh);
  EXPECT_THAT(what, HasSubstr("fifo_world.yaml"));
  EXPECT_THAT(what, HasSubstr("not a regular file"));

  fs::create_symlink("/dev/zero", dir_ / "zero.yaml");
  what = errorWithin(std::chrono::seconds(5),
                     [&] { loadPlanningScene((dir_ / "zero.yaml").string()); });
  EXPECT_THAT(what, HasSubstr("zero.yaml: scene file is not a regular file"));
  fs::create_symlink("/dev/zero", dir_ / "zero.urdf");
  what = errorWithin(std::chrono::seconds(5),
                     [&] { RobotModel::fromUrdfFile((dir_ / "zero.urdf").string()); });
  EXPECT_THAT(what, HasSubstr("not a regular file"));
}

// D8, D9: a 100 MB STL peaked at 4 GB inside assimp, a 100 MB YAML scene exhausted 8 GB in
// yaml-cpp. Files beyond the reader's documented limit are refused before they are read (the
// files here are sparse: their size costs no disk).
TEST_F(HostileInput, FilesBeyondTheSizeLimitAreRefusedBeforeReading) {
  const fs::path stl = dir_ / "huge.stl";
  {
    std::ofstream out(stl, std::ios::binary);
    char header[84] = {};
    const std::uint32_t triangles = 2000000;
    std::memcpy(header + 80, &triangles, 4);
    out.write(header, sizeof header);
  }
  fs::resize_file(stl, 84 + 50 * 2000000ull);  // 100 MB
  std::string what = errorWithin(std::chrono::seconds(5), [&] { loadMesh(stl.string()); });
  EXPECT_THAT(what, HasSubstr("huge.stl: mesh file is 95 MiB, more than the limit of"));
  // The limit is an option: a small one refuses a small file.
  MeshLoadOptions small;
  small.max_file_bytes = 100;
  writeBoxObj("box.obj", Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_NO_THROW(loadMesh((dir_ / "box.obj").string()));
  EXPECT_THAT(errorOf([&] { loadMesh((dir_ / "box.obj").string(), small); }),
              HasSubstr("more than the limit of"));

  // A scene of 200,000 boxes (about 10 MB of valid YAML).
  std::string yaml = "robot: {mesh: a.stl}\nenvironment:\n";
  const std::string item = "  - {box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [1, 2, 3]}}\n";
  yaml.reserve(item.size() * 200000 + 64);
  for (int i = 0; i < 200000; ++i) yaml += item;
  const std::string scene = write("huge.yaml", yaml);
  what = errorWithin(std::chrono::seconds(5), [&] { loadScene(scene); });
  EXPECT_THAT(what, HasSubstr("huge.yaml: scene file is"));
  EXPECT_THAT(what, HasSubstr("more than the limit"));
}

// D10: a 30,000-link URDF exhausted memory (a links x links matrix and a pair list). The link
// count is checked before anything of that size is allocated.
TEST_F(HostileInput, RobotsWithTooManyLinksAreRefusedEarly) {
  std::ostringstream urdf;
  urdf << "<robot name=\"snake\">\n<link name=\"l0\"/>\n";
  for (int i = 1; i < 30000; ++i) {
    urdf << "<link name=\"l" << i << "\"/><joint name=\"j" << i
         << "\" type=\"fixed\"><parent link=\"l" << i - 1 << "\"/><child link=\"l" << i
         << "\"/></joint>\n";
  }
  urdf << "</robot>\n";
  const std::string path = write("snake.urdf", urdf.str());
  const std::string what =
      errorWithin(std::chrono::seconds(5), [&] { RobotModel::fromUrdfFile(path); });
  EXPECT_THAT(what, HasSubstr("snake.urdf"));
  EXPECT_THAT(what, HasSubstr("30000 links, more than the limit"));
}

// D16: write errors were ignored: `--out /dev/full` and stdout on /dev/full exited 0 saying
// "written".
TEST_F(HostileInput, WriteErrorsFailWithAMessage) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const std::string scene = freeFlyingScene();
  CliResult r = runCli(dir_, "plan " + scene + " --out /dev/full");
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.err, HasSubstr("/dev/full: write error"));
  EXPECT_THAT(r.err, Not(HasSubstr("path written")));
  r = runCli(dir_, "plan " + scene, "/dev/full");
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.err, HasSubstr("standard output: write error"));
  r = runCli(dir_, "info " + scene, "/dev/full");
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.err, HasSubstr("standard output: write error"));
}

// D18: a prismatic joint with +-1e9 m limits let OMPL's "The fraction of the extent must be
// larger than 0" escape, naming nothing. Now an octomotion::Error names the joint.
TEST_F(HostileInput, StateSpacesTooLargeToCheckNameTheJoint) {
  const std::string tail =
      "  <link name=\"tip\"><collision><geometry><sphere radius=\"0.05\"/></geometry>"
      "</collision></link>\n"
      "  <joint name=\"slide\" type=\"prismatic\"><parent link=\"arm\"/><child link=\"tip\"/>"
      "<axis xyz=\"1 0 0\"/><limit lower=\"-1e9\" upper=\"1e9\" effort=\"1\" velocity=\"1\"/>"
      "</joint>\n";
  write("slide.urdf", armUrdf(tail));
  const std::string scene =
      write("slide.yaml",
            "robot: {urdf: slide.urdf}\noctree: {resolution: 0.05}\n"
            // The universe is the environment the robot can reach, so it is small.
            "environment: [{box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [0.5, 0.5, 0]}}]\n");
  const std::string what = errorOf([&] { loadPlanningScene(scene); });
  EXPECT_THAT(what, HasSubstr("slide.yaml"));
  EXPECT_THAT(what, HasSubstr("joint 'slide' with limits [-1e+09, 1e+09]"));
}

// ---------------------------------------------------------------------------------------------
// Messages that did not locate the problem.

TEST_F(HostileInput, MessagesNameTheFieldAndTheFile) {
  // --resolution 1e-9 printed as "0.000000 m" with no field.
  const std::string scene = freeFlyingScene();
  SceneOverrides fine;
  fine.resolution = 1e-9;
  std::string what = errorOf([&] { loadPlanningScene(scene, fine); });
  EXPECT_THAT(what, HasSubstr("free.yaml"));
  EXPECT_THAT(what, HasSubstr("--resolution 1e-09 m"));
  EXPECT_THAT(what, Not(HasSubstr("0.000000")));

  // resolution: auto on a degenerate scene said "must be finite and > 0".
  const std::string vast =
      freeFlyingScene("", "{min: [-1e300, -1e300, -1e300], max: [1e300, 1e300, 1e300]}");
  SceneOverrides automatic;
  automatic.auto_resolution = true;
  what = errorOf([&] { loadPlanningScene(vast, automatic); });
  EXPECT_THAT(what, HasSubstr("free.yaml"));
  EXPECT_THAT(what, HasSubstr("octree.resolution auto: the scene's extent (diagonal inf m)"));

  // A .cfg with `robot =` empty named its directory.
  const std::string cfg_tail =
      "start.x = 0\nstart.y = 0\nstart.z = 0\ngoal.x = 1\ngoal.y = 0\ngoal.z = 0\n";
  what = errorOf(
      [&] { parseOmplAppCfg("[problem]\nrobot =\nworld = w.obj\n" + cfg_tail, "/s/e.cfg"); });
  EXPECT_THAT(what, HasSubstr("[problem] robot: empty"));

  // time_limit = nan named an internal key.
  what = errorOf([&] {
    parseOmplAppCfg(
        "[problem]\nrobot = r\nworld = w\n" + cfg_tail + "[benchmark]\ntime_limit = nan\n",
        "/s/nan.cfg");
  });
  EXPECT_THAT(what, HasSubstr("[benchmark] time_limit: expected a finite number, got 'nan'"));
  EXPECT_THAT(what, Not(HasSubstr("__")));

  // Mesh errors of a .cfg robot named the mesh, not the .cfg.
  write("garbage.stl", "solid nothing here\nfacet normal oops\n");
  writeBoxObj("world.obj", Eigen::Vector3d::Constant(-0.1), Eigen::Vector3d::Constant(0.1));
  const std::string cfg =
      write("bad_robot.cfg", "[problem]\nrobot = garbage.stl\nworld = world.obj\n" + cfg_tail);
  what = errorOf([&] { loadPlanningScene(cfg); });
  EXPECT_THAT(what, HasSubstr("bad_robot.cfg"));
  EXPECT_THAT(what, HasSubstr("garbage.stl"));
}

}  // namespace
}  // namespace octomotion
