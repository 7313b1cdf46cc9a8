// Conservative rounding against exact FCL, fused checker path, every scene, 10,000 uniform states
// each: no missed contact, and free space eaten by the margin of docs/validation.md §2 only.
#include "conservative_common.h"

namespace octomotion::validation {
namespace {

class ConservativeFused : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeFused, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservative(GetParam(), "octree-fused", 0, kStates);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeFused, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

// The arms again with self-collision trees at a quarter of the 2 cm link voxels
// (self_link_resolution): the same guarantees, delta_self from the finer voxels.
class ConservativeFusedFinerSelfTrees : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeFusedFinerSelfTrees, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservative(GetParam(), "octree-fused", 0, kStates, 0.005);
}

INSTANTIATE_TEST_SUITE_P(
    Arms, ConservativeFusedFinerSelfTrees,
    ::testing::Values(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml",
                      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cage.yaml",
                      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cluttered_table.yaml"),
    [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
