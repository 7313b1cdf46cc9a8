// The trade study's bookkeeping (issue #5): false-positive/false-negative counting against the
// exact reference on hand-made answers, percentiles, the CSV layout, and a tiny study of a real
// scene whose conservative rows must never miss a contact FCL finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/tools/experiment_name.h"
#include "octomotion/tools/trade_study.h"

namespace octomotion {
namespace {

std::size_t fieldCount(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

TEST(TradeStudyTest, ScoresFalsePositivesAndNegativesAgainstTheReference) {
  // reference: 3 colliding, 5 free
  const std::vector<bool> reference = {true, true, true, false, false, false, false, false};
  const std::vector<bool> answers = {true, false, true, true, true, false, false, true};
  CheckRow row;
  scoreAgainstReference(answers, reference, row);
  EXPECT_EQ(row.states, 8u);
  EXPECT_EQ(row.colliding_states, 3u);
  EXPECT_EQ(row.free_states, 5u);
  EXPECT_EQ(row.false_negatives, 1u);  // state 1
  EXPECT_EQ(row.false_positives, 3u);  // states 3, 4, 7
  EXPECT_DOUBLE_EQ(row.fn_rate, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(row.fp_rate, 3.0 / 5.0);

  // The reference scored against itself is perfect; all-free has no colliding states to miss.
  scoreAgainstReference(reference, reference, row);
  EXPECT_EQ(row.false_positives + row.false_negatives, 0u);
  const std::vector<bool> none(4, false);
  scoreAgainstReference(none, none, row);
  EXPECT_EQ(row.colliding_states, 0u);
  EXPECT_DOUBLE_EQ(row.fn_rate, 0.0);

  EXPECT_THROW(scoreAgainstReference(none, reference, row), InvalidArgument);
}

TEST(TradeStudyTest, PercentileIsNearestRank) {
  std::vector<double> v = {5, 1, 4, 2, 3, 10, 9, 8, 7, 6};
  EXPECT_DOUBLE_EQ(percentile(v, 0.5), 5);
  EXPECT_DOUBLE_EQ(percentile(v, 0.9), 9);
  EXPECT_DOUBLE_EQ(percentile(v, 1.0), 10);
  std::vector<double> one = {3};
  EXPECT_DOUBLE_EQ(percentile(one, 0.9), 3);
  std::vector<double> empty;
  EXPECT_DOUBLE_EQ(percentile(empty, 0.5), 0);
}

TEST(TradeStudyTest, CsvRowsHaveTheHeadersColumns) {
  CheckRow check;
  check.scene = "s";
  check.checker = CheckerKind::kOctreeFused;
  check.resolution = 0.01;
  check.rounding = "conservative";
  std::ostringstream out;
  writeCheckCsv({check, check}, out);
  std::istringstream in(out.str());
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, kCheckCsvColumns);
  int rows = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(fieldCount(line), fieldCount(header)) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2);

  PlanRow plan;
  plan.scene = "s";
  plan.planner = "RRTConnect";
  plan.checker = CheckerKind::kFcl;
  std::ostringstream pout;
  writePlanCsv({plan}, pout);
  std::istringstream pin(pout.str());
  std::getline(pin, header);
  EXPECT_EQ(header, kPlanCsvColumns);
  std::getline(pin, line);
  EXPECT_EQ(fieldCount(line), fieldCount(header));
}

TEST(TradeStudyTest, DefaultResolutionsGoFromCoarseToFine) {
  const std::vector<double> arm = defaultResolutions(false, 1.0);
  ASSERT_GE(arm.size(), 5u);
  EXPECT_DOUBLE_EQ(arm.front(), 0.08);
  EXPECT_DOUBLE_EQ(arm.back(), 0.005);
  const std::vector<double> body = defaultResolutions(true, 0.005);
  ASSERT_GE(body.size(), 5u);
  EXPECT_DOUBLE_EQ(body.front(), 0.08);
  EXPECT_DOUBLE_EQ(body.back(), 0.005);
  EXPECT_TRUE(std::is_sorted(body.rbegin(), body.rend()));
}

// A small real study, every row's answers scored here against FCL's on the same states: the
// conservative octree and FCL+OctoMap (conservative voxels too) never say free where FCL finds a
// contact, while center rounding does miss some (so the scoring can see a miss), and the study's
// own counts agree.
TEST(TradeStudyTest, ConservativeSettingsHaveNoFalseNegatives) {
  TradeStudyOptions options;
  options.scene_path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/narrow_passage.yaml";
  options.states = 300;
  options.resolutions = {0.05, 0.02};
  options.runs = 0;
  options.keep_answers = true;
  const TradeStudyResult result = runTradeStudy(options);
  EXPECT_TRUE(result.free_flying);
  EXPECT_TRUE(result.planning.empty());
  // fcl + per resolution: fcl-octomap + 2 roundings x 2 paths.
  ASSERT_EQ(result.checks.size(), 1u + 2u * 5u);
  const CheckRow& fcl = result.checks.front();
  ASSERT_EQ(fcl.checker, CheckerKind::kFcl);
  ASSERT_EQ(fcl.answers.size(), 300u);
  const auto fcl_colliding =
      static_cast<std::size_t>(std::count(fcl.answers.begin(), fcl.answers.end(), true));
  EXPECT_GT(fcl_colliding, 0u);
  EXPECT_LT(fcl_colliding, fcl.answers.size());
  std::size_t center_misses = 0;
  for (const CheckRow& r : result.checks) {
    const std::string setting = std::string(checkerKindName(r.checker)) + " " +
                                std::to_string(r.resolution) + " " + r.rounding;
    SCOPED_TRACE(setting);
    ASSERT_EQ(r.answers.size(), fcl.answers.size());
    std::size_t false_negatives = 0, false_positives = 0;
    for (std::size_t i = 0; i < r.answers.size(); ++i) {
      false_negatives += fcl.answers[i] && !r.answers[i] ? 1 : 0;
      false_positives += !fcl.answers[i] && r.answers[i] ? 1 : 0;
    }
    EXPECT_EQ(r.colliding_states, fcl_colliding);
    EXPECT_EQ(r.false_negatives, false_negatives);
    EXPECT_EQ(r.false_positives, false_positives);
    if (r.rounding == "conservative" || r.checker == CheckerKind::kFclOctomap) {
      EXPECT_EQ(false_negatives, 0u);
    } else if (r.rounding == "center") {
      center_misses += false_negatives;
    }
    if (isOctreeChecker(r.checker)) {
      EXPECT_GT(r.memory_bytes, 0u);
      // Paired with FCL+OctoMap's environment-only passes at the same resolution.
      EXPECT_GT(r.env_speedup_vs_fcl_octomap, 0.0);
      EXPECT_GT(r.env_mean_us, 0.0);
    }
  }
  EXPECT_GT(center_misses, 0u);
  // Both paths answer identically for the same model.
  for (const CheckRow& a : result.checks) {
    for (const CheckRow& b : result.checks) {
      if (a.checker == CheckerKind::kOctree && b.checker == CheckerKind::kOctreeFused &&
          a.resolution == b.resolution && a.rounding == b.rounding) {
        EXPECT_EQ(a.answers, b.answers);
      }
    }
  }
  std::ostringstream md;
  writeMarkdown(result, md);
  EXPECT_NE(md.str().find("| fcl | exact |"), std::string::npos);
}

// A check row of 100 states for the target reports: FCL's (mean 10 us) or a conservative one
// at 2 cm with its mean and ratio to FCL.
CheckRow targetRow(CheckerKind checker, double mean_us, double speedup_vs_fcl = 1) {
  CheckRow row;
  row.checker = checker;
  row.states = 100;
  row.mean_us = mean_us;
  if (checker != CheckerKind::kFcl) {
    row.resolution = 0.02;
    row.rounding = "conservative";
    row.speedup_vs_fcl = speedup_vs_fcl;
  }
  return row;
}

// The targets are the caller's: the report names them and the verdicts follow them.
TEST(TradeStudyTest, TargetsAreTheCallers) {
  TradeStudyResult result;
  result.scene = "s";
  CheckRow octree = targetRow(CheckerKind::kOctreeFused, 1, 10);
  octree.env_speedup_vs_fcl_octomap = 4;
  result.checks = {targetRow(CheckerKind::kFcl, 10), octree};
  const StudyTargets easy = {0.02, 5.0, 2.0, 3.0, 10.0, 3.0, 100};
  std::ostringstream met;
  writeTargets(result, easy, met);
  EXPECT_NE(met.str().find("Targets for s"), std::string::npos);
  EXPECT_NE(met.str().find("target >= 5: **met**"), std::string::npos) << met.str();
  EXPECT_NE(met.str().find("target >= 2: **met**"), std::string::npos) << met.str();
  StudyTargets hard = easy;
  hard.full_speedup = 20;
  std::ostringstream missed;
  writeTargets(result, hard, missed);
  EXPECT_NE(missed.str().find("target >= 20: **missed**"), std::string::npos) << missed.str();
}

// Without FCL+OctoMap rows (--no-fcl-octomap) the fastest setting without misses is the one
// reported, not the first.
TEST(TradeStudyTest, TargetsWithoutFclOctomapPickTheFastestSetting) {
  TradeStudyResult result;
  result.scene = "s";
  result.checks = {targetRow(CheckerKind::kFcl, 10), targetRow(CheckerKind::kOctree, 100, 0.1),
                   targetRow(CheckerKind::kOctreeFused, 2, 5)};
  const StudyTargets targets = {0.02, 3.0, 2.0, 3.0, 10.0, 3.0, 100};
  std::ostringstream out;
  writeTargets(result, targets, out);
  EXPECT_NE(out.str().find("full check, octree-fused 2 cm conservative"), std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("target >= 3: **met**"), std::string::npos) << out.str();
}

// A small arm study: bookshelf, 400 states, the fused conservative octree at 2 cm against FCL.
TradeStudyOptions bookshelfFusedConservative() {
  TradeStudyOptions options;
  options.scene_path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml";
  options.states = 400;
  options.resolutions = {0.02};
  options.roundings = {Rounding::kConservative};
  options.octree_checkers = {CheckerKind::kOctreeFused};
  options.fcl_octomap = false;
  options.runs = 0;
  return options;
}

// An arm with finer self-collision trees: the setting is named in the markdown, counts their
// memory, and keeps every conservative row free of false negatives; the finer self trees clear
// self false positives of the same states.
TEST(TradeStudyTest, FinerSelfTreesAreMeasuredAndCounted) {
  TradeStudyOptions options = bookshelfFusedConservative();
  const TradeStudyResult same = runTradeStudy(options);
  options.self_link_resolution_ratio = 0.125;  // finer than the default link trees (1/4)
  const TradeStudyResult finer = runTradeStudy(options);
  ASSERT_EQ(same.checks.size(), 2u);
  ASSERT_EQ(finer.checks.size(), 2u);
  const CheckRow& a = same.checks[1];
  const CheckRow& b = finer.checks[1];
  EXPECT_EQ(b.false_negatives, 0u);
  EXPECT_LT(b.false_positives, a.false_positives);
  EXPECT_GT(b.memory_bytes, a.memory_bytes);  // the second trees are counted
  std::ostringstream md;
  writeMarkdown(finer, md);
  EXPECT_NE(md.str().find("Self-collision trees at 0.125"), std::string::npos);
}

// Self-pair tables from the scene options (as `--self-pair-tables on` sets them): only
// conservative answers change, they stay free of false negatives and lose self false positives.
TEST(TradeStudyTest, SelfPairTablesAreHonoured) {
  TradeStudyOptions options = bookshelfFusedConservative();
  const TradeStudyResult plain = runTradeStudy(options);
  options.overrides.self_pair_tables = true;
  const TradeStudyResult tabled = runTradeStudy(options);
  EXPECT_FALSE(plain.self_pair_tables);
  EXPECT_TRUE(tabled.self_pair_tables);
  ASSERT_EQ(plain.checks.size(), 2u);
  ASSERT_EQ(tabled.checks.size(), 2u);
  const CheckRow& a = plain.checks[1];
  const CheckRow& b = tabled.checks[1];
  EXPECT_EQ(b.false_negatives, 0u);
  EXPECT_LT(b.false_positives, a.false_positives);
  EXPECT_EQ(b.env_fp_rate, a.env_fp_rate);    // the environment half is unchanged
  EXPECT_GT(b.memory_bytes, a.memory_bytes);  // the tables are counted
  std::ostringstream md;
  writeMarkdown(tabled, md);
  EXPECT_NE(md.str().find("Self-pair tables on"), std::string::npos);
}

// The experiment name as OMPL's scripts/ompl_benchmark_statistics.py reads a log (Planner
// Arena's import): an optional "<library> version <v>" line, then a line whose first word is
// "Experiment", of which it keeps the last whitespace-separated word. Debian's libompl-dev
// does not ship the script and nothing is downloaded in tests, so its rule is followed here.
std::string arenaExperimentName(const std::string& log_text) {
  std::istringstream in(log_text);
  std::string line;
  for (int i = 0; i < 2 && std::getline(in, line); ++i) {
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string w; words >> w;) tokens.push_back(w);
    if (i == 0 && tokens.size() > 1 && tokens[1] == "version") continue;
    if (tokens.empty() || tokens[0] != "Experiment") return "";  // the script stops here
    return tokens.back();
  }
  return "";
}

TEST(TradeStudyTest, ExperimentNamesAreOneWordKeepingSceneCheckerAndResolution) {
  EXPECT_EQ(experimentName("bookshelf small", "octree-fused", 0.02, "conservative"),
            "bookshelf-small_octree-fused_2cm_conservative");
  EXPECT_EQ(experimentName("shelf_0001", "fcl", 0.005), "shelf_0001_fcl_5mm");
  EXPECT_EQ(experimentName("a\tb", "fcl", 0.0), "a-b_fcl");
  const std::string name = experimentName("x y", "octree-fused", 0.0125, "nearest");
  EXPECT_EQ(arenaExperimentName("Experiment " + name + "\n"), name);
  EXPECT_EQ(arenaExperimentName("OMPL version 1.5.2\nExperiment " + name + "\n"), name);
  EXPECT_NE(experimentName("s", "fcl", 0.01), experimentName("s", "fcl", 0.02));
}

// Planning through ompl::tools::Benchmark: every planning row has its runs, and the planner's
// own solve time (measured inside Benchmark's run, without its termination-condition thread) is
// positive and never above Benchmark's time of the same runs; the .log files carry both.
TEST(TradeStudyTest, PlanningRecordsBenchmarksTimeAndThePlannersOwn) {
  TradeStudyOptions options = bookshelfFusedConservative();
  options.states = 20;
  options.runs = 3;
  options.planners = {{"RRTConnect", 2.0}};
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "octomotion_trade_study_planning_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  options.log_dir = dir.string();
  const TradeStudyResult result = runTradeStudy(options);
  std::set<std::string> experiments;
  ASSERT_EQ(result.planning.size(), 2u);  // FCL and the fused conservative octree at 2 cm
  for (const PlanRow& r : result.planning) {
    SCOPED_TRACE(checkerKindName(r.checker));
    EXPECT_EQ(r.runs, 3u);
    EXPECT_EQ(r.solved, 3u);  // RRTConnect solves the bookshelf in milliseconds at 2 cm
    EXPECT_GT(r.median_solve_time, 0.0);
    EXPECT_LE(r.median_solve_time, r.median_time);
    std::ifstream log(r.log_file);
    ASSERT_TRUE(log.good()) << r.log_file;
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("solve time REAL"), std::string::npos);
    EXPECT_NE(text.find("\ntime REAL"), std::string::npos);  // Benchmark's own
    // What Planner Arena's import keeps of the experiment line is the whole name.
    const std::string expected =
        experimentName(r.scene, checkerKindName(r.checker), r.resolution, r.rounding);
    EXPECT_NE(text.find("\nExperiment " + expected + "\n"), std::string::npos)
        << text.substr(0, 120);
    EXPECT_EQ(arenaExperimentName(text), expected);
    experiments.insert(arenaExperimentName(text));
  }
  EXPECT_EQ(experiments.size(), result.planning.size());  // FCL and octree stay apart
  std::ostringstream md;
  writeMarkdown(result, md);
  EXPECT_NE(md.str().find("median solve s"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace octomotion
