// Randomised differential validation against exact FCL (docs/validation.md §6): generated robots
// and environments, random resolutions, roundings and checker paths, a million states by default.
// Prints, per checker path, the missed contacts (none allowed with conservative rounding) and
// the rejected free states' FCL distances as a fraction of the path's margin; exits 1 on any
// missed conservative contact or any rejection beyond the margin.
//
//   validation_differential_bench [--states N] [--per-case N] [--seed S] [--panda DIR]
//                                 [--work-dir DIR] [--verbose]
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "differential.h"

int main(int argc, char** argv) {
  using namespace octomotion::validation;
  DifferentialOptions options;
  options.source_dir = OCTOMOTION_SOURCE_DIR;
  options.work_dir = (std::filesystem::temp_directory_path() / "octomotion_differential").string();
  const std::string shared_panda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
  if (std::filesystem::exists(shared_panda + "/panda.urdf")) options.panda_dir = shared_panda;
  bool verbose = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << arg << ": missing value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (arg == "--states") {
        options.states = std::stoull(value());
      } else if (arg == "--per-case") {
        options.states_per_case = std::stoull(value());
      } else if (arg == "--seed") {
        options.seed = std::stoull(value());
      } else if (arg == "--panda") {
        options.panda_dir = value();
      } else if (arg == "--work-dir") {
        options.work_dir = value();
      } else if (arg == "--verbose") {
        verbose = true;
      } else {
        std::cerr << "unknown option " << arg
                  << " (--states N, --per-case N, --seed S, --panda DIR, --work-dir DIR, "
                     "--verbose)\n";
        return 2;
      }
    } catch (const std::exception&) {
      std::cerr << arg << ": expected a whole number\n";
      return 2;
    }
  }
  if (verbose) options.log = &std::cerr;
  std::cout << "differential validation: seed " << options.seed << ", " << options.states
            << " states, " << options.states_per_case << " per case, Panda "
            << (options.panda_dir.empty() ? "not found" : options.panda_dir) << ", files in "
            << options.work_dir << "\n";
  const auto start = std::chrono::steady_clock::now();
  const DifferentialReport report = runDifferential(options);
  std::cout << formatReport(report) << "took "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
  return report.failures.empty() ? 0 : 1;
}
