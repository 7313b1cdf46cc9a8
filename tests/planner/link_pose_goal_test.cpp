// Goals given as a link pose (ompl/link_pose_goal.h, `problem.goal: {link: ...}`): the scene key
// and its errors; scenes that plan to such a goal, whose path ends with the link within the
// tolerances (checked here by forward kinematics) in a valid state, with every planner the
// command line offers; goal samples taken from several threads at once.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <ompl/base/goals/GoalStates.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/link_pose_goal.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "slowdown.h"

namespace octomotion {
namespace {

using test::kSlowdown;

namespace fs = std::filesystem;
namespace ob = ompl::base;

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kPandaDir = kSource + "/../shared/data/panda";

std::string writeScene(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(::testing::TempDir()) / "octomotion_link_pose_goal";
  fs::create_directories(dir);
  const fs::path path = dir / (name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

std::string list(const Eigen::VectorXd& v) {
  std::ostringstream s;
  s.precision(17);
  s << "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
  s << "]";
  return s.str();
}

// The octo7 bookshelf scene with its goal replaced by the hand's pose at the scene's own joint
// goal (reachable and free by construction), or, when `environment` is false, in open space.
struct Octo7Scene {
  std::string path;
  Eigen::Isometry3d X_target;
};
Octo7Scene octo7Scene(const std::string& name, const std::string& planner, bool environment) {
  RobotModelOptions options;
  options.package_paths = {kSource};
  const RobotModel robot = RobotModel::fromUrdfFile(kSource + "/robots/octo7/octo7.urdf", options);
  const std::vector<double> q_goal = {-2.16, -0.502, 1.442, -1.4, -0.815, -0.618, 1.199, 0.02};
  RobotData data = robot.makeData();
  robot.forwardKinematics(q_goal.data(), q_goal.size(), data);
  Octo7Scene scene;
  scene.X_target = data.linkPose(robot.linkIndex("hand"));
  const Eigen::Quaterniond r(scene.X_target.linear());
  std::ostringstream text;
  text << "robot:\n  urdf: " << kSource << "/robots/octo7/octo7.urdf\n  srdf: " << kSource
       << "/robots/octo7/octo7.srdf\n  package_path: [" << kSource << "]\n";
  if (environment) {
    text << "environment:\n"
            "  - {name: back, box: {size: [0.02, 0.84, 1.2]}, pose: {xyz: [0.86, 0, 0.6]}}\n"
            "  - {name: side_left, box: {size: [0.32, 0.02, 1.2]}, pose: {xyz: [0.70, -0.41, "
            "0.6]}}\n"
            "  - {name: side_right, box: {size: [0.32, 0.02, 1.2]}, pose: {xyz: [0.70, 0.41, "
            "0.6]}}\n"
            "  - {name: board_low, box: {size: [0.32, 0.8, 0.02]}, pose: {xyz: [0.70, 0, 0.30]}}\n"
            "  - {name: board_middle, box: {size: [0.32, 0.8, 0.02]}, pose: {xyz: [0.70, 0, "
            "0.65]}}\n"
            "  - {name: board_high, box: {size: [0.32, 0.8, 0.02]}, pose: {xyz: [0.70, 0, "
            "1.00]}}\n";
  } else {
    text << "environment:\n  - {name: far, box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [0, 2, 0]}}\n";
  }
  text << "octree: {resolution: 0.01}\n"
       << "problem:\n  start: [0, 0, 0, 0, 0, 0, 0, 0]\n"
       << "  goal:\n    link: hand\n    position: " << list(scene.X_target.translation()) << "\n"
       << "    orientation: " << list(r.coeffs()) << "\n"
       << "    tolerance: {position: 0.002, orientation: 0.02}\n"
       << "  planner: " << planner << "\n  time: 60\n  seed: 3\n";
  scene.path = writeScene(name, text.str());
  return scene;
}

// The path's last state has the link within the tolerances (forward kinematics here, not the
// goal's code), and every state of the path is valid.
void expectEndsAtTheLinkPose(const PlanningScene& scene, const PlanResult& result,
                             const std::string& link, const Eigen::Vector3d& position,
                             const std::optional<Eigen::Quaterniond>& orientation,
                             double position_tolerance, double orientation_tolerance) {
  ASSERT_TRUE(result.solved);
  ASSERT_TRUE(result.path);
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  for (std::size_t i = 0; i < result.path->getStateCount(); ++i) {
    EXPECT_TRUE(si->isValid(result.path->getState(static_cast<unsigned>(i)))) << "state " << i;
  }
  const RobotModel& robot = scene.model->robot();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(stateToConfiguration(robot, result.path->getStates().back(), q, X_WB));
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data);
  const Eigen::Isometry3d& X = data.linkPose(robot.linkIndex(link));
  EXPECT_LE((X.translation() - position).norm(), position_tolerance);
  if (orientation) {
    EXPECT_LE(Eigen::AngleAxisd(orientation->toRotationMatrix().transpose() * X.linear()).angle(),
              orientation_tolerance * (1 + 1e-9));
  }
  EXPECT_TRUE(scene.setup->getGoal()->isSatisfied(result.path->getStates().back()));
}

TEST(LinkPoseGoal, Octo7PlansIntoTheBookshelf) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const Octo7Scene s = octo7Scene("octo7_bookshelf", "RRTConnect", true);
  PlanningScene scene = loadPlanningScene(s.path);
  ASSERT_TRUE(scene.setup->getGoal()->hasType(ob::GOAL_SAMPLEABLE_REGION));
  const PlanResult result = plan(scene);
  expectEndsAtTheLinkPose(scene, result, "hand", s.X_target.translation(),
                          Eigen::Quaterniond(s.X_target.linear()), 0.002, 0.02);
}

TEST(LinkPoseGoal, PandaPlansToAHandPoseOverATable) {
  if (!fs::exists(kPandaDir + "/panda.urdf")) GTEST_SKIP() << "no " << kPandaDir;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string path = writeScene("panda_table", "robot:\n  urdf: " + kPandaDir +
                                                         "/panda.urdf\n  srdf: " + kPandaDir +
                                                         "/panda.srdf\n"
                                                         "environment:\n"
                                                         "  - {name: table, box: {size: [0.6, "
                                                         "1.0, 0.2]}, pose: {xyz: [0.55, 0, "
                                                         "0.1]}}\n"
                                                         "octree: {resolution: 0.01}\n"
                                                         "problem:\n"
                                                         "  start: [0, -0.785, 0, -2.356, 0, "
                                                         "1.571, 0.785, 0.02]\n"
                                                         "  goal: {link: panda_hand, position: "
                                                         "[0.5, 0.2, 0.45], rpy: [3.14159, 0, "
                                                         "0]}\n"
                                                         "  time: 60\n  seed: 5\n");
  PlanningScene scene = loadPlanningScene(path);
  const PlanResult result = plan(scene);
  const Eigen::Quaterniond down(rotationFromRpy(3.14159, 0, 0));
  expectEndsAtTheLinkPose(scene, result, "panda_hand", Eigen::Vector3d(0.5, 0.2, 0.45), down,
                          LinkPoseGoalSpec().position_tolerance,
                          LinkPoseGoalSpec().orientation_tolerance);
}

// The example of docs/robots.md ("Goals as a link pose") plans as the page says: the hand ends
// within the tolerances it gives.
TEST(LinkPoseGoal, RobotsDocExamplePlans) {
  if (!fs::exists(kPandaDir + "/panda.urdf")) GTEST_SKIP() << "no " << kPandaDir;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  std::ifstream in(kSource + "/docs/robots.md");
  std::string line, yaml;
  bool section = false, inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) section = line == "## Goals as a link pose";
    if (!section) continue;
    if (!inside && line == "```yaml") {
      inside = true;
    } else if (inside && line == "```") {
      break;
    } else if (inside) {
      yaml += line + "\n";
    }
  }
  ASSERT_FALSE(yaml.empty()) << "no yaml block in the section";
  // The page shows docs/examples/panda_shelf.yaml as it is.
  const std::string file = kSource + "/docs/examples/panda_shelf.yaml";
  std::ifstream example(file);
  const std::string text((std::istreambuf_iterator<char>(example)),
                         std::istreambuf_iterator<char>());
  EXPECT_EQ(yaml, text) << "docs/robots.md's example differs from " << file;
  PlanningScene scene = loadPlanningScene(file);
  const LinkPoseGoalSpec goal = *scene.spec.problem.goal->link_pose;
  const PlanResult result = plan(scene);
  expectEndsAtTheLinkPose(scene, result, goal.link, goal.position, goal.orientation,
                          goal.position_tolerance, goal.orientation_tolerance);
}

