// A source tree against an exact primitive (box, ball, cylinder), instead of against the
// primitive's voxels.
//
// A conservative voxel query carries two margins: the placed source's voxels reach up to a
// voxel diagonal beyond the object, and the obstacle's voxels up to one beyond the obstacle.
// When the obstacle is a primitive its shape is known, so the source's own black voxels can be
// tested against the shape itself: the obstacle's margin is gone and only the source voxels'
// remains (a voxel diagonal). The test is conservative — every black voxel that overlaps the
// shape is found — so, with the source voxelized conservatively, no contact of the object with
// the shape is missed. The planner uses it for the scene's primitives under
// `octree.exact_primitives` (docs/planner.md, "Exact primitives").
#pragma once

#include <cstdint>

#include <Eigen/Geometry>

#include "octomotion/motion/collides.h"
#include "octomotion/octree/shapes.h"

namespace octomotion {

// A primitive in its own frame P (centred at P's origin; a cylinder's axis is P's z), with the
// squared distance from a point to it precomputed for the per-leaf loop.
class PrimitiveShape {
 public:
  enum class Kind : std::uint8_t { kBox, kBall, kCylinder };
  explicit PrimitiveShape(const Primitive& primitive);
  Kind kind() const { return kind_; }

  // Squared Euclidean distance from p_P to the solid (0 inside or on it).
  double squaredDistance(const double p_P[3]) const;
  // kBox: its half extents.
  Eigen::Vector3d boxHalfExtents() const { return {a_[0], a_[1], a_[2]}; }

 private:
  Kind kind_;
  double a_[3];  // the shape's own box's half sides (boxHalfSides): a ball's radius in a_[0],
                 // a cylinder's radius in a_[0] and half length in a_[2]
};

// True iff a black voxel of `source`, placed in P by X_PS (the pose of the source tree's frame —
// the frame its grid is laid out in — in the primitive's frame), meets `shape`: exactly for a
// box (separating axes of the leaf cube and the box), and for a ball or cylinder when the
// voxel's bounding sphere meets it (a larger black leaf answers yes when its centre is in the
// shape, else by its sub-cubes). Every voxel that overlaps the shape is found, so a yes for a
// leaf that does not overlap it means a black voxel within (√3 − 1)/2 of its side of the
// shape; every black voxel overlaps the object (conservative rounding), so the object is then
// within a voxel diagonal of the shape. Gray nodes are pruned by the bounding sphere of the box
// of their black voxels. Allocation-free, const, thread-safe.
bool blackLeafMeetsPrimitive(const MovableSource& source, const Eigen::Isometry3d& X_PS,
                             const PrimitiveShape& shape);

}  // namespace octomotion
