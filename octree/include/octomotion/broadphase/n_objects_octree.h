// The N-objects octree broad phase (Shaffer & Herb, as implemented in the N-objects octree
// collision-detection report §2): an octree over the axis-aligned bounding boxes of moving
// objects in which a leaf splits when its (N+1)-th object arrives and eight sibling leaves merge
// when together they hold N or fewer distinct objects (§2.2, §2.4). An object lives in every leaf
// its closed box touches.
//
// Per time step (§2.4) each moved object drops the leaves it left and enters neighbours found
// with Samet's greater-or-equal-size neighbour finding (direction.h): only in the directions the
// box grew toward (the report's "direction of motion") and reaches beyond the leaf, with a
// per-node time stamp so each neighbour is tested once per object per step. Splits and merges
// are applied once all objects have moved (rebalance()).
//
// Candidate pairs (§2.3) are co-residents of a leaf whose boxes overlap. Instead of the report's
// n x n table of "last tested" steps, a pair is reported only by the leaf owning the minimum
// corner of the two boxes' intersection (leaves own half-open cubes), so each overlapping pair
// comes out exactly once with no extra memory.
//
// N = kUnlimited keeps one leaf holding every object: the exhaustive all-pairs test (§1.4).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "octomotion/broadphase/aabb.h"
#include "octomotion/broadphase/direction.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/world_grid.h"

namespace octomotion::broadphase {

namespace detail {

// Bit j set iff box j (of n <= 64, as coordinate arrays) overlaps the closed box
// [lx,hx] x [ly,hy] x [lz,hz]. Two boxes per SSE2 instruction: the all-pairs loops' kernel.
inline std::uint64_t overlapBits(const double* lo_x, const double* lo_y, const double* lo_z,
                                 const double* hi_x, const double* hi_y, const double* hi_z,
                                 std::size_t n, double lx, double ly, double lz, double hx,
                                 double hy, double hz) {
  std::uint64_t bits = 0;
  std::size_t j = 0;
#if defined(__SSE2__)
  const __m128d vlx = _mm_set1_pd(lx), vly = _mm_set1_pd(ly), vlz = _mm_set1_pd(lz);
  const __m128d vhx = _mm_set1_pd(hx), vhy = _mm_set1_pd(hy), vhz = _mm_set1_pd(hz);
  for (; j + 2 <= n; j += 2) {
    __m128d m = _mm_and_pd(_mm_cmple_pd(vlx, _mm_loadu_pd(hi_x + j)),
                           _mm_cmple_pd(_mm_loadu_pd(lo_x + j), vhx));
    m = _mm_and_pd(m, _mm_cmple_pd(vly, _mm_loadu_pd(hi_y + j)));
    m = _mm_and_pd(m, _mm_cmple_pd(_mm_loadu_pd(lo_y + j), vhy));
    m = _mm_and_pd(m, _mm_cmple_pd(vlz, _mm_loadu_pd(hi_z + j)));
    m = _mm_and_pd(m, _mm_cmple_pd(_mm_loadu_pd(lo_z + j), vhz));
    bits |= static_cast<std::uint64_t>(_mm_movemask_pd(m)) << j;
  }
#endif
  for (; j < n; ++j) {
    const bool hit = (lx <= hi_x[j]) & (lo_x[j] <= hx) & (ly <= hi_y[j]) & (lo_y[j] <= hy) &
                     (lz <= hi_z[j]) & (lo_z[j] <= hz);
    bits |= static_cast<std::uint64_t>(hit) << j;
  }
  return bits;
}

}  // namespace detail

class NObjectsOctree {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  static constexpr std::uint32_t kUnlimited = std::numeric_limits<std::uint32_t>::max();

  struct Options {
    // N: the most objects a leaf holds before it splits; kUnlimited = exhaustive.
    std::uint32_t leaf_capacity = 10;
    // Levels below the root; leaves at the finest level never split (objects that all overlap
    // one point would otherwise split forever).
    int max_depth = 12;
  };

  // Work counters: pairs of the last forEachCandidatePair(), the rest since construction.
  struct Counters {
    std::uint64_t coresident_pairs = 0;  // pairs of co-residents examined (with repeats)
    std::uint64_t candidate_pairs = 0;   // distinct overlapping pairs reported
    std::uint64_t total_coresident_pairs = 0, total_candidate_pairs = 0;  // since construction
    std::uint64_t splits = 0, merges = 0, reroots = 0;
    std::uint64_t neighbour_queries = 0;
  };

