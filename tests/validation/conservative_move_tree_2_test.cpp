// Conservative rounding against exact FCL, moveTree checker path ("octree"), every scene: states
// 6666..10000 of the 10,000 uniform states of conservative_fused_test (the three
// conservative_move_tree_*_test executables cover all of them; one would exceed the CI time
// budget).
#include "conservative_common.h"

namespace octomotion::validation {
namespace {

class ConservativeMoveTree2 : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeMoveTree2, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  checkConservativeShard(GetParam(), CheckerKind::kOctree, 2, 3);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeMoveTree2, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
