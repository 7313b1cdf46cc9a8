// The guarantees of conservative rounding, against exact FCL (docs/validation.md §1-2), on every
// scene in robots/scenes, for both checker paths, arms and rigid bodies, 10,000 uniform random
// states each (fixed seed):
//  - no false negatives: every state FCL finds in collision (environment, or a checked self
//    pair) the octree checker finds in collision too, for the same reason;
//  - free space is eaten by a bounded margin only: a state the octree checker rejects but FCL
//    does not lies within delta_env = sqrt(3) (r_e + r_l) of the environment (FCL distance), or
//    within delta_self = 2 sqrt(3) r_s between the links of a checked pair (r_s: the self
//    pairs' link voxels, r_l unless self_link_resolution sets finer ones); with exact primitives
//    in a scene of primitives only, delta_env = sqrt(3) r_l, the link voxels' margin alone.
#pragma once

#include <cmath>
#include <iostream>
#include <sstream>

#include "validation_common.h"

namespace octomotion::validation {

inline constexpr std::size_t kStates = 10000;
inline constexpr std::uint64_t kSeed = 0x5eed0001;

// What one run found: FCL's contacts and the octree checker's extra (false-positive) answers.
struct ConservativeCounts {
  std::size_t fcl_env = 0, extra_env = 0, extra_self = 0;
};

// Checks states [begin, end) of the scene's kStates uniform states (kSeed) with one checker path.
inline ConservativeCounts checkConservative(const std::string& scene_file, CheckerKind checker,
                                            std::size_t begin, std::size_t end,
                                            std::optional<double> self_link_resolution = {},
                                            bool exact_primitives = false) {
  const PlanningScene scene = loadValidationScene(scene_file, Rounding::kConservative, checker,
                                                  self_link_resolution, exact_primitives);
  if (exact_primitives) {
    EXPECT_GT(scene.model->report().exact_primitives, 0u) << "exact primitives not applied";
  }
  // Exact primitives and nothing else: the environment's voxel drops out of the margin.
  const bool only_primitives =
      exact_primitives && scene.model->report().exact_primitives_other_objects == 0;
  const OctreeCollisionModel& octree = *scene.model;
  const std::shared_ptr<const FclCollisionModel> reference = exactReference(scene);
  const FclCollisionModel& fcl = *reference;
  const CheckerPath path = octreeCheckerPath(checker);
  const Resolutions r = resolutionsOf(octree);
  // docs/validation.md §2: a voxel of each tree lies between the two surfaces.
  const double delta_env =
      std::sqrt(3.0) * ((only_primitives ? 0.0 : r.environment) + r.link) + kTieSlack;
  const double delta_self = 2 * std::sqrt(3.0) * r.self_link + kTieSlack;

  const OctreeBackend checked(scene.model, path);
  const std::unique_ptr<BackendScratch> scratch = checked.makeBackendScratch();
  const std::unique_ptr<BackendScratch> exact = fcl.makeBackendScratch();
  std::size_t fcl_env = 0, fcl_self = 0, octree_env = 0, octree_self = 0;
  std::size_t missed_env = 0, missed_self = 0, extra_env = 0, extra_self = 0;
  std::size_t beyond_env = 0, beyond_self = 0;
  double worst_env = 0, worst_self = 0;  // largest FCL distance of a rejected free state
  std::string first_failure;
  const std::vector<Sample> samples = uniformSamples(scene, kStates, kSeed);
  for (std::size_t i = begin; i < end; ++i) {
    const Sample& s = samples[i];
    const auto [fe, fs, oe, os] = answersAt(s, fcl, *exact, checked, *scratch);
    fcl_env += fe;
    fcl_self += fs;
    octree_env += oe;
    octree_self += os;
    if (fe && !oe) {
      ++missed_env;
      if (first_failure.empty()) first_failure = "missed environment contact at " + describe(s);
    }
    if (fs && !os) {
      ++missed_self;
      if (first_failure.empty()) first_failure = "missed self contact at " + describe(s);
    }
    if (oe && !fe) {
      ++extra_env;
      const double d = fcl.environmentDistance(fcl.scratchOf(*exact), 2 * delta_env);
      worst_env = std::max(worst_env, d);
      if (d > delta_env) {
        ++beyond_env;
        if (first_failure.empty()) {
          first_failure =
              "environment rejected at FCL distance " + std::to_string(d) + " at " + describe(s);
        }
      }
    }
    if (os && !fs) {
      ++extra_self;
      const double d = fcl.selfDistance(fcl.scratchOf(*exact), 2 * delta_self);
      worst_self = std::max(worst_self, d);
      if (d > delta_self) {
        ++beyond_self;
        if (first_failure.empty()) {
          first_failure =
              "self pair rejected at FCL distance " + std::to_string(d) + " at " + describe(s);
        }
      }
    }
  }
  std::cout << "[ rates    ] " << sceneLabel(scene_file) << " " << checkerKindName(checker)
            << (exact_primitives ? " exact-primitives" : "") << " states " << begin << ".." << end
            << " r_e " << r.environment << " r_l " << r.link << " r_s " << r.self_link
            << ": FCL env " << fcl_env << " self " << fcl_self << ", octree env " << octree_env
            << " self " << octree_self << " of " << (end - begin) << "; false positives env "
            << extra_env << " (worst FCL distance " << worst_env << " <= delta " << delta_env
            << ") self " << extra_self << " (worst " << worst_self << " <= delta " << delta_self
            << ")\n";
  EXPECT_EQ(missed_env, 0u) << first_failure;
  EXPECT_EQ(missed_self, 0u) << first_failure;
  EXPECT_EQ(beyond_env, 0u) << first_failure;
  EXPECT_EQ(beyond_self, 0u) << first_failure;
  // Not vacuous: the scene must put the robot against its environment some of the time.
  EXPECT_GT(fcl_env, 0u) << "no sampled state touches the environment";
  return {fcl_env, extra_env, extra_self};
}

// The kStates states of the checker path split into `shards` executables (CI time budget: the
// moveTree path materialises a tree per link and pair), shard `shard` of them here. (A scene
// planned through the moveTree path keeps its link trees at the environment's voxel,
// loadPlanningScene; the fused path's test checks the default link trees, 1/4 of it.)
inline void checkConservativeShard(const std::string& scene_file, CheckerKind checker,
                                   std::size_t shard, std::size_t shards) {
  checkConservative(scene_file, checker, kStates * shard / shards, kStates * (shard + 1) / shards);
}

}  // namespace octomotion::validation
