// RobotModel: URDF/SRDF loading, package:// resolution, collision filtering and forward
// kinematics checked against hand-computed poses (tests/data/urdf/arm.urdf is documented there).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/planner/robot/package_locator.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kDataDir = std::string(OCTOMOTION_TEST_DATA_DIR) + "/urdf";
const std::string kArm = kDataDir + "/arm.urdf";
const std::string kPackages = kDataDir + "/packages";

// Expects `f` to throw an octomotion::Error whose message contains every fragment.
template <typename F>
void expectError(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << fragments.front();
  } catch (const Error& e) {
    // OCTOMOTION_PRINT_ERRORS=1 shows the messages users would see.
    if (std::getenv("OCTOMOTION_PRINT_ERRORS") != nullptr) std::cerr << e.what() << "\n";
    for (const std::string& fragment : fragments) {
      EXPECT_THAT(e.what(), HasSubstr(fragment));
    }
  }
}

// Restores the package-path environment variables a test changes.
class EnvironmentGuard {
 public:
  EnvironmentGuard() {
    for (const char* name : {"OCTOMOTION_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
      const char* value = std::getenv(name);
      saved_.emplace_back(name, value ? std::optional<std::string>(value) : std::nullopt);
      unsetenv(name);
    }
  }
  ~EnvironmentGuard() {
    for (const auto& [name, value] : saved_) {
      if (value) {
        setenv(name.c_str(), value->c_str(), 1);
      } else {
        unsetenv(name.c_str());
      }
    }
  }

 private:
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

// A scratch directory for URDFs written by the tests, removed afterwards.
class TempDir {
 public:
  TempDir() {
    path_ =
        fs::temp_directory_path() / ("octomotion_robot_model_test_" + std::to_string(::getpid()) +
                                     "_" + std::to_string(counter_++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string path() const { return path_.string(); }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

Eigen::Isometry3d translation(double x, double y, double z) {
  return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
}
Eigen::Isometry3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Isometry3d(Eigen::AngleAxisd(angle, axis));
}

void expectPoseNear(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected,
                    double tolerance = 1e-12) {
  EXPECT_TRUE(actual.matrix().isApprox(expected.matrix(), tolerance) ||
              (actual.matrix() - expected.matrix()).norm() < tolerance)
      << "actual\n"
      << actual.matrix() << "\nexpected\n"
      << expected.matrix();
}

std::string robotXml(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n" + body + "\n</robot>\n";
}

const char* kLimit = "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& extra = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + extra + "</joint>";
}

// --- Structure ---

TEST(RobotModel, ArmStructureInDepthFirstFileOrder) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  EXPECT_EQ(arm.name(), "arm");
  EXPECT_EQ(arm.sourcePath(), kArm);
  EXPECT_FALSE(arm.isFreeFlying());
  const std::vector<std::string> links = {"base", "upper",       "fore",        "tool",
                                          "hand", "finger_left", "finger_right"};
  ASSERT_EQ(arm.linkCount(), static_cast<int>(links.size()));
  for (int i = 0; i < arm.linkCount(); ++i) EXPECT_EQ(arm.link(i).name, links[i]) << i;
  ASSERT_EQ(arm.jointCount(), arm.linkCount() - 1);
  for (int j = 0; j < arm.jointCount(); ++j) {
    EXPECT_EQ(arm.joint(j).child_link, j + 1);  // joint j is the parent joint of link j + 1
    EXPECT_EQ(arm.link(j + 1).parent_joint, j);
    EXPECT_LT(arm.joint(j).parent_link, arm.joint(j).child_link);
  }
  EXPECT_EQ(arm.link(0).parent_joint, -1);
  EXPECT_EQ(arm.link(arm.linkIndex("finger_right")).parent_link, arm.linkIndex("hand"));
  EXPECT_EQ(arm.link(arm.linkIndex("hand")).child_joints.size(), 2u);

  // Variables: movable non-mimic joints, depth-first, siblings in file order.
  ASSERT_EQ(arm.variableCount(), 4);
  const std::vector<std::string> variables = {"shoulder", "elbow", "wrist", "slider"};
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(arm.variables()[v].name, variables[v]);
    EXPECT_EQ(arm.variableIndex(variables[v]), v);
  }
  EXPECT_DOUBLE_EQ(arm.variables()[0].lower, -2.0);
  EXPECT_DOUBLE_EQ(arm.variables()[0].upper, 2.0);
  EXPECT_FALSE(arm.variables()[0].continuous);
  EXPECT_TRUE(arm.variables()[2].continuous);
  EXPECT_DOUBLE_EQ(arm.variables()[2].lower, -M_PI);
  EXPECT_DOUBLE_EQ(arm.variables()[2].upper, M_PI);
  EXPECT_DOUBLE_EQ(arm.variables()[3].lower, 0.0);
  EXPECT_DOUBLE_EQ(arm.variables()[3].upper, 0.04);

  const Joint& elbow = arm.joint(arm.jointIndex("elbow"));
  EXPECT_EQ(elbow.type, JointType::kRevolute);
  EXPECT_TRUE(elbow.axis.isApprox(Eigen::Vector3d::UnitZ()));  // <axis xyz="0 0 2"> normalized
  EXPECT_DOUBLE_EQ(elbow.max_velocity, 1.5);
  EXPECT_DOUBLE_EQ(elbow.max_effort, 10.0);
  EXPECT_EQ(arm.joint(arm.jointIndex("tool_mount")).type, JointType::kFixed);
  EXPECT_EQ(arm.joint(arm.jointIndex("wrist")).type, JointType::kContinuous);
  const Joint& mirror = arm.joint(arm.jointIndex("finger_mirror"));
  EXPECT_TRUE(mirror.isMimic());
  EXPECT_EQ(mirror.mimic_master, arm.jointIndex("slider"));
  EXPECT_DOUBLE_EQ(mirror.mimic_multiplier, -1.0);
  EXPECT_EQ(mirror.variable, -1);
  expectError([&] { arm.variableIndex("finger_mirror"); }, {"finger_mirror", "mimic"});
  expectError([&] { arm.variableIndex("tool_mount"); }, {"tool_mount", "fixed"});
  expectError([&] { arm.linkIndex("nope"); }, {"nope"});
  EXPECT_EQ(arm.findJoint("nope"), -1);
  EXPECT_STREQ(toString(JointType::kPrismatic), "prismatic");
}

TEST(RobotModel, CollisionGeometryPerLink) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  // base: URDF box size is full extents.
  const Link& base = arm.link(arm.linkIndex("base"));
  ASSERT_EQ(base.collision.size(), 1u);
  const Box& box = std::get<Box>(std::get<Primitive>(base.collision[0].geometry));
  EXPECT_TRUE(box.half_extents.isApprox(Eigen::Vector3d(0.2, 0.2, 0.05)));
  expectPoseNear(base.collision[0].X_LE, translation(0, 0, 0.05));

  // upper: two <collision> elements, each with its own origin.
  const Link& upper = arm.link(arm.linkIndex("upper"));
  ASSERT_EQ(upper.collision.size(), 2u);
  EXPECT_EQ(upper.collision[0].name, "upper_body");
  const Cylinder& cylinder = std::get<Cylinder>(std::get<Primitive>(upper.collision[0].geometry));
  EXPECT_DOUBLE_EQ(cylinder.radius, 0.05);
  EXPECT_DOUBLE_EQ(cylinder.length, 1.0);
  expectPoseNear(upper.collision[0].X_LE,
                 translation(0.5, 0, 0) * rotation(M_PI / 2, Eigen::Vector3d::UnitY()), 1e-12);
  // The cylinder's z axis now lies along the link's x axis.
  EXPECT_TRUE((upper.collision[0].X_LE.linear() * Eigen::Vector3d::UnitZ())
                  .isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  const Sphere& sphere = std::get<Sphere>(std::get<Primitive>(upper.collision[1].geometry));
  EXPECT_DOUBLE_EQ(sphere.radius, 0.08);
  expectPoseNear(upper.collision[1].X_LE, translation(1, 0, 0));

  // fore: a mesh relative to the URDF's directory, with its scale.
  const Link& fore = arm.link(arm.linkIndex("fore"));
  ASSERT_EQ(fore.collision.size(), 1u);
  const MeshRef& mesh = std::get<MeshRef>(fore.collision[0].geometry);
  EXPECT_TRUE(fs::path(mesh.path).is_absolute());
  EXPECT_TRUE(fs::equivalent(mesh.path, kDataDir + "/meshes/tetra.stl"));
  EXPECT_TRUE(mesh.scale.isApprox(Eigen::Vector3d(0.5, 0.25, 0.125)));

  EXPECT_FALSE(arm.link(arm.linkIndex("tool")).hasCollision());
}

TEST(RobotModel, MeshRefLoadsWithRobotConvention) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  const MeshRef& ref = std::get<MeshRef>(arm.link(arm.linkIndex("fore")).collision[0].geometry);
  MeshLoadOptions options;
  options.keep_root_transform = false;
  options.scale = ref.scale;
  const TriangleMesh mesh = loadMesh(ref.path, options);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-1e9);
  for (const auto& v : mesh.vertices) max = max.cwiseMax(v);
  EXPECT_TRUE(max.isApprox(Eigen::Vector3d(0.5, 0.25, 0.125)));
}

