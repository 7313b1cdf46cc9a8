// The octomotion command, run as a user would: results on stdout, one-line errors and a non-zero
// status on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using octomotion::test::CliRun;
using octomotion::test::lines;
using ::testing::HasSubstr;
using ::testing::Not;

CliRun run(const std::string& args) {
  return octomotion::test::runCli(args, "octomotion_cli_test");
}

std::string scene(const char* name) {
  return std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + name;
}

TEST(Cli, InfoDescribesWhatIsModelled) {
  const CliRun r = run("info " + scene("bookshelf.yaml") + " --resolution 0.02");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("resolution: 0.02 m"));
  EXPECT_THAT(r.out, HasSubstr("universe: depth"));
  EXPECT_THAT(r.out, HasSubstr("joint order: joint1 joint2 joint3 joint4 joint5 joint6 joint7 "
                               "finger_joint1"));
  EXPECT_THAT(r.out, HasSubstr("hand: "));
  EXPECT_THAT(r.out, HasSubstr("self-collision pairs checked: "));
  // The defaults: link trees at 1/4 of the voxel for the environment queries, the self pairs'
  // trees at the voxel itself.
  EXPECT_THAT(r.out, HasSubstr("links (source voxels 0.005 m; self-collision trees 0.02 m)"));
  // The links are tested most-often-hit first: the shares printed are non-increasing.
  const std::string order = "environment tested in the order (share of sampled states hitting): ";
  const std::size_t at = r.out.find(order);
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream shares(
      r.out.substr(at + order.size(), r.out.find('\n', at) - at - order.size()));
  std::string link, share, percent;
  double previous = 100.0;
  int links = 0;
  while (shares >> link >> share >> percent) {
    const double value = std::stod(share.substr(1));  // "(7.4" -> 7.4
    EXPECT_LE(value, previous) << link;
    previous = value;
    ++links;
  }
  EXPECT_EQ(links, 9);  // octo7 has 11 links; the base and link1 are never tested here
  // The black-cell grid of the fused query's first probes and the clearance grid serve both
  // roundings.
  EXPECT_THAT(r.out, HasSubstr("environment black-cell grid: level "));
  const CliRun center =
      run("info " + scene("bookshelf.yaml") + " --resolution 0.02 --rounding center");
  ASSERT_EQ(center.status, 0) << center.err;
  EXPECT_THAT(center.out, HasSubstr("environment black-cell grid: level "));
  EXPECT_THAT(r.out, HasSubstr("environment clearance grid: level "));
  EXPECT_THAT(center.out, HasSubstr("environment clearance grid: level "));
  const CliRun fine = run("info " + scene("bookshelf.yaml") +
                          " --resolution 0.02 --link-resolution 0.01 --self-link-resolution 0.005");
  ASSERT_EQ(fine.status, 0) << fine.err;
  EXPECT_THAT(fine.out, HasSubstr("links (source voxels 0.01 m; self-collision trees 0.005 m)"));
  // A link resolution given alone serves the self pairs too: one tree per link.
  const CliRun given = run("info " + scene("bookshelf.yaml") + " --link-resolution 0.01");
  ASSERT_EQ(given.status, 0) << given.err;
  EXPECT_THAT(given.out, HasSubstr("links (source voxels 0.01 m):"));
  EXPECT_THAT(given.out, Not(HasSubstr("self-collision trees")));
  // The moveTree path materialises every link leaf: its scenes keep link trees at the voxel.
  const CliRun move_tree =
      run("info " + scene("bookshelf.yaml") + " --resolution 0.02 --checker octree");
  ASSERT_EQ(move_tree.status, 0) << move_tree.err;
  EXPECT_THAT(move_tree.out, HasSubstr("links (source voxels 0.02 m):"));
  // Exact primitives: off by default; on, the links are tested against the bookshelf's 8 boxes.
  EXPECT_THAT(r.out, Not(HasSubstr("exact primitives")));
  const CliRun exact =
      run("info " + scene("bookshelf.yaml") + " --resolution 0.02 --exact-primitives on");
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_THAT(exact.out,
              HasSubstr("exact primitives: the links' source voxels tested against 8 primitives"));
  // A point-cloud scene cannot use them: said on stderr, and the voxel answers stand.
  const CliRun cloud =
      run("info " + scene("scan_table.yaml") + " --resolution 0.02 --exact-primitives on");
  ASSERT_EQ(cloud.status, 0) << cloud.err;
  EXPECT_THAT(cloud.err, HasSubstr("octree.exact_primitives: not applied"));
  EXPECT_THAT(cloud.out, Not(HasSubstr("exact primitives")));
}

