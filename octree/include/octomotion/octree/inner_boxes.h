// A few large axis-aligned boxes that lie entirely inside a tree's black voxels: a solid core of
// the object, in its grid's frame. Where such a box overlaps a solid obstacle with room to
// spare, every voxelization of the two that keeps the voxels they overlap (conservative
// rounding) shares a black voxel: a collision is certain without a traversal. The planner tests
// links' cores against box obstacles this way before the tree query (docs/planner.md).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "octomotion/octree/octree.h"

namespace octomotion {

struct InnerBoxOptions {
  int max_boxes = 3;
  // The boxes are made of cells of the finest level whose grid has at most this many cells per
  // axis (entirely black cells only): coarser cells, faster build, smaller boxes.
  int max_cells_per_axis = 64;
  // A box is kept only if it is at least this many cells thick on every axis.
  int min_cells = 2;
};

// Boxes (in the coordinates of tree.grid(), metres) whose every point lies in a black voxel of
// `tree`, in the order found: each grows from the cell deepest inside the black region (L-inf
// distance to the nearest cell that is not entirely black) among those no earlier box covers,
// a layer at a time on every face that stays black. Empty when no box is thick enough.
// Deterministic. Throws InvalidArgument for options below 1.
std::vector<Eigen::AlignedBox3d> innerBoxes(const Octree& tree,
                                            const InnerBoxOptions& options = {});

}  // namespace octomotion