// --- Forward kinematics ---

TEST(RobotModel, ForwardKinematicsMatchesHandComputedPoses) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  RobotData data = arm.makeData();
  const int upper = arm.linkIndex("upper"), fore = arm.linkIndex("fore"),
            tool = arm.linkIndex("tool"), hand = arm.linkIndex("hand"),
            left = arm.linkIndex("finger_left"), right = arm.linkIndex("finger_right");

  // q = (shoulder, elbow, wrist, slider).
  Eigen::VectorXd q(4);
  q << M_PI / 2, -M_PI / 2, 0.0, 0.01;
  arm.forwardKinematics(q, data);
  expectPoseNear(data.linkPose(0), Eigen::Isometry3d::Identity());
  expectPoseNear(data.linkPose(upper),
                 translation(0, 0, 0.1) * rotation(M_PI / 2, Eigen::Vector3d::UnitZ()));
  // The forearm starts 1 m along the upper arm (now world +y) and points along world +x.
  expectPoseNear(data.linkPose(fore), translation(0, 1, 0.1));
  // Fixed joint with rpy origin: 0.5 m further, turned 90 degrees about z.
  expectPoseNear(data.linkPose(tool),
                 translation(0.5, 1, 0.1) * rotation(M_PI / 2, Eigen::Vector3d::UnitZ()));
  expectPoseNear(data.linkPose(hand),
                 translation(0.5, 1.1, 0.1) * rotation(M_PI / 2, Eigen::Vector3d::UnitZ()));
  // Prismatic along the hand's y (world -x); the mimic finger moves the other way.
  expectPoseNear(data.linkPose(left),
                 translation(0.5 - 0.03, 1.1, 0.1) * rotation(M_PI / 2, Eigen::Vector3d::UnitZ()));
  expectPoseNear(data.linkPose(right),
                 translation(0.5 + 0.03, 1.1, 0.1) * rotation(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_DOUBLE_EQ(data.joint_values[static_cast<std::size_t>(arm.jointIndex("finger_mirror"))],
                   -0.01);

  // Continuous wrist about the tool's x axis (world y): the finger offset tilts up.
  q << 0.0, 0.0, 0.7, 0.02;
  arm.forwardKinematics(q, data);
  const double d = 0.02 + 0.02;
  EXPECT_TRUE(data.linkPose(left).translation().isApprox(
      Eigen::Vector3d(1.5 - d * std::cos(0.7), 0.1, 0.1 + d * std::sin(0.7)), 1e-12))
      << data.linkPose(left).translation().transpose();
  EXPECT_TRUE(data.linkPose(right).translation().isApprox(
      Eigen::Vector3d(1.5 + d * std::cos(0.7), 0.1, 0.1 - d * std::sin(0.7)), 1e-12));
}

TEST(RobotModel, PlanarArmClosedFormAndBasePose) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  RobotData data = arm.makeData();
  RobotData based = arm.makeData();
  const int tool = arm.linkIndex("tool");
  const Eigen::Isometry3d X_WB =
      translation(0.3, -2, 1) * rotation(0.4, Eigen::Vector3d(1, 2, 3).normalized());
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> angle(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = angle(rng), b = angle(rng), w = 3 * angle(rng);
    Eigen::VectorXd q(4);
    q << a, b, w, 0.02;
    arm.forwardKinematics(q, data);
    // Two-link planar arm end point (lengths 1 and 0.5), height 0.1.
    const Eigen::Vector3d expected(std::cos(a) + 0.5 * std::cos(a + b),
                                   std::sin(a) + 0.5 * std::sin(a + b), 0.1);
    EXPECT_TRUE(data.linkPose(tool).translation().isApprox(expected, 1e-12));
    const Eigen::Matrix3d R_expected =
        Eigen::AngleAxisd(a + b + M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_TRUE(data.linkPose(tool).linear().isApprox(R_expected, 1e-12));
    // The base pose premultiplies every link pose.
    arm.forwardKinematics(q.data(), 4, based, X_WB);
    for (int i = 0; i < arm.linkCount(); ++i) {
      expectPoseNear(based.linkPose(i), X_WB * data.linkPose(i), 1e-12);
    }
  }
}

TEST(RobotModel, ForwardKinematicsRejectsBadInput) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  RobotData data = arm.makeData();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  expectError([&] { arm.forwardKinematics(q, data); }, {"3", "4"});
  q = Eigen::VectorXd::Zero(4);
  q[1] = std::nan("");
  expectError([&] { arm.forwardKinematics(q, data); }, {"q[1]", "elbow"});
  q[1] = 0.0;
  RobotData wrong = RobotModel::fromMesh(kDataDir + "/meshes/tetra.stl").makeData();
  expectError([&] { arm.forwardKinematics(q, wrong); }, {"RobotData"});
  EXPECT_TRUE(arm.withinLimits(q));
  q[2] = 100.0;  // continuous: always within limits
  EXPECT_TRUE(arm.withinLimits(q));
  q[3] = 0.05;  // slider upper limit is 0.04
  EXPECT_FALSE(arm.withinLimits(q));
  EXPECT_FALSE(arm.withinLimits(Eigen::VectorXd::Zero(2)));
}

