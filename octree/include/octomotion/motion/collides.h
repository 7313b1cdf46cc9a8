// The fused motion query: does the source tree, moved by X_WS, share a black voxel with the
// environment? Equivalent to intersects(moveTree(source, X_WS, env.grid(), rounding), env) —
// same colour rule, same arithmetic for every voxel decision — but no target tree is built:
// the environment tree and the moved source tree are descended together (a parallel traversal
// in the sense of Ahuja & Nash 1984 §5, with Weng & Ahuja 1987 §4's Relation B tests, both ways,
// as the pruning rule), and the walk stops at the first shared black voxel.
//  - Gray environment cells: the moved source pieces (tight boxes of source subtrees, split
//    into their children only when much larger than the cell) prune every environment subtree
//    none of them can reach; black children are examined before gray ones.
//  - Black environment cells: the source tree is descended under the pieces reaching the cell
//    and each moved black leaf probes the cell's voxel nearest to its centre with the colour
//    rule; leaves whose probe failed are settled exactly on the cell's children.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/motion/black_cell_grid.h"
#include "octomotion/motion/clearance_grid.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"

namespace octomotion {

namespace detail {
// One moved piece of the source during a query: a gray source node (tight box of its black
// voxels) or one of its black leaves.
struct CollisionItem {
  double g[3];   // moved centre, target voxels
  double rt[3];  // half-extent of the moved piece along the target axes
  double rs[3];  // half-extent along the source axes, in target voxels
  double split;  // gray node: split against cells of half side below this (target voxels)
  std::uint32_t node;
  std::int8_t leaf;   // -1: the gray node itself; k: black child k of `node`
  std::int8_t level;  // level of the leaf cube (leaf items)
  std::uint8_t mask;  // children of the current cell it may reach (set while visiting it)
};
}  // namespace detail

// A source tree prepared once for many collision queries (immutable, shareable across
// threads): its internal nodes with the tight box of the black voxels under each.
class MovableSource {
 public:
  // A gray source piece is split into its children only when it is more than `expand_factor`
  // times larger than the target cell it is tested against (>= 1).
  //  - kExpandFactorDefault: for links against environments, keeping the source whole until
  //    black cells are reached (then probeBelow descends it) beats eager splitting, whose cost
  //    is making and testing many small pieces.
  //  - kExpandFactorDeepPairs: a link's self-collision tree at least kDeepPairLevels deep,
  //    moved onto another link's tree of the same resolution (OctreeCollisionModel picks it per
  //    self tree): two solid shapes that are close along a whole joint need tight pieces early.
  //    Shallower trees do better with the default.
  //  - kExpandFactorSparse: a node whose black voxels fill less than kSparseFill of its box
  //    (the X of a drone's arms, the two legs of an L bar) is split at this factor when it is
  //    smaller: its box is mostly air, and testing it whole against the cells of a nearby wall
  //    costs more than its few children do. Solid links fill most of their boxes and are
  //    unaffected.
  //  bench/motion_bench measures the query (docs/planner.md, "Tuned constants").
  static constexpr double kExpandFactorDefault = 8.0;
  static constexpr double kExpandFactorDeepPairs = 2.0;
  static constexpr double kExpandFactorSparse = 2.0;
  static constexpr double kSparseFill = 0.5;
  static constexpr int kDeepPairLevels = 8;
  explicit MovableSource(const Octree& source, double expand_factor = kExpandFactorDefault);
  double expandFactor() const { return expand_factor_; }

  const WorldGrid& grid() const { return grid_; }
  Color rootColor() const { return root_; }
  std::size_t nodeCount() const { return nodes_.size(); }

  struct Node {
    double centre[3];  // box of the node's black voxels, source grid coordinates
    double half[3];
    double split_half;  // split against cells of half side below s * split_half (see above)
    std::uint32_t first_child;
    std::uint8_t black, gray;
    std::int8_t level;  // level of the node's cube
    Voxel origin;       // min corner of the node's cube
    std::uint32_t childIndex(int k) const {
      return first_child + static_cast<std::uint32_t>(childRank(gray, k));
    }
  };
  const std::vector<Node>& nodes() const { return nodes_; }
  // The largest black leaves (deep inside the object): tried first by every query.
  const std::vector<Cube>& coreLeaves() const { return core_; }
  // Centres of black leaves spread over the object (greedily the farthest apart, from the
  // largest leaf), source grid coordinates: tried against the environment's BlackCellGrid,
  // when the query has one, before anything else.
  static constexpr std::size_t kGridProbes = 16;
  const std::vector<std::array<double, 3>>& gridProbes() const { return grid_probes_; }

 private:
  WorldGrid grid_;
  Color root_;
  std::vector<Node> nodes_;
  std::vector<Cube> core_;
  std::vector<std::array<double, 3>> grid_probes_;
  double expand_factor_;
};

// Per-thread reusable buffers of the fused query: after the first few queries, collides()
// allocates nothing. Not shareable between concurrent queries.
class CollisionScratch {
 public:
  CollisionScratch() {
    items.reserve(1024);
    pieces.reserve(64);
  }
  std::vector<detail::CollisionItem> items;   // stack of the pieces reaching each visited cell
  std::vector<detail::CollisionItem> pieces;  // the source pieces not proven clear
};

// True iff intersects(moveTree(source, X_WS, environment.grid(), rounding), environment).
// On true, *witness (if given) receives a voxel black in both. Const and thread-safe given one
// scratch per thread. Throws InvalidArgument for an invalid pose.
// `solid` (optional): the environment's BlackCellGrid; the source's grid probes that land in a
// black cell answer at once (same answer, found sooner). Under centre rounding a probe answers
// only if the voxel it lands in is black in the moved tree (its centre in a moved black leaf,
// looked up in the source tree and confirmed by the colour rule).
// `clearance` (optional, either rounding): the environment's ClearanceGrid; before the descent
// the moved source is split (at most kClearanceSplits nodes, breadth first) into pieces, and a
// piece whose bounding sphere lies within the clearance at its centre is dropped (same answer;
// a free pose near an obstacle descends only what is near it). The split budget is small
// because more pieces make a contact that the BlackCellGrid's probes miss dearer to find. The
// pieces are kept for the descent even when not all are clear: the pieces left are tighter
// than the whole source, so the descent starts closer to the obstacle. bench/motion_bench
// (FusedWithClearanceGrid) measures the query with and without the grid.
constexpr int kClearanceSplits = 4;
bool collides(const MovableSource& source, const Eigen::Isometry3d& X_WS, const Octree& environment,
              Rounding rounding, CollisionScratch& scratch, Cube* witness = nullptr,
              const BlackCellGrid* solid = nullptr, const ClearanceGrid* clearance = nullptr);

// Convenience form for one-off queries: prepares the source and scratch on every call
// (allocates, O(source size)); use MovableSource + CollisionScratch in loops.
bool collides(const Octree& source, const Eigen::Isometry3d& X_WS, const Octree& environment,
              Rounding rounding, Cube* witness = nullptr);

}  // namespace octomotion
