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
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/planner/trade_study.h"

namespace {

using namespace octomotion;

const char* kUsage = R"(usage: tradeoff_bench [options]
  --scenes DIR            scene directory (default robots/scenes); every *.yaml in it
  --only NAME[,NAME]      only these scene files (stems, e.g. bookshelf)
  --out-dir DIR           output directory (default tradeoff-results)
  --states N              uniform states per scene (default 20000)
  --move-tree-states N    states for the slow moveTree path (default 2000)
  --runs N                planning runs per planner and setting (default 20)
  --planners NAME[:S],..  default RRTConnect:5,RRTstar:1
  --no-fcl-octomap        leave out FCL+OctoMap
  --link-ratio R          octree link trees at R x each resolution (default 0.25, the library's)
  --self-link-ratio R     self-collision link trees at R x each resolution (default: --link-ratio
                          if given, else 1, the library's defaults)
  --self-pair-tables on|off  joint-space tables for self pairs (default: the scene's setting)
  --exact-primitives on|off  the links tested against primitives' exact shapes (default: the
                           scene's setting)
)";

double number(const std::string& flag, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x) || x < 0) {
    throw InvalidArgument(flag + ": expected a number >= 0, got '" + v + "'");
  }
  return x;
}

std::vector<std::string> split(const std::string& v) {
  std::vector<std::string> items;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

int run(int argc, char** argv) {
  std::string scenes_dir = "robots/scenes", out_dir = "tradeoff-results";
  std::vector<std::string> only;
  TradeStudyOptions base;
  base.move_tree_states = 2000;
  base.planners = {{"RRTConnect", 5.0}, {"RRTstar", 1.0}};
  auto onOff = [](const std::string& flag, const std::string& v) {
    if (v != "on" && v != "off") throw InvalidArgument(flag + ": expected on or off");
    return v == "on";
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InvalidArgument(arg + ": missing value");
      return argv[++i];
    };
    if (arg == "--scenes") {
      scenes_dir = value();
    } else if (arg == "--only") {
      only = split(value());
    } else if (arg == "--out-dir") {
      out_dir = value();
    } else if (arg == "--states") {
      base.states = static_cast<std::size_t>(number(arg, value()));
    } else if (arg == "--move-tree-states") {
      base.move_tree_states = static_cast<std::size_t>(number(arg, value()));
    } else if (arg == "--runs") {
      base.runs = static_cast<unsigned>(number(arg, value()));
    } else if (arg == "--planners") {
      base.planners.clear();
      for (const std::string& p : split(value())) {
        const auto colon = p.find(':');
        base.planners.push_back({p.substr(0, colon), colon == std::string::npos
                                                         ? 0.0
                                                         : number(arg, p.substr(colon + 1))});
      }
    } else if (arg == "--link-ratio") {
      const double r = number(arg, value());
      if (!(r > 0 && r <= 1)) throw InvalidArgument("--link-ratio: must be in (0, 1]");
      base.link_resolution_ratio = r;
    } else if (arg == "--self-link-ratio") {
      const double r = number(arg, value());
      if (!(r > 0 && r <= 1)) throw InvalidArgument("--self-link-ratio: must be in (0, 1]");
      base.self_link_resolution_ratio = r;
    } else if (arg == "--self-pair-tables") {
      base.overrides.self_pair_tables = onOff(arg, value());
    } else if (arg == "--exact-primitives") {
      base.overrides.exact_primitives = onOff(arg, value());
    } else if (arg == "--no-fcl-octomap") {
      base.fcl_octomap = false;
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    } else {
      throw InvalidArgument("unknown option " + arg + "\n" + kUsage);
    }
  }
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
    writeTargets(result, markdown);
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