TEST(RobotModel, MimicChainsComposeAndFollowTheirMaster) {
  // c mimics b (x2 + 0.1), b mimics a (x-1 + 0.5): c = 2 * (-a + 0.5) + 0.1 = -2a + 1.1.
  const std::string xml =
      robotXml("<link name=\"r\"/><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>" +
               joint("ja", "prismatic", "r", "a", std::string("<axis xyz=\"1 0 0\"/>") + kLimit) +
               joint("jb", "prismatic", "r", "b",
                     std::string("<axis xyz=\"0 1 0\"/>") + kLimit +
                         "<mimic joint=\"ja\" multiplier=\"-1\" offset=\"0.5\"/>") +
               joint("jc", "revolute", "r", "c",
                     std::string("<axis xyz=\"0 0 1\"/>") + kLimit +
                         "<mimic joint=\"jb\" multiplier=\"2\" offset=\"0.1\"/>"));
  const RobotModel model = RobotModel::fromUrdfString(xml, "mimic.urdf", kDataDir);
  ASSERT_EQ(model.variableCount(), 1);
  const Joint& jc = model.joint(model.jointIndex("jc"));
  EXPECT_EQ(jc.mimic_master, model.jointIndex("ja"));
  EXPECT_DOUBLE_EQ(jc.mimic_multiplier, -2.0);
  EXPECT_DOUBLE_EQ(jc.mimic_offset, 1.1);
  RobotData data = model.makeData();
  Eigen::VectorXd q(1);
  q << 0.3;
  model.forwardKinematics(q, data);
  expectPoseNear(data.linkPose(model.linkIndex("a")), translation(0.3, 0, 0));
  expectPoseNear(data.linkPose(model.linkIndex("b")), translation(0, 0.2, 0));
  expectPoseNear(data.linkPose(model.linkIndex("c")),
                 rotation(-2 * 0.3 + 1.1, Eigen::Vector3d::UnitZ()));
  // <mimic> without multiplier/offset: identity map.
  const RobotModel plain = RobotModel::fromUrdfString(
      robotXml("<link name=\"r\"/><link name=\"a\"/><link name=\"b\"/>" +
               joint("ja", "continuous", "r", "a") +
               joint("jb", "continuous", "r", "b", "<mimic joint=\"ja\"/>")),
      "plain_mimic.urdf", kDataDir);
  EXPECT_DOUBLE_EQ(plain.joint(1).mimic_multiplier, 1.0);
  EXPECT_DOUBLE_EQ(plain.joint(1).mimic_offset, 0.0);
}

TEST(RobotModel, JointAxesAnyDirection) {
  // Coordinate axes of either sign (the shortcut path) and oblique axes (the general path) all
  // agree with X_PJ * Rot(axis, v) / X_PJ * Trans(axis * v).
  const std::vector<Eigen::Vector3d> axes = {
      Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(),    Eigen::Vector3d::UnitY(),
      -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),     -Eigen::Vector3d::UnitZ(),
      Eigen::Vector3d(1, 1, 0),  Eigen::Vector3d(-0.3, 2, 0.7)};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::string type : {"revolute", "prismatic"}) {
    for (const Eigen::Vector3d& axis : axes) {
      std::ostringstream xyz;
      xyz << axis.x() << " " << axis.y() << " " << axis.z();
      const RobotModel model = RobotModel::fromUrdfString(
          robotXml("<link name=\"p\"/><link name=\"c\"/>" +
                   joint("j", type, "p", "c",
                         "<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0.4 -0.5 0.6\"/><axis xyz=\"" +
                             xyz.str() + "\"/>" + kLimit)),
          "axis.urdf", kDataDir);
      const Eigen::Isometry3d X_PJ = model.joint(0).X_PJ;
      const Eigen::Vector3d unit = axis.normalized();
      const Eigen::Isometry3d X_WB = translation(u(rng), u(rng), u(rng)) *
                                     rotation(u(rng), Eigen::Vector3d(1, -1, 2).normalized());
      RobotData data = model.makeData();
      for (int trial = 0; trial < 10; ++trial) {
        const double v = u(rng);
        model.forwardKinematics(&v, 1, data, X_WB);
        const Eigen::Isometry3d motion = type == "revolute"
                                             ? rotation(v, unit)
                                             : Eigen::Isometry3d(Eigen::Translation3d(unit * v));
        expectPoseNear(data.linkPose(1), X_WB * X_PJ * motion, 1e-12);
      }
    }
  }
}

