// Internals shared by the builders (voxelize.cpp, voxelize_mesh.cpp). Everything here works in
// continuous grid coordinates: one unit per voxel, 0 at the universe's minimum corner, so a cube
// of level L with integer origin o spans [o, o + 2^L] exactly.
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "octomotion/motion/pose.h"
#include "octomotion/octree/octree_builder.h"
#include "octomotion/octree/rounding.h"

namespace octomotion::detail {

enum class Overlap { kOutside, kInside, kPartial };

// Internal-level tests are made on the test box grown by this margin (grid units), so that an
// "outside" or "inside" verdict above level 0 holds even if the exact level-0 predicate rounds
// the other way on a voxel that only grazes the object. Coordinates are below 2^21 voxels, where
// a double's spacing is < 5e-10, so 1e-7 covers several roundings of every transform.
inline constexpr double kInternalMargin = 1e-7;

// Conservative rounding: a voxel is black when the object meets its interior, i.e. the voxel
// shrunk by kFaceTie per side (grid units; the motion kernel's tie tolerance,
// kMotionTieTolerance). A face that lies on a voxel boundary, as the faces of a box authored at
// round coordinates do in a grid whose origin is at another of its faces, then adds no layer
// beyond it (the closed voxel added a whole voxel there, the largest margin any face gets); an
// object that reaches into a voxel by more than 1e-6 voxel still blackens it, so contacts are
// kept up to that tie, as the moved trees keep them.
inline constexpr double kFaceTie = kMotionTieTolerance;

// The box a cube is tested with. Conservative: the closed cube itself. Centre: the box spanned by
// the centres of its voxels (the cube shrunk by half a voxel per side), so "box touches object"
// = "some voxel centre is in the object" for convex objects and "box inside object" = "every
// centre is" (Weng & Ahuja 1987 §4, Relation B's smaller cube q). At level 0 the centre box is
// the voxel centre point.
struct TestBox {
  Eigen::Vector3d lo, hi;
};

inline double shrinkOf(Rounding rounding) {
  return rounding == Rounding::kCenter ? 0.5 : 0.0;
}

inline TestBox testBox(const Cube& cube, double shrink, double margin) {
  const Eigen::Vector3d o(cube.origin.x, cube.origin.y, cube.origin.z);
  const double s = static_cast<double>(cube.side());
  const double grow = margin - shrink;
  return {o.array() - grow, o.array() + s + grow};
}

// Throws InvalidArgument naming `what` unless X is finite with a proper rotation (orthonormal to
// 1e-6, determinant +1) as its linear part.
void validatePose(const Eigen::Isometry3d& X, const char* what);

// The same rigid pose, re-orthonormalised (so SAT formulas that assume orthonormal axes hold to
// the last bit), expressed from the shape frame to grid coordinates (rotation unchanged,
// translation and lengths divided by the voxel size).
struct GridPose {
  Eigen::Matrix3d R;  // columns: shape axes in the grid (= world) frame
  Eigen::Vector3d t;  // shape origin in grid coordinates
};
GridPose toGridPose(const WorldGrid& grid, const Eigen::Isometry3d& X_WS);

}  // namespace octomotion::detail
