// A compact region octree (black/white/gray) stored as internal nodes only: each node keeps the
// colours of its eight children in two bit masks (Weng & Ahuja 1987 §5, Lemma: I = (T-1)/8), and
// its gray children sit in one contiguous block, found by popcount. No pointer per node.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "octomotion/octree/bits.h"
#include "octomotion/octree/world_grid.h"

namespace octomotion {

enum class Color : std::uint8_t { kWhite, kBlack, kGray };

// One internal (gray) node. Child `k` is black if bit k of `black` is set, gray if bit k of
// `gray` is set, white otherwise. Gray child k is nodes[first_child + childRank(gray, k)], where
// childRank (bits.h) = popcount(gray & ((1<<k)-1)).
struct OctreeNode {
  std::uint32_t first_child = 0;
  std::uint8_t black = 0;
  std::uint8_t gray = 0;
  std::uint8_t occupied() const { return static_cast<std::uint8_t>(black | gray); }
  std::uint32_t childIndex(int k) const {
    return first_child + static_cast<std::uint32_t>(childRank(gray, k));
  }
  friend bool operator==(const OctreeNode& a, const OctreeNode& b) {
    return a.first_child == b.first_child && a.black == b.black && a.gray == b.gray;
  }
};
static_assert(sizeof(OctreeNode) == 8, "an internal node is 8 bytes");

// Inclusive integer bounds of the black voxels.
struct VoxelBounds {
  Voxel min, max;
};

class Octree {
 public:
  // An all-white (empty) tree.
  explicit Octree(const WorldGrid& grid);
  static Octree full(const WorldGrid& grid);
  // Black exactly at the listed voxels; throws InvalidArgument for a voxel outside the universe.
  static Octree fromVoxels(const WorldGrid& grid, const std::vector<Voxel>& voxels);
  // Adopts a node array after checking every structural invariant (indices in range, each node
  // referenced once, depth respected, compaction); throws Error saying what is wrong.
  static Octree fromNodes(const WorldGrid& grid, Color root, std::vector<OctreeNode> nodes);

  const WorldGrid& grid() const { return grid_; }
  // kGray when the tree has internal nodes (then nodes()[0] is the root), else the universe's
  // colour.
  Color rootColor() const { return root_; }
  const std::vector<OctreeNode>& nodes() const { return nodes_; }

  bool empty() const { return root_ == Color::kWhite; }
  std::size_t internalNodeCount() const { return nodes_.size(); }
  std::size_t blackLeafCount() const;
  std::size_t bytes() const { return sizeof(*this) + nodes_.size() * sizeof(OctreeNode); }
  std::uint64_t blackVoxelCount() const;
  double volume() const;  // cubic metres
  bool occupied(const Voxel& v) const;
  // False outside the universe: nothing is modelled there.
  bool occupiedAt(const Eigen::Vector3d& p_W) const;
  std::optional<VoxelBounds> bounds() const;

  // Calls f(const Cube&) for every black leaf in depth-first label order.
  template <class F>
  void forEachBlackLeaf(F&& f) const;
  std::vector<Cube> blackLeaves() const;
  std::vector<Voxel> blackVoxels() const;  // expands leaves; for tests and small trees

  // Checks the compaction and layout invariants; returns false and says why on failure.
  bool checkInvariants(std::string* why = nullptr) const;

  // Same grid and same occupancy (compact trees are canonical, so this is structural).
  friend bool operator==(const Octree& a, const Octree& b);
  friend bool operator!=(const Octree& a, const Octree& b) { return !(a == b); }

 private:
  Octree(const WorldGrid& grid, Color root, std::vector<OctreeNode> nodes)
      : grid_(grid), root_(root), nodes_(std::move(nodes)) {}
  friend class OctreeBuilder;

  template <class F>
  void forEachBlackLeafFrom(std::uint32_t index, const Cube& cube, F& f) const;

  WorldGrid grid_;
  Color root_ = Color::kWhite;
  std::vector<OctreeNode> nodes_;
};

template <class F>
void Octree::forEachBlackLeaf(F&& f) const {
  if (root_ == Color::kBlack) {
    f(grid_.universe());
  } else if (root_ == Color::kGray) {
    forEachBlackLeafFrom(0, grid_.universe(), f);
  }
}

template <class F>
void Octree::forEachBlackLeafFrom(std::uint32_t index, const Cube& cube, F& f) const {
  const OctreeNode& node = nodes_[index];
  for (int k = 0; k < 8; ++k) {
    if (node.black & (1u << k)) {
      f(cube.child(k));
    } else if (node.gray & (1u << k)) {
      forEachBlackLeafFrom(node.childIndex(k), cube.child(k), f);
    }
  }
}

}  // namespace octomotion
