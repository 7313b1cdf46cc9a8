// Scene files: every field parsed, relative paths anchored at the scene, and every bad field
// reported with the file and the field's name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "octomotion/error.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {
namespace {

using ::testing::HasSubstr;

const char* kFullScene = R"(
name: shelf
robot:
  urdf: ../robots/octo7/octo7.urdf
  srdf: ../robots/octo7/octo7.srdf
  package_path: [..]
environment:
  - name: board
    box: {size: [0.8, 0.3, 0.02]}
    pose: {xyz: [0.6, 0, 0.4], rpy: [0, 0, 1.5707963267948966]}
  - sphere: {radius: 0.1}
    pose: {xyz: [1, 2, 3], quat: [0, 0, 0, 2]}
  - cylinder: {radius: 0.05, length: 0.3}
    pose: {axis: [0, 1, 0], theta: 0.5}
  - mesh: {file: meshes/table.stl, scale: [0.001, 0.001, 0.001]}
  - pointcloud: {file: scan.pcd}
  - octomap: {file: /maps/room.bt}
octree: {resolution: 0.01, link_resolution: 0.02, self_link_resolution: 0.004,
         self_pair_tables: true, exact_primitives: true, rounding: center,
         checker: octree}
problem:
  start: [0, 0.1, 0, -1.2, 0, 1.0, 0, 0.02]
  goal: [0.5, 0.3, 0, -1.0, 0, 1.2, 0, 0.02]
  planner: RRTstar
  time: 2.5
  seed: 42
)";

