// The bad-input corpus (tests/data/bad/, one file per failure class): every loader rejects its
// file with an octomotion::Error that names the file and says what is wrong, and the command line
// turns the same files into one line on stderr and a non-zero exit status.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "octomotion/error.h"
#include "octomotion/octree/io.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion {
namespace {

using ::testing::HasSubstr;

std::string bad(const std::string& name) {
  return std::string(OCTOMOTION_TEST_DATA_DIR) + "/bad/" + name;
}

struct Case {
  std::string file;
  std::function<void(const std::string&)> load;
  std::string says;  // a phrase the message must contain
};

void expectRejected(const Case& c) {
  const std::string path = bad(c.file);
  try {
    c.load(path);
    ADD_FAILURE() << c.file << " was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(c.file)) << "the message must name the file";
    EXPECT_THAT(e.what(), HasSubstr(c.says)) << c.file;
  } catch (const std::exception& e) {
    ADD_FAILURE() << c.file << ": not an octomotion::Error: " << e.what();
  }
}

const auto urdf = [](const std::string& p) { RobotModel::fromUrdfFile(p); };
const auto mesh = [](const std::string& p) { loadMesh(p); };
const auto scene = [](const std::string& p) { loadPlanningScene(p); };
const auto cloud = [](const std::string& p) { pointcloud::loadPointCloud(p); };
const auto octree = [](const std::string& p) { loadOctree(p); };
const auto octomap = [](const std::string& p) { importOctoMap(p); };

TEST(BadInput, RobotFiles) {
  for (const Case& c :
       {Case{"syntax_error.urdf", urdf, "line"},
        Case{"missing_mesh.urdf", urdf, "does_not_exist.stl"},
        Case{"unknown_joint_type.urdf", urdf, "twisty"}, Case{"cycle.urdf", urdf, "cycle"},
        Case{"nan_origin.urdf", urdf, "origin"}, Case{"negative_box.urdf", urdf, "box"},
        Case{"truncated_utf8.urdf", urdf, "truncated UTF-8 sequence at line 7"},
        Case{"deep_nesting.urdf", urdf, "XML elements nest more than 256 deep at line 3"}}) {
    expectRejected(c);
  }
  RobotModelOptions options;
  options.package_paths = {OCTOMOTION_SOURCE_DIR};
  RobotModel robot = RobotModel::fromUrdfFile(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/octo7/octo7.urdf", options);
  expectRejected(
      {"unknown_link.srdf", [&](const std::string& p) { robot.loadSrdfFile(p); }, "no_such_link"});
}

TEST(BadInput, Meshes) {
  for (const Case& c : {Case{"garbage.stl", mesh, ""}, Case{"empty.stl", mesh, ""},
                        Case{"truncated_binary.stl", mesh, ""},
                        Case{"deep_nesting.dae", mesh, "XML elements nest more than 256 deep"},
                        // Both made assimp 5.2's Collada importer loop without end (fuzz/known).
                        Case{"dangling_source.dae", mesh, "line 14) names no element"},
                        Case{"non_integer_index.dae", mesh, "p (line 26) holds a character"}}) {
    expectRejected(c);
  }
}

TEST(BadInput, Scenes) {
  for (const Case& c :
       {Case{"unknown_key.yaml", scene, "environment[0].colour"},
        Case{"negative_radius.yaml", scene, "environment[0].sphere.radius"},
        Case{"yaml_syntax.yaml", scene, "YAML syntax error"},
        Case{"missing_robot.yaml", scene, "robot"},
        Case{"missing_world_mesh.yaml", scene, "no_such_world.stl"},
        Case{"missing_start.cfg", scene, "start.x"}, Case{"bad_number.cfg", scene, "start.x"}}) {
    expectRejected(c);
  }
  // A resolution that would need more than kMaxDepth levels fails before any allocation.
  try {
    loadPlanningScene(bad("too_fine.yaml"));
    ADD_FAILURE() << "too_fine.yaml was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("coarser resolution"));
  }
}

TEST(BadInput, PointCloudsAndTrees) {
  for (const Case& c :
       {Case{"truncated_binary.pcd", cloud, ""}, Case{"missing_z.ply", cloud, "z"},
        Case{"bad_number.xyz", cloud, "line 2"}, Case{"bad_magic.omt", octree, "magic"},
        Case{"unknown_version.omt", octree, ""}, Case{"truncated.bt", octomap, ""}}) {
    expectRejected(c);
  }
}

// Found by fuzz/urdf_fuzz (truncated_utf8.urdf is its input): TinyXML steps over the bytes a
// UTF-8 lead byte announces without looking at them, so a lead byte just before the end of the
// text made it read past the buffer, in our scan and again inside urdfdom. Text that is not
// well-formed UTF-8 is now rejected before any XML parser sees it.
TEST(BadInput, XmlThatIsNotUtf8IsRejectedBeforeParsing) {
  const std::string head = "<robot name=\"r\"><link name=\"a\"/></robot>";
  // Well-formed multi-byte text is accepted (a comment in German and a CJK link name).
  EXPECT_NO_THROW(RobotModel::fromUrdfString(
      "<!-- Gr\xC3\xBC\xC3\x9F -->\n<robot name=\"r\"><link name=\"\xE8\x85\x95\"/></robot>",
      "ok.urdf", "."));
  struct Text {
    std::string xml;
    std::string says;
  };
  for (const Text& t : {Text{head + "\n\xE0", "truncated UTF-8 sequence at line 2 (byte offset"},
                        Text{head + "\xF0\x9F\x98", "truncated UTF-8 sequence"},
                        Text{head + "\xC3<", "truncated UTF-8 sequence"},
                        Text{"\x80" + head, "invalid UTF-8 byte at line 1 (byte offset 0)"},
                        Text{head + "\xFF", "invalid UTF-8 byte"},
                        Text{head + std::string(1, '\0') + "<x/>", "NUL byte"}}) {
    try {
      RobotModel::fromUrdfString(t.xml, "text.urdf", ".");
      ADD_FAILURE() << "accepted: " << t.says;
    } catch (const FileError& e) {
      EXPECT_THAT(e.what(), HasSubstr("text.urdf"));
      EXPECT_THAT(e.what(), HasSubstr(t.says));
    }
  }
  RobotModel robot = RobotModel::fromUrdfString(head, "ok.urdf", ".");
  try {
    robot.loadSrdfString("<robot name=\"r\">\xE0", "text.srdf");
    ADD_FAILURE() << "SRDF accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("text.srdf"));
    EXPECT_THAT(e.what(), HasSubstr("truncated UTF-8 sequence"));
  }
}

// Found by fuzz/pointcloud_fuzz: a finite double beyond float's range became an infinite float
// point (through a conversion that is undefined behaviour). Such points are now skipped and
// counted, like NaN/inf ones.
TEST(BadInput, PointCoordinatesBeyondFloatRangeAreSkipped) {
  const pointcloud::PointCloud points = pointcloud::loadPointCloud(bad("huge_coordinate.xyz"));
  ASSERT_EQ(points.points.size(), 1u);
  EXPECT_TRUE(points.points[0].allFinite());
  EXPECT_EQ(points.skipped_non_finite, 2u);
}

TEST(BadInput, TreesTooLargeForTheMemoryLimitFailEarly) {
  RobotModelOptions robot_options;
  robot_options.package_paths = {OCTOMOTION_SOURCE_DIR};
  const RobotModel robot = RobotModel::fromUrdfFile(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/octo7/octo7.urdf", robot_options);
  const EnvironmentGeometry env = EnvironmentGeometry::load(
      loadScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml").environment);
  CollisionModelOptions options;
  options.resolution = 0.01;
  options.link_resolution = 0.01;     // (the default, 1/4 of the voxel, needs 16x as many)
  options.max_surface_voxels = 1500;  // link0 (18 x 18 x 14 cm) has about 1,860 at 1 cm
  try {
    OctreeCollisionModel model(robot, env, options);
    ADD_FAILURE() << "built past the limit";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("link link0"));
    EXPECT_THAT(e.what(), HasSubstr("coarser resolution"));
  }
  options.max_surface_voxels = 20000;  // the links fit; the 1.2 m x 0.84 m back wall does not
  try {
    OctreeCollisionModel model(robot, env, options);
    ADD_FAILURE() << "built past the limit";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("back"));
  }
}

struct CliResult {
  int status;
  std::string err;
};

CliResult runCli(const std::string& args) {
  const auto err_path = std::filesystem::temp_directory_path() / "octomotion_bad_input_stderr";
  const std::string cmd =
      std::string(OCTOMOTION_CLI) + " " + args + " >/dev/null 2>" + err_path.string();
  const int raw = std::system(cmd.c_str());
  std::ifstream in(err_path);
  std::stringstream s;
  s << in.rdbuf();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, s.str()};
}

TEST(BadInput, CommandLineSaysOneLineAndFails) {
  for (const char* file :
       {"unknown_key.yaml", "negative_radius.yaml", "yaml_syntax.yaml", "missing_robot.yaml",
        "missing_world_mesh.yaml", "missing_start.cfg", "too_fine.yaml"}) {
    const CliResult r = runCli("info " + bad(file));
    EXPECT_NE(r.status, 0) << file;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << file << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("octomotion: error: ")) << file;
  }
  const std::string scene_file =
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/narrow_passage.yaml";
  for (const auto& [file, says] : {std::pair<const char*, const char*>{"missing_column.csv", "qw"},
                                   {"bad_number.csv", "column z"}}) {
    const CliResult r = runCli("check " + scene_file + " --states " + bad(file));
    EXPECT_NE(r.status, 0) << file;
    EXPECT_THAT(r.err, HasSubstr(file));
    EXPECT_THAT(r.err, HasSubstr(says));
  }
}

}  // namespace
}  // namespace octomotion
