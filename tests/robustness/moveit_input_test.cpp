// Bad MoveIt input: a PlanningScene or MotionPlanRequest that is missing a field, has a wrong
// dimension count, a plane, a cone, an unknown type or operation, or a request the planner cannot
// honour, is refused with a FileError naming the file and the field path; so are scenes whose
// frames name no link, whose mimic joints disagree, or that mount a rigid body.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/scene/moveit_scene.h"

namespace octomotion {
namespace {

using ::testing::HasSubstr;

// One object of a PlanningScene, the rest of the message around it.
std::string sceneWith(const std::string& object) {
  return "world:\n  collision_objects:\n    - id: first\n      primitives: [{type: box, "
         "dimensions: [1, 1, 1]}]\n      primitive_poses: [{position: [0, 0, 0], orientation: "
         "[0, 0, 0, 1]}]\n" +
         object;
}

struct Case {
  std::string what;
  std::string text;
  std::string field;  // the field path the message must name
  std::string says;   // and a phrase it must contain
};

void expectFileError(const Case& c, const std::function<void(const std::string&)>& parse) {
  try {
    parse(c.text);
    ADD_FAILURE() << c.what << ": accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.yaml: ")) << c.what;
    EXPECT_THAT(e.what(), HasSubstr(c.field)) << c.what;
    EXPECT_THAT(e.what(), HasSubstr(c.says)) << c.what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << c.what << ": not a FileError: " << e.what();
  }
}

TEST(MoveItInput, BadPlanningScenesNameTheField) {
  const std::string o = "    - id: second\n";
  const std::string pose =
      "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n";
  const Case cases[] = {
      {"no world", "name: x\n", "world", "missing"},
      {"missing dimensions", sceneWith(o + "      primitives: [{type: box}]\n" + pose),
       "world.collision_objects[1].primitives[0].dimensions", "missing"},
      {"wrong dimension count",
       sceneWith(o + "      primitives: [{type: cylinder, dimensions: [1, 2, 3]}]\n" + pose),
       "world.collision_objects[1].primitives[0].dimensions", "[height, radius]"},
      {"non-positive size",
       sceneWith(o + "      primitives: [{type: sphere, dimensions: [0]}]\n" + pose),
       "world.collision_objects[1].primitives[0].dimensions[0]", "must be > 0"},
      {"unknown type", sceneWith(o + "      primitives: [{type: torus, dimensions: [1]}]\n" + pose),
       "world.collision_objects[1].primitives[0].type", "unknown value 'torus'"},
      {"cone", sceneWith(o + "      primitives: [{type: cone, dimensions: [1, 1]}]\n" + pose),
       "world.collision_objects[1].primitives[0].type", "cones are not supported"},
      {"a plane",
       sceneWith(o + "      planes: [{coef: [0, 0, 1, 0]}]\n      plane_poses: [{position: [0, 0, "
                     "0], orientation: [0, 0, 0, 1]}]\n"),
       "world.collision_objects[1].planes", "object 'second': planes are not supported"},
      {"missing pose", sceneWith(o + "      primitives: [{type: sphere, dimensions: [1]}]\n"),
       "world.collision_objects[1].primitive_poses", "one pose per primitives entry"},
      {"missing orientation",
       sceneWith(o + "      primitives: [{type: sphere, dimensions: [1]}]\n"
                     "      primitive_poses: [{position: [0, 0, 0]}]\n"),
       "world.collision_objects[1].primitive_poses[0].orientation", "missing"},
      {"quaternion of 3",
       sceneWith(o + "      primitives: [{type: sphere, dimensions: [1]}]\n"
                     "      primitive_poses: [{position: [0, 0, 0], "
                     "orientation: [0, 0, 1]}]\n"),
       "world.collision_objects[1].primitive_poses[0].orientation", "expected 4 numbers"},
      {"no id", sceneWith("    - primitives: [{type: sphere, dimensions: [1]}]\n" + pose),
       "world.collision_objects[1].id", "missing"},
      {"no shapes", sceneWith(o), "world.collision_objects[1]", "has no primitives or meshes"},
      {"MOVE", sceneWith("    - {id: first, operation: 3}\n"),
       "world.collision_objects[1].operation", "MOVE is not supported"},
      {"unknown operation", sceneWith("    - {id: first, operation: 7}\n"),
       "world.collision_objects[1].operation", "unknown value '7'"},
      {"mesh index out of range",
       sceneWith(o + "      meshes: [{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], triangles: "
                     "[{vertex_indices: [0, 1, 3]}]}]\n      mesh_poses: [{position: [0, 0, 0], "
                     "orientation: [0, 0, 0, 1]}]\n"),
       "world.collision_objects[1].meshes[0].triangles[0].vertex_indices", "not one of the 3"},
      {"a typo", sceneWith(o + "      primitve_poses: []\n"),
       "world.collision_objects[1].primitve_poses", "unknown field"},
      {"attached objects",
       "robot_state: {attached_collision_objects: [{link_name: hand}]}\nworld: {}\n",
       "robot_state.attached_collision_objects", "not supported"},
      {"text for a number",
       sceneWith(o + "      primitives: [{type: box, dimensions: [1, wide, 1]}]\n" + pose),
       "world.collision_objects[1].primitives[0].dimensions[1]", "expected a number"},
  };
  for (const Case& c : cases) {
    expectFileError(c, [](const std::string& text) { parseMoveItScene(text, "bad.yaml"); });
  }
}

