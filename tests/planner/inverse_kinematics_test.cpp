// Inverse kinematics (robot/inverse_kinematics.h): the analytic Jacobian against finite
// differences of forward kinematics (revolute, continuous, prismatic and mimic joints); targets
// made by forward kinematics of random in-limit configurations, solved from other random seeds,
// on the Panda, the shipped octo7 and octo6, and octo7 with held joints made fixed: every
// reported success is checked by forward kinematics, and nearly every target is reached;
// unreachable targets fail within the iteration cap; bad input is an InvalidArgument.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "joint_states.h"
#include "octomotion/planner/robot/inverse_kinematics.h"

namespace octomotion {
namespace {

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kPandaDir = kSource + "/../shared/data/panda";

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

RobotModel octo(const std::string& name) {
  RobotModelOptions options;
  options.package_paths = {kSource};
  return RobotModel::fromUrdfFile(kSource + "/robots/" + name + "/" + name + ".urdf", options);
}

// octo7 with joint2 and joint5 held (made fixed), as an SRDF group reduction leaves a model: IK
// must only see the remaining variables.
RobotModel octo7WithHeldJoints() {
  std::string urdf = readText(kSource + "/robots/octo7/octo7.urdf");
  for (const char* joint : {"joint2", "joint5"}) {
    const std::string from = std::string("<joint name=\"") + joint + "\" type=\"revolute\">";
    const auto at = urdf.find(from);
    EXPECT_NE(at, std::string::npos) << joint;
    urdf.replace(at, from.size(), std::string("<joint name=\"") + joint + "\" type=\"fixed\">");
  }
  RobotModelOptions options;
  options.package_paths = {kSource};
  return RobotModel::fromUrdfString(urdf, "octo7_held", kSource + "/robots/octo7", options);
}

// The pose errors, computed here without the solver's code: the distance between positions and
// the angle of the relative rotation.
void poseErrors(const RobotModel& robot, const std::vector<double>& q, int link,
                const Eigen::Isometry3d& X_WB, const Eigen::Isometry3d& X_target, double& position,
                double& angle) {
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data, X_WB);
  const Eigen::Isometry3d& X = data.linkPose(link);
  position = (X.translation() - X_target.translation()).norm();
  angle = Eigen::AngleAxisd(X_target.linear().transpose() * X.linear()).angle();
}

// The Jacobian's columns against central differences of forward kinematics: the linear part is
// d(position)/dq, the angular part the rotation vector of R(q + h) R(q - h)^T over 2h.
void expectJacobianMatchesDifferences(const RobotModel& robot, const std::string& link_name,
                                      std::uint64_t seed) {
  const InverseKinematics ik(robot);
  const int link = robot.linkIndex(link_name);
  RobotData data = robot.makeData();
  constexpr double h = 1e-6;
  for (const std::vector<double>& q : test::uniformJointStates(robot, 20, seed)) {
    const Eigen::Matrix<double, 6, Eigen::Dynamic> J = ik.jacobian(link, q);
    ASSERT_EQ(J.cols(), robot.variableCount());
    for (int v = 0; v < robot.variableCount(); ++v) {
      std::vector<double> plus = q, minus = q;
      plus[static_cast<std::size_t>(v)] += h;
      minus[static_cast<std::size_t>(v)] -= h;
      robot.forwardKinematics(plus.data(), plus.size(), data);
      const Eigen::Isometry3d X_plus = data.linkPose(link);
      robot.forwardKinematics(minus.data(), minus.size(), data);
      const Eigen::Isometry3d X_minus = data.linkPose(link);
      const Eigen::Vector3d linear = (X_plus.translation() - X_minus.translation()) / (2 * h);
      const Eigen::AngleAxisd delta(X_plus.linear() * X_minus.linear().transpose());
      const Eigen::Vector3d angular = delta.axis() * delta.angle() / (2 * h);
      EXPECT_LT((J.col(v).head<3>() - linear).norm(), 1e-6)
          << link_name << " variable " << robot.variables()[static_cast<std::size_t>(v)].name;
      EXPECT_LT((J.col(v).tail<3>() - angular).norm(), 1e-6)
          << link_name << " variable " << robot.variables()[static_cast<std::size_t>(v)].name;
    }
  }
}

TEST(InverseKinematics, JacobianMatchesFiniteDifferences) {
  // arm.urdf: revolute, an axis of length 2 (normalised by the loader), a fixed joint, a
  // continuous wrist, a prismatic finger and a mimic finger of multiplier -1.
  const RobotModel arm =
      RobotModel::fromUrdfFile(std::string(OCTOMOTION_TEST_DATA_DIR) + "/urdf/arm.urdf");
  for (const char* link : {"fore", "tool", "hand", "finger_left", "finger_right"}) {
    expectJacobianMatchesDifferences(arm, link, 3);
  }
  const RobotModel robot = octo("octo7");
  for (const char* link : {"link4", "hand", "right_finger"}) {
    expectJacobianMatchesDifferences(robot, link, 4);
  }
}

struct Reach {
  int targets = 0;
  int successes = 0;
};

// Targets: the link's pose at random in-limit configurations (so every one is reachable); each
// solved from a configuration of another random stream. Every success must be one by forward
// kinematics, within the limits.
Reach solveReachableTargets(const RobotModel& robot, const std::string& link_name,
                            bool with_orientation, int count, const Eigen::Isometry3d& X_WB) {
  IkOptions options;
  options.position_tolerance = 1e-3;
  options.orientation_tolerance = 1e-2;
  const InverseKinematics ik(robot, X_WB, options);
  const int link = robot.linkIndex(link_name);
  IkScratch scratch = ik.makeScratch();
  std::mt19937_64 rng(11);
  RobotData data = robot.makeData();
  const auto goals = test::uniformJointStates(robot, count, 5);
  const auto seeds = test::uniformJointStates(robot, count, 6);
  Reach reach;
  for (int k = 0; k < count; ++k) {
    const std::vector<double>& q_goal = goals[static_cast<std::size_t>(k)];
    robot.forwardKinematics(q_goal.data(), q_goal.size(), data, X_WB);
    const Eigen::Isometry3d X_target = data.linkPose(link);
    std::optional<Eigen::Quaterniond> orientation;
    if (with_orientation) orientation = Eigen::Quaterniond(X_target.linear());
    const LinkPoseTarget target = ik.target(link_name, X_target.translation(), orientation);
    const IkResult r = ik.solve(target, seeds[static_cast<std::size_t>(k)], rng, scratch);
    ++reach.targets;
    EXPECT_LE(r.iterations, options.max_iterations * options.max_attempts);
    EXPECT_EQ(r.q.size(), static_cast<std::size_t>(robot.variableCount()));
    if (!r.success) continue;
    ++reach.successes;
    double position = 0, angle = 0;
    poseErrors(robot, r.q, link, X_WB, X_target, position, angle);
    EXPECT_LE(position, options.position_tolerance) << "target " << k;
    if (with_orientation) {
      EXPECT_LE(angle, options.orientation_tolerance * (1 + 1e-9)) << "target " << k;
    }
    EXPECT_NEAR(r.position_error, position, 1e-12);
    EXPECT_TRUE(robot.withinLimits(
        Eigen::Map<const Eigen::VectorXd>(r.q.data(), static_cast<Eigen::Index>(r.q.size()))))
        << "target " << k;
  }
  return reach;
}

// Every target is reachable by construction and each solve has 20 starts, so a solver that
// misses more than 1 target in 20 is broken, not unlucky: the rare misses are targets whose
// every start descends into a joint limit.
constexpr double kMinSuccessRate = 0.95;

void expectReaches(const RobotModel& robot, const std::string& link, bool with_orientation,
                   int count, const Eigen::Isometry3d& X_WB = Eigen::Isometry3d::Identity()) {
  const Reach reach = solveReachableTargets(robot, link, with_orientation, count, X_WB);
  std::cout << robot.name() << " " << link << (with_orientation ? " pose" : " position") << ": "
            << reach.successes << " of " << reach.targets << " solved\n";
  EXPECT_GE(reach.successes, kMinSuccessRate * reach.targets)
      << robot.name() << " " << link << (with_orientation ? " pose" : " position") << ": "
      << reach.successes << " of " << reach.targets;
}

TEST(InverseKinematics, ReachesPandaPoses) {
  if (!std::filesystem::exists(kPandaDir + "/panda.urdf")) GTEST_SKIP() << "no " << kPandaDir;
  const RobotModel panda = RobotModel::fromUrdfFile(kPandaDir + "/panda.urdf");
  expectReaches(panda, "panda_hand", true, 200);
  expectReaches(panda, "panda_hand", false, 200);
  // A mounted robot: targets and solutions both in the world.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translation() = Eigen::Vector3d(0.4, -1.0, 0.1);
  X_WB.linear() = Eigen::AngleAxisd(1.57, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  expectReaches(panda, "panda_link8", true, 100, X_WB);
}

TEST(InverseKinematics, ReachesShippedArmPoses) {
  expectReaches(octo("octo7"), "hand", true, 200);
  expectReaches(octo("octo7"), "left_finger", false, 100);
  expectReaches(octo("octo6"), "tool0", true, 200);
}

TEST(InverseKinematics, ReachesPosesWithHeldJoints) {
  const RobotModel robot = octo7WithHeldJoints();
  ASSERT_EQ(robot.variableCount(), octo("octo7").variableCount() - 2);
  // Five arm joints left: a full pose is six constraints, so targets are reachable only because
  // they come from the reduced model's own kinematics.
  expectReaches(robot, "hand", true, 100);
}

TEST(InverseKinematics, UnreachableTargetFailsWithinTheCap) {
  const RobotModel robot = octo("octo7");
  IkOptions options;
  options.max_iterations = 60;
  options.max_attempts = 7;
  const InverseKinematics ik(robot, Eigen::Isometry3d::Identity(), options);
  const std::vector<double> seed(static_cast<std::size_t>(robot.variableCount()), 0.0);
  for (const bool with_orientation : {false, true}) {
    std::optional<Eigen::Quaterniond> orientation;
    if (with_orientation) orientation = Eigen::Quaterniond::Identity();
    const LinkPoseTarget target = ik.target("hand", Eigen::Vector3d(10, 0, 0.5), orientation);
    const IkResult r = ik.solve(target, seed, 1);
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.attempts, options.max_attempts);
    EXPECT_LE(r.iterations, options.max_iterations * options.max_attempts);
    EXPECT_GT(r.position_error, 8.0);  // the arm is about a metre long
    ASSERT_EQ(r.q.size(), seed.size());
    EXPECT_TRUE(robot.withinLimits(
        Eigen::Map<const Eigen::VectorXd>(r.q.data(), static_cast<Eigen::Index>(r.q.size()))));
  }
}

TEST(InverseKinematics, SameSeedSameAnswer) {
  const RobotModel robot = octo("octo7");
  const InverseKinematics ik(robot);
  const LinkPoseTarget target =
      ik.target("hand", Eigen::Vector3d(0.4, 0.2, 0.6), Eigen::Quaterniond(0, 1, 0, 0));
  const std::vector<double> seed(static_cast<std::size_t>(robot.variableCount()), 0.3);
  const IkResult a = ik.solve(target, seed, 42);
  const IkResult b = ik.solve(target, seed, 42);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.iterations, b.iterations);
}

