// `octomotion bench SCENE`: the speed/accuracy trade study of one scene (docs/trade-off.md).
// Writes SCENE_checks.csv, SCENE_planning.csv, SCENE.md, the gnuplot data SCENE_tradeoff.dat and
// SCENE_planning.dat, and the ompl::tools::Benchmark logs (logs/*.log) to --out-dir; the
// markdown tables also go to stdout.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/planner/trade_study.h"

namespace octomotion::cli {

namespace {

const char* kBenchUsage = R"(usage: octomotion bench SCENE [bench options] [options]
The speed/accuracy trade study: every octree setting and FCL (+ FCL+OctoMap) on the same
uniformly sampled states, and planning with ompl::tools::Benchmark.
bench options:
  --states N               uniform states checked by every checker (default 20000)
  --move-tree-states N     the moveTree path checks only the first N of the states (it is
                           slow at fine resolutions; default: all)
  --runs N                 planning runs per planner and setting (default 20; 0: no planning)
  --resolutions A,B,...    voxel sizes in metres (default: 8 cm .. 5 mm for arms, body
                           diagonal / 4 .. / 64 for rigid bodies)
  --roundings LIST         conservative,center (default both)
  --paths LIST             octree,octree-fused (default both)
  --planners NAME[:S],...  OMPL planners, each with an optional time limit in seconds
                           (default RRTConnect,RRTstar with the scene's --time)
  --plan-every-setting     plan with every setting (default: the fused conservative octree at
                           every resolution, the others at the scene's resolution, FCL)
  --no-fcl-octomap         leave out FCL+OctoMap
  --link-ratio R           octree link trees at R x each resolution (default 0.25, the library's)
  --self-link-ratio R      self-collision trees at R x each resolution (default: --link-ratio if
                           given, else 1, the library's defaults)
  --out-dir DIR            where the CSV, markdown, plot data and logs go (default .)
  --seed N                 seeds the states and OMPL (default 1)
  --time S                 default planning time limit (default: the scene's)
  --package-path DIR       extra package:// search path (repeatable)
  --self-pair-tables on|off  joint-space tables for self pairs in every conservative setting
                           (default: the scene's octree.self_pair_tables)
  --exact-primitives on|off  the links tested against the primitives' exact shapes in every
                           conservative setting (default: the scene's octree.exact_primitives)
  --max-surface-voxels N   the memory guard (default: the scene's, else the library's)
)";

std::vector<std::string> splitList(const std::string& flag, const std::string& value) {
  std::vector<std::string> items;
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) throw InvalidArgument(flag + ": empty item in '" + value + "'");
    items.push_back(item);
  }
  if (items.empty()) throw InvalidArgument(flag + ": expected a list, got '" + value + "'");
  return items;
}

std::size_t parseCount(const std::string& flag, const std::string& value) {
  const double v = parseNumber(flag, value);
  if (v < 0 || v != std::floor(v) || v > 1e9) {
    throw InvalidArgument(flag + ": expected a whole number, got '" + value + "'");
  }
  return static_cast<std::size_t>(v);
}

void writeFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ofstream out(path);
  if (!out) throw FileError(path, "cannot write");
  write(out);
  out.close();  // a full disk shows when the buffer is flushed
  if (!out) throw FileError(path, "write error (disk full?)");
}

}  // namespace

int benchCommand(const std::vector<std::string>& args) {
  TradeStudyOptions options;
  std::string out_dir = ".";
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw InvalidArgument(arg + ": missing value");
      return args[++i];
    };
    if (arg == "--states") {
      options.states = parseCount(arg, value());
      if (options.states == 0) throw InvalidArgument("--states: must be > 0");
    } else if (arg == "--move-tree-states") {
      options.move_tree_states = parseCount(arg, value());
    } else if (arg == "--runs") {
      options.runs = static_cast<unsigned>(parseCount(arg, value()));
    } else if (arg == "--resolutions") {
      options.resolutions.clear();
      for (const std::string& r : splitList(arg, value())) {
        const double v = parseNumber(arg, r);
        if (!(v > 0)) throw InvalidArgument("--resolutions: " + r + " must be > 0");
        options.resolutions.push_back(v);
      }
    } else if (arg == "--link-ratio") {
      const double r = parseNumber(arg, value());
      if (!(r > 0 && r <= 1)) throw InvalidArgument("--link-ratio: must be in (0, 1]");
      options.link_resolution_ratio = r;
    } else if (arg == "--self-link-ratio") {
      const double r = parseNumber(arg, value());
      if (!(r > 0 && r <= 1)) throw InvalidArgument("--self-link-ratio: must be in (0, 1]");
      options.self_link_resolution_ratio = r;
    } else if (arg == "--roundings") {
      options.roundings.clear();
      for (const std::string& r : splitList(arg, value())) {
        options.roundings.push_back(roundingFromString(r.c_str()));
      }
    } else if (arg == "--paths") {
      options.paths.clear();
      for (const std::string& p : splitList(arg, value())) {
        options.paths.push_back(checkerPathFromName(p));
      }
    } else if (arg == "--planners") {
      options.planners.clear();
      for (const std::string& p : splitList(arg, value())) {
        StudyPlanner planner;
        const auto colon = p.find(':');
        planner.name = p.substr(0, colon);
        if (colon != std::string::npos) {
          planner.time = parseNumber(arg, p.substr(colon + 1));
          if (!(planner.time > 0)) throw InvalidArgument("--planners: " + p + ": time must be > 0");
          if (planner.time > kMaxPlanningSeconds) {
            throw InvalidArgument("--planners: " + p + ": " + planningTimeTooLong(planner.time));
          }
        }
        options.planners.push_back(planner);
      }
    } else if (arg == "--plan-every-setting") {
      options.plan_every_setting = true;
    } else if (arg == "--no-fcl-octomap") {
      options.fcl_octomap = false;
    } else if (arg == "--out-dir") {
      out_dir = value();
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kBenchUsage;
      return 0;
    } else if (parseSceneOption(arg, value, options.overrides)) {
      continue;
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("bench: unknown option " + arg + " (octomotion bench --help)");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 1) throw InvalidArgument("bench: expected one scene (see --help)");
  if (options.overrides.resolution || options.overrides.auto_resolution ||
      options.overrides.checker || options.overrides.rounding || options.overrides.planner ||
      options.overrides.link_resolution || options.overrides.self_link_resolution) {
    throw InvalidArgument(
        "bench: --resolution/--rounding/--checker/--planner/--link-resolution/"
        "--self-link-resolution do not apply; use --resolutions, --roundings, --paths, "
        "--planners, --link-ratio, --self-link-ratio");
  }
  options.scene_path = positional.front();
  if (options.overrides.seed) options.seed = *options.overrides.seed;
  std::filesystem::create_directories(out_dir);
  options.log_dir = out_dir + "/logs";
  if (options.runs > 0) std::filesystem::create_directories(options.log_dir);
  options.progress = [](const std::string& line) { std::cerr << "octomotion: " << line << "\n"; };

  const TradeStudyResult result = runTradeStudy(options);
  const std::string stem = out_dir + "/" + result.scene;
  writeFile(stem + "_checks.csv", [&](std::ostream& o) { writeCheckCsv(result.checks, o); });
  writeFile(stem + "_planning.csv", [&](std::ostream& o) { writePlanCsv(result.planning, o); });
  writeFile(stem + "_tradeoff.dat", [&](std::ostream& o) { writeTradeoffPlotData(result, o); });
  if (!result.planning.empty()) {
    writeFile(stem + "_planning.dat", [&](std::ostream& o) { writePlanningPlotData(result, o); });
  }
  writeFile(stem + ".md", [&](std::ostream& o) {
    writeMarkdown(result, o);
    writeTargets(result, o);
  });
  writeMarkdown(result, std::cout);
  writeTargets(result, std::cout);
  std::cerr << "octomotion: results in " << out_dir << " (plot: scripts/plot_tradeoff.sh "
            << out_dir << ")\n";
  return 0;
}

}  // namespace octomotion::cli
