// Private to the planner library: the environment tree's region-wise rebuild for world updates
// (OctreeCollisionModel::addObject and the others): only the voxels an update touches are
// voxelized again, the rest of the tree is copied.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "octomotion/octree/octree.h"

namespace octomotion::detail {

// The voxels of `grid` a black voxel of an object inside `box_W` can occupy (those the box
// meets, under any rounding), grown by one voxel against floating-point ties; nullopt when the
// box misses the universe or is empty.
std::optional<VoxelBounds> touchedVoxels(const WorldGrid& grid, const Eigen::AlignedBox3d& box_W);
// The smallest voxel box holding both.
VoxelBounds merge(const VoxelBounds& a, const VoxelBounds& b);
bool overlap(const VoxelBounds& a, const VoxelBounds& b);

// `outside`'s voxels outside `region` and `inside`'s voxels in it (inclusive bounds), as one
// compact tree; both trees on the same grid (InvalidArgument otherwise). Costs a copy of the
// trees' nodes: nothing is voxelized.
Octree spliceRegion(const Octree& outside, const Octree& inside, const VoxelBounds& region);

}  // namespace octomotion::detail
