// The trade study's scoring and its writers: CSV, markdown tables, targets and gnuplot data.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/tools/trade_study.h"
#include "study_format.h"

namespace octomotion {

std::string resolutionLabel(double r) {
  return r >= 0.01 ? fmt(r * 100, 3) + " cm" : fmt(r * 1000, 3) + " mm";
}

std::string settingName(CheckerKind checker, double resolution, const std::string& rounding) {
  std::string s = checkerKindName(checker);
  if (resolution > 0) s += " " + resolutionLabel(resolution);
  if (!rounding.empty()) s += " " + rounding;
  return s;
}

double percentile(std::vector<double>& values, double p) {
  if (values.empty()) return 0.0;
  const double rank = std::ceil(p * static_cast<double>(values.size()));
  const std::size_t k =
      std::min(values.size() - 1, static_cast<std::size_t>(std::max(rank, 1.0)) - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

void scoreAgainstReference(const std::vector<bool>& answers, const std::vector<bool>& reference,
                           CheckRow& row) {
  if (answers.size() != reference.size()) {
    throw InvalidArgument("scoreAgainstReference: " + std::to_string(answers.size()) +
                          " answers for " + std::to_string(reference.size()) + " states");
  }
  row.states = reference.size();
  row.free_states = row.colliding_states = row.false_positives = row.false_negatives = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (reference[i]) {
      ++row.colliding_states;
      if (!answers[i]) ++row.false_negatives;
    } else {
      ++row.free_states;
      if (answers[i]) ++row.false_positives;
    }
  }
  row.fp_rate = row.free_states ? static_cast<double>(row.false_positives) /
                                      static_cast<double>(row.free_states)
                                : 0.0;
  row.fn_rate = row.colliding_states ? static_cast<double>(row.false_negatives) /
                                           static_cast<double>(row.colliding_states)
                                     : 0.0;
}

const char* const kCheckCsvColumns =
    "scene,checker,resolution_m,rounding,states,free_states,colliding_states,mean_us,"
    "median_free_us,p90_free_us,median_colliding_us,p90_colliding_us,env_mean_us,"
    "false_positives,false_negatives,fp_rate,fn_rate,env_fp_rate,env_fn_rate,memory_bytes,"
    "build_s,speedup_vs_fcl,env_speedup_vs_fcl_octomap";
const char* const kPlanCsvColumns =
    "scene,planner,checker,resolution_m,rounding,time_limit_s,runs,solved,median_time_s,"
    "median_first_solution_s,median_length,log_file,median_solve_time_s";

void writeCheckCsv(const std::vector<CheckRow>& rows, std::ostream& out, bool header) {
  if (header) out << kCheckCsvColumns << '\n';
  out << std::setprecision(6);
  for (const CheckRow& r : rows) {
    out << r.scene << ',' << checkerKindName(r.checker) << ',' << r.resolution << ',' << r.rounding
        << ',' << r.states << ',' << r.free_states << ',' << r.colliding_states << ',' << r.mean_us
        << ',' << r.median_free_us << ',' << r.p90_free_us << ',' << r.median_colliding_us << ','
        << r.p90_colliding_us << ',' << r.env_mean_us << ',' << r.false_positives << ','
        << r.false_negatives << ',' << r.fp_rate << ',' << r.fn_rate << ',' << r.env_fp_rate << ','
        << r.env_fn_rate << ',' << r.memory_bytes << ',' << r.build_seconds << ','
        << r.speedup_vs_fcl << ',' << r.env_speedup_vs_fcl_octomap << '\n';
  }
}

void writePlanCsv(const std::vector<PlanRow>& rows, std::ostream& out, bool header) {
  if (header) out << kPlanCsvColumns << '\n';
  out << std::setprecision(6);
  for (const PlanRow& r : rows) {
    out << r.scene << ',' << r.planner << ',' << checkerKindName(r.checker) << ',' << r.resolution
        << ',' << r.rounding << ',' << r.time_limit << ',' << r.runs << ',' << r.solved << ','
        << r.median_time << ',' << r.median_first_solution << ',' << r.median_length << ','
        << r.log_file << ',' << r.median_solve_time << '\n';
  }
}

namespace {

std::string cell(double v, int precision = 3) {
  return v < 0 ? "–" : fmt(v, precision);
}
std::string percent(double rate) {
  return fmt(100 * rate, 3);
}

const CheckRow* findRow(const TradeStudyResult& r, CheckerKind checker, double resolution,
                        const std::string& rounding) {
  for (const CheckRow& row : r.checks) {
    if (row.checker == checker && row.resolution == resolution && row.rounding == rounding) {
      return &row;
    }
  }
  return nullptr;
}

const PlanRow* findPlan(const TradeStudyResult& r, const std::string& planner,
                        CheckerKind checker) {
  for (const PlanRow& row : r.planning) {
    if (row.planner == planner && row.checker == checker) return &row;
  }
  return nullptr;
}

}  // namespace

void writeMarkdown(const TradeStudyResult& result, std::ostream& out) {
  out << "### " << result.scene << "\n\n";
  const CheckRow& fcl = result.checks.front();
  out << fcl.states << " uniform states (" << fcl.colliding_states << " colliding per FCL, "
      << fcl.free_states << " free); times in microseconds per check, forward kinematics "
      << "included; FP % of free states, FN % of colliding states.";
  out << " Octree link source trees at " << result.link_resolution_ratio
      << " x the environment resolution.";
  if (!result.free_flying && result.self_link_resolution_ratio != result.link_resolution_ratio) {
    out << " Self-collision trees at " << result.self_link_resolution_ratio
        << " x the environment resolution.";
  }
  if (result.self_pair_tables) {
    out << " Self-pair tables on (conservative settings; docs/planner.md, \"Self-pair tables\").";
  }
  if (result.exact_primitives) {
    out << " Exact primitives on (conservative settings; docs/planner.md, \"Exact primitives\").";
  }
  out << "\n\n";
  out << "| checker | resolution | rounding | mean | free median | free p90 | colliding median "
         "| colliding p90 | env-only mean | FP % | FN % | env FP % | env FN % | memory KiB | build "
         "s | FCL / this |\n"
      << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const CheckRow& r : result.checks) {
    out << "| " << checkerKindName(r.checker) << " | "
        << (r.resolution > 0 ? resolutionLabel(r.resolution) : "exact") << " | "
        << (r.rounding.empty() ? "–" : r.rounding) << " | " << fmt(r.mean_us) << " | "
        << fmt(r.median_free_us) << " | " << fmt(r.p90_free_us) << " | "
        << fmt(r.median_colliding_us) << " | " << fmt(r.p90_colliding_us) << " | "
        << cell(r.env_mean_us) << " | " << percent(r.fp_rate) << " | " << percent(r.fn_rate)
        << " | " << (r.env_fp_rate < 0 ? "–" : percent(r.env_fp_rate)) << " | "
        << (r.env_fn_rate < 0 ? "–" : percent(r.env_fn_rate)) << " | "
        << (r.memory_bytes ? fmt(static_cast<double>(r.memory_bytes) / 1024.0) : "–") << " | "
        << fmt(r.build_seconds) << " | " << fmt(r.speedup_vs_fcl) << " |\n";
  }
  out << "\n";
  if (!result.planning.empty()) {
    out << "| planner | checker | resolution | rounding | limit s | solved | median time s | "
           "median solve s | median first solution s | median length |\n"
        << "|---|---|---|---|--:|--:|--:|--:|--:|--:|\n";
    for (const PlanRow& r : result.planning) {
      out << "| " << r.planner << " | " << checkerKindName(r.checker) << " | "
          << (r.resolution > 0 ? resolutionLabel(r.resolution) : "exact") << " | "
          << (r.rounding.empty() ? "–" : r.rounding) << " | " << fmt(r.time_limit) << " | "
          << r.solved << "/" << r.runs << " | " << fmt(r.median_time) << " | "
          << fmt(r.median_solve_time) << " | " << cell(r.median_first_solution) << " | "
          << cell(r.median_length) << " |\n";
    }
    out << "\n";
  }
}

void writeTargets(const TradeStudyResult& result, const StudyTargets& targets, std::ostream& out) {
  const CheckRow& fcl = result.checks.front();
  auto verdict = [](double ratio, double target) {
    return ratio >= target ? "**met** (" + fmt(ratio / target, 3) + "x the target)"
                           : "**missed** (" + fmt(ratio, 3) + "x of the " + fmt(target, 3) +
                                 "x asked; short by a factor " + fmt(target / ratio, 3) + ")";
  };
  out << "Targets for " << result.scene << " (" << fcl.states << " states; FCL mean "
      << fmt(fcl.mean_us) << " us):\n\n";
  if (!result.free_flying) {
    // The best octree setting whose false-positive rate is at most targets.max_fp_rate.
    const CheckRow* best = nullptr;
    // Without FCL+OctoMap in the study (--no-fcl-octomap) the environment ratio is 0 for every
    // row; the full check's ratio alone then ranks them.
    auto score = [&](const CheckRow& r) {
      const double full = r.speedup_vs_fcl / targets.full_speedup;
      if (!(r.env_speedup_vs_fcl_octomap > 0)) return full;
      return std::min(full, r.env_speedup_vs_fcl_octomap / targets.env_speedup_vs_fcl_octomap);
    };
    for (const CheckRow& r : result.checks) {
      // Only settings that never miss a contact count (center rounding does miss some).
      if (!isOctreeChecker(r.checker) || r.false_negatives > 0 || r.fp_rate > targets.max_fp_rate) {
        continue;
      }
      if (!best || score(r) > score(*best)) best = &r;
    }
    if (!best) {
      const CheckRow* lowest = nullptr;
      for (const CheckRow& r : result.checks) {
        if (r.checker != CheckerKind::kOctreeFused || r.false_negatives > 0) continue;
        if (!lowest || r.fp_rate < lowest->fp_rate) lowest = &r;
      }
      out << "- no octree setting without false negatives reaches a false-positive rate <= "
          << percent(targets.max_fp_rate)
          << " %: the targets are **missed** at every resolution measured";
      if (lowest) {
        out << "; the lowest is "
            << settingName(lowest->checker, lowest->resolution, lowest->rounding) << " with FP "
            << percent(lowest->fp_rate) << " % (environment only: " << percent(lowest->env_fp_rate)
            << " %), mean " << fmt(lowest->mean_us)
            << " us, FCL / octree = " << fmt(lowest->speedup_vs_fcl)
            << ", FCL+OctoMap / octree (environment only) = "
            << cell(lowest->env_speedup_vs_fcl_octomap);
      }
      out << ".\n";
    } else {
      out << "- full check, " << settingName(best->checker, best->resolution, best->rounding)
          << " (FP " << percent(best->fp_rate) << " %): mean " << fmt(best->mean_us)
          << " us, FCL / octree = " << fmt(best->speedup_vs_fcl)
          << " — target >= " << fmt(targets.full_speedup) << ": "
          << verdict(best->speedup_vs_fcl, targets.full_speedup) << "\n";
      if (best->env_speedup_vs_fcl_octomap > 0) {
        out << "- environment only, same setting: " << fmt(best->env_mean_us)
            << " us, FCL+OctoMap / octree = " << fmt(best->env_speedup_vs_fcl_octomap)
            << " — target >= " << fmt(targets.env_speedup_vs_fcl_octomap) << ": "
            << verdict(best->env_speedup_vs_fcl_octomap, targets.env_speedup_vs_fcl_octomap)
            << "\n";
      }
    }
    if (fcl.states < targets.states) {
      out << "- (fewer than the " << targets.states << " states the target asks for)\n";
    }
  } else {
    for (const CheckRow& r : result.checks) {
      if (r.checker != CheckerKind::kOctreeFused || r.rounding != "conservative") continue;
      const CheckRow* octomap = findRow(result, CheckerKind::kFclOctomap, r.resolution, "");
      out << "- " << settingName(r.checker, r.resolution, r.rounding) << ": mean " << fmt(r.mean_us)
          << " us, FCL / octree = " << fmt(r.speedup_vs_fcl)
          << " (target >= " << fmt(targets.rigid_full_speedup) << ": "
          << verdict(r.speedup_vs_fcl, targets.rigid_full_speedup) << ")";
      if (octomap) {
        const double ratio = octomap->mean_us / r.mean_us;
        out << ", FCL+OctoMap / octree = " << fmt(ratio)
            << " (target >= " << fmt(targets.rigid_speedup_vs_fcl_octomap) << ": "
            << verdict(ratio, targets.rigid_speedup_vs_fcl_octomap) << ")";
      }
      out << "\n";
    }
  }
  const PlanRow* fcl_plan = findPlan(result, "RRTConnect", CheckerKind::kFcl);
  if (fcl_plan) {
    for (const PlanRow& r : result.planning) {
      if (r.planner != "RRTConnect" || r.checker != CheckerKind::kOctreeFused ||
          r.rounding != "conservative") {
        continue;
      }
      const double ratio = r.median_time > 0 ? fcl_plan->median_time / r.median_time : 0;
      const double solve_ratio =
          r.median_solve_time > 0 ? fcl_plan->median_solve_time / r.median_solve_time : 0;
      out << "- RRTConnect, " << settingName(r.checker, r.resolution, r.rounding) << ": solved "
          << r.solved << "/" << r.runs << " vs FCL " << fcl_plan->solved << "/" << fcl_plan->runs
          << (r.solved >= fcl_plan->solved ? " (met)" : " (**missed**)")
          << "; median time FCL / octree = " << fmt(ratio)
          << " — target >= " << fmt(targets.planning_speedup) << ": "
          << verdict(ratio, targets.planning_speedup)
          << "; the planners' own solve times, FCL / octree = " << fmt(solve_ratio) << " — "
          << verdict(solve_ratio, targets.planning_speedup) << "\n";
    }
  }
  out << "\n";
}

namespace {

// gnuplot data: one block per curve (blocks two blank lines apart, each headed by the curve's
// quoted name and `columns`), curves in order of first appearance; `name(row)` picks a row's
// curve and `point(row)` writes its lines.
template <class Row, class Name, class Point>
void writeCurves(const std::vector<Row>& rows, const char* columns, Name name, Point point,
                 std::ostream& out) {
  std::vector<std::string> curves;
  for (const Row& r : rows) {
    const std::string n = name(r);
    if (std::find(curves.begin(), curves.end(), n) == curves.end()) curves.push_back(n);
  }
  out << std::setprecision(6);
  bool first = true;
  for (const std::string& curve : curves) {
    if (!first) out << "\n\n";
    first = false;
    out << '"' << curve << "\" " << columns << '\n';
    for (const Row& r : rows) {
      if (name(r) == curve) point(r);
    }
  }
  out << '\n';
}

std::string withRounding(const std::string& name, const std::string& rounding) {
  return rounding.empty() ? name : name + " " + rounding;
}

}  // namespace

void writeTradeoffPlotData(const TradeStudyResult& result, std::ostream& out) {
  // Curves: each checker x rounding across resolutions; FCL is one point at 0 %.
  writeCurves(
      result.checks, "fp_percent mean_us resolution_cm",
      [](const CheckRow& r) { return withRounding(checkerKindName(r.checker), r.rounding); },
      [&](const CheckRow& r) {
        out << 100 * r.fp_rate << ' ' << r.mean_us << ' ' << 100 * r.resolution << '\n';
      },
      out);
}

void writePlanningPlotData(const TradeStudyResult& result, std::ostream& out) {
  double lo = INFINITY, hi = 0;
  for (const PlanRow& r : result.planning) {
    if (r.resolution > 0) {
      lo = std::min(lo, r.resolution);
      hi = std::max(hi, r.resolution);
    }
  }
  writeCurves(
      result.planning, "resolution_cm median_time_s solved",
      [](const PlanRow& r) {
        return withRounding(r.planner + " " + checkerKindName(r.checker), r.rounding);
      },
      [&](const PlanRow& r) {
        if (r.resolution > 0) {
          out << 100 * r.resolution << ' ' << r.median_time << ' ' << r.solved << '\n';
        } else if (hi > 0) {  // the exact checker: a flat line across the range
          out << 100 * lo << ' ' << r.median_time << ' ' << r.solved << '\n'
              << 100 * hi << ' ' << r.median_time << ' ' << r.solved << '\n';
        }
      },
      out);
}

}  // namespace octomotion
