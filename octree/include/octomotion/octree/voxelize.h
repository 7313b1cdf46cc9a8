// Builders: voxelize a primitive, a triangle mesh or a point set into a compact Octree.
//
// Each builder works top-down from the universe (Weng & Ahuja 1987 §4): every cube is classified
// against the object as inside / outside / partial, partial cubes are split, and level-0 voxels
// are decided by the rounding mode's per-voxel predicate:
//   - Rounding::kConservative: black iff the object meets the voxel's interior (the voxel shrunk
//     by 1e-6 voxel per side, the motion kernel's tie tolerance), so a solid's face lying on a
//     voxel boundary adds no voxels beyond it. Meshes add one rule, since a mesh need not bound
//     a solid: a voxel that a triangle only grazes (on its boundary, within the tie) is also
//     black unless a voxel sharing that part of its boundary has its centre inside the solid —
//     so every point of every triangle lies in a closed black voxel, also for double-sided
//     faces, open sheets and soups, whose parity finds no inside;
//   - Rounding::kCenter: black iff the voxel centre is on or inside the object (§3).
// The result equals that predicate applied to every voxel of the universe; the parts of the
// object outside the universe are dropped. The per-voxel tests are exact (up to floating-point
// rounding) for every primitive: box by the 15 separating axes, sphere by the nearest point,
// cylinder by clipping the voxel to the cylinder's slab and testing the projected polygon against
// the disc -- no over-approximation beyond rounding. Above level 0 "outside" and "inside" are
// only claimed with a 1e-7-voxel safety margin, so they never contradict the voxel rule.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/octree/shapes.h"

namespace octomotion {

// X_WS is the pose of the shape frame in the world. Throws InvalidArgument for a bad shape or a
// pose that is not finite or whose linear part is not a rotation.
Octree voxelize(const WorldGrid& grid, const Primitive& shape, const Eigen::Isometry3d& X_WS,
                Rounding rounding);

// The rule voxelize() applies to a single voxel (black or not), computed the same way the
// builder computes it at level 0. For tests and for checking single voxels; slow in bulk.
bool voxelIsBlack(const WorldGrid& grid, const Primitive& shape, const Eigen::Isometry3d& X_WS,
                  Rounding rounding, const Voxel& voxel);

// A closed mesh is voxelized solid: the object is the surface plus what it encloses, found by
// ray parity (so nested shells make cavities and orientation does not matter). "Closed" means
// every edge (vertices identified by position) is used by an even number of triangles -- every
// closed manifold (isClosedManifold), and also e.g. two solids sharing an edge or a closed mesh
// with a flipped triangle, for which parity is still well defined. A mesh whose every face is
// written twice (front and back, as SketchUp exports) is closed by that count but encloses
// nothing: it is its surface. Any other mesh (a hole, a dangling fin) is voxelized as the shell
// of voxels its triangles touch (including those they only touch on their boundary), whatever
// the rounding (a surface has no inside, so the centre rule would drop it), and a warning goes to
// `warnings`. In conservative rounding every point of every triangle lies in a closed black voxel.
// Throws InvalidArgument for an empty mesh, a bad index or vertex, or a bad pose.
Octree voxelizeMesh(const WorldGrid& grid, const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                    Rounding rounding, const WarningSink& warnings = {});

// Each point marks the voxel containing it (half-open voxels); points outside the universe are
// skipped. Throws InvalidArgument for a non-finite point.
Octree voxelizePoints(const WorldGrid& grid, const std::vector<Eigen::Vector3d>& points_W);

}  // namespace octomotion
