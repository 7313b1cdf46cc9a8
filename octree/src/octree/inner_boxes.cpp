#include "octomotion/octree/inner_boxes.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "octomotion/error.h"

namespace octomotion {

namespace {

// Dense grid of a tree's cells at one level: which are entirely black.
class CellGrid {
 public:
  CellGrid(const Octree& tree, int level)
      : level_(level), n_(static_cast<int>(tree.grid().sideVoxels() >> level)) {
    solid_.assign(static_cast<std::size_t>(n_) * n_ * n_, 0);
    // Leaves at or above the level cover whole cells; smaller ones leave their cell partly
    // white (a compact tree merges eight black children, so no cell is black piecewise).
    tree.forEachBlackLeaf([&](const Cube& leaf) {
      if (leaf.level < level_) return;
      const int w = 1 << (leaf.level - level_);
      const int x0 = static_cast<int>(leaf.origin.x >> level_);
      const int y0 = static_cast<int>(leaf.origin.y >> level_);
      const int z0 = static_cast<int>(leaf.origin.z >> level_);
      for (int z = z0; z < z0 + w; ++z) {
        for (int y = y0; y < y0 + w; ++y) {
          for (int x = x0; x < x0 + w; ++x) solid_[index(x, y, z)] = 1;
        }
      }
    });
  }
  int n() const { return n_; }
  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * static_cast<std::size_t>(n_) +
            static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(n_) +
           static_cast<std::size_t>(x);
  }
  bool solid(int x, int y, int z) const { return solid_[index(x, y, z)] != 0; }
  // Every cell of the inclusive cell box [lo, hi] is solid.
  bool allSolid(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          if (!solid(x, y, z)) return false;
        }
      }
    }
    return true;
  }

  // Chessboard (L-inf) distance from each solid cell to the nearest cell that is not solid or
  // lies outside the grid, 0 on those: two raster passes over the 26-neighbourhood (exact for
  // this metric, Rosenfeld & Pfaltz 1966).
  std::vector<int> depthInside() const {
    std::vector<int> d(solid_.size(), 0);
    const int big = n_ + 1;
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = solid_[i] ? big : 0;
    auto at = [&](int x, int y, int z) {
      if (x < 0 || y < 0 || z < 0 || x >= n_ || y >= n_ || z >= n_) return 0;
      return d[index(x, y, z)];
    };
    // Forward: the 13 neighbours before a cell in raster order; backward: the 13 after it.
    for (int pass = 0; pass < 2; ++pass) {
      const int s = pass == 0 ? -1 : 1;
      for (int zi = 0; zi < n_; ++zi) {
        const int z = pass == 0 ? zi : n_ - 1 - zi;
        for (int yi = 0; yi < n_; ++yi) {
          const int y = pass == 0 ? yi : n_ - 1 - yi;
          for (int xi = 0; xi < n_; ++xi) {
            const int x = pass == 0 ? xi : n_ - 1 - xi;
            int& v = d[index(x, y, z)];
            if (v == 0) continue;
            int best = v;
            for (int dz = 0; dz <= 1; ++dz) {
              for (int dy = dz ? -1 : 0; dy <= 1; ++dy) {
                for (int dx = (dz || dy) ? -1 : 1; dx <= 1; ++dx) {
                  best = std::min(best, at(x + s * dx, y + s * dy, z + s * dz) + 1);
                }
              }
            }
            v = best;
          }
        }
      }
    }
    return d;
  }

 private:
  int level_;
  int n_;
  std::vector<std::uint8_t> solid_;
};

}  // namespace

std::vector<Eigen::AlignedBox3d> innerBoxes(const Octree& tree, const InnerBoxOptions& options) {
  if (options.max_boxes < 1 || options.max_cells_per_axis < 1 || options.min_cells < 1) {
    throw InvalidArgument("innerBoxes: max_boxes, max_cells_per_axis and min_cells must be >= 1");
  }
  std::vector<Eigen::AlignedBox3d> boxes;
  if (tree.empty()) return boxes;
  const WorldGrid& grid = tree.grid();
  int level = 0;
  while (level < grid.depth() &&
         (grid.sideVoxels() >> level) > static_cast<std::uint32_t>(options.max_cells_per_axis)) {
    ++level;
  }
  const CellGrid cells(tree, level);
  const int n = cells.n();
  const std::vector<int> depth = cells.depthInside();
  std::vector<std::uint8_t> covered(depth.size(), 0);

  for (int k = 0; k < options.max_boxes; ++k) {
    // The seed: the deepest cell no box covers yet (first in raster order among ties).
    std::size_t seed = 0;
    int seed_depth = 0;
    for (std::size_t i = 0; i < depth.size(); ++i) {
      if (!covered[i] && depth[i] > seed_depth) {
        seed_depth = depth[i];
        seed = i;
      }
    }
    if (seed_depth == 0) break;  // every solid cell is covered
    const std::size_t un = static_cast<std::size_t>(n);
    std::array<int, 3> lo{static_cast<int>(seed % un), static_cast<int>(seed / un % un),
                          static_cast<int>(seed / (un * un))};
    std::array<int, 3> hi = lo;
    // Grow one layer at a time on each face in turn while the layer is solid.
    for (bool grew = true; grew;) {
      grew = false;
      for (int a = 0; a < 3; ++a) {
        for (int side = 0; side < 2; ++side) {
          std::array<int, 3> layer_lo = lo, layer_hi = hi;
          const int at = side == 0 ? lo[a] - 1 : hi[a] + 1;
          if (at < 0 || at >= n) continue;
          layer_lo[a] = layer_hi[a] = at;
          if (!cells.allSolid(layer_lo, layer_hi)) continue;
          (side == 0 ? lo : hi)[a] = at;
          grew = true;
        }
      }
    }
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) covered[cells.index(x, y, z)] = 1;
      }
    }
    if (hi[0] - lo[0] + 1 < options.min_cells || hi[1] - lo[1] + 1 < options.min_cells ||
        hi[2] - lo[2] + 1 < options.min_cells) {
      continue;
    }
    auto voxel = [level](const std::array<int, 3>& c) {
      return Voxel{static_cast<std::uint32_t>(c[0]) << level,
                   static_cast<std::uint32_t>(c[1]) << level,
                   static_cast<std::uint32_t>(c[2]) << level};
    };
    boxes.emplace_back(grid.cubeMin(Cube{level, voxel(lo)}), grid.cubeMax(Cube{level, voxel(hi)}));
  }
  return boxes;
}

}  // namespace octomotion
