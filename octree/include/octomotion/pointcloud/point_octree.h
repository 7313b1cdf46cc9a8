// A point-region (PR) octree over 3-D points: insert, exact search, remove, k-nearest and radius
// search. Cells split when they hold more than `bucket_size` points (or stop at `max_depth`);
// eight siblings collapse back when their subtree holds no more than `bucket_size`.
//
// Storage is compact for millions of points: nodes are 12 bytes in one array (eight children
// contiguous, octant labels bit 0 = +x, bit 1 = +y, bit 2 = +z as elsewhere in octomotion); points
// (float x, y, z + a 32-bit id) live in 64-byte chunks of four carved from one pooled array, a
// leaf chaining as many chunks as it needs. Nothing is allocated per point; queries allocate
// nothing beyond the caller's output vector.
//
// The insert/search descent follows the classic PR-octree insertion: pick the child octant by
// comparing with the cell centre, split a full leaf and re-insert its points.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace octomotion::pointcloud {

struct Neighbour {
  std::uint32_t id = 0;    // id returned by insert() (or the index in the build vector)
  float distance2 = 0.0f;  // squared Euclidean distance to the query
};

class PointOctree {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  // Points per storage chunk: 4 x 16-byte entries = one 64-byte cache line. Leaves chain
  // ceil(count / 4) chunks, so a sparse leaf wastes at most 3 slots.
  static constexpr std::uint32_t kChunk = 4;

  struct Options {
    std::uint32_t bucket_size = 16;  // most points in a leaf above max_depth (1..4096)
    int max_depth = 20;              // levels below the root (0..30)
  };

  // An empty tree over the cube [min, min + side]^3. InvalidArgument for a non-finite corner,
  // side <= 0 or options out of range.
  PointOctree(const Eigen::Vector3d& min, double side, Options options);
  PointOctree(const Eigen::Vector3d& min, double side) : PointOctree(min, side, Options{}) {}
  // Bulk build over the points' bounding cube (slightly enlarged); point i gets id i. Throws
  // InvalidArgument for a non-finite point.
  static PointOctree build(const std::vector<Eigen::Vector3f>& points, Options options);
  static PointOctree build(const std::vector<Eigen::Vector3f>& points) {
    return build(points, Options{});
  }

  // Inserts a point (duplicates allowed) and returns its id (ids continue after build()'s).
  // InvalidArgument for a non-finite point or one outside the root cube.
  std::uint32_t insert(const Eigen::Vector3f& p);
  // Exact search: some stored point has exactly these coordinates.
  bool contains(const Eigen::Vector3f& p) const;
  // Removes one stored point with exactly these coordinates; false if there is none.
  bool remove(const Eigen::Vector3f& p);

  // The k nearest points, nearest first (ties in any order); fewer if the tree holds fewer.
  void kNearest(const Eigen::Vector3f& q, std::size_t k, std::vector<Neighbour>* out) const;
  // Every point within distance `radius` (inclusive), in no particular order.
  void radiusSearch(const Eigen::Vector3f& q, float radius, std::vector<Neighbour>* out) const;
  // Distance from q to the nearest stored point (the clearance to the nearest obstacle point);
  // +infinity when the tree is empty.
  double nearestDistance(const Eigen::Vector3f& q) const;
  // The same when it is below `upper_bound`; otherwise some value >= upper_bound (cells farther
  // than the bound are never visited: the fast form for "is anything nearer than this?").
  double nearestDistance(const Eigen::Vector3f& q, double upper_bound) const;

  std::size_t size() const { return nodes_.empty() ? 0 : nodes_[0].count; }
  bool empty() const { return size() == 0; }
  const Eigen::Vector3d& min() const { return min_; }
  double side() const { return side_; }
  const Options& options() const { return options_; }
  std::size_t nodeCount() const { return live_nodes_; }
  std::size_t leafCount() const;
  int height() const;  // deepest leaf level (root = 0)
  // Bytes held by nodes and point buckets (capacity included).
  std::size_t bytes() const;
  // Calls f(const Eigen::Vector3f&, id) for every stored point.
  template <class F>
  void forEachPoint(F&& f) const;

  // Structure: counts, bucket limits, every point inside its leaf's cell, merged siblings.
  bool checkInvariants(std::string* why = nullptr) const;

 private:
  struct Node {
    std::uint32_t first_child = kNone;  // eight consecutive nodes, or kNone for a leaf
    std::uint32_t bucket = kNone;       // leaf: first bucket of its chain (kNone if empty)
    std::uint32_t count = 0;            // points in the subtree
  };
  struct Entry {
    float x, y, z;
    std::uint32_t id;
  };
  struct Cell {
    double cx, cy, cz, half;  // centre and half side
    Cell child(int k) const {
      const double h = half * 0.5;
      return {cx + ((k & 1) ? h : -h), cy + ((k & 2) ? h : -h), cz + ((k & 4) ? h : -h), h};
    }
    int octant(const Entry& e) const {
      return (static_cast<double>(e.x) >= cx ? 1 : 0) | (static_cast<double>(e.y) >= cy ? 2 : 0) |
             (static_cast<double>(e.z) >= cz ? 4 : 0);
    }
  };

  Cell rootCell() const;
  std::uint32_t allocateChildren(std::uint32_t parent);
  std::uint32_t allocateBucket();
  void freeChain(std::uint32_t bucket);
  void appendToLeaf(std::uint32_t leaf, const Entry& e);
  void splitLeaf(std::uint32_t leaf, const Cell& cell, int depth);
  void collapse(std::uint32_t node);
  template <class F>
  void forEachEntryBelow(std::uint32_t node, F&& f) const;
  // The branch-and-bound descent shared by kNearest, radiusSearch and nearestDistance.
  template <bool kNearestFirst, class Search>
  void descend(const Eigen::Vector3f& q, Search& search) const;
  void buildFrom(std::uint32_t node, const Cell& cell, int depth, Entry* begin, Entry* end,
                 Entry* scratch);
  void checkPoint(const Eigen::Vector3f& p, const char* what) const;

  Options options_;
  Eigen::Vector3d min_;
  double side_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> free_node_blocks_;
  std::size_t live_nodes_ = 0;
  // Chunk b holds entries [b * kChunk, b * kChunk + bucket_count_[b]) and continues in
  // bucket_next_[b]. A leaf's chain is full chunks after a partly filled head.
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> bucket_count_, bucket_next_, free_buckets_;
  std::uint32_t next_id_ = 0;
  std::vector<Entry> scratch_;  // reused by split and collapse
};

template <class F>
void PointOctree::forEachEntryBelow(std::uint32_t node, F&& f) const {
  const Node& n = nodes_[node];
  if (n.first_child != kNone) {
    for (std::uint32_t c = n.first_child; c < n.first_child + 8; ++c) {
      if (nodes_[c].count) forEachEntryBelow(c, f);
    }
    return;
  }
  for (std::uint32_t b = n.bucket; b != kNone; b = bucket_next_[b]) {
    const Entry* e = &entries_[static_cast<std::size_t>(b) * kChunk];
    for (std::uint32_t i = 0; i < bucket_count_[b]; ++i) f(e[i]);
  }
}

template <class F>
void PointOctree::forEachPoint(F&& f) const {
  if (nodes_.empty() || nodes_[0].count == 0) return;
  forEachEntryBelow(0, [&](const Entry& e) { f(Eigen::Vector3f(e.x, e.y, e.z), e.id); });
}

}  // namespace octomotion::pointcloud