TEST(RobotModel, SharedModelIsThreadSafe) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  std::vector<Eigen::VectorXd> configurations;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 64; ++i) {
    Eigen::VectorXd q(4);
    q << u(rng), u(rng), u(rng), 0.02 + 0.02 * u(rng);
    configurations.push_back(q);
  }
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> expected;
  RobotData data = arm.makeData();
  for (const auto& q : configurations) {
    arm.forwardKinematics(q, data);
    expected.push_back(data.linkPose(arm.linkCount() - 1));
  }
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      RobotData mine = arm.makeData();
      for (int round = 0; round < 50; ++round) {
        for (std::size_t i = 0; i < configurations.size(); ++i) {
          arm.forwardKinematics(configurations[i], mine);
          if (!mine.linkPose(arm.linkCount() - 1).isApprox(expected[i], 0.0)) ++mismatches[t];
        }
      }
    });
  }
  for (auto& thread : threads) thread.join();
  for (int m : mismatches) EXPECT_EQ(m, 0);
}

TEST(RobotModel, LongChainMatchesClosedForm) {
  // 300 revolute joints about z, 0.01 m apart: a planar chain whose tip is the sum of the
  // segment vectors at the cumulative angles. Exercises the iterative depth-first layout.
  const int n = 300;
  std::string body = "<link name=\"l0\"/>";
  for (int i = 1; i <= n; ++i) {
    body += "<link name=\"l" + std::to_string(i) + "\"/>";
    body += joint("j" + std::to_string(i), "continuous", "l" + std::to_string(i - 1),
                  "l" + std::to_string(i), "<origin xyz=\"0.01 0 0\"/><axis xyz=\"0 0 1\"/>");
  }
  const RobotModel chain = RobotModel::fromUrdfString(robotXml(body), "chain.urdf", kDataDir);
  ASSERT_EQ(chain.variableCount(), n);
  EXPECT_EQ(chain.link(n).name, "l" + std::to_string(n));
  RobotData data = chain.makeData();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i) q[i] = u(rng);
  chain.forwardKinematics(q, data);
  // Link i sits 0.01 along the x axis of link i-1, which is turned by q_1 + ... + q_{i-1}.
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double angle = 0.0;
  for (int i = 0; i < n; ++i) {
    tip += 0.01 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
    angle += q[i];
  }
  EXPECT_TRUE(data.linkPose(n).translation().isApprox(tip, 1e-10));
  EXPECT_NEAR(Eigen::AngleAxisd(data.linkPose(n).linear()).angle(),
              std::abs(std::remainder(angle, 2 * M_PI)), 1e-9);
}

// The models under robots/ (package octomotion_robots, found below the repository root).
TEST(RobotModel, RepositoryRobotsLoad) {
  EnvironmentGuard guard;
  RobotModelOptions options;
  options.package_paths = {OCTOMOTION_SOURCE_DIR};
  const std::string robots = std::string(OCTOMOTION_SOURCE_DIR) + "/robots";
  for (const std::string name : {"octo6", "octo7"}) {
    SCOPED_TRACE(name);
    RobotModel arm = RobotModel::fromUrdfFile(robots + "/" + name + "/" + name + ".urdf", options);
    EXPECT_EQ(arm.name(), name);
    EXPECT_EQ(arm.variableCount(), name == "octo6" ? 6 : 8);
    for (const Link& link : arm.links()) {
      for (const CollisionElement& e : link.collision) {
        if (const auto* mesh = std::get_if<MeshRef>(&e.geometry)) {
          EXPECT_TRUE(
              fs::equivalent(fs::path(mesh->path).parent_path(), robots + "/meshes/" + name))
              << mesh->path;
        }
      }
    }
    arm.loadSrdfFile(robots + "/" + name + "/" + name + ".srdf");
    EXPECT_FALSE(arm.checkedPairs().empty());
    RobotData data = arm.makeData();
    const Eigen::VectorXd q = Eigen::VectorXd::Zero(arm.variableCount());
    arm.forwardKinematics(q, data);
    for (int i = 0; i < arm.linkCount(); ++i) EXPECT_TRUE(data.linkPose(i).matrix().allFinite());
  }
  const RobotModel octo7 = RobotModel::fromUrdfFile(robots + "/octo7/octo7.urdf", options);
  EXPECT_TRUE(octo7.joint(octo7.jointIndex("finger_joint2")).isMimic());
  for (const std::string name : {"l_piece", "drone"}) {
    RobotModelOptions rigid = options;
    rigid.base = BaseMotion::kFreeFlying;
    const RobotModel body = RobotModel::fromUrdfFile(robots + "/rigid/" + name + ".urdf", rigid);
    EXPECT_TRUE(body.isFreeFlying());
    EXPECT_EQ(body.variableCount(), 0);
  }
}

TEST(RobotModel, UrdfdomWarningsGoToTheSink) {
  std::vector<std::string> warnings;
  RobotModelOptions options;
  options.warnings = [&](const std::string& w) { warnings.push_back(w); };
  const RobotModel model = RobotModel::fromUrdfString(
      robotXml("<link name=\"a\"><visual><geometry><sphere radius=\"1\"/></geometry>"
               "<material name=\"undeclared\"/></visual></link>"),
      "warn.urdf", kDataDir, options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("warn.urdf"));
  EXPECT_THAT(warnings[0], HasSubstr("undeclared"));
  EXPECT_FALSE(model.link(0).hasCollision());  // visual geometry is not collision geometry
}

// --- Free-flying bodies ---

