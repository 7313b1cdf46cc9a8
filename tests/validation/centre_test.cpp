// Centre rounding (Rounding::kCenter, Weng & Ahuja 1987 §3) against exact FCL, fused checker
// path, every scene, 10,000 uniform states each (docs/validation.md §3). Centre rounding keeps
// volumes but may miss thin contacts, so it is measured, not guaranteed:
//  - false positive (octree rejects, FCL free): only within w_fp = (sqrt(3)/2) r_l of contact,
//    asserted per state; so the rate is at most the share of free states within w_fp;
//  - false negative (FCL contact, octree free): only when the overlap holds no ball of radius
//    w_fn = (sqrt(3)/2) (r_e + r_l) (environment) or sqrt(3) r_l (self pairs), i.e. in a band
//    of that depth about contact; the rate is asserted below twice the share of free states
//    within w_fn of contact (the band's mirror image on the free side).
#include <cmath>
#include <iostream>

#include "validation_common.h"

namespace octomotion::validation {
namespace {

constexpr std::size_t kStates = 10000;
constexpr std::uint64_t kSeed = 0x5eed0002;

class Centre : public ::testing::TestWithParam<std::string> {};

struct Rates {
  std::size_t contacts = 0;        // FCL finds contact
  std::size_t missed = 0;          // ... and the octree does not
  std::size_t extra = 0;           // the octree finds contact, FCL does not
  std::size_t extra_too_far = 0;   // ... farther than w_fp from contact
  std::size_t free_within_fp = 0;  // FCL free within w_fp of contact
  std::size_t free_within_fn = 0;  // FCL free within w_fn of contact
  double worst_extra = 0;          // largest FCL distance of a false positive
};

void count(Rates& r, bool fcl_hit, bool octree_hit, double distance, double w_fp, double w_fn) {
  r.contacts += fcl_hit;
  if (fcl_hit && !octree_hit) ++r.missed;
  if (fcl_hit) return;
  r.free_within_fp += distance <= w_fp;
  r.free_within_fn += distance <= w_fn;
  if (octree_hit) {
    ++r.extra;
    r.worst_extra = std::max(r.worst_extra, distance);
    r.extra_too_far += distance > w_fp;
  }
}

void expectWithinBounds(const Rates& r, const char* what, const std::string& scene) {
  SCOPED_TRACE(std::string(what) + " of " + scene);
  EXPECT_EQ(r.extra_too_far, 0u) << "false positives beyond w_fp (worst " << r.worst_extra << ")";
  EXPECT_LE(r.extra, r.free_within_fp);
  // Small counts: allow a few beyond twice the band (a band of 0-2 states says little).
  EXPECT_LE(r.missed, 2 * r.free_within_fn + 5) << "false negatives beyond the contact band";
}

TEST_P(Centre, FalseRatesStayWithinTheContactBand) {
  const PlanningScene scene = loadValidationScene(GetParam(), Rounding::kCenter);
  const OctreeCollisionModel& octree = *scene.model;
  const std::shared_ptr<const FclCollisionModel> reference = exactReference(scene);
  const FclCollisionModel& fcl = *reference;
  const Resolutions res = resolutionsOf(octree);
  const double w_fp = std::sqrt(3.0) / 2 * res.link + kTieSlack;
  const double w_fn_env = std::sqrt(3.0) / 2 * (res.environment + res.link);
  const double w_fn_self = std::sqrt(3.0) * res.link;

  const OctreeBackend checked(scene.model, CheckerPath::kFused);
  const std::unique_ptr<BackendScratch> scratch = checked.makeBackendScratch();
  const std::unique_ptr<BackendScratch> exact = fcl.makeBackendScratch();
  FclCollisionModel::Scratch& fcl_scratch = fcl.scratchOf(*exact);
  Rates env, self;
  for (const Sample& s : uniformSamples(scene, kStates, kSeed)) {
    const auto [fe, fs, oe, os] = answersAt(s, fcl, *exact, checked, *scratch);
    count(env, fe, oe, fe ? 0.0 : fcl.environmentDistance(fcl_scratch, w_fn_env * 1.001), w_fp,
          w_fn_env);
    count(self, fs, os, fs ? 0.0 : fcl.selfDistance(fcl_scratch, w_fn_self * 1.001), w_fp,
          w_fn_self);
  }
  auto rate = [](std::size_t n) { return 100.0 * static_cast<double>(n) / kStates; };
  std::cout << "[ rates    ] " << sceneLabel(GetParam()) << " centre r_e " << res.environment
            << " r_l " << res.link << ": env contacts " << env.contacts << ", missed " << env.missed
            << " (" << rate(env.missed) << "%, bound 2 x " << env.free_within_fn << "), extra "
            << env.extra << " (" << rate(env.extra) << "%, bound " << env.free_within_fp
            << ", worst " << env.worst_extra << " <= " << w_fp << "); self contacts "
            << self.contacts << ", missed " << self.missed << " (" << rate(self.missed)
            << "%, bound 2 x " << self.free_within_fn << "), extra " << self.extra << " ("
            << rate(self.extra) << "%, bound " << self.free_within_fp << ", worst "
            << self.worst_extra << ")\n";
  expectWithinBounds(env, "environment", sceneLabel(GetParam()));
  expectWithinBounds(self, "self pairs", sceneLabel(GetParam()));
  EXPECT_GT(env.contacts, 0u) << "no sampled state touches the environment";
}

INSTANTIATE_TEST_SUITE_P(Scenes, Centre, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