TEST(InverseKinematics, RejectsBadInput) {
  const RobotModel robot = octo("octo7");
  const InverseKinematics ik(robot);
  const std::vector<double> seed(static_cast<std::size_t>(robot.variableCount()), 0.0);
  EXPECT_THROW(ik.target("no_such_link", Eigen::Vector3d::Zero()), InvalidArgument);
  EXPECT_THROW(ik.target("hand", Eigen::Vector3d(NAN, 0, 0)), InvalidArgument);
  EXPECT_THROW(ik.target("hand", Eigen::Vector3d(0, INFINITY, 0)), InvalidArgument);
  EXPECT_THROW(ik.target("hand", Eigen::Vector3d::Zero(), Eigen::Quaterniond(0, 0, 0, 0)),
               InvalidArgument);
  EXPECT_THROW(ik.target("hand", Eigen::Vector3d::Zero(), Eigen::Quaterniond(NAN, 0, 0, 1)),
               InvalidArgument);
  LinkPoseTarget bad_link;
  bad_link.link = robot.linkCount();
  EXPECT_THROW(ik.solve(bad_link, seed), InvalidArgument);
  LinkPoseTarget nan_target = ik.target("hand", Eigen::Vector3d::Zero());
  nan_target.position.z() = NAN;
  EXPECT_THROW(ik.solve(nan_target, seed), InvalidArgument);
  const LinkPoseTarget target = ik.target("hand", Eigen::Vector3d(0.3, 0, 0.5));
  EXPECT_THROW(ik.solve(target, std::vector<double>(2, 0.0)), InvalidArgument);
  std::vector<double> nan_seed = seed;
  nan_seed[1] = NAN;
  EXPECT_THROW(ik.solve(target, nan_seed), InvalidArgument);
  IkOptions options;
  options.position_tolerance = 0;
  EXPECT_THROW(InverseKinematics(robot, Eigen::Isometry3d::Identity(), options), InvalidArgument);
  options = IkOptions();
  options.max_attempts = 0;
  EXPECT_THROW(InverseKinematics(robot, Eigen::Isometry3d::Identity(), options), InvalidArgument);
  const RobotModel body = RobotModel::rigidBody("body", {});
  EXPECT_THROW(InverseKinematics{body}, InvalidArgument);
}

}  // namespace
}  // namespace octomotion
