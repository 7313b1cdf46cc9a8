// `octomotion bench SCENE`: the speed/accuracy trade study of one scene (docs/trade-off.md).
// Writes SCENE_checks.csv, SCENE_planning.csv, SCENE.md, the gnuplot data SCENE_tradeoff.dat and
// SCENE_planning.dat, and the ompl::tools::Benchmark logs (logs/*.log) to --out-dir; the
// markdown tables also go to stdout.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/tools/study_options.h"
#include "octomotion/tools/trade_study.h"

namespace octomotion::cli {

namespace {

const char* kBenchUsage = R"(usage: octomotion bench SCENE [options]
The speed/accuracy trade study: every octree setting and FCL (+ FCL+OctoMap) on the same
uniformly sampled states, and planning with ompl::tools::Benchmark.
options:
)";

void writeFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ofstream out(path);
  if (!out) throw FileError(path, "cannot write");
  write(out);
  out.close();  // a full disk shows when the buffer is flushed
  if (!out) throw FileError(path, "write error (disk full?)");
}

}  // namespace

int benchCommand(const std::vector<std::string>& args) {
  tools::StudyCommandOptions parsed;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (arg == "-h" || arg == "--help") {
      std::cout << kBenchUsage;
      tools::studyOptions().writeHelp(std::cout);
      return 0;
    } else if (tools::studyOptions().parse(arg, value, parsed)) {
      continue;
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("bench: unknown option " + arg + " (octomotion bench --help)");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 1) throw InvalidArgument("bench: expected one scene (see --help)");
  tools::finishStudyOptions(parsed);
  TradeStudyOptions& options = parsed.study;
  const std::string& out_dir = parsed.out_dir;
  options.scene_path = positional.front();
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
    writeTargets(result, tools::kTradeOffTargets, o);
  });
  writeMarkdown(result, std::cout);
  writeTargets(result, tools::kTradeOffTargets, std::cout);
  std::cerr << "octomotion: results in " << out_dir << " (plot: scripts/plot_tradeoff.sh "
            << out_dir << ")\n";
  return 0;
}

}  // namespace octomotion::cli