TEST(RobotModel, FreeFlyingRigidBodies) {
  const RobotModel body =
      RobotModel::fromMesh(kDataDir + "/meshes/tetra.stl", Eigen::Vector3d(2, 2, 2));
  EXPECT_TRUE(body.isFreeFlying());
  EXPECT_EQ(body.name(), "tetra");
  EXPECT_EQ(body.linkCount(), 1);
  EXPECT_EQ(body.variableCount(), 0);
  EXPECT_TRUE(body.checkedPairs().empty());
  const MeshRef& ref = std::get<MeshRef>(body.link(0).collision.at(0).geometry);
  EXPECT_TRUE(fs::path(ref.path).is_absolute());
  EXPECT_TRUE(ref.scale.isApprox(Eigen::Vector3d(2, 2, 2)));
  RobotData data = body.makeData();
  const Eigen::Isometry3d X_WB =
      translation(1, 2, 3) * rotation(1.0, Eigen::Vector3d(0, 1, 1).normalized());
  body.forwardKinematics(nullptr, 0, data, X_WB);
  expectPoseNear(data.linkPose(0), X_WB);

  expectError([&] { RobotModel::fromMesh(kDataDir + "/meshes/missing.stl"); }, {"missing.stl"});
  expectError(
      [&] { RobotModel::fromMesh(kDataDir + "/meshes/tetra.stl", Eigen::Vector3d(1, 0, 1)); },
      {"scale"});
  CollisionElement bad;
  bad.geometry = Primitive(Sphere{-1.0});
  expectError([&] { RobotModel::rigidBody("ball", {bad}); }, {"ball", "element 0"});
  CollisionElement ok;
  ok.geometry = Primitive(Box{Eigen::Vector3d(1, 2, 3)});
  EXPECT_EQ(RobotModel::rigidBody("box", {ok}).link(0).name, "box");

  // A one-link URDF loaded as a free flyer.
  RobotModelOptions options;
  options.base = BaseMotion::kFreeFlying;
  const RobotModel urdf_body = RobotModel::fromUrdfString(
      robotXml("<link name=\"only\"><collision><geometry><sphere radius=\"0.5\"/></geometry>"
               "</collision></link>"),
      "body.urdf", kDataDir, options);
  EXPECT_TRUE(urdf_body.isFreeFlying());
  EXPECT_EQ(urdf_body.variableCount(), 0);
}

// --- package:// and other URIs ---

void expectPackageMeshesResolved(const RobotModel& model) {
  const Link& body = model.link(0);
  ASSERT_EQ(body.collision.size(), 2u);
  const MeshRef& a = std::get<MeshRef>(body.collision[0].geometry);
  const MeshRef& b = std::get<MeshRef>(body.collision[1].geometry);
  EXPECT_TRUE(fs::equivalent(a.path, kPackages + "/octo_test_pkg/meshes/tetra.stl")) << a.path;
  EXPECT_TRUE(fs::equivalent(b.path, kPackages + "/vendor/nested_dir/tetra.stl")) << b.path;
  EXPECT_TRUE(b.scale.isApprox(Eigen::Vector3d(2, 2, 2)));
  expectPoseNear(body.collision[1].X_LE, translation(0, 0, 1));
}

TEST(PackageUris, ResolvedThroughEnvironmentVariables) {
  EnvironmentGuard guard;
  const std::string urdf = kDataDir + "/package_mesh.urdf";
  expectError([&] { RobotModel::fromUrdfFile(urdf); },
              {urdf, "link 'body'", "package://octo_test_pkg/meshes/tetra.stl", "not found"});
  setenv("OCTOMOTION_PACKAGE_PATH", ("/nonexistent/dir:" + kPackages).c_str(), 1);
  expectPackageMeshesResolved(RobotModel::fromUrdfFile(urdf));
  unsetenv("OCTOMOTION_PACKAGE_PATH");
  setenv("ROS_PACKAGE_PATH", kPackages.c_str(), 1);
  expectPackageMeshesResolved(RobotModel::fromUrdfFile(urdf));
  // The environment can be switched off.
  RobotModelOptions no_env;
  no_env.use_environment_package_paths = false;
  expectError([&] { RobotModel::fromUrdfFile(urdf, no_env); }, {urdf, "octo_test_pkg"});
}

TEST(PackageUris, ResolvedThroughApiOption) {
  EnvironmentGuard guard;
  RobotModelOptions options;
  options.package_paths = {kPackages};
  expectPackageMeshesResolved(RobotModel::fromUrdfFile(kDataDir + "/package_mesh.urdf", options));
}

TEST(PackageUris, LocatorRules) {
  EnvironmentGuard guard;
  setenv("OCTOMOTION_PACKAGE_PATH", "/a::/b", 1);
  setenv("ROS_PACKAGE_PATH", "/c", 1);
  EXPECT_EQ(PackageLocator::environmentSearchPaths(), (std::vector<std::string>{"/a", "/b", "/c"}));
  const PackageLocator with_env({"/first"});
  EXPECT_EQ(with_env.searchPaths(), (std::vector<std::string>{"/first", "/a", "/b", "/c"}));

  const PackageLocator locator({kPackages}, false);
  ASSERT_TRUE(locator.findPackage("octo_test_pkg").has_value());  // by directory name
  EXPECT_TRUE(fs::equivalent(*locator.findPackage("octo_test_pkg"), kPackages + "/octo_test_pkg"));
  ASSERT_TRUE(locator.findPackage("renamed_pkg").has_value());  // by package.xml, crawled
  EXPECT_TRUE(
      fs::equivalent(*locator.findPackage("renamed_pkg"), kPackages + "/vendor/nested_dir"));
  // A directory below the top level is found by its package.xml name only.
  EXPECT_FALSE(locator.findPackage("nested_dir").has_value());
  EXPECT_FALSE(locator.findPackage("no_such_pkg").has_value());
  EXPECT_FALSE(locator.findPackage("").has_value());
  EXPECT_FALSE(locator.findPackage("../urdf").has_value());
  // A search directory that is itself the package.
  const PackageLocator self({kPackages + "/vendor/nested_dir"}, false);
  EXPECT_TRUE(self.findPackage("renamed_pkg").has_value());

  // URI forms.
  EXPECT_EQ(locator.resolve("package://octo_test_pkg/meshes/tetra.stl", "/ignored"),
            fs::path(kPackages + "/octo_test_pkg/meshes/tetra.stl").lexically_normal().string());
  EXPECT_EQ(locator.resolve("file:///abs/mesh.stl", "/base"), "/abs/mesh.stl");
  EXPECT_EQ(locator.resolve("/abs/mesh.stl", "/base"), "/abs/mesh.stl");
  EXPECT_EQ(locator.resolve("meshes/../m.stl", "/base/dir"), "/base/dir/m.stl");
  expectError([&] { locator.resolve("http://example.com/m.stl", "/base"); },
              {"unsupported scheme"});
  expectError([&] { locator.resolve("package://", "/base"); }, {"no package"});
  expectError([&] { locator.resolve("", "/base"); }, {"empty"});
  expectError([&] { locator.resolve("package://nope/m.stl", "/base"); }, {"nope", kPackages});
}

