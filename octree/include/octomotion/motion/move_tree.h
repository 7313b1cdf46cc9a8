// Octrees of objects in arbitrary motion (Weng & Ahuja 1987 §4): the target tree of a source
// tree moved by a rigid pose, built leaf by leaf with Relation B tests and condensation at the
// earliest opportunity. Time and space O(K n) on average (Theorem 3).
#pragma once

#include <cstddef>

#include <Eigen/Geometry>

#include "octomotion/motion/pose.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"

namespace octomotion {

// Table 2's counters for one moveTree call.
struct MoveStats {
  std::size_t black_leaves = 0;    // B: black leaves of the target tree
  std::size_t internal_nodes = 0;  // I: internal nodes of the target tree
  std::size_t peak_nodes = 0;      // M: most builder nodes alive at once (its root included)
  bool clipped = false;            // some moved black cube reached outside the target universe
};

// The source tree (on its own grid, origin in frame S, voxel size possibly different from the
// target's) moved by X_WS onto `target_grid`. A target voxel is black iff
//   kCenter:       its centre is on or inside some moved black cube (§3, within
//                  kMotionTieTolerance);
//   kConservative: it overlaps some moved black cube by more than kMotionTieTolerance on every
//                  separating axis (exact box/box test; face contact alone does not count, so
//                  the identity pose reproduces the tree instead of dilating it).
// Parts moved outside the target universe are dropped (stats->clipped is set); nothing wraps.
// Throws InvalidArgument for an invalid pose (see validatePose). Apply every pose to the
// source tree (use compose for successive motions), never to a moved tree.
Octree moveTree(const Octree& source, const Eigen::Isometry3d& X_WS, const WorldGrid& target_grid,
                Rounding rounding, MoveStats* stats = nullptr);

}  // namespace octomotion
