// Experiment names for ompl::tools::Benchmark logs that survive Planner Arena's import.
#pragma once

#include <string>

namespace octomotion {

// "bookshelf_small_octree-fused_2cm_conservative": the scene, the checker, the resolution (left
// out when not positive) and the rounding (left out when empty), joined by `_`, each part with
// every character outside [A-Za-z0-9._-] replaced by `-`. OMPL's ompl_benchmark_statistics.py
// (which fills Planner Arena's database) keeps only the last whitespace-separated word of a
// log's "Experiment" line, so the name is a single word: nothing of it is lost there, and logs
// of different settings of one scene stay different experiments.
std::string experimentName(const std::string& scene, const std::string& checker, double resolution,
                           const std::string& rounding = "");

}  // namespace octomotion
