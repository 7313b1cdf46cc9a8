// `octomotion bench-set`: on a tiny generated folder (two shipped scenes, and two MotionBenchMaker
// problems as MoveIt pairs when ../shared/data has them), every problem is planned once per
// checker, every solved path is free under exact FCL at 100x the motion step's density, and the
// OMPL logs have the structure ompl_benchmark_statistics.py reads. A bad folder is a one-line
// error naming it. Also: `octomotion plan` writes the simplified waypoints unless asked to
// interpolate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "mbm_problems.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::csvFields;
using test::lines;
const auto slurp = test::readText;

test::CliRun runCli(const std::string& args) {
  return test::runCli(args, "octomotion_bench_set_cli");
}
using ::testing::HasSubstr;

// A shipped scene with its relative paths made absolute, so it loads from another folder.
void copyScene(const std::string& name, const fs::path& to) {
  const std::string robots = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/";
  std::string text = slurp(robots + "scenes/" + name);
  for (std::size_t at = text.find("../"); at != std::string::npos; at = text.find("../", at)) {
    text.replace(at, 3, robots);
    at += robots.size();
  }
  std::ofstream(to / name) << text;
}

// ompl_benchmark_statistics.py's reading of a log (readBenchmarkLog), as checks: the header
// lines it skips or parses, the planner's properties ("name TYPE"), then one "; "-terminated
// line per run with one field per property, then ".".
struct ParsedLog {
  std::string experiment;
  std::vector<std::string> properties;
  std::vector<std::vector<std::string>> runs;
};

ParsedLog parseOmplLog(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  ParsedLog log;
  auto next = [&]() {
    EXPECT_TRUE(static_cast<bool>(std::getline(in, line))) << path;
    return line;
  };
  auto leadingCount = [&](const std::string& l, const std::string& rest) {
    EXPECT_THAT(l, HasSubstr(rest)) << path;
    return std::stoul(l.substr(0, l.find(' ')));
  };
  EXPECT_THAT(next(), HasSubstr("OMPL version"));
  const std::string experiment = next();
  EXPECT_EQ(experiment.rfind("Experiment ", 0), 0u);
  log.experiment = experiment.substr(11);
  // The parser keeps the last word of the name: it must be the whole name.
  EXPECT_EQ(log.experiment.find(' '), std::string::npos) << log.experiment;
  const unsigned long experiment_properties = leadingCount(next(), "experiment properties");
  for (unsigned long i = 0; i < experiment_properties; ++i) next();
  EXPECT_EQ(next().rfind("Running on ", 0), 0u);
  EXPECT_EQ(next().rfind("Starting at ", 0), 0u);
  for (int block = 0; block < 2; ++block) {  // setup and CPU info, each between <<<| and |>>>
    EXPECT_EQ(next(), "<<<|");
    while (std::getline(in, line) && line != "|>>>") {
    }
  }
  leadingCount(next(), "is the random seed");
  leadingCount(next(), "seconds per run");
  leadingCount(next(), "MB per run");
  const unsigned long run_count = leadingCount(next(), "runs per planner");
  leadingCount(next(), "seconds spent to collect the data");
  const unsigned long enums = leadingCount(next(), "enum type");
  for (unsigned long i = 0; i < enums; ++i) next();
  EXPECT_EQ(leadingCount(next(), "planners"), 1u);
  EXPECT_THAT(next(), HasSubstr("geometric_RRTConnect"));
  const unsigned long common = leadingCount(next(), "common properties");
  for (unsigned long i = 0; i < common; ++i) next();
  const unsigned long properties = leadingCount(next(), "properties for each run");
  for (unsigned long i = 0; i < properties; ++i) {
    log.properties.push_back(next());
    const std::string type = line.substr(line.rfind(' ') + 1);
    EXPECT_TRUE(type == "REAL" || type == "INTEGER" || type == "BOOLEAN") << line;
  }
  EXPECT_EQ(leadingCount(next(), "runs"), run_count);
  for (unsigned long r = 0; r < run_count; ++r) {
    next();
    std::vector<std::string> fields;
    std::size_t from = 0;
    for (std::size_t at = line.find("; "); at != std::string::npos; at = line.find("; ", from)) {
      fields.push_back(line.substr(from, at - from));
      from = at + 2;
    }
    EXPECT_EQ(fields.size(), properties) << line;
    log.runs.push_back(fields);
  }
  // Optional progress properties, then the end of the planner.
  while (std::getline(in, line) && line != ".") {
  }
  EXPECT_EQ(line, ".");
  return log;
}

