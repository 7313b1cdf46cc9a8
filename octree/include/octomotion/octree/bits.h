// Bit helpers for child masks and 64-bit masks: one name per operation, so every caller computes
// it the same way. Child masks are the 8-bit `black`/`gray` masks of octree nodes (bit k = child
// with label k).
#pragma once

#include <cstdint>

namespace octomotion {

// Number of set bits of a child mask (x < 256). The POPCNT instruction when the build has it
// (x86-64 with -mpopcnt, the default; see OCTOMOTION_POPCNT), else a few shifts and masks rather
// than a call into libgcc.
inline int popcount8(unsigned x) {
#if defined(__POPCNT__)
  return __builtin_popcount(x);
#else
  x = x - ((x >> 1) & 0x55u);
  x = (x & 0x33u) + ((x >> 2) & 0x33u);
  return static_cast<int>((x + (x >> 4)) & 0x0fu);
#endif
}

// Index of the lowest set bit of x; x != 0.
inline int lowestBit(unsigned x) {
  return __builtin_ctz(x);
}
inline int lowestBit64(std::uint64_t x) {
  return __builtin_ctzll(x);
}

// Index of the highest set bit of x; x != 0.
inline int highestBit64(std::uint64_t x) {
  return 63 - __builtin_clzll(x);
}

// The rank of child k among the children set in `mask`: the number of set bits below bit k
// (0 <= k < 8). Gray child k of a node is nodes[first_child + childRank(gray, k)].
inline int childRank(unsigned mask, int k) {
  return popcount8(mask & ((1u << k) - 1u));
}

}  // namespace octomotion
