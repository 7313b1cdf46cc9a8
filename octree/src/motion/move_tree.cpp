// moveTree: fdleaf / intersect / condense of Weng & Ahuja 1987 §4.
#include "octomotion/motion/move_tree.h"

#include "internal/kernel.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {

namespace {

using detail::MotionFrame;

enum class Relation { kOutside, kInside, kPartial };

// intersect(): inserts one moved black cube into the target tree from the root down.
class Inserter {
 public:
  Inserter(const MotionFrame& f, OctreeBuilder& builder, Rounding rounding)
      : f_(f), b_(builder), rounding_(rounding), margin_(detail::rejectMargin(rounding)) {}

  bool clipped = false;

  void insertLeaf(const Cube& leaf) {
    double u[3];
    detail::cubeCentre(leaf, u);
    detail::movePoint(f_, u, g_);
    hs_ = detail::movedHalf(f_, leaf.level);
    // Out-of-space check of fdleaf: the paper stops with an error; we clip.
    bool disjoint = false;
    for (int i = 0; i < 3; ++i) {
      const double ext = hs_ * f_.rowsum[i];
      if (g_[i] - ext < -kMotionTieTolerance || g_[i] + ext > f_.side + kMotionTieTolerance) {
        clipped = true;
      }
      if (g_[i] + ext < 0.0 || g_[i] - ext > f_.side) disjoint = true;
    }
    if (disjoint) return;
    const Cube universe = b_.grid().universe();
    if (b_.node(OctreeBuilder::kRoot).black == 0xff) return;
    switch (relation(universe)) {
      case Relation::kOutside:
        return;
      case Relation::kInside:
        b_.paint(universe, true);
        return;
      case Relation::kPartial:
        for (int k = 0; k < 8; ++k) insertChild(OctreeBuilder::kRoot, k, universe.child(k));
        return;
    }
  }

 private:
  // Relation B between the moved cube and an upright target cube, with the circumscribing
  // spheres of disa/disb replaced by the cubes' exact projection radii (never weaker): the
  // moved cube against the target axes (disa, l1 < l2), and the target cube moved backwards
  // against the upright source cube, i.e. in the source axes (disb, l1 >= l2). Both are applied
  // at every level because each costs a few flops. "Inside" tests the corners of q, the cube
  // spanned by the target cube's voxel centres, in the source axes.
  Relation relation(const Cube& cell) const {
    double e[3];
    detail::cubeCentre(cell, e);
    const double d[3] = {e[0] - g_[0], e[1] - g_[1], e[2] - g_[2]};
    const double hc = detail::cellReach(rounding_, cell.level);
    for (int i = 0; i < 3; ++i) {
      if (std::fabs(d[i]) > hc + hs_ * f_.rowsum[i] + margin_) return Relation::kOutside;
    }
    double q[3];
    for (int j = 0; j < 3; ++j) {
      q[j] = f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2];
      if (std::fabs(q[j]) > hs_ + hc * f_.colsum[j] + margin_) return Relation::kOutside;
    }
    // Every voxel centre of the cell within `slack` of the moved cube (Chebyshev, source axes)
    // is accepted with margin: tol/2 in centre mode; in conservative mode a centre within
    // 0.28 (< (0.5 - 2 tol)/sqrt(3)) of the cube puts the voxel at distance < 0.5 - 2 tol, so the
    // voxel overlaps the cube by more than tol on every axis.
    const double slack = rounding_ == Rounding::kCenter ? 0.5 * kMotionTieTolerance : 0.28;
    const double hq = detail::halfSide(cell.level) - 0.5;
    for (int j = 0; j < 3; ++j) {
      if (!(std::fabs(q[j]) + hq * f_.colsum[j] <= hs_ + slack)) return Relation::kPartial;
    }
    return Relation::kInside;
  }

  // Mask of the voxel children of a level-1 cell that the moved cube turns black.
  std::uint8_t voxelMask(const Cube& cell) const {
    std::uint8_t mask = 0;
    for (int k = 0; k < 8; ++k) {
      if (detail::voxelAccepts(f_, rounding_, cell.child(k).origin, g_, hs_)) {
        mask = static_cast<std::uint8_t>(mask | (1u << k));
      }
    }
    return mask;
  }

  void insertChild(std::uint32_t parent, int k, const Cube& cell) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
    if (b_.node(parent).black & bit) return;  // already black: nothing to add
    if (cell.level == 0) {
      if (detail::voxelAccepts(f_, rounding_, cell.origin, g_, hs_)) {
        b_.node(parent).black = static_cast<std::uint8_t>(b_.node(parent).black | bit);
      }
      return;
    }
    const Relation rel = relation(cell);
    if (rel == Relation::kOutside) return;
    if (rel == Relation::kInside) {
      makeBlack(parent, k);
      return;
    }
    if (cell.level == 1) {
      // Colour the eight voxels at once: no split/condense churn at the bottom level.
      const std::uint8_t mask = voxelMask(cell);
      if (!mask) return;
      if (b_.node(parent).gray & bit) {
        const std::uint32_t c = b_.node(parent).child[static_cast<std::size_t>(k)];
        b_.node(c).black = static_cast<std::uint8_t>(b_.node(c).black | mask);
        b_.condense(parent, k);
      } else if (mask == 0xff) {
        b_.node(parent).black = static_cast<std::uint8_t>(b_.node(parent).black | bit);
      } else {
        const std::uint32_t c = b_.split(parent, k);
        b_.node(c).black = mask;
      }
      return;
    }
    const std::uint32_t c = b_.split(parent, k);
    for (int j = 0; j < 8; ++j) insertChild(c, j, cell.child(j));
    b_.condense(parent, k);  // condense at the earliest opportunity
  }

  // Child k of parent becomes black; a gray child's subtree is released bottom-up.
  void makeBlack(std::uint32_t parent, int k) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
    if (b_.node(parent).gray & bit) {
      const std::uint32_t c = b_.node(parent).child[static_cast<std::size_t>(k)];
      for (std::uint8_t g = b_.node(c).gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
        makeBlack(c, lowestBit(g));
      }
      b_.node(c).black = 0xff;
      b_.condense(parent, k);
    } else {
      b_.node(parent).black = static_cast<std::uint8_t>(b_.node(parent).black | bit);
    }
  }

  const MotionFrame& f_;
  OctreeBuilder& b_;
  Rounding rounding_;
  double margin_;
  double g_[3] = {0, 0, 0};
  double hs_ = 0;
};

}  // namespace

Octree moveTree(const Octree& source, const Eigen::Isometry3d& X_WS, const WorldGrid& target_grid,
                Rounding rounding, MoveStats* stats) {
  MotionFrame f = detail::makeMotionFrame(X_WS, source.grid(), target_grid, "moveTree");
  if (rounding == Rounding::kConservative) detail::addEdgeAxes(f);
  OctreeBuilder builder(target_grid);
  Inserter inserter(f, builder, rounding);
  // fdleaf: every black leaf of the source, in depth-first label order.
  source.forEachBlackLeaf([&](const Cube& leaf) { inserter.insertLeaf(leaf); });
  Octree out = builder.build();
  if (stats) {
    stats->black_leaves = out.blackLeafCount();
    stats->internal_nodes = out.internalNodeCount();
    stats->peak_nodes = builder.peakNodeCount();
    stats->clipped = inserter.clipped;
  }
  return out;
}

}  // namespace octomotion