TEST(BenchSet, EveryProblemOncePerCheckerAndSolvedPathsFreeUnderFcl) {
  const fs::path dir = fs::temp_directory_path() / "octomotion_bench_set_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "problems" / "shipped");
  copyScene("bookshelf.yaml", dir / "problems" / "shipped");
  copyScene("cluttered_table.yaml", dir / "problems" / "shipped");
  std::set<std::string> expected = {"shipped/bookshelf", "shipped/cluttered_table"};
  const test::MbmProblems mbm;
  const std::string panda = test::MbmProblems::panda();
  std::string robot_args;
  if (!mbm.problems().empty() && fs::exists(panda + "/panda.urdf")) {
    const fs::path set = dir / "problems" / mbm.problems().front().set;
    fs::create_directories(set);
    for (std::size_t i = 0; i < 2; ++i) {
      const test::MbmProblem& p = mbm.problems()[i];
      fs::copy_file(p.scene, set / fs::path(p.scene).filename());
      fs::copy_file(p.request, set / fs::path(p.request).filename());
      expected.insert(p.set + "/" + fs::path(p.request).stem().string());
    }
    robot_args = " --robot " + panda + "/panda.urdf --srdf " + panda + "/panda.srdf";
  }
  const fs::path out_dir = dir / "out";
  const CliRun r = runCli("bench-set " + dir.string() + " --checkers octree-fused,fcl --time 5" +
                          " --seed 1 --out-dir " + out_dir.string() + robot_args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| shipped | octree-fused |"));
  EXPECT_THAT(r.out, HasSubstr("| shipped | fcl |"));

  // The CSV: one row per problem and checker, each solved path re-checked and free.
  const std::vector<std::string> csv = lines(slurp(out_dir / "results.csv"));
  ASSERT_FALSE(csv.empty());
  const std::vector<std::string> header = csvFields(csv.front());
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const char* c :
       {"set", "problem", "checker", "solved", "fcl_recheck_states", "fcl_recheck_colliding",
        "state_checks", "motion_checks", "seed", "error"}) {
    ASSERT_TRUE(column.count(c)) << c;
  }
  std::map<std::string, int> seen;  // "set/problem checker"
  // --seed gives each problem its own seed, the same for each of its checkers.
  std::map<std::string, std::set<std::string>> seeds;  // per problem
  std::size_t solved = 0;
  for (std::size_t i = 1; i < csv.size(); ++i) {
    const std::vector<std::string> f = csvFields(csv[i]);
    ASSERT_EQ(f.size(), header.size()) << csv[i];
    const std::string problem = f[column["set"]] + "/" + f[column["problem"]];
    EXPECT_TRUE(expected.count(problem)) << problem;
    ++seen[problem + " " + f[column["checker"]]];
    EXPECT_NE(f[column["seed"]], "0") << csv[i];
    seeds[problem].insert(f[column["seed"]]);
    EXPECT_EQ(f[column["error"]], "") << csv[i];
    if (f[column["solved"]] != "1") continue;
    ++solved;
    EXPECT_GT(std::stoul(f[column["fcl_recheck_states"]]), 0u) << csv[i];
    EXPECT_EQ(f[column["fcl_recheck_colliding"]], "0") << csv[i];
    EXPECT_GT(std::stoul(f[column["state_checks"]]), 0u) << csv[i];
    EXPECT_GT(std::stoul(f[column["motion_checks"]]), 0u) << csv[i];
  }
  EXPECT_EQ(seen.size(), 2 * expected.size());
  for (const auto& [key, count] : seen) EXPECT_EQ(count, 1) << key;
  std::set<std::string> distinct;
  for (const auto& [problem, values] : seeds) {
    EXPECT_EQ(values.size(), 1u) << problem;
    distinct.insert(values.begin(), values.end());
  }
  EXPECT_EQ(distinct.size(), seeds.size());
  EXPECT_GT(solved, 0u);

  // One log per set and checker, each with a run per problem of the set.
  std::size_t logs = 0;
  for (const auto& entry : fs::directory_iterator(out_dir / "logs")) {
    SCOPED_TRACE(entry.path().string());
    const ParsedLog log = parseOmplLog(entry.path().string());
    ++logs;
    EXPECT_THAT(log.properties, ::testing::Contains("time REAL"));
    EXPECT_THAT(log.properties, ::testing::Contains("solved BOOLEAN"));
    EXPECT_THAT(log.properties, ::testing::Contains("state checks INTEGER"));
    EXPECT_EQ(log.runs.size(), 2u);  // two problems in each set
  }
  EXPECT_EQ(logs, 2 * (expected.size() / 2));  // sets x checkers
  fs::remove_all(dir);
}

