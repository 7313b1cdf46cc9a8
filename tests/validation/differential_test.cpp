// The randomised differential validation (docs/validation.md §6, bench/validation_differential_
// bench for millions of states), bounded: a fixed seed, generated rigid bodies of 1 cm to 100 m
// in generated environments, the shipped arms and the real Panda (when ../shared/data holds it),
// every checker path. No missed contact with conservative rounding, and no rejected free state
// beyond its path's margin, with either rounding.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "differential.h"

namespace octomotion::validation {
namespace {

TEST(Differential, GeneratedScenesAgreeWithFclWithinTheMargins) {
  DifferentialOptions options;
  options.seed = 0x5eed0024;
  options.states = 16000;
  options.states_per_case = 400;
  options.source_dir = OCTOMOTION_SOURCE_DIR;
  const std::string panda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
  if (std::filesystem::exists(panda + "/panda.urdf")) options.panda_dir = panda;
  options.work_dir = (std::filesystem::temp_directory_path() /
                      ("octomotion_differential_test_" + std::to_string(::getpid())))
                         .string();
  const DifferentialReport report = runDifferential(options);
  std::cout << formatReport(report);
  EXPECT_GE(report.cases, 30u);
  EXPECT_TRUE(report.failures.empty()) << report.failures.front();
  // Not vacuous: contacts were there to miss, on both paths and both roundings.
  std::size_t contacts = 0;
  for (const auto& [name, tally] : report.paths) contacts += tally.fcl_env + tally.fcl_self;
  EXPECT_GT(contacts, report.states / 20);
  EXPECT_TRUE(report.paths.count("conservative fused") &&
              report.paths.count("conservative moveTree") && report.paths.count("center fused"));
  std::filesystem::remove_all(options.work_dir);
}

}  // namespace
}  // namespace octomotion::validation
