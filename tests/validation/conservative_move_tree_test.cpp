// Conservative rounding against exact FCL, moveTree checker path, every scene, on the 10,000
// uniform states of conservative_fused_test. The path is slow, so ctest runs this executable as
// state shards (tests/CMakeLists.txt): OCTOMOTION_STATE_SHARD=i/n checks the i-th of n equal
// slices of the states; without it, all of them.
#include <cstdlib>
#include <sstream>
#include <string>

#include "conservative_common.h"

namespace octomotion::validation {
namespace {

struct Shard {
  std::size_t index = 0, count = 1;
};

Shard shardFromEnvironment() {
  const char* text = std::getenv("OCTOMOTION_STATE_SHARD");
  if (text == nullptr) return {};
  Shard s;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> s.index >> slash >> s.count) || slash != '/' || s.count == 0 || s.index >= s.count) {
    ADD_FAILURE() << "OCTOMOTION_STATE_SHARD must be i/n with i < n, got '" << text << "'";
    return {};
  }
  return s;
}

class ConservativeMoveTree : public ::testing::TestWithParam<std::string> {};

TEST_P(ConservativeMoveTree, NeverMissesAndEatsFreeSpaceByTheMarginOnly) {
  const Shard shard = shardFromEnvironment();
  checkConservativeShard(GetParam(), CheckerKind::kOctree, shard.index, shard.count);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ConservativeMoveTree, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

}  // namespace
}  // namespace octomotion::validation
