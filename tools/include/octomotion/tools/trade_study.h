// The speed/accuracy trade study (docs/trade-off.md): for one scene, every octree setting
// (resolution x rounding x checker path) and the FCL references are run on the same uniformly
// sampled states in the same process, so their times are comparable and their answers can be
// scored against FCL's exact one. Planning is measured with ompl::tools::Benchmark, whose .log
// files ompl_benchmark_statistics.py and Planner Arena read.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {

// A planner and the time limit of each of its runs.
struct StudyPlanner {
  std::string name;   // an OMPL planner known to makePlanner
  double time = 0.0;  // seconds per run; 0: the scene's problem.time
};

struct TradeStudyOptions {
  std::string scene_path;
  // Applied to the scene as loadPlanningScene applies them (loadSceneInputs): package paths, the
  // time limit, and the octree options that hold for every setting (self_pair_tables,
  // exact_primitives, max_surface_voxels). The settings themselves (resolution, rounding,
  // checker, link resolutions) come from the fields below, the seed from `seed`.
  SceneOverrides overrides;
  std::vector<double> resolutions;  // metres; empty: defaultResolutions()
  std::vector<Rounding> roundings = {Rounding::kConservative, Rounding::kCenter};
  // Also conservative rounding refined with FCL (RefineMode::kExact), rounding label
  // "conservative+exact".
  bool refine_exact = false;
  // The octree checker paths measured (kOctree, kOctreeFused; the FCL kinds are always run).
  std::vector<CheckerKind> octree_checkers = {CheckerKind::kOctree, CheckerKind::kOctreeFused};
  bool fcl_octomap = true;  // also FCL+OctoMap at every resolution (when it is built in)
  // The links' source-tree voxel size as a multiple of each resolution; empty: the library's
  // default (kDefaultLinkResolutionRatio). Finer link trees shrink the conservative margin.
  std::optional<double> link_resolution_ratio;
  // Self-collision trees at this multiple of each resolution; empty: link_resolution_ratio when
  // that is set, else 1 (the library's defaults, CollisionModelOptions::self_link_resolution).
  std::optional<double> self_link_resolution_ratio;
  std::size_t states = 20000;
  // The moveTree path is orders of magnitude slower at fine resolutions; it checks only the
  // first `move_tree_states` of the same states (0: all of them).
  std::size_t move_tree_states = 0;
  // Seeds the states and, before the planning runs, OMPL's random numbers.
  std::uint64_t seed = 1;
  // Planning (skipped when `runs` is 0 or the scene has no start and goal).
  std::vector<StudyPlanner> planners = {{"RRTConnect", 0.0}, {"RRTstar", 0.0}};
  unsigned runs = 20;
  // Which settings plan: false plans the fused conservative octree at every resolution, the
  // other octree settings at the resolution closest to the scene's, FCL, and FCL+OctoMap at
  // that resolution; true plans every setting.
  bool plan_every_setting = false;
  std::string log_dir;  // where the Benchmark .log files go; empty: none written
  // Keep every row's answers (CheckRow::answers), so that a caller can score them itself.
  bool keep_answers = false;
  std::function<void(const std::string&)> progress;  // one line per step; may be empty
};

// The resolutions from coarse to fine: 8, 4, 2, 1, 0.5 cm for fixed-base robots; for free-flying
// bodies 16, 8, 4, 2 and 1 times the scene's own resolution (its `octree.resolution`, or the
// automatic one, which is scaled to the scene and the body).
std::vector<double> defaultResolutions(bool free_flying, double scene_resolution);

// One checker setting over the state set. Times include forward kinematics; "free" and
// "colliding" classify the states by FCL's exact answer.
struct CheckRow {
  std::string scene;
  CheckerKind checker = CheckerKind::kFcl;
  double resolution = 0;  // metres; 0 for fcl
  std::string rounding;   // conservative | center; empty for fcl and fcl-octomap
  std::size_t states = 0, free_states = 0, colliding_states = 0;
  double mean_us = 0;  // full check (environment and self-collision); median of 5 timed passes
  double median_free_us = 0, p90_free_us = 0;
  double median_colliding_us = 0, p90_colliding_us = 0;
  double env_mean_us = -1;          // environment only (median of 5 passes); -1 when not measured
  std::size_t false_positives = 0;  // says collision, FCL says free
  std::size_t false_negatives = 0;  // says free, FCL says collision
  double fp_rate = 0;               // false_positives / free_states
  double fn_rate = 0;               // false_negatives / colliding_states
  // The environment-only answers against FCL's environment-only answers (the split of the
  // errors between the environment and self-collision); -1 when not measured.
  double env_fp_rate = -1, env_fn_rate = -1;
  std::size_t memory_bytes =
      0;  // octree: environment, link and self trees, pair tables; 0 if unknown
  double build_seconds = 0;
  // FCL's full-check time / this one's: the median over 5 rounds of a timed FCL pass over the
  // same states right before this checker's pass (so both see the same machine load); it can
  // differ a little from the ratio of the two mean_us, each a median over its own rounds.
  double speedup_vs_fcl = 1;
  // FCL+OctoMap's environment-only time at the same resolution / this one's, paired like
  // speedup_vs_fcl (an FCL+OctoMap environment-only pass right before each of this checker's);
  // -1 when not measured.
  double env_speedup_vs_fcl_octomap = -1;
  // The full check's answer (true: in collision) for each of the first `states` states, when
  // TradeStudyOptions::keep_answers is set; every row's state i is the same state.
  std::vector<bool> answers;
};