// Every planner the command line offers (makePlanner) reaches the goal in open space; those that
// need goal states (plannerNeedsGoalStates) plan to pre-sampled IK solutions. Left out: FMT, a
// batch of a fixed number of samples that may end without a solution, and LazyPRM, whose solve
// (OMPL 1.6) leaks the goal samples of the vertices it removes, which LeakSanitizer reports.
TEST(LinkPoseGoal, EveryPlannerReachesIt) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  for (const char* planner : {"RRTConnect", "RRT", "RRTstar", "InformedRRTstar", "BITstar", "PRM",
                              "PRMstar", "KPIECE1", "BKPIECE1", "LBKPIECE1", "EST", "SBL"}) {
    SCOPED_TRACE(planner);
    const Octo7Scene s = octo7Scene(std::string("octo7_open_") + planner, planner, false);
    SceneOverrides overrides;
    // The optimising planners use all of it; the others stop when solved. Sanitizer builds
    // check states several times slower.
    overrides.time = 2 * kSlowdown;
    PlanningScene scene = loadPlanningScene(s.path, overrides);
    EXPECT_EQ(scene.setup->getGoal()->hasType(ob::GOAL_STATES), plannerNeedsGoalStates(planner));
    const PlanResult result = plan(scene);
    expectEndsAtTheLinkPose(scene, result, "hand", s.X_target.translation(),
                            Eigen::Quaterniond(s.X_target.linear()), 0.002, 0.02);
  }
}

