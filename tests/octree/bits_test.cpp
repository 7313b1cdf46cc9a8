// bits.h: every helper against a plain loop over the bits, for every child mask and for 64-bit
// masks with one and several bits set.
#include "octomotion/octree/bits.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace octomotion {
namespace {

TEST(Bits, ChildMaskHelpersMatchLoops) {
  for (unsigned mask = 0; mask < 256; ++mask) {
    int count = 0;
    for (int k = 0; k < 8; ++k) {
      EXPECT_EQ(childRank(mask, k), count) << mask << " " << k;
      if (mask & (1u << k)) ++count;
    }
    EXPECT_EQ(popcount8(mask), count) << mask;
    if (mask == 0) continue;
    int lowest = 0;
    while (!(mask & (1u << lowest))) ++lowest;
    EXPECT_EQ(lowestBit(mask), lowest) << mask;
  }
}

TEST(Bits, SixtyFourBitHelpersMatchLoops) {
  for (int i = 0; i < 64; ++i) {
    const std::uint64_t one = std::uint64_t{1} << i;
    EXPECT_EQ(lowestBit64(one), i);
    EXPECT_EQ(highestBit64(one), i);
    for (int j = i; j < 64; ++j) {
      const std::uint64_t two = one | (std::uint64_t{1} << j);
      EXPECT_EQ(lowestBit64(two), i) << i << " " << j;
      EXPECT_EQ(highestBit64(two), j) << i << " " << j;
    }
  }
  EXPECT_EQ(lowestBit64(~std::uint64_t{0}), 0);
  EXPECT_EQ(highestBit64(~std::uint64_t{0}), 63);
}

}  // namespace
}  // namespace octomotion