TEST(PackageUris, ShallowestPackageWins) {
  // Two copies of package "dup": a deep one under "a_build/..." (listed first by name) and a
  // shallow one under "z_src". Breadth-first search returns the shallow one.
  TempDir dir;
  const fs::path root(dir.path());
  const std::string manifest = "<package><name>dup</name></package>";
  fs::create_directories(root / "a_build/x/y/copy");
  fs::create_directories(root / "z_src/real");
  dir.write("a_build/x/y/copy/package.xml", manifest);
  dir.write("z_src/real/package.xml", manifest);
  const PackageLocator locator({dir.path()}, false);
  ASSERT_TRUE(locator.findPackage("dup").has_value());
  EXPECT_TRUE(fs::equivalent(*locator.findPackage("dup"), root / "z_src/real"));
  // Too deep (depth 5) is not found.
  fs::create_directories(root / "d1/d2/d3/d4/deep");
  dir.write("d1/d2/d3/d4/deep/package.xml", "<package><name>deep</name></package>");
  EXPECT_FALSE(locator.findPackage("deep").has_value());
}

TEST(PackageUris, FileSchemeInUrdf) {
  const std::string xml =
      robotXml("<link name=\"l\"><collision><geometry><mesh filename=\"file://" + kDataDir +
               "/meshes/tetra.stl\"/></geometry></collision></link>");
  const RobotModel model = RobotModel::fromUrdfString(xml, "file_uri.urdf", "/nonexistent");
  EXPECT_TRUE(fs::equivalent(std::get<MeshRef>(model.link(0).collision[0].geometry).path,
                             kDataDir + "/meshes/tetra.stl"));
}

// --- Collision filter ---

std::vector<std::pair<std::string, std::string>> namedPairs(
    const RobotModel& model, const std::vector<std::pair<int, int>>& pairs) {
  std::vector<std::pair<std::string, std::string>> named;
  for (const auto& [a, b] : pairs) named.emplace_back(model.link(a).name, model.link(b).name);
  return named;
}

using NamedPairs = std::vector<std::pair<std::string, std::string>>;

TEST(CollisionFilter, AdjacentLinksDisabledByDefault) {
  const RobotModel arm = RobotModel::fromUrdfFile(kArm);
  // tool has no geometry, so hand is also adjacent to fore (MoveIt Setup Assistant's rule).
  EXPECT_EQ(namedPairs(arm, arm.disabledPairs()), (NamedPairs{{"base", "upper"},
                                                              {"upper", "fore"},
                                                              {"fore", "tool"},
                                                              {"fore", "hand"},
                                                              {"tool", "hand"},
                                                              {"hand", "finger_left"},
                                                              {"hand", "finger_right"}}));
  EXPECT_TRUE(arm.collisionAllowed(arm.linkIndex("fore"), arm.linkIndex("hand")));
  EXPECT_TRUE(arm.collisionAllowed(arm.linkIndex("hand"), arm.linkIndex("fore")));
  EXPECT_TRUE(arm.collisionAllowed(2, 2));
  EXPECT_FALSE(arm.collisionAllowed(arm.linkIndex("base"), arm.linkIndex("fore")));
  EXPECT_FALSE(arm.collisionAllowed(arm.linkIndex("finger_left"), arm.linkIndex("finger_right")));
  // 6 links with geometry -> 15 pairs, 5 of them adjacent.
  EXPECT_EQ(arm.checkedPairs().size(), 10u);
  for (const auto& [a, b] : arm.checkedPairs()) {
    EXPECT_LT(a, b);
    EXPECT_FALSE(arm.collisionAllowed(a, b));
    EXPECT_TRUE(arm.link(a).hasCollision() && arm.link(b).hasCollision());
  }
  expectError([&] { arm.collisionAllowed(0, 7); }, {"link_b", "7"});
}

TEST(CollisionFilter, SrdfPairsHonoured) {
  RobotModel arm = RobotModel::fromUrdfFile(kArm);
  arm.loadSrdfFile(kDataDir + "/arm.srdf");  // replaces the adjacent defaults
  EXPECT_EQ(
      namedPairs(arm, arm.disabledPairs()),
      (NamedPairs{{"base", "upper"}, {"hand", "finger_left"}, {"finger_left", "finger_right"}}));
  EXPECT_FALSE(arm.collisionAllowed(arm.linkIndex("upper"), arm.linkIndex("fore")));
  EXPECT_EQ(arm.checkedPairs().size(), 12u);

  arm.resetCollisionFilterToAdjacent();
  arm.loadSrdfFile(kDataDir + "/arm.srdf", SrdfMode::kMerge);
  EXPECT_EQ(arm.disabledPairs().size(), 8u);  // 7 adjacent + finger pair
  EXPECT_EQ(arm.checkedPairs().size(), 9u);

  arm.loadSrdfString(
      "<robot name=\"arm\"><disable_default_collisions link=\"base\"/>"
      "<enable_collisions link1=\"base\" link2=\"finger_left\"/></robot>",
      "inline.srdf", SrdfMode::kReplace);
  for (int i = 0; i < arm.linkCount(); ++i) {
    EXPECT_EQ(arm.collisionAllowed(0, i), arm.link(i).name != "finger_left") << i;
  }
  EXPECT_EQ(namedPairs(arm, arm.checkedPairs()).front(),
            (std::pair<std::string, std::string>{"base", "finger_left"}));
}