TEST(MoveItInput, BadRequestsNameTheField) {
  const std::string start = "start_state: {joint_state: {name: [j1, j2], position: [0, 0]}}\n";
  const std::string goal =
      "goal_constraints: [{joint_constraints: [{joint_name: j1, position: 1}]}]\n";
  const Case cases[] = {
      {"no group", start + goal, "group_name", "missing"},
      {"no start", "group_name: arm\n" + goal, "start_state", "missing"},
      {"positions and names differ",
       "group_name: arm\nstart_state: {joint_state: {name: [j1, j2], position: [0]}}\n" + goal,
       "start_state.joint_state.position", "one position per name"},
      {"a joint twice",
       "group_name: arm\nstart_state: {joint_state: {name: [j1, j1], position: [0, 0]}}\n" + goal,
       "start_state.joint_state.name[1]", "given twice"},
      {"two goals",
       "group_name: arm\n" + start +
           "goal_constraints: [{joint_constraints: [{joint_name: j1, "
           "position: 1}]}, {joint_constraints: [{joint_name: j1, "
           "position: 2}]}]\n",
       "goal_constraints", "alternative goals are not supported"},
      {"no goal", "group_name: arm\n" + start + "goal_constraints: []\n", "goal_constraints",
       "expected one goal, got 0"},
      {"empty goal", "group_name: arm\n" + start + "goal_constraints: [{name: g}]\n",
       "goal_constraints[0]", "nothing to plan to"},
      {"goal joint without position",
       "group_name: arm\n" + start +
           "goal_constraints: [{joint_constraints: [{joint_name: j1}]}]\n",
       "goal_constraints[0].joint_constraints[0].position", "missing"},
      {"joints and a pose",
       "group_name: arm\n" + start +
           "goal_constraints: [{joint_constraints: [{joint_name: j1, position: 1}], "
           "position_constraints: [{link_name: hand}]}]\n",
       "goal_constraints[0]", "together with pose constraints"},
      {"a region of two primitives",
       "group_name: arm\n" + start +
           "goal_constraints: [{position_constraints: [{link_name: hand, constraint_region: "
           "{primitives: [{type: sphere, dimensions: [0.1]}, {type: sphere, dimensions: [0.1]}], "
           "primitive_poses: []}}]}]\n",
       "goal_constraints[0].position_constraints[0].constraint_region", "expected one primitive"},
      {"path constraints",
       "group_name: arm\n" + start + goal +
           "path_constraints: {joint_constraints: [{joint_name: j1, position: 0}]}\n",
       "path_constraints.joint_constraints", "not supported"},
      {"a moved virtual joint",
       "group_name: arm\nstart_state: {joint_state: {name: [j1], position: [0]}, "
       "multi_dof_joint_state: {joint_names: [virtual_joint], transforms: [{translation: [1, 0, "
       "0], rotation: [0, 0, 0, 1]}]}}\n" +
           goal,
       "start_state.multi_dof_joint_state.transforms[0]", "robot.pose"},
  };
  for (const Case& c : cases) {
    expectFileError(c, [](const std::string& text) { parseMoveItRequest(text, "bad.yaml"); });
  }
}

