#include "octomotion/motion/black_cell_grid.h"

namespace octomotion {

BlackCellGrid::BlackCellGrid(const Octree& tree, std::size_t max_cells) {
  const int depth = tree.grid().depth();
  while (level_ < depth && (std::uint64_t{1} << (3 * (depth - level_))) > max_cells) ++level_;
  cells_ = std::uint64_t{1} << (depth - level_);
  side_ = static_cast<double>(tree.grid().sideVoxels());
  bits_.assign(static_cast<std::size_t>((cells_ * cells_ * cells_ + 63) / 64), 0);
  // Black leaves at or above the grid's level mark every cell they cover; smaller ones leave
  // their cell partly white (not black).
  tree.forEachBlackLeaf([&](const Cube& leaf) {
    if (leaf.level < level_) return;
    const std::uint64_t n = std::uint64_t{1} << (leaf.level - level_);
    const std::uint64_t x0 = leaf.origin.x >> level_, y0 = leaf.origin.y >> level_,
                        z0 = leaf.origin.z >> level_;
    for (std::uint64_t z = z0; z < z0 + n; ++z) {
      for (std::uint64_t y = y0; y < y0 + n; ++y) {
        for (std::uint64_t x = x0; x < x0 + n; ++x) {
          const std::uint64_t i = (z * cells_ + y) * cells_ + x;
          bits_[static_cast<std::size_t>(i >> 6)] |= std::uint64_t{1} << (i & 63u);
        }
      }
    }
  });
}

}  // namespace octomotion