TEST(CollisionFilter, ApiEditsPairs) {
  RobotModel arm = RobotModel::fromUrdfFile(kArm);
  arm.disableCollision("finger_left", "finger_right");
  EXPECT_TRUE(arm.collisionAllowed(arm.linkIndex("finger_right"), arm.linkIndex("finger_left")));
  EXPECT_EQ(arm.checkedPairs().size(), 9u);
  arm.enableCollision(arm.linkIndex("hand"), arm.linkIndex("finger_left"));
  EXPECT_FALSE(arm.collisionAllowed(arm.linkIndex("hand"), arm.linkIndex("finger_left")));
  EXPECT_EQ(arm.checkedPairs().size(), 10u);
  arm.clearDisabledCollisions();
  EXPECT_TRUE(arm.disabledPairs().empty());
  EXPECT_EQ(arm.checkedPairs().size(), 15u);
  expectError([&] { arm.disableCollision("hand", "nope"); }, {"nope"});
  expectError([&] { arm.enableCollision(-1, 0); }, {"link_a", "-1"});
}

TEST(CollisionFilter, BadSrdfNamesFileAndLeavesFilterUntouched) {
  RobotModel arm = RobotModel::fromUrdfFile(kArm);
  const auto before = arm.disabledPairs();
  TempDir dir;
  const std::string unknown =
      dir.write("unknown_link.srdf",
                "<robot name=\"arm\">\n<disable_collisions link1=\"base\" link2=\"upper\"/>\n"
                "<disable_collisions link1=\"base\" link2=\"ghost\"/>\n</robot>");
  expectError([&] { arm.loadSrdfFile(unknown); }, {unknown, "ghost", "line 3", "link2"});
  EXPECT_EQ(arm.disabledPairs(), before);
  const std::string missing_attr =
      dir.write("missing.srdf", "<robot><disable_collisions link1=\"base\"/></robot>");
  expectError([&] { arm.loadSrdfFile(missing_attr); }, {missing_attr, "link2"});
  const std::string syntax = dir.write("syntax.srdf", "<robot><disable_collisions </robot>");
  expectError([&] { arm.loadSrdfFile(syntax); }, {syntax, "syntax"});
  expectError([&] { arm.loadSrdfFile(dir.path() + "/absent.srdf"); }, {"absent.srdf"});
  expectError([&] { arm.loadSrdfString("<srdf/>", "root.srdf"); }, {"root.srdf", "<robot>"});
  EXPECT_EQ(arm.disabledPairs(), before);
}

// --- Malformed URDFs ---

class MalformedUrdf : public ::testing::Test {
 protected:
  // Writes the URDF to a file, loads it, and expects an Error naming the file and fragments.
  void expectRejected(const std::string& xml, std::vector<std::string> fragments) {
    const std::string path = dir_.write("bad" + std::to_string(count_++) + ".urdf", xml);
    fragments.insert(fragments.begin(), path);
    expectError([&] { RobotModel::fromUrdfFile(path); }, fragments);
  }
  TempDir dir_;
  int count_ = 0;
};

const std::string kTwoLinks = "<link name=\"a\"/><link name=\"b\"/>";

// Mutated copies of arm.urdf (characters deleted, replaced or inserted, biased towards XML
// syntax and number spellings) either load or throw octomotion::Error: never crash, hang or
// throw anything else. Fixed seed; run under ASan/UBSan in CI.
TEST(MalformedUrdfFuzz, MutantsLoadOrThrowError) {
  std::ifstream in(kArm);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string original = buffer.str();
  const std::string alphabet = "<>/\"= -.0123456789eEnaif\n";
  std::mt19937_64 rng(20261121);
  int loaded = 0, rejected = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const std::size_t at = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          text.erase(at, 1 + rng() % 4);
          break;
        case 1:
          text[at] = c;
          break;
        default:
          text.insert(at, 1, c);
      }
    }
    try {
      const RobotModel model = RobotModel::fromUrdfString(text, "mutant.urdf", kDataDir);
      ++loaded;
      // Whatever loaded is usable.
      RobotData data = model.makeData();
      const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.variableCount());
      model.forwardKinematics(q, data);
      for (int i = 0; i < model.linkCount(); ++i) {
        ASSERT_TRUE(data.linkPose(i).matrix().allFinite()) << text;
      }
    } catch (const Error& e) {
      ++rejected;
      EXPECT_THAT(e.what(), HasSubstr("mutant.urdf"));
    } catch (const std::exception& e) {
      ADD_FAILURE() << "non-octomotion exception " << e.what() << " for\n" << text;
    }
  }
  // Both outcomes occur, so the mutations are neither all harmless nor all fatal.
  EXPECT_GT(loaded, 20);
  EXPECT_GT(rejected, 20);
}

TEST_F(MalformedUrdf, SyntaxAndFileErrors) {
  expectRejected("<robot name=\"r\">\n<link name=\"a\">\n</robot>", {"syntax", "line"});
  expectRejected("<model name=\"r\"/>", {"<model>", "<robot>"});
  expectRejected("", {"syntax"});
  expectRejected(robotXml(""), {"no <link>"});
  expectRejected(
      "<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
      "<xacro:macro name=\"m\"><link name=\"a\"/></xacro:macro>\n</robot>",
      {"xacro", "line 2"});
  expectError([] { RobotModel::fromUrdfFile(kDataDir); }, {kDataDir, "not a regular file"});
  expectError([] { RobotModel::fromUrdfFile("/nonexistent/robot.urdf"); },
              {"/nonexistent/robot.urdf", "does not exist"});
}