// Options that name one setting are the study's own lists (--resolutions, --self-link-ratio ...):
// a one-setting option would otherwise be silently ignored.
TEST(Cli, BenchRejectsSingleSettingOptions) {
  for (const char* option :
       {"--resolution 0.01", "--link-resolution 0.002", "--self-link-resolution 0.002"}) {
    const CliRun r = run("bench " + scene("bookshelf.yaml") + " --states 10 --runs 0 " + option);
    EXPECT_NE(r.status, 0) << option;
    EXPECT_THAT(r.err, HasSubstr("do not apply")) << option;
  }
}

TEST(Cli, CheckReadsColumnsByName) {
  const fs::path csv = fs::temp_directory_path() / "octomotion_cli_states.csv";
  {
    std::ofstream out(csv);
    // Columns in another order than the joints, plus an extra one that is ignored.
    out << "finger_joint1,joint7,joint6,joint5,joint4,joint3,joint2,joint1,comment\n"
        << "0,0,0,0,0,0,0,0,upright\n"                                // free
        << "0.02,1.199,-0.618,-0.815,-1.4,1.442,-0.502,-2.16,goal\n"  // the scene's goal: free
        << "0,0,1.5,0,0,0,1.6,0,into the shelf\n"                     // leans into the shelf
        << "0,0,0,0,0,0,nan,0,nan\n"                                  // NaN: invalid
        << "0,0,0,0,0,0,9,0,beyond the limit\n";                      // out of bounds: invalid
  }
  const CliRun r = run("check " + scene("bookshelf.yaml") + " --states " + csv.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u) << r.out;
  EXPECT_EQ(rows[0], "index,valid,time_ns");
  const char* expected[] = {"0,1,", "1,1,", "2,0,", "3,0,", "4,0,"};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(rows[i + 1].rfind(expected[i], 0), 0u) << rows[i + 1];

  {
    std::ofstream out(csv);
    out << "joint1,joint2\n0,0\n";
  }
  const CliRun bad = run("check " + scene("bookshelf.yaml") + " --states " + csv.string());
  EXPECT_NE(bad.status, 0);
  EXPECT_THAT(bad.err, HasSubstr("missing column 'joint3'"));
  EXPECT_EQ(lines(bad.err).size(), 2u);  // the "loaded" progress line and the error
  fs::remove(csv);
}

TEST(Cli, PlanWritesOmplPathFormat) {
  const fs::path path = fs::temp_directory_path() / "octomotion_cli_path.txt";
  const CliRun r =
      run("plan " + scene("narrow_passage.yaml") + " --time 60 --seed 3 --out " + path.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("solved in"));
  std::ifstream in(path);
  std::vector<std::array<double, 7>> states;
  for (std::string line; std::getline(in, line);) {
    std::stringstream s(line);
    std::array<double, 7> v{};
    for (double& x : v) ASSERT_TRUE(static_cast<bool>(s >> x)) << line;
    states.push_back(v);
  }
  ASSERT_GE(states.size(), 2u);
  // x y z qx qy qz qw: starts at the scene's start (rpy 90 degrees about x) and ends at the goal.
  EXPECT_NEAR(states.front()[0], -0.7, 1e-9);
  EXPECT_NEAR(std::abs(states.front()[3]), std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(states.back()[0], 0.4, 1e-9);
  EXPECT_NEAR(std::abs(states.back()[6]), 1.0, 1e-9);
  fs::remove(path);
}

TEST(Cli, BadInputIsOneLineAndNonZero) {
  for (const std::string& args :
       {std::string("plan /no/such/scene.yaml"), std::string("info"),
        std::string("frobnicate ") + scene("bookshelf.yaml"),
        "info " + scene("bookshelf.yaml") + " --rounding sideways",
        "info " + scene("bookshelf.yaml") + " --resolution -1",
        "info " + scene("bookshelf.yaml") + " --checker bullet",
        "info " + scene("bookshelf.yaml") + " --self-link-resolution 0",
        "info " + scene("bookshelf.yaml") + " --exact-primitives yes",
        "plan " + scene("bookshelf.yaml") + " --time", "check " + scene("bookshelf.yaml")}) {
    const CliRun r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(lines(r.err).size(), 1u) << args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr("octomotion: error: ")) << args;
  }
}

}  // namespace