  // An empty tree whose root cube is `root` (InvalidArgument if it is not a valid box); the root
  // cube is the smallest cube with the same centre containing the box.
  NObjectsOctree(const Aabb& root, Options options);
  // The report's heuristic (§2.2): the root is 150 % of the objects' initial bounding box.
  static NObjectsOctree forBoxes(const std::vector<Aabb>& boxes, Options options);

  // Adds an object, returning its id (ids are 0, 1, 2, ...). InvalidArgument for a non-finite or
  // inverted box. A box leaving the root re-roots the tree (150 % of all boxes) at rebalance().
  std::uint32_t add(const Aabb& box);
  // The object's box moved to `box` (same checks as add()).
  void move(std::uint32_t id, const Aabb& box);
  // Applies the splits and merges left pending by add()/move(), or re-roots.
  void rebalance();

  // Calls f(a, b) with a < b once for every pair of objects whose boxes overlap (rebalancing
  // first). Allocation-free after the first calls.
  template <class F>
  void forEachCandidatePair(F&& f);

  std::size_t objectCount() const { return objects_.size(); }
  const Aabb& box(std::uint32_t id) const { return objects_[id].box; }
  const Aabb& rootBox() const { return root_box_; }
  const Options& options() const { return options_; }
  const Counters& counters() const { return counters_; }
  Counters& counters() { return counters_; }

  // --- Node-level access (neighbour finding, tests, diagnostics). Node 0 is the root. ---
  bool isLive(std::uint32_t n) const { return n < nodes_.size() && nodes_[n].live; }
  bool isLeaf(std::uint32_t n) const { return nodes_[n].first_child == kNone; }
  std::uint32_t parent(std::uint32_t n) const { return nodes_[n].parent; }
  std::uint32_t child(std::uint32_t n, int label) const {
    return nodes_[n].first_child + static_cast<std::uint32_t>(label);
  }
  int childLabel(std::uint32_t n) const { return nodes_[n].label; }
  // The node's cube in finest-level integer units: level 0 is a finest cell, the root has level
  // max_depth and origin 0.
  Cube cube(std::uint32_t n) const { return nodes_[n].cube; }
  Aabb nodeBox(std::uint32_t n) const;
  const std::vector<std::uint32_t>& objectsIn(std::uint32_t n) const { return nodes_[n].objects; }
  const std::vector<std::uint32_t>& leavesOf(std::uint32_t id) const { return objects_[id].leaves; }
  std::size_t nodeSlots() const { return nodes_.size(); }
  std::size_t liveNodeCount() const { return live_nodes_; }
  std::size_t leafCount() const;

  // Samet's greater-or-equal-size neighbour of node n in direction d: the smallest node of size
  // >= n's whose cube touches n's face/edge/vertex d; kNone outside the root. O(depth), usually
  // O(1) amortised.
  std::uint32_t gtEqNeighbour(std::uint32_t n, Direction d) const;
  std::uint32_t gtEqFaceNeighbour(std::uint32_t n, Direction face) const;
  std::uint32_t gtEqEdgeNeighbour(std::uint32_t n, Direction edge) const;
  std::uint32_t gtEqVertexNeighbour(std::uint32_t n, Direction vertex) const;

  // Checks the split/merge and membership invariants; false with a reason on failure.
  bool checkInvariants(std::string* why = nullptr) const;

 private:
  struct Node {
    double min[3], max[3];
    Cube cube;
    std::uint32_t parent = kNone;
    std::uint32_t first_child = kNone;  // eight consecutive nodes, or kNone for a leaf
    std::uint64_t stamp = 0;            // last (object, step) that tested this node
    std::uint8_t label = 0;
    bool live = false;
    std::uint8_t at_root_max = 0;        // bit a: the cube's max face on axis a is the root's
    std::vector<std::uint32_t> objects;  // leaves only
  };
  struct Object {
    Aabb box;
    std::vector<std::uint32_t> leaves;
    std::uint64_t mark = 0;
  };

