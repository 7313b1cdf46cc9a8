// Euclidean distance from a point to the black voxels of a tree.
#pragma once

#include <Eigen/Core>

#include "octomotion/octree/octree.h"

namespace octomotion {

// min(best, distance in metres from p_W to the nearest black voxel of `tree`), the voxels taken as
// closed boxes (0 on or inside one): `best` unchanged when no black voxel is closer than it, and
// for an empty tree. Depth-first branch and bound over the tree: a subtree is skipped when its
// cube is at least `best` away, so a small `best` (the distance to beat) prunes most of it.
double distanceToBlack(const Octree& tree, const Eigen::Vector3d& p_W, double best);

}  // namespace octomotion
