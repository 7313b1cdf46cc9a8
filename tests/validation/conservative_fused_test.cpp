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

}  // namespace
}  // namespace octomotion::validation