struct PlanRow {
  std::string scene, planner;
  CheckerKind checker = CheckerKind::kFcl;
  double resolution = 0;
  std::string rounding;
  double time_limit = 0;
  unsigned runs = 0, solved = 0;  // exact solutions
  double median_time = 0;         // seconds, over every run (unsolved ones count the limit)
  // The same for the planner's own solve, without what Benchmark's "time REAL" adds to every
  // run (its termination-condition thread, up to 1 ms); the logs' "solve time REAL".
  double median_solve_time = 0;
  double median_first_solution = -1;  // seconds, solved runs, from Benchmark's progress data
  double median_length = -1;          // simplified path length, solved runs; -1 if none
  std::string log_file;
};

struct TradeStudyResult {
  std::string scene;
  bool free_flying = false;
  double scene_resolution = 0;
  // The link and self-collision trees' voxel sizes used, as multiples of each resolution.
  double link_resolution_ratio = kDefaultLinkResolutionRatio;
  double self_link_resolution_ratio = 1.0;
  bool self_pair_tables = false;  // the scene's octree.self_pair_tables
  bool exact_primitives = false;  // the scene's octree.exact_primitives
  std::vector<CheckRow> checks;
  std::vector<PlanRow> planning;
};

// Runs the study. Throws octomotion::Error for a bad scene or option.
TradeStudyResult runTradeStudy(const TradeStudyOptions& options);

// Scoring against the reference, exposed for tests: counts disagreements of `answers` with the
// exact `reference` (true = in collision) and sets the rows' counts and rates.
void scoreAgainstReference(const std::vector<bool>& answers, const std::vector<bool>& reference,
                           CheckRow& row);
// Median and the 90th percentile (nearest rank) of `values` (which is reordered); 0 when empty.
double percentile(std::vector<double>& values, double p);

// Writers. The CSVs have a header line; writeCheckCsv's columns are kCheckCsvColumns.
extern const char* const kCheckCsvColumns;
extern const char* const kPlanCsvColumns;
void writeCheckCsv(const std::vector<CheckRow>& rows, std::ostream& out, bool header = true);
void writePlanCsv(const std::vector<PlanRow>& rows, std::ostream& out, bool header = true);
void writeMarkdown(const TradeStudyResult& result, std::ostream& out);
// gnuplot data: one block per checker curve (index i), first line the curve's title.
// Trade-off: false-positive rate (%) vs mean check time (us). Planning: resolution (cm) vs
// median planning time (s), one block per planner x checker.
void writeTradeoffPlotData(const TradeStudyResult& result, std::ostream& out);
void writePlanningPlotData(const TradeStudyResult& result, std::ostream& out);

// Targets for the octree checkers against the references (docs/trade-off.md, "Targets"); the
// programs that report them supply the values.
struct StudyTargets {
  // Fixed-base robots: the best octree setting without false negatives and at most this
  // false-positive rate must be full_speedup x FCL's full check and env_speedup_vs_fcl_octomap x
  // FCL+OctoMap's environment-only check.
  double max_fp_rate;
  double full_speedup;
  double env_speedup_vs_fcl_octomap;
  // Free-flying bodies: the fused conservative octree at every resolution against FCL and
  // FCL+OctoMap.
  double rigid_full_speedup;
  double rigid_speedup_vs_fcl_octomap;
  // RRTConnect's median planning time with FCL / with the fused conservative octree.
  double planning_speedup;
  std::size_t states;  // the state count the targets are stated for
};

// `targets` evaluated on one scene's rows: one markdown bullet per target with the measured
// ratio and margin.
void writeTargets(const TradeStudyResult& result, const StudyTargets& targets, std::ostream& out);

// "octree-fused 2 cm conservative": a setting's name in progress lines, tables and log names.
std::string settingName(CheckerKind checker, double resolution, const std::string& rounding);
// "2 cm", "5 mm".
std::string resolutionLabel(double resolution);

}  // namespace octomotion