  void initRoot();
  void setNodeGeometry(std::uint32_t n, const Cube& cube);
  std::uint32_t allocateChildren(std::uint32_t parent);
  bool nodeOverlaps(std::uint32_t n, const Aabb& b) const;
  int childMask(std::uint32_t n, const Aabb& b) const;
  void addToLeaf(std::uint32_t leaf, std::uint32_t id);
  void removeFromLeaf(std::uint32_t leaf, std::uint32_t id);
  void insertFrom(std::uint32_t n, std::uint32_t id);
  void enter(std::uint32_t n, std::uint32_t id);
  void split(std::uint32_t leaf);
  bool tryMerge(std::uint32_t n);
  void reroot();
  bool owns(const Node& leaf, const double r[3]) const;
  void checkBox(const Aabb& box, const char* what) const;

  Options options_;
  Aabb root_box_;
  double unit_ = 1.0;  // side of a finest cell
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> free_blocks_;
  std::size_t live_nodes_ = 0;
  std::vector<Object> objects_;
  std::uint64_t stamp_ = 0;
  std::uint64_t mark_ = 0;
  bool needs_reroot_ = false;
  std::vector<std::uint32_t> overfull_, merge_candidates_, worklist_;
  struct PairScratch {
    static constexpr std::size_t kChunk = 64;
    std::vector<double> lo[3], hi[3];
    void resize(std::size_t n) {
      if (lo[0].size() >= n) return;
      for (int a = 0; a < 3; ++a) {
        lo[a].resize(n);
        hi[a].resize(n);
      }
    }
  };
  PairScratch scratch_;
  Counters counters_;
};

inline bool NObjectsOctree::owns(const Node& leaf, const double r[3]) const {
  for (int a = 0; a < 3; ++a) {
    if (r[a] < leaf.min[a]) return false;
    if (r[a] >= leaf.max[a] && !(((leaf.at_root_max >> a) & 1) && r[a] == leaf.max[a]))
      return false;
  }
  return true;
}

template <class F>
void NObjectsOctree::forEachCandidatePair(F&& f) {
  rebalance();
  std::uint64_t coresident = 0, candidates = 0;
  PairScratch& s = scratch_;
  for (const Node& leaf : nodes_) {
    if (!leaf.live || leaf.first_child != kNone || leaf.objects.size() < 2) continue;
    // The leaf's boxes as six contiguous coordinate arrays: the all-pairs loop below is then
    // branch-free and vectorisable.
    const std::size_t count = leaf.objects.size();
    s.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Aabb& b = objects_[leaf.objects[i]].box;
      for (int a = 0; a < 3; ++a) {
        s.lo[a][i] = b.min[a];
        s.hi[a][i] = b.max[a];
      }
    }
    coresident += count * (count - 1) / 2;
    const double* __restrict lo_x = s.lo[0].data();
    const double* __restrict lo_y = s.lo[1].data();
    const double* __restrict lo_z = s.lo[2].data();
    const double* __restrict hi_x = s.hi[0].data();
    const double* __restrict hi_y = s.hi[1].data();
    const double* __restrict hi_z = s.hi[2].data();
    for (std::size_t i = 0; i + 1 < count; ++i) {
      const double lx = lo_x[i], ly = lo_y[i], lz = lo_z[i];
      const double hx = hi_x[i], hy = hi_y[i], hz = hi_z[i];
      for (std::size_t j0 = i + 1; j0 < count; j0 += PairScratch::kChunk) {
        const std::size_t n = count - j0 < PairScratch::kChunk ? count - j0 : PairScratch::kChunk;
        std::uint64_t hits = detail::overlapBits(lo_x + j0, lo_y + j0, lo_z + j0, hi_x + j0,
                                                 hi_y + j0, hi_z + j0, n, lx, ly, lz, hx, hy, hz);
        while (hits) {
          const std::size_t j = j0 + static_cast<std::size_t>(lowestBit64(hits));
          hits &= hits - 1;
          // Report from the one leaf owning the intersection's minimum corner.
          const double r[3] = {lx > lo_x[j] ? lx : lo_x[j], ly > lo_y[j] ? ly : lo_y[j],
                               lz > lo_z[j] ? lz : lo_z[j]};
          if (!owns(leaf, r)) continue;
          ++candidates;
          const std::uint32_t ia = leaf.objects[i], ib = leaf.objects[j];
          if (ia < ib) {
            f(ia, ib);
          } else {
            f(ib, ia);
          }
        }
      }
    }
  }
  counters_.coresident_pairs = coresident;
  counters_.candidate_pairs = candidates;
  counters_.total_coresident_pairs += coresident;
  counters_.total_candidate_pairs += candidates;
}

}  // namespace octomotion::broadphase
