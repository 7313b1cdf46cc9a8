// Conservative rounding against exact FCL, fused checker path, every scene, 10,000 uniform states
// each: no missed contact, and free space eaten by the margin of docs/validation.md §2 only —
// with the voxel answers and with exact primitives.
#include "conservative_common.h"

namespace octomotion::validation {
namespace {

class ConservativeFused : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeFused, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservative(GetParam(), CheckerKind::kOctreeFused, 0, kStates);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeFused, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

// The arms again with self-collision trees at a quarter of the 2 cm link voxels
// (self_link_resolution): the same guarantees, delta_self from the finer voxels.
class ConservativeFusedFinerSelfTrees : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeFusedFinerSelfTrees, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservative(GetParam(), CheckerKind::kOctreeFused, 0, kStates, 0.005);
}

INSTANTIATE_TEST_SUITE_P(
    Arms, ConservativeFusedFinerSelfTrees,
    ::testing::Values(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml",
                      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cage.yaml",
                      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cluttered_table.yaml"),
    [](const auto& param_info) { return testName(param_info.param); });

// Exact primitives (every scene with boxes, balls or cylinders, and a table with two meshes among
// them): the same guarantees, with delta_env = sqrt(3) r_l — the link voxels' margin alone —
// where every obstacle is a primitive, and, on the same states, no more environment false
// positives than the voxel answers (fewer where those have 20 or more).
class ConservativeFusedExactPrimitives : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeFusedExactPrimitives, NeverMissesAndEatsFreeSpaceByTheLinkMarginOnly) {
  const ConservativeCounts voxels =
      checkConservative(GetParam(), CheckerKind::kOctreeFused, 0, kStates);
  const ConservativeCounts exact =
      checkConservative(GetParam(), CheckerKind::kOctreeFused, 0, kStates, {}, true);
  EXPECT_EQ(exact.fcl_env, voxels.fcl_env);
  EXPECT_LE(exact.extra_env, voxels.extra_env);
  // Where the voxels' margin rejects more than a handful of free states, it must show.
  if (voxels.extra_env >= 20) {
    EXPECT_LT(exact.extra_env, voxels.extra_env);
  }
  EXPECT_EQ(exact.extra_self, voxels.extra_self);  // the self half is untouched
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeFusedExactPrimitives,
                         ::testing::ValuesIn(primitiveSceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
