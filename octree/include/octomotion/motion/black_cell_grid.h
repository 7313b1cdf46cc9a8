// A dense bit grid of an environment tree's black cells at one level: "is the cell holding this
// point black?" in a handful of instructions, where a walk down the tree costs one step per
// level. collides() uses it to try a few points of the moved source before any traversal: a
// point of a black source leaf inside a black environment cell is a shared voxel when the voxel
// holding it is black in the moved tree (always under conservative rounding; under centre
// rounding when that voxel's centre lies in a moved black leaf, which the query checks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "octomotion/octree/octree.h"

namespace octomotion {

class BlackCellGrid {
 public:
  // The grid of `tree`'s cells at the finest level whose grid has at most `max_cells` cells
  // (a bit each): 2^21 bits is 256 KiB, small enough to stay in a typical L2 cache.
  static constexpr std::size_t kDefaultMaxCells = std::size_t{1} << 21;
  explicit BlackCellGrid(const Octree& tree, std::size_t max_cells = kDefaultMaxCells);

  int level() const { return level_; }
  double sideVoxels() const { return side_; }  // of the tree's universe
  std::size_t bytes() const { return sizeof(*this) + bits_.size() * sizeof(std::uint64_t); }

  // True iff the point g (grid coordinates, in voxels of the tree's grid) lies in the universe
  // and the level-level() cell holding it is entirely black.
  bool black(const double g[3]) const {
    if (!(g[0] >= 0.0 && g[1] >= 0.0 && g[2] >= 0.0 && g[0] < side_ && g[1] < side_ &&
          g[2] < side_)) {
      return false;
    }
    const std::uint64_t x = static_cast<std::uint32_t>(g[0]) >> level_;
    const std::uint64_t y = static_cast<std::uint32_t>(g[1]) >> level_;
    const std::uint64_t z = static_cast<std::uint32_t>(g[2]) >> level_;
    const std::uint64_t i = (z * cells_ + y) * cells_ + x;
    return (bits_[i >> 6] >> (i & 63u)) & 1u;
  }

 private:
  int level_ = 0;
  std::uint64_t cells_ = 1;  // per axis
  double side_ = 0;          // universe side, voxels
  std::vector<std::uint64_t> bits_;
};

}  // namespace octomotion