TEST(BenchSet, BadFolderIsOneLineNamingIt) {
  const CliRun missing = runCli("bench-set /no/such/folder");
  EXPECT_NE(missing.status, 0);
  EXPECT_THAT(missing.err, HasSubstr("/no/such/folder"));
  EXPECT_EQ(lines(missing.err).size(), 1u) << missing.err;

  const fs::path empty = fs::temp_directory_path() / "octomotion_bench_set_empty";
  fs::create_directories(empty);
  const CliRun none = runCli("bench-set " + empty.string());
  EXPECT_NE(none.status, 0);
  EXPECT_THAT(none.err, HasSubstr(empty.string()));
  EXPECT_THAT(none.err, HasSubstr("no problems"));
  EXPECT_EQ(lines(none.err).size(), 1u) << none.err;

  // A MoveIt request without its scene names the request.
  std::ofstream(empty / "request0001.yaml") << "group_name: arm\n";
  const CliRun orphan = runCli("bench-set " + empty.string());
  EXPECT_NE(orphan.status, 0);
  EXPECT_THAT(orphan.err, HasSubstr("request0001.yaml"));
  EXPECT_EQ(lines(orphan.err).size(), 1u) << orphan.err;
  fs::remove_all(empty);
}

TEST(PlanCli, WritesTheSimplifiedWaypointsUnlessAskedToInterpolate) {
  const std::string scene = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml";
  const fs::path path = fs::temp_directory_path() / "octomotion_bench_set_plan.txt";
  auto states = [&](const std::string& extra) {
    const CliRun r = runCli("plan " + scene + " --seed 1 --out " + path.string() + extra);
    EXPECT_EQ(r.status, 0) << r.err;
    std::vector<std::string> rows;
    for (const std::string& l : lines(slurp(path))) {
      if (!l.empty() && l[0] != '#') rows.push_back(l);
    }
    return rows;
  };
  const std::vector<std::string> waypoints = states("");
  const std::vector<std::string> dense = states(" --interpolation 0.01");
  ASSERT_GE(waypoints.size(), 2u);
  // The same seed plans the same path: the dense one passes through the waypoints' ends, with
  // many more states.
  EXPECT_GT(dense.size(), 4 * waypoints.size());
  EXPECT_EQ(waypoints.front(), dense.front());
  EXPECT_EQ(waypoints.back(), dense.back());
  fs::remove(path);
}

}  // namespace
}  // namespace octomotion
