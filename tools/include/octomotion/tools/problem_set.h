// A planning benchmark over a folder of problems (`octomotion bench-set`, docs/benchmarking.md):
// every problem is planned with each checker in turn, in one process, back to back, and every
// solved path is re-checked with exact FCL at a density far above the planner's motion step.
// Results: one row per problem, checker and run; per set and checker, a summary; OMPL benchmark
// logs (ompl_benchmark_statistics.py, Planner Arena) and a CSV.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion::tools {

// One problem of a set: a scene file, or a MoveIt PlanningScene / MotionPlanRequest pair (the
// MotionBenchMaker layout: sceneNNNN.yaml or scene_sensedNNNN.yaml beside requestNNNN.yaml).
struct SetProblem {
  std::string set;             // the folder's name
  std::string name;            // the scene file's stem, or requestNNNN
  std::string scene;           // a scene file (empty for a MoveIt pair)
  std::string moveit_scene;    // a MoveIt pair's files (empty for a scene file)
  std::string moveit_request;  //
};

// The problems under `dir`: its own scene files (*.yaml, *.cfg) or MoveIt pairs, else those of
// its sub-folders, two levels down at most (a folder of sets, or the MotionBenchMaker archive
// extracted: problems/<set>/...). A folder holding MoveIt requests is a set of pairs; its other
// YAML files are not scenes. Sorted by set, then by name. Throws FileError naming `dir` when it
// is not a folder or holds no problem, and naming a request whose scene is missing.
std::vector<SetProblem> findProblems(const std::string& dir);

struct ProblemSetOptions {
  std::string dir;
  std::vector<CheckerKind> checkers = {CheckerKind::kOctreeFused, CheckerKind::kFcl};
  SceneOverrides overrides;  // planner, time, seed, resolution...; the checker is set per run
  std::size_t runs = 1;      // plans per problem and checker
  std::size_t limit = 0;     // the first N problems of each set; 0: all
  // MoveIt pairs become scenes with this robot (required for them) and joints held at values
  // (problem.fixed); the request gives the group, the start, the goal and the time.
  std::string urdf, srdf;
  std::map<std::string, double> fixed;
  std::string scene_dir;         // where the pairs' scene files are written (required for pairs)
  double recheck_density = 100;  // FCL re-check states per state of the planner's motion step
  // Called before each problem × checker (done of total, and what) and once at the end.
  std::function<void(std::size_t done, std::size_t total, const std::string& what)> progress;
};

struct ProblemRun {
  std::string set, problem;
  CheckerKind checker = CheckerKind::kOctreeFused;
  double resolution = 0;  // the octree's, metres
  std::size_t run = 0;
  std::uint64_t seed = 0;  // the problem's own seed (problem_set.cpp, problemSeed); 0: unseeded
  std::string error;    // the problem failed to load (e.g. a start in collision for this checker)
  bool solved = false;  // an exact solution
  double seconds = 0;   // the planner's solve time (the limit when not solved)
  double time_limit = 0;
  std::size_t state_checks = 0;       // StateValidityChecker::isValid calls during the solve
  std::size_t motion_checks = 0;      // MotionValidator::checkMotion calls during the solve
  std::size_t waypoints = 0;          // of the simplified path
  double length = 0;                  // of the simplified path
  std::size_t recheck_states = 0;     // states of the dense FCL re-check
  std::size_t recheck_colliding = 0;  // of them, in collision (or invalid) for exact FCL
};

struct ProblemSetResult {
  std::string planner;
  std::vector<ProblemRun> runs;  // per problem, then checker, then run
  double seconds = 0;            // wall time of the whole benchmark
};

// Plans every problem; a problem that fails to load for a checker is a row with `error` set
// (not solved). Throws for bad options (no checker, pairs without a robot).
ProblemSetResult runProblemSet(const ProblemSetOptions& options);

// Per set and checker: problems, solved, planning-time median and 90th percentile (unsolved runs
// count at the limit), mean checks per plan, FCL re-check states and collisions.
struct SetSummary {
  std::string set;
  CheckerKind checker = CheckerKind::kOctreeFused;
  double resolution = 0;
  std::size_t problems = 0, runs = 0, solved = 0, load_errors = 0;
  double median_seconds = 0, p90_seconds = 0;
  double state_checks = 0, motion_checks = 0;  // mean per plan
  std::size_t recheck_states = 0, recheck_colliding = 0;
};
// Sets in order, each followed by the same set over all sets ("all") last.
std::vector<SetSummary> summarize(const ProblemSetResult& result);

void writeSummaryMarkdown(const std::vector<SetSummary>& summary, std::ostream& out);
// One row per problem, checker and run.
void writeProblemCsv(const ProblemSetResult& result, std::ostream& out);
// One OMPL benchmark log per set and checker in `dir` (each problem × run is one of the
// planner's runs); returns the files written. Throws FileError when one cannot be written.
std::vector<std::string> writeOmplLogs(const ProblemSetResult& result,
                                       const ProblemSetOptions& options, const std::string& dir);

}  // namespace octomotion::tools
