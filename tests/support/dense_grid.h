// The brute-force oracle of our property tests: a dense 2^n x 2^n x 2^n array of voxel colours.
// Only for small depths (n <= 7 keeps it at 2 MB).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "octomotion/octree/octree.h"

namespace octomotion::test {

class DenseGrid {
 public:
  explicit DenseGrid(int depth)
      : depth_(depth), side_(1u << depth), cells_(std::size_t{side_} * side_ * side_, 0) {}

  int depth() const { return depth_; }
  std::uint32_t side() const { return side_; }
  bool get(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    return cells_[index(x, y, z)] != 0;
  }
  bool get(const Voxel& v) const { return get(v.x, v.y, v.z); }
  void set(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool black = true) {
    cells_[index(x, y, z)] = black ? 1 : 0;
  }
  void set(const Voxel& v, bool black = true) { set(v.x, v.y, v.z, black); }
  std::size_t count() const {
    std::size_t n = 0;
    for (auto c : cells_) n += c;
    return n;
  }

  static DenseGrid fromTree(const Octree& t) {
    DenseGrid g(t.grid().depth());
    t.forEachBlackLeaf([&](const Cube& c) {
      for (std::uint32_t z = 0; z < c.side(); ++z)
        for (std::uint32_t y = 0; y < c.side(); ++y)
          for (std::uint32_t x = 0; x < c.side(); ++x)
            g.set(c.origin.x + x, c.origin.y + y, c.origin.z + z);
    });
    return g;
  }
  std::vector<Voxel> voxels() const {
    std::vector<Voxel> out;
    for (std::uint32_t z = 0; z < side_; ++z)
      for (std::uint32_t y = 0; y < side_; ++y)
        for (std::uint32_t x = 0; x < side_; ++x)
          if (get(x, y, z)) out.push_back({x, y, z});
    return out;
  }
  Octree toTree(const WorldGrid& grid) const { return Octree::fromVoxels(grid, voxels()); }

  friend bool operator==(const DenseGrid& a, const DenseGrid& b) {
    return a.depth_ == b.depth_ && a.cells_ == b.cells_;
  }

 private:
  std::size_t index(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    return (std::size_t{z} * side_ + y) * side_ + x;
  }
  int depth_;
  std::uint32_t side_;
  std::vector<std::uint8_t> cells_;
};

// A random shape that exercises compaction: a few solid boxes and balls (large uniform
// regions) plus scattered single voxels (fragmentation). Deterministic for a given rng state.
inline DenseGrid randomShape(int depth, std::mt19937_64& rng, int boxes = 3, int dots = 20) {
  DenseGrid g(depth);
  const std::uint32_t side = g.side();
  std::uniform_int_distribution<std::uint32_t> coord(0, side - 1);
  for (int b = 0; b < boxes; ++b) {
    std::uint32_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      std::uint32_t p = coord(rng), q = coord(rng);
      lo[a] = std::min(p, q);
      hi[a] = std::max(p, q);
    }
    const bool ball = rng() & 1;
    const double cx = (lo[0] + hi[0]) / 2.0, cy = (lo[1] + hi[1]) / 2.0, cz = (lo[2] + hi[2]) / 2.0,
                 r = (hi[0] - lo[0]) / 2.0 + 0.5;
    for (std::uint32_t z = lo[2]; z <= hi[2]; ++z)
      for (std::uint32_t y = lo[1]; y <= hi[1]; ++y)
        for (std::uint32_t x = lo[0]; x <= hi[0]; ++x) {
          if (ball && (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) > r * r)
            continue;
          g.set(x, y, z);
        }
  }
  for (int d = 0; d < dots; ++d) g.set(coord(rng), coord(rng), coord(rng));
  return g;
}

}  // namespace octomotion::test