class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("octomotion_moveit_input_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  static std::string octo7() {
    const std::string src = OCTOMOTION_SOURCE_DIR;
    return "robot:\n  urdf: " + src + "/robots/octo7/octo7.urdf\n  package_path: [" + src + "]\n";
  }
  void expectRejected(const std::string& scene, const std::string& says) {
    try {
      loadSceneInputs(scene);
      ADD_FAILURE() << scene << " was accepted";
    } catch (const FileError& e) {
      EXPECT_THAT(e.what(), HasSubstr(scene));
      EXPECT_THAT(e.what(), HasSubstr(says));
    }
  }
  std::filesystem::path dir_;
};

TEST_F(SceneFiles, ErrorsInMoveItFilesNameTheSceneAndTheFile) {
  write("ps.yaml", sceneWith("    - {id: first, operation: move}\n"));
  const std::string scene = write("s.yaml", octo7() + "environment:\n  - moveit_scene: ps.yaml\n");
  expectRejected(scene, "environment[0].moveit_scene: " + (dir_ / "ps.yaml").string() +
                            ": world.collision_objects[1].operation");
  const std::string request = write("r.yaml", octo7() + "problem: {moveit_request: none.yaml}\n");
  expectRejected(request, "problem.moveit_request");
}

TEST_F(SceneFiles, FramesAreLinksOrTheModelFrameAndMimicsMustAgree) {
  expectRejected(write("frame.yaml", octo7() + "environment:\n  - {name: cup, frame: gripper, "
                                               "sphere: {radius: 0.1}}\n"),
                 "environment object 'cup': frame 'gripper' is not a link");
  write("ps.yaml",
        "world:\n  collision_objects:\n    - id: cup\n      header: {frame_id: world}\n"
        "      primitives: [{type: sphere, dimensions: [0.1]}]\n"
        "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n");
  const std::string moveit_frame =
      write("moveit_frame.yaml", octo7() + "environment:\n  - moveit_scene: ps.yaml\n");
  expectRejected(moveit_frame, "frame 'world' is not a link");
  // With an SRDF whose virtual joint hangs the robot from 'world', that is the root's frame.
  write("v.srdf",
        "<robot name=\"octo7\"><virtual_joint name=\"v\" type=\"floating\" "
        "parent_frame=\"world\" child_link=\"link0\"/></robot>\n");
  const SceneInputs in = loadSceneInputs(
      write("virtual.yaml", octo7() + "  srdf: v.srdf\n  pose: {xyz: [1, 2, 3]}\nenvironment:\n"
                                      "  - moveit_scene: ps.yaml\n"));
  ASSERT_EQ(in.spec.environment.size(), 1u);
  EXPECT_EQ(in.spec.environment[0].X_WO.translation(), Eigen::Vector3d(1, 2, 3));
  write(
      "r.yaml",
      "group_name: arm\nstart_state: {joint_state: {name: [joint1, finger_joint1, finger_joint2], "
      "position: [0, 0.02, 0.03]}}\ngoal_constraints: [{joint_constraints: [{joint_name: joint1, "
      "position: 1}]}]\n");
  write("arm.srdf",
        "<robot name=\"octo7\"><group name=\"arm\"><joint name=\"joint1\"/></group></robot>\n");
  expectRejected(
      write("mimic.yaml", octo7() + "  srdf: arm.srdf\nproblem: {moveit_request: r.yaml}\n"),
      "problem.start.finger_joint2: mimic joint 'finger_joint2' = 0.03, but its master "
      "'finger_joint1' = 0.02");
  expectRejected(
      write("vector.yaml", octo7() + "environment:\n  - {frame: link3, sphere: {radius: 0.1}}\n"
                                     "problem: {start: [0, 0, 0]}\n"),
      "problem.start: expected 8 joint values");
}

TEST_F(SceneFiles, AMountIsForFixedBaseRobotsAndFinite) {
  const std::string src = OCTOMOTION_SOURCE_DIR;
  try {
    parseSceneYaml(
        "robot: {mesh: " + src + "/robots/meshes/rigid/drone.stl, pose: {xyz: [1, 0, 0]}}\n",
        "bad.yaml");
    ADD_FAILURE() << "a mounted rigid body was accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.yaml: robot.pose: a free-flying mesh robot has no mount"));
  }
  try {
    parseSceneYaml("robot: {urdf: a.urdf, pose: {xyz: [1, .nan, 0]}}\n", "bad.yaml");
    ADD_FAILURE() << "a NaN mount was accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("robot.pose.xyz[1]"));
  }
}

}  // namespace
}  // namespace octomotion
