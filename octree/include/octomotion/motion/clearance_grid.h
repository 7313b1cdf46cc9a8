// A dense grid of lower bounds on the distance from each cell of an environment tree to its
// black voxels: "is a ball of radius r around this point clear of the environment?" in one
// lookup. collides() uses it to drop the pieces of the moved source that are provably far from
// every black voxel (the moved source's black voxels all touch its moved pieces), so a free pose
// near an obstacle descends only the parts of the source that are close to it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "octomotion/octree/octree.h"

namespace octomotion {

class ClearanceGrid {
 public:
  // The grid of `tree`'s cells at the finest level whose grid has at most `max_cells` cells (a
  // byte each): 2^21 is 2 MiB. The certified motion validator takes its bounds as clearances,
  // and cells of half the side leave fewer links to the exact distances and prove longer
  // intervals; the queries along a path read a small part of it.
  static constexpr std::size_t kDefaultMaxCells = std::size_t{1} << 21;
  // Distances are stored in quarters of a cell, up to 255 quarters (about 64 cells).
  static constexpr int kStepsPerCell = 4;
  explicit ClearanceGrid(const Octree& tree, std::size_t max_cells = kDefaultMaxCells);

  // After black voxels were added to the tree, all within `added` (voxel bounds of the tree's
  // grid): lowers every cell's bound to its distance to the cells `added` covers, so the grid
  // stays a lower bound for the changed tree without a new distance transform (looser than a
  // rebuilt grid near `added`). Black voxels taken away need no change: bounds only grow then.
  void addBlack(const VoxelBounds& added);

  int level() const { return level_; }
  double cellVoxels() const { return step_ * kStepsPerCell; }  // a cell's side
  double sideVoxels() const { return side_; }                  // of the tree's universe
  std::size_t bytes() const { return sizeof(*this) + steps_.size(); }

  // A lower bound, in voxels of the tree's grid, on the distance from the point g (grid
  // coordinates) to every black voxel of the tree; 0 outside the universe. It is the distance
  // from the cell holding g to the nearest cell holding a black voxel (box to box), rounded
  // down to a quarter of a cell.
  double clearance(const double g[3]) const {
    if (!(g[0] >= 0.0 && g[1] >= 0.0 && g[2] >= 0.0 && g[0] < side_ && g[1] < side_ &&
          g[2] < side_)) {
      return 0.0;
    }
    const std::uint64_t x = static_cast<std::uint32_t>(g[0]) >> level_;
    const std::uint64_t y = static_cast<std::uint32_t>(g[1]) >> level_;
    const std::uint64_t z = static_cast<std::uint32_t>(g[2]) >> level_;
    return static_cast<double>(steps_[static_cast<std::size_t>((z * cells_ + y) * cells_ + x)]) *
           step_;
  }

 private:
  int level_ = 0;
  std::uint64_t cells_ = 1;  // per axis
  double side_ = 0;          // universe side, voxels
  double step_ = 0;          // voxels per stored step
  std::vector<std::uint8_t> steps_;
};

}  // namespace octomotion
