// The speed/accuracy trade study (docs/trade-off.md) on one scene, small enough to finish in
// well under a minute: the octo7 arm of bookshelf.yaml checked on the same uniform states by
// the octree at three resolutions (both roundings, both checker paths), FCL+OctoMap and FCL, and
// a few RRTConnect runs with ompl::tools::Benchmark. Prints the tables, writes the CSV, the
// Benchmark logs and the plot (gnuplot, when installed) to the directory given (default: a
// temporary one), and checks its own results: conservative settings never miss a contact FCL
// finds, both checker paths agree, and a finer resolution has fewer false positives.
// Run from the repository root: build/demos/speed_accuracy [OUT_DIR]
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <ompl/util/Console.h>

#include "octomotion/tools/study_options.h"
#include "octomotion/tools/trade_study.h"

namespace {

using namespace octomotion;

int failures = 0;
void expect(bool ok, const std::string& what) {
  if (!ok) {
    std::cerr << "speed_accuracy: FAILED: " << what << "\n";
    ++failures;
  }
}

}  // namespace

int main(int argc, char** argv) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  try {
    const std::filesystem::path out_dir =
        argc > 1 ? std::filesystem::path(argv[1])
                 : std::filesystem::temp_directory_path() / "octomotion_speed_accuracy";
    std::filesystem::create_directories(out_dir / "logs");

    TradeStudyOptions options;
    options.scene_path = "robots/scenes/bookshelf.yaml";
    options.states = 3000;
    options.resolutions = {0.04, 0.02, 0.01};
    options.planners = {{"RRTConnect", 2.0}};
    options.runs = 3;
    options.log_dir = (out_dir / "logs").string();
    options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    const TradeStudyResult result = runTradeStudy(options);

    writeMarkdown(result, std::cout);
    writeTargets(result, tools::kTradeOffTargets, std::cout);
    {
      std::ofstream csv(out_dir / "checks.csv"), plan(out_dir / "planning.csv"),
          dat(out_dir / (result.scene + "_tradeoff.dat"));
      writeCheckCsv(result.checks, csv);
      writePlanCsv(result.planning, plan);
      writeTradeoffPlotData(result, dat);
    }

    // Its own checks.
    const CheckRow& fcl = result.checks.front();
    expect(fcl.checker == CheckerKind::kFcl, "FCL is the reference");
    expect(fcl.colliding_states > 0 && fcl.free_states > 0, "both free and colliding states");
    double coarsest_fp = -1, finest_fp = -1;
    for (const CheckRow& r : result.checks) {
      if (r.rounding == "conservative" || r.checker == CheckerKind::kFclOctomap) {
        expect(r.false_negatives == 0, settingName(r.checker, r.resolution, r.rounding) + " at " +
                                           std::to_string(r.resolution) +
                                           " m missed a contact (conservative FN must be 0)");
      }
      if (r.checker == CheckerKind::kOctreeFused && r.rounding == "conservative") {
        if (r.resolution == 0.04) coarsest_fp = r.fp_rate;
        if (r.resolution == 0.01) finest_fp = r.fp_rate;
      }
      for (const CheckRow& b : result.checks) {
        if (r.checker == CheckerKind::kOctree && b.checker == CheckerKind::kOctreeFused &&
            r.resolution == b.resolution && r.rounding == b.rounding) {
          expect(r.false_positives == b.false_positives && r.false_negatives == b.false_negatives,
                 "the checker paths disagree at " + std::to_string(r.resolution) + " m");
        }
      }
    }
    expect(coarsest_fp >= 0 && finest_fp >= 0 && finest_fp <= coarsest_fp,
           "false positives shrink from 4 cm to 1 cm");
    expect(!result.planning.empty(), "planning ran");
    for (const PlanRow& p : result.planning) {
      expect(std::filesystem::exists(p.log_file), "Benchmark log " + p.log_file);
    }

    // The plot, when gnuplot is installed.
    const std::string gp = "scripts/plot_tradeoff.gp";
    if (std::filesystem::exists(gp) && std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
      const std::filesystem::path png = out_dir / (result.scene + "_tradeoff.png");
      const std::string command =
          "gnuplot -e \"dat='" + (out_dir / (result.scene + "_tradeoff.dat")).string() +
          "'; png='" + png.string() + "'; kind='tradeoff'; name='" + result.scene + "'\" " + gp;
      expect(std::system(command.c_str()) == 0 && std::filesystem::exists(png), "gnuplot plot");
      std::cerr << "speed_accuracy: plot " << png.string() << "\n";
    } else {
      std::cerr << "speed_accuracy: gnuplot not found; plot data in " << out_dir.string() << "\n";
    }
    std::cerr << "speed_accuracy: results in " << out_dir.string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "speed_accuracy: error: " << e.what() << "\n";
    return 1;
  }
  if (failures) std::cerr << "speed_accuracy: " << failures << " check(s) failed\n";
  return failures ? 1 : 0;
}
