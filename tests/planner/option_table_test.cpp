// The option tables of the octomotion command and bench/tradeoff_bench: one parser and one help
// text per table, scene options applied the same way everywhere.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/tools/option_table.h"
#include "octomotion/tools/study_options.h"

namespace octomotion::tools {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Parses `args` with `table` as the commands do; returns the arguments no option took.
template <class Target>
std::vector<std::string> parseAll(const OptionTable<Target>& table,
                                  const std::vector<std::string>& args, Target& target) {
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (!table.parse(arg, value, target)) rest.push_back(arg);
  }
  return rest;
}

TEST(OptionTable, SceneOptionsFillTheOverrides) {
  SceneOverrides o;
  const auto rest =
      parseAll(sceneOptions(),
               {"--checker", "fcl-octomap", "--resolution", "auto", "--seed", "7",
                "--self-pair-tables", "on", "--package-path", "a", "--package-path", "b", "scene"},
               o);
  EXPECT_EQ(rest, std::vector<std::string>{"scene"});
  EXPECT_EQ(o.checker, CheckerKind::kFclOctomap);
  EXPECT_TRUE(o.auto_resolution);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_EQ(o.self_pair_tables, true);
  EXPECT_EQ(o.package_paths, (std::vector<std::string>{"a", "b"}));
  EXPECT_THROW(parseAll(sceneOptions(), {"--checker", "bullet"}, o), InvalidArgument);
  EXPECT_THROW(parseAll(sceneOptions(), {"--time", "0"}, o), InvalidArgument);
  EXPECT_THROW(parseAll(sceneOptions(), {"--exact-primitives", "yes"}, o), InvalidArgument);
  EXPECT_THROW(parseAll(sceneOptions(), {"--resolution"}, o), InvalidArgument);
}

TEST(OptionTable, StudyOptionsShareTheSceneOptions) {
  StudyCommandOptions o;
  parseAll(studyOptions(),
           {"--states", "10", "--paths", "octree-fused", "--roundings", "center", "--seed", "3",
            "--no-fcl-octomap", "--planners", "RRTConnect:2,PRM", "--out-dir", "d"},
           o);
  finishStudyOptions(o);
  EXPECT_EQ(o.study.states, 10u);
  EXPECT_EQ(o.study.octree_checkers, std::vector<CheckerKind>{CheckerKind::kOctreeFused});
  EXPECT_EQ(o.study.roundings, std::vector<Rounding>{Rounding::kCenter});
  EXPECT_EQ(o.study.seed, 3u);  // --seed seeds the states as well as OMPL
  EXPECT_FALSE(o.study.fcl_octomap);
  ASSERT_EQ(o.study.planners.size(), 2u);
  EXPECT_DOUBLE_EQ(o.study.planners[0].time, 2.0);
  EXPECT_EQ(o.study.planners[1].name, "PRM");
  EXPECT_EQ(o.out_dir, "d");
  StudyCommandOptions bad;
  EXPECT_THROW(parseAll(studyOptions(), {"--paths", "fcl"}, bad), InvalidArgument);
  EXPECT_THROW(parseAll(studyOptions(), {"--states", "0"}, bad), InvalidArgument);
  // A one-setting scene option is parsed, then refused with the study's replacement named.
  parseAll(studyOptions(), {"--rounding", "center"}, bad);
  EXPECT_THROW(finishStudyOptions(bad), InvalidArgument);
}

TEST(OptionTable, HelpListsWhatIsParsed) {
  std::ostringstream study, scene;
  studyOptions().writeHelp(study);
  sceneOptions().writeHelp(scene);
  for (const char* flag : {"--states N", "--paths LIST", "--seed N", "--self-pair-tables on|off"}) {
    EXPECT_THAT(study.str(), HasSubstr(flag));
  }
  // The study's own lists replace the one-setting options, which its help leaves out.
  EXPECT_THAT(study.str(), Not(HasSubstr("--resolution ")));
  EXPECT_THAT(scene.str(), HasSubstr("--resolution METRES|auto"));
  EXPECT_THAT(scene.str(), HasSubstr("--checker octree|octree-fused|fcl|fcl-octomap"));
}

}  // namespace
}  // namespace octomotion::tools
