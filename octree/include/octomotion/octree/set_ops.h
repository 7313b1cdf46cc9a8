// Boolean operations on two trees of the same grid, each producing a compact tree.
#pragma once

#include "octomotion/octree/octree.h"

namespace octomotion {

// Throw InvalidArgument if the grids differ.
Octree unite(const Octree& a, const Octree& b);
Octree intersect(const Octree& a, const Octree& b);

}  // namespace octomotion
