// The trade study's command-line options, shared by `octomotion bench` and
// bench/tradeoff_bench: one table, one parser, one help text.
#pragma once

#include <string>

#include "octomotion/tools/option_table.h"
#include "octomotion/tools/trade_study.h"

namespace octomotion::tools {

struct StudyCommandOptions {
  TradeStudyOptions study;
  std::string out_dir = ".";  // where the CSV, markdown, plot data and logs go
};

// The study flags (--states, --resolutions, --paths, ...) followed by the scene options
// (sceneOptions(), into study.overrides).
const OptionTable<StudyCommandOptions>& studyOptions();

// After parsing: refuses the scene options that the study's own flags replace (--resolution,
// --rounding, --checker, --planner, --link-resolution, --self-link-resolution) and seeds the
// study with --seed.
void finishStudyOptions(StudyCommandOptions& options);

// The study's targets (docs/trade-off.md, "Targets"), which both bench programs report.
inline constexpr StudyTargets kTradeOffTargets = {
    /*max_fp_rate=*/0.02,
    /*full_speedup=*/5.0,
    /*env_speedup_vs_fcl_octomap=*/10.0,
    /*rigid_full_speedup=*/3.0,
    /*rigid_speedup_vs_fcl_octomap=*/10.0,
    /*planning_speedup=*/3.0,
    /*states=*/20000};

}  // namespace octomotion::tools