TEST(LinkPoseGoal, SamplesFromSeveralThreads) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const Octo7Scene s = octo7Scene("octo7_threads", "RRTConnect", true);
  PlanningScene scene = loadPlanningScene(s.path);
  const auto goal = scene.setup->getGoal()->as<LinkPoseGoal>();
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  std::atomic<int> valid{0}, wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      ob::State* state = si->allocState();
      for (int k = 0; k < 5; ++k) {
        if (goal->sampleValidGoal(state, 20)) {
          ++valid;
          // What sampleValidGoal calls valid is a valid state inside the goal.
          if (!si->isValid(state) || !goal->isSatisfied(state)) ++wrong;
          double distance = -1;
          goal->isSatisfied(state, &distance);
          if (!(distance >= 0 && distance <= goal->getThreshold() + 1e-12)) ++wrong;
        }
      }
      si->freeState(state);
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_GT(valid.load(), 0);
}

TEST(LinkPoseGoal, SceneKey) {
  const SceneSpec spec = parseSceneYaml(
      "robot: {urdf: arm.urdf}\n"
      "problem:\n  start: [0, 0]\n"
      "  goal: {link: hand, position: [0.1, 0.2, 0.3], rpy: [0, 0, 1.5],\n"
      "         tolerance: {position: 0.005, orientation: 0.1}}\n",
      "/tmp/scene.yaml");
  ASSERT_TRUE(spec.problem.goal && spec.problem.goal->link_pose);
  const LinkPoseGoalSpec& goal = *spec.problem.goal->link_pose;
  EXPECT_EQ(goal.link, "hand");
  EXPECT_EQ(goal.position, Eigen::Vector3d(0.1, 0.2, 0.3));
  ASSERT_TRUE(goal.orientation);
  EXPECT_TRUE(goal.orientation->toRotationMatrix().isApprox(
      Eigen::AngleAxisd(1.5, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  EXPECT_EQ(goal.position_tolerance, 0.005);
  EXPECT_EQ(goal.orientation_tolerance, 0.1);

  // A quaternion [x, y, z, w], normalised; no orientation at all: position only.
  const SceneSpec quat = parseSceneYaml(
      "robot: {urdf: arm.urdf}\nproblem: {goal: {link: hand, position: [0, 0, 1], orientation: "
      "[0, 0, 2, 0]}}\n",
      "/tmp/scene.yaml");
  ASSERT_TRUE(quat.problem.goal->link_pose->orientation);
  EXPECT_TRUE(quat.problem.goal->link_pose->orientation->isApprox(Eigen::Quaterniond(0, 0, 0, 1)));
  const SceneSpec position_only = parseSceneYaml(
      "robot: {urdf: arm.urdf}\nproblem: {goal: {link: hand, position: [0, 0, 1]}}\n",
      "/tmp/scene.yaml");
  EXPECT_FALSE(position_only.problem.goal->link_pose->orientation);
  EXPECT_EQ(position_only.problem.goal->link_pose->position_tolerance,
            LinkPoseGoalSpec().position_tolerance);
}

TEST(LinkPoseGoal, SceneKeyErrorsNameTheField) {
  auto error = [](const std::string& goal) {
    try {
      parseSceneYaml("robot: {urdf: arm.urdf}\nproblem: {goal: " + goal + "}\n", "/tmp/scene.yaml");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto expectMentions = [&](const std::string& goal, const std::string& field) {
    const std::string message = error(goal);
    EXPECT_NE(message.find(field), std::string::npos) << goal << " -> " << message;
    EXPECT_NE(message.find("/tmp/scene.yaml"), std::string::npos) << message;
  };
  expectMentions("{link: hand}", "problem.goal.position");
  expectMentions("{link: hand, position: [0, 1]}", "problem.goal.position");
  expectMentions("{link: hand, position: [0, 0, .nan]}", "problem.goal.position[2]");
  expectMentions("{link: '', position: [0, 0, 0]}", "problem.goal.link");
  expectMentions("{link: hand, position: [0, 0, 0], frame: world}", "problem.goal.frame");
  expectMentions("{link: hand, position: [0, 0, 0], orientation: [0, 0, 0, 0]}",
                 "problem.goal.orientation");
  expectMentions("{link: hand, position: [0, 0, 0], orientation: [0, 0, 1]}",
                 "problem.goal.orientation");
  expectMentions("{link: hand, position: [0, 0, 0], orientation: [0, 0, 0, 1], rpy: [0, 0, 0]}",
                 "problem.goal");
  expectMentions("{link: hand, position: [0, 0, 0], tolerance: {position: 0}}",
                 "problem.goal.tolerance.position");
  expectMentions("{link: hand, position: [0, 0, 0], tolerance: {orientation: -1}}",
                 "problem.goal.tolerance.orientation");
  expectMentions("{link: hand, position: [0, 0, 0], tolerance: {angle: 1}}",
                 "problem.goal.tolerance.angle");
}

TEST(LinkPoseGoal, UnknownLinkAndRigidBodiesAreRefused) {
  const Octo7Scene s = octo7Scene("octo7_unknown_link", "RRTConnect", false);
  std::string text;
  {
    std::ifstream in(s.path);
    std::stringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  const auto at = text.find("link: hand");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, "link: claw");
  const std::string path = writeScene("octo7_claw", text);
  try {
    loadPlanningScene(path);
    ADD_FAILURE() << "no error";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("problem.goal.link"), std::string::npos) << message;
    EXPECT_NE(message.find("claw"), std::string::npos) << message;
  }

  // A one-link URDF flies free in SE(3): its goal is a pose, not a link pose.
  const std::string body = writeScene(
      "rigid_link_goal",
      "robot: {urdf: " + kSource + "/robots/rigid/l_piece.urdf, package_path: " + kSource +
          "}\nenvironment:\n  - {box: {size: [0.1, 0.1, 0.1]}}\n" +
          "problem: {bounds: {min: [-1, -1, -1], max: [1, 1, 1]}, start: " +
          "{xyz: [0.5, 0.5, 0.5]}, goal: {link: l_piece, position: [0, 0, 0]}}\n");
  try {
    loadPlanningScene(body);
    ADD_FAILURE() << "no error";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("problem.goal"), std::string::npos) << message;
    EXPECT_NE(message.find("free-flying"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace octomotion