TEST_F(MalformedUrdf, JointTypesAndReferences) {
  expectRejected(robotXml(kTwoLinks + joint("spin", "screw", "a", "b")),
                 {"joint 'spin'", "unknown type 'screw'"});
  expectRejected(robotXml(kTwoLinks + joint("drift", "floating", "a", "b")),
                 {"joint 'drift'", "floating", "kFreeFlying"});
  expectRejected(robotXml(kTwoLinks + joint("slide", "planar", "a", "b")),
                 {"joint 'slide'", "planar"});
  expectRejected(
      robotXml(kTwoLinks + "<joint name=\"j\"><parent link=\"a\"/><child link=\"b\"/></joint>"),
      {"joint 'j'", "no type"});
  expectRejected(robotXml(kTwoLinks + joint("j", "fixed", "a", "ghost")),
                 {"joint 'j'", "child link 'ghost'"});
  expectRejected(robotXml(kTwoLinks + "<link name=\"a\"/>" + joint("j", "fixed", "a", "b")),
                 {"link 'a'", "twice"});
  expectRejected(robotXml(kTwoLinks + "<link/>"), {"<link>", "no name"});
  expectRejected(robotXml(kTwoLinks + joint("j", "revolute", "a", "b")), {"urdfdom", "j"});
}

TEST_F(MalformedUrdf, TreeStructure) {
  // A pure cycle has no root.
  expectRejected(
      robotXml(kTwoLinks + joint("ab", "fixed", "a", "b") + joint("ba", "fixed", "b", "a")),
      {"cycle", "joint 'ab'"});
  // A root plus a detached cycle.
  expectRejected(robotXml("<link name=\"root\"/>" + kTwoLinks + "<link name=\"c\"/>" +
                          joint("rc", "fixed", "root", "c") + joint("ab", "fixed", "a", "b") +
                          joint("ba", "fixed", "b", "a")),
                 {"cycle", "not reachable"});
  expectRejected(
      robotXml(kTwoLinks + joint("aa", "fixed", "a", "a") + joint("ab", "fixed", "a", "b")),
      {"cycle"});
  expectRejected(robotXml(kTwoLinks + "<link name=\"c\"/>" + joint("ab", "fixed", "a", "b") +
                          joint("cb", "fixed", "c", "b")),
                 {"link 'b'", "joint 'ab'", "joint 'cb'", "tree"});
  expectRejected(robotXml(kTwoLinks), {"several root links", "'a'", "'b'"});
}

TEST_F(MalformedUrdf, BadNumbers) {
  expectRejected(robotXml("<link name=\"base\"><collision><origin xyz=\"nan 0 0\"/><geometry><box "
                          "size=\"1 1 1\"/></geometry></collision></link>"),
                 {"nan", "base"});
  expectRejected(robotXml("<link name=\"base\"><collision><geometry><box size=\"-1 2 3\"/>"
                          "</geometry></collision></link>"),
                 {"link 'base'", "box size", "-1", "line"});
  expectRejected(robotXml("<link name=\"base\"><collision><geometry><box size=\"1 0 3\"/>"
                          "</geometry></collision></link>"),
                 {"link 'base'", "box size"});
  expectRejected(robotXml("<link name=\"base\"><collision><geometry><sphere radius=\"-0.1\"/>"
                          "</geometry></collision></link>"),
                 {"link 'base'", "sphere radius"});
  expectRejected(robotXml("<link name=\"base\"><collision><geometry><cylinder radius=\"0.1\" "
                          "length=\"0\"/></geometry></collision></link>"),
                 {"link 'base'", "cylinder"});
  expectRejected(robotXml("<link name=\"base\"><collision><geometry><mesh "
                          "filename=\"meshes/tetra.stl\" scale=\"1 0 1\"/></geometry></collision>"
                          "</link>"),
                 {"link 'base'", "scale"});
  expectRejected(
      robotXml(kTwoLinks + joint("j", "revolute", "a", "b",
                                 "<origin xyz=\"0 0 0\" rpy=\"inf 0 0\"/>" + std::string(kLimit))),
      {"urdfdom", "inf"});
  expectRejected(robotXml(kTwoLinks + joint("j", "revolute", "a", "b",
                                            std::string("<axis xyz=\"0 0 0\"/>") + kLimit)),
                 {"joint 'j'", "axis"});
  expectRejected(robotXml(kTwoLinks + joint("j", "prismatic", "a", "b",
                                            "<limit lower=\"1\" upper=\"-1\" effort=\"1\" "
                                            "velocity=\"1\"/>")),
                 {"joint 'j'", "lower <= upper"});
}

TEST_F(MalformedUrdf, MissingMeshesAndBadUris) {
  expectRejected(robotXml("<link name=\"body\"><collision><geometry><mesh "
                          "filename=\"meshes/absent.stl\"/></geometry></collision></link>"),
                 {"link 'body'", "meshes/absent.stl", "does not exist"});
  expectRejected(robotXml("<link name=\"body\"><collision><geometry><mesh "
                          "filename=\"package://ghost_pkg/m.stl\"/></geometry></collision></link>"),
                 {"link 'body'", "package://ghost_pkg/m.stl", "ghost_pkg"});
  expectRejected(robotXml("<link name=\"body\"><collision><geometry><mesh "
                          "filename=\"ftp://host/m.stl\"/></geometry></collision></link>"),
                 {"link 'body'", "ftp://host/m.stl", "scheme"});
}

TEST_F(MalformedUrdf, BadMimics) {
  const std::string three = "<link name=\"r\"/><link name=\"a\"/><link name=\"b\"/>";
  expectRejected(robotXml(three + joint("ja", "continuous", "r", "a") +
                          joint("jb", "continuous", "r", "b", "<mimic joint=\"ghost\"/>")),
                 {"jb", "ghost"});
  expectRejected(robotXml(three + joint("ja", "continuous", "r", "a", "<mimic joint=\"jb\"/>") +
                          joint("jb", "continuous", "r", "b", "<mimic joint=\"ja\"/>")),
                 {"cycle"});
  expectRejected(robotXml(three + joint("ja", "fixed", "r", "a") +
                          joint("jb", "continuous", "r", "b", "<mimic joint=\"ja\"/>")),
                 {"jb", "fixed joint 'ja'"});
  expectRejected(robotXml(three + joint("ja", "continuous", "r", "a") +
                          joint("jb", "fixed", "r", "b", "<mimic joint=\"ja\"/>")),
                 {"jb", "fixed", "mimic"});
}

}  // namespace
}  // namespace octomotion
