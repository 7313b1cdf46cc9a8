// The speed/accuracy trade study (docs/trade-off.md) over every scene in robots/scenes/*.yaml: each
// octree setting (resolution x rounding x checker path), FCL and FCL+OctoMap on the same uniform
// states, and planning with ompl::tools::Benchmark. A plain program rather than a Google
// Benchmark one: every measurement is a distribution over a state set (medians, p90, means and
// error rates per setting), which the library computes itself. Run from the repository root:
//   build/bench/tradeoff_bench --out-dir docs/trade-off
//   scripts/plot_tradeoff.sh docs/trade-off          (SCENE_tradeoff.png, SCENE_planning.png)
//   scripts/tradeoff_summary.py docs/trade-off       (per-scene markdown tables)
// Writes checks.csv, planning.csv, results.md (tables + targets), SCENE_tradeoff.dat and
// SCENE_planning.dat (gnuplot data) and logs/*.log (ompl_benchmark_statistics.py reads them).
// The output folders (docs/trade-off/, the default tradeoff-results/) are not kept in git:
// these commands regenerate them; docs/trade-off.md lists the study's commands.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/tools/study_options.h"
#include "octomotion/tools/trade_study.h"

namespace {

using namespace octomotion;

const char* kUsage = R"(usage: tradeoff_bench [options]
The trade study of `octomotion bench` over every scene in a directory, with these defaults:
--out-dir tradeoff-results --move-tree-states 2000 --planners RRTConnect:5,RRTstar:1
options:
  --scenes DIR             scene directory (default robots/scenes); every *.yaml in it
  --only NAME[,NAME]       only these scene files (stems, e.g. bookshelf)
)";

int run(int argc, char** argv) {
  std::string scenes_dir = "robots/scenes";
  std::vector<std::string> only;
  tools::StudyCommandOptions parsed;
  parsed.out_dir = "tradeoff-results";
  parsed.study.move_tree_states = 2000;
  parsed.study.planners = {{"RRTConnect", 5.0}, {"RRTstar", 1.0}};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InvalidArgument(arg + ": missing value");
      return argv[++i];
    };
    if (arg == "--scenes") {
      scenes_dir = value();
    } else if (arg == "--only") {
      only = tools::parseList(arg, value());
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      tools::studyOptions().writeHelp(std::cout);
      return 0;
    } else if (!tools::studyOptions().parse(arg, value, parsed)) {
      throw InvalidArgument("unknown option " + arg + " (tradeoff_bench --help)");
    }
  }
  tools::finishStudyOptions(parsed);
  TradeStudyOptions& base = parsed.study;
  const std::string& out_dir = parsed.out_dir;
  std::vector<std::string> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(scenes_dir)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string stem = entry.path().stem().string();
    if (!only.empty() && std::find(only.begin(), only.end(), stem) == only.end()) continue;
    scenes.push_back(entry.path().string());
  }
  std::sort(scenes.begin(), scenes.end());
  if (scenes.empty()) throw InvalidArgument("no scenes (*.yaml) in " + scenes_dir);
  std::filesystem::create_directories(out_dir + "/logs");
  base.log_dir = out_dir + "/logs";
  base.progress = [](const std::string& line) { std::cerr << line << std::endl; };

  std::ofstream checks(out_dir + "/checks.csv"), planning(out_dir + "/planning.csv"),
      markdown(out_dir + "/results.md");
  if (!checks || !planning || !markdown) throw FileError(out_dir, "cannot write the results");
  bool header = true;
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& scene : scenes) {
    TradeStudyOptions options = base;
    options.scene_path = scene;
    TradeStudyResult result;
    try {
      result = runTradeStudy(options);
    } catch (const Error& e) {
      std::cerr << "tradeoff_bench: " << scene << " skipped: " << e.what() << std::endl;
      continue;
    }
    writeCheckCsv(result.checks, checks, header);
    writePlanCsv(result.planning, planning, header);
    header = false;
    writeMarkdown(result, markdown);
    writeTargets(result, tools::kTradeOffTargets, markdown);
    checks.flush();
    planning.flush();
    markdown.flush();
    std::ofstream tradeoff(out_dir + "/" + result.scene + "_tradeoff.dat");
    writeTradeoffPlotData(result, tradeoff);
    if (!result.planning.empty()) {
      std::ofstream plan(out_dir + "/" + result.scene + "_planning.dat");
      writePlanningPlotData(result, plan);
    }
    std::cerr << "tradeoff_bench: " << result.scene << " done after "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s" << std::endl;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "tradeoff_bench: error: " << e.what() << "\n";
    return 1;
  }
}
