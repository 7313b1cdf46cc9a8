// A mutable octree for building and editing: nodes hold eight child indices so cubes can be
// painted, split and condensed in place; build() condenses and lays the result out as a compact
// Octree. Deleted nodes are recycled, and the live/peak node counts are what Weng & Ahuja's
// Table 2 calls I and M.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "octomotion/octree/octree.h"

namespace octomotion {

class OctreeBuilder {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Node {
    std::uint8_t black = 0;  // bit k: child k is a black leaf
    std::uint8_t gray = 0;   // bit k: child k is node child[k]
    std::array<std::uint32_t, 8> child{kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
  };

  explicit OctreeBuilder(const WorldGrid& grid);
  explicit OctreeBuilder(const Octree& tree);

  const WorldGrid& grid() const { return grid_; }

  // Paints a cube (any level <= depth) black or white, splitting and condensing on the way.
  void paint(const Cube& cube, bool black);
  void setVoxel(const Voxel& v, bool black = true) { paint(Cube{0, v}, black); }

  // The compact, canonically laid out tree.
  Octree build() const;

  // Low-level access for algorithms that descend the tree themselves (e.g. moveTree).
  // The root is always node 0, standing for the universe cube.
  static constexpr std::uint32_t kRoot = 0;
  Node& node(std::uint32_t i) { return nodes_[i]; }
  const Node& node(std::uint32_t i) const { return nodes_[i]; }
  // Makes child k of `parent` gray, its eight children taking the child's former colour.
  std::uint32_t split(std::uint32_t parent, int k);
  // If gray child k of `parent` has eight black or eight white children, deletes it and gives
  // its colour to the parent's mask. Returns true when it condensed.
  bool condense(std::uint32_t parent, int k);

  // Room for this many nodes without reallocating (a hint; building works without it).
  void reserve(std::size_t nodes) { nodes_.reserve(nodes); }

  std::size_t liveNodeCount() const { return live_; }
  std::size_t peakNodeCount() const { return peak_; }

 private:
  std::uint32_t allocate();
  void release(std::uint32_t i);
  void paintFrom(std::uint32_t index, const Cube& cell, const Cube& target, bool black);

  WorldGrid grid_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> free_;
  std::size_t live_ = 0;
  std::size_t peak_ = 0;
};

}  // namespace octomotion
