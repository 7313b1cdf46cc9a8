// Why a state is invalid, from the command line: a start in collision is refused at once in one
// line naming the link and the object, with the voxel-margin hint when the exact shapes do not
// touch (a large body at the auto resolution, as in OMPL.app's alpha-1.5.cfg, whose start FCL
// accepts); `check --explain` adds a reason column that reads back as CSV.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using octomotion::test::CliRun;
using octomotion::test::csvFields;
using octomotion::test::lines;
using octomotion::test::runCli;
using ::testing::HasSubstr;
using ::testing::Not;

class CliExplain : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("octomotion_cli_explain_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // A large rigid body (a 2 m x 2 m slab, so the auto resolution is coarse) next to a post.
    write("slab.urdf",
          "<robot name=\"slab\"><link name=\"slab\"><collision><geometry>"
          "<box size=\"2 2 0.2\"/></geometry></collision></link></robot>\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  // The slab's start at y = `start_y`: its edge at start_y + 1; the post's face at y = 1.02.
  std::string slabScene(const std::string& name, double start_y) const {
    std::ostringstream s;
    s << "robot: {urdf: slab.urdf}\n"
         "environment:\n"
         "  - {name: post, box: {size: [0.2, 0.2, 2]}, pose: {xyz: [0, 1.12, 0]}}\n"
         "  - {name: wall, box: {size: [0.2, 6, 2]}, pose: {xyz: [3.5, 0, 0]}}\n"
         "octree: {resolution: auto}\n"
         "problem:\n"
         "  start: {xyz: [0, "
      << start_y
      << ", 0]}\n"
         "  goal: {xyz: [0, -1.5, 0]}\n"
         "  bounds: {min: [-3, -3, -1], max: [3, 3, 1]}\n"
         "  time: 60\n";
    return write(name, s.str());
  }

  CliRun run(const std::string& args) const { return runCli(args, "octomotion_cli_explain_run"); }

  fs::path dir_;
};

TEST_F(CliExplain, StartInCollisionNamesLinkAndObjectInOneLine) {
  const std::string scene = slabScene("into_post.yaml", 0.1);  // 8 cm into the post
  for (const std::string command : {"plan", "info"}) {
    const CliRun r = run(command + " " + scene);
    EXPECT_EQ(r.status, 1) << command;
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_THAT(r.err, HasSubstr("into_post.yaml: problem.start is in collision for the "
                                 "octree-fused checker: link slab with object post"));
    EXPECT_THAT(r.err, Not(HasSubstr("wall")));
    EXPECT_THAT(r.err, Not(HasSubstr("margin")));  // the exact shapes overlap
  }
  // The exact checker says the same, without a margin.
  const CliRun exact = run("info " + scene + " --checker fcl");
  EXPECT_EQ(exact.status, 1);
  EXPECT_THAT(exact.err, HasSubstr("in collision for the fcl checker: link slab with object post"));
}

TEST_F(CliExplain, StartWithinTheVoxelMarginSaysSo) {
  // 1 mm from the post: free for FCL, but within the auto resolution's voxels (several cm).
  const std::string scene = slabScene("near_post.yaml", 0.019);
  const CliRun r = run("plan " + scene + " --refine none");  // the voxels alone
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_THAT(r.err, HasSubstr("problem.start is in collision for the octree-fused checker: "
                               "link slab with object post; the exact shapes do not touch: within "
                               "the voxel margin of resolution "));
  EXPECT_THAT(r.err, HasSubstr("try a finer --resolution"));
  // FCL accepts the same start, and so do the defaults (exact refine).
  const CliRun exact = run("info " + scene + " --checker fcl");
  EXPECT_EQ(exact.status, 0) << exact.err;
  const CliRun defaults = run("info " + scene);
  EXPECT_EQ(defaults.status, 0) << defaults.err;
  EXPECT_THAT(defaults.out, HasSubstr("refine exact"));
}

TEST_F(CliExplain, CheckExplainAddsAReasonColumn) {
  const std::string scene = slabScene("states_scene.yaml", 0.1);  // check takes any start
  const std::string states = write("states.csv",
                                   "x,y,z,qx,qy,qz,qw\n"
                                   "0,-1.5,0,0,0,0,1\n"
                                   "0,0.1,0,0,0,0,1\n"
                                   "0,nan,0,0,0,0,1\n");
  const CliRun plain = run("check " + scene + " --states " + states);
  ASSERT_EQ(plain.status, 0) << plain.err;
  const std::vector<std::string> plain_lines = lines(plain.out);
  ASSERT_EQ(plain_lines.size(), 4u);
  EXPECT_EQ(plain_lines[0], "index,valid,time_ns");  // unchanged without the flag
  EXPECT_EQ(csvFields(plain_lines[1]).size(), 3u);

  const CliRun r = run("check " + scene + " --states " + states + " --explain");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> rows = lines(r.out);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], "index,valid,time_ns,reason");
  std::vector<std::vector<std::string>> fields;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    fields.push_back(csvFields(rows[i]));
    ASSERT_EQ(fields.back().size(), 4u) << rows[i];
    EXPECT_EQ(fields.back()[0], std::to_string(i - 1));
  }
  EXPECT_EQ(fields[0][1], "1");
  EXPECT_EQ(fields[0][3], "");
  EXPECT_EQ(fields[1][1], "0");
  EXPECT_EQ(fields[1][3], "link slab with object post");
  EXPECT_EQ(fields[2][1], "0");
  EXPECT_THAT(fields[2][3], HasSubstr("not finite"));
}

TEST_F(CliExplain, CheckExplainQuotesReasonsWithCommas) {
  // octo7 in the bookshelf: a joint beyond its limits, whose reason holds "[lower, upper]".
  const std::string scene =
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml --resolution 0.02";
  const std::string states =
      write("arm.csv",
            "joint1,joint2,joint3,joint4,joint5,joint6,joint7,finger_joint1\n"
            "100,0,0,0,0,0,0,0\n");
  const CliRun r = run("check " + scene + " --states " + states + " --explain");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> rows = lines(r.out);
  ASSERT_EQ(rows.size(), 2u);
  const std::vector<std::string> fields = csvFields(rows[1]);
  ASSERT_EQ(fields.size(), 4u) << rows[1];
  EXPECT_EQ(fields[1], "0");
  EXPECT_THAT(fields[3], HasSubstr("joint 'joint1' = 100 is outside its limits ["));
  EXPECT_THAT(fields[3], HasSubstr(", "));
}

TEST_F(CliExplain, ExplainIsForCheckOnly) {
  const CliRun r = run("info " + slabScene("free.yaml", -1.5) + " --explain");
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.err, HasSubstr("--explain: check only"));
}

}  // namespace