TEST(Scene, ParsesEveryField) {
  const SceneSpec s = parseSceneYaml(kFullScene, "/data/scenes/shelf.yaml");
  EXPECT_EQ(s.name, "shelf");
  EXPECT_EQ(s.robot.urdf, "/data/robots/octo7/octo7.urdf");
  EXPECT_EQ(s.robot.srdf, "/data/robots/octo7/octo7.srdf");
  ASSERT_EQ(s.robot.package_paths.size(), 1u);
  EXPECT_EQ(s.robot.package_paths[0], "/data/");
  EXPECT_FALSE(s.robot.keep_mesh_root_transform);  // URDF convention
  ASSERT_EQ(s.environment.size(), 6u);
  const EnvironmentObject& board = s.environment[0];
  EXPECT_EQ(board.name, "board");
  ASSERT_TRUE(std::holds_alternative<Box>(board.primitive));
  EXPECT_TRUE(
      std::get<Box>(board.primitive).half_extents.isApprox(Eigen::Vector3d(0.4, 0.15, 0.01)));
  // yaw of 90 degrees maps x to y.
  EXPECT_TRUE((board.X_WO.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(board.X_WO.translation().isApprox(Eigen::Vector3d(0.6, 0, 0.4)));
  EXPECT_EQ(s.environment[1].name, "environment[1]");
  // quat [0,0,0,2] is normalised to the identity.
  EXPECT_TRUE(s.environment[1].X_WO.linear().isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(s.environment[2].X_WO.linear().isApprox(
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).toRotationMatrix()));
  EXPECT_EQ(s.environment[3].kind, EnvironmentObject::Kind::kMesh);
  EXPECT_EQ(s.environment[3].file, "/data/scenes/meshes/table.stl");
  EXPECT_DOUBLE_EQ(s.environment[3].scale.x(), 0.001);
  EXPECT_EQ(s.environment[4].kind, EnvironmentObject::Kind::kPointCloud);
  EXPECT_EQ(s.environment[5].kind, EnvironmentObject::Kind::kOctomap);
  EXPECT_EQ(s.environment[5].file, "/maps/room.bt");
  ASSERT_TRUE(s.octree.resolution.has_value());
  EXPECT_DOUBLE_EQ(*s.octree.resolution, 0.01);
  EXPECT_DOUBLE_EQ(*s.octree.link_resolution, 0.02);
  EXPECT_DOUBLE_EQ(*s.octree.self_link_resolution, 0.004);
  EXPECT_TRUE(s.octree.self_pair_tables);
  EXPECT_TRUE(s.octree.exact_primitives);
  EXPECT_EQ(s.octree.rounding, Rounding::kCenter);
  EXPECT_EQ(s.octree.checker, CheckerKind::kOctree);
  ASSERT_TRUE(s.problem.start && s.problem.goal);
  EXPECT_EQ(s.problem.start->joints.size(), 8u);
  EXPECT_DOUBLE_EQ(s.problem.goal->joints[5], 1.2);
  EXPECT_EQ(s.problem.planner, "RRTstar");
  EXPECT_DOUBLE_EQ(s.problem.time, 2.5);
  EXPECT_EQ(s.problem.seed, 42u);
}

TEST(Scene, RigidBodyWithPoseStatesAndDefaults) {
  const SceneSpec s = parseSceneYaml(R"(
robot: {mesh: l.stl}
problem:
  start: {xyz: [0, 0, 1]}
  goal: {xyz: [1, 0, 1], rpy: [0, 0, 3.14159]}
  bounds: {min: [-1, -1, 0], max: [2, 1, 2]}
)",
                                     "/s/rigid.yml");
  EXPECT_EQ(s.name, "rigid");
  EXPECT_EQ(s.robot.mesh, "/s/l.stl");
  EXPECT_TRUE(s.robot.keep_mesh_root_transform);
  EXPECT_FALSE(s.octree.resolution.has_value());  // auto
  EXPECT_EQ(s.octree.rounding, Rounding::kConservative);
  EXPECT_EQ(s.octree.checker, CheckerKind::kOctreeFused);
  ASSERT_TRUE(s.problem.start->pose.has_value());
  EXPECT_TRUE(s.problem.goal->pose->translation().isApprox(Eigen::Vector3d(1, 0, 1)));
  ASSERT_TRUE(s.problem.bounds.has_value());
  EXPECT_DOUBLE_EQ(s.problem.bounds->max().x(), 2.0);
  EXPECT_EQ(s.problem.planner, "RRTConnect");
}

void expectError(const std::string& yaml, const std::string& field) {
  try {
    parseSceneYaml(yaml, "/s/bad.yaml");
    ADD_FAILURE() << "accepted: " << yaml;
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/s/bad.yaml"));
    EXPECT_THAT(e.what(), HasSubstr(field)) << yaml;
  }
}

TEST(Scene, BadFieldsAreNamed) {
  expectError("robot: {urdf: a.urdf, mesh: b.stl}", "robot");
  expectError("robot: {mesh: m.stl}\noctree: {self_pair_tables: maybe}", "octree.self_pair_tables");
  expectError("robot: {mesh: m.stl}\noctree: {exact_primitives: 1}", "octree.exact_primitives");
  expectError("robot: {}", "robot");
  expectError("environment: []", "robot: missing");
  expectError("robot: {mesh: m.stl}\nenvironment:\n  - box: {size: [1, 0, 1]}",
              "environment[0].box.size");
  expectError("robot: {mesh: m.stl}\nenvironment:\n  - box: {size: [1, 1]}",
              "environment[0].box.size");
  expectError("robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: -1}",
              "environment[0].sphere.radius");
  expectError("robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: .nan}",
              "environment[0].sphere.radius");
  expectError(
      "robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: 1}\n    box: {size: [1,1,1]}",
      "environment[0]");
  expectError(
      "robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: 1}\n    pose: {xyz: [0, 0, 0], "
      "quat: [0, 0, 0, 0]}",
      "environment[0].pose.quat");
  expectError(
      "robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: 1}\n    pose: {xyz: [0, zero, 0]}",
      "environment[0].pose.xyz[1]");
  expectError("robot: {mesh: m.stl}\nenvironment:\n  - sphere: {radius: 1}\n    colour: red",
              "environment[0].colour");
  expectError("robot: {mesh: m.stl}\noctree: {resolution: 0}", "octree.resolution");
  expectError("robot: {mesh: m.stl}\noctree: {rounding: round}", "octree.rounding");
  expectError("robot: {mesh: m.stl}\noctree: {checker: bullet}", "octree.checker");
  expectError("robot: {mesh: m.stl}\nproblem: {time: -1}", "problem.time");
  expectError("robot: {mesh: m.stl}\nproblem: {seed: 1.5}", "problem.seed");
  expectError("robot: {mesh: m.stl}\nproblem: {start: 3}", "problem.start");
  expectError("robot: {mesh: m.stl}\nproblem: {bounds: {min: [0, 0, 0], max: [1, 0, 1]}}",
              "problem.bounds");
  expectError("robot: {mesh: m.stl}\nproblem: [", "YAML syntax error");
  expectError("- just a list", "expected a YAML mapping");
  expectError("robot: {mesh: m.stl}\nrobots: {}", "robots");
}

TEST(Scene, OmplAppCfg) {
  // A problem in OMPL.app's format (our own numbers).
  const char* cfg = R"([problem]
name = corridor
world = corridor_env.dae
robot = corridor_robot.dae
start.x = 10
start.y = -5.5
start.z = 2
start.theta = 0
start.axis.x = 1
start.axis.y = 0
start.axis.z = 0
goal.x = 40
goal.y = 5
goal.z = 2
goal.theta = 1.5707963267948966
goal.axis.x = 0
goal.axis.y = 0
goal.axis.z = 2
volume.min.x = 0
volume.min.y = -10
volume.min.z = 0
volume.max.x = 50
volume.max.y = 10
volume.max.z = 5

[benchmark]
time_limit = 12.5
run_count = 10

[planner]
rrtconnect=
kpiece=
kpiece.range = 3
)";
  const SceneSpec s = parseOmplAppCfg(cfg, "/omplapp/3D/corridor.cfg");
  EXPECT_EQ(s.name, "corridor");
  EXPECT_EQ(s.robot.mesh, "/omplapp/3D/corridor_robot.dae");
  EXPECT_TRUE(s.robot.keep_mesh_root_transform);
  EXPECT_TRUE(s.robot.center_mesh_vertices);
  ASSERT_EQ(s.environment.size(), 1u);
  EXPECT_EQ(s.environment[0].file, "/omplapp/3D/corridor_env.dae");
  EXPECT_TRUE(s.problem.start->pose->translation().isApprox(Eigen::Vector3d(10, -5.5, 2)));
  // The axis is normalised: 90 degrees about z.
  EXPECT_TRUE((s.problem.goal->pose->linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY()));
  ASSERT_TRUE(s.problem.bounds.has_value());
  EXPECT_DOUBLE_EQ(s.problem.bounds->min().y(), -10);
  EXPECT_DOUBLE_EQ(s.problem.time, 12.5);

  EXPECT_THROW(parseOmplAppCfg("[problem]\nworld = w.dae\n", "/x.cfg"), FileError);
  try {
    parseOmplAppCfg("[problem]\nworld=w\nrobot=r\nstart.x=abc\n", "/x.cfg");
    ADD_FAILURE();
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("start.x"));
  }
  EXPECT_THROW(parseOmplAppCfg("[problem\n", "/x.cfg"), FileError);
  EXPECT_THROW(parseOmplAppCfg("[problem]\nno equals sign\n", "/x.cfg"), FileError);
}

TEST(Scene, SceneWithoutDirectoryIsRelativeToTheWorkingDirectory) {
  const SceneSpec s = parseSceneYaml("robot: {mesh: body.stl}", "scene.yaml");
  EXPECT_EQ(s.robot.mesh, (std::filesystem::current_path() / "body.stl").string());
}

TEST(Scene, LoadDispatchesOnExtension) {
  EXPECT_THROW(loadScene("/definitely/missing.yaml"), FileError);
  EXPECT_THROW(loadScene(std::string(OCTOMOTION_SOURCE_DIR) + "/README.md"), FileError);
}

TEST(Scene, RpyFollowsUrdf) {
  // Roll, then pitch, then yaw about fixed axes: R = Rz(y) Ry(p) Rx(r).
  const Eigen::Matrix3d R = rotationFromRpy(0.1, 0.2, 0.3);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(R.isApprox(expected));
  for (CheckerKind kind : kCheckerKinds) EXPECT_EQ(parseCheckerKind(checkerKindName(kind)), kind);
  EXPECT_STREQ(checkerKindName(CheckerKind::kFclOctomap), "fcl-octomap");
  EXPECT_THROW(parseCheckerKind("FCL"), InvalidArgument);
}

}  // namespace
}  // namespace octomotion
