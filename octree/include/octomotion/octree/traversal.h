// Simultaneous (parallel) traversal of two trees on one grid (Ahuja & Nash 1984 §5, citing
// Ahuja et al. 1980): both trees are walked together and `a.occupied & b.occupied` skips every
// pair of disjoint subtrees in one instruction, so the cost follows the nodes the trees share.
#pragma once

#include <vector>

#include "octomotion/octree/octree.h"

namespace octomotion {

// True iff some voxel is black in both trees. Throws InvalidArgument if the grids differ.
bool intersects(const Octree& a, const Octree& b);

// The black cubes of a ∩ b, as the leaves of the compact intersection tree would be (maximal
// cubes, depth-first label order). Empty iff !intersects(a, b).
std::vector<Cube> overlappingCubes(const Octree& a, const Octree& b);

}  // namespace octomotion
