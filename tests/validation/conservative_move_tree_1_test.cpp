// Conservative rounding against exact FCL, moveTree checker path ("octree"), every scene: states
// 3333..6666 of the 10,000 uniform states of conservative_fused_test (the three
// conservative_move_tree_*_test executables cover all of them; one would exceed the CI time
// budget).
#include "conservative_common.h"

namespace octomotion::validation {
namespace {

class ConservativeMoveTree1 : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeMoveTree1, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservativeShard(GetParam(), CheckerKind::kOctree, 1, 3);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeMoveTree1, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
