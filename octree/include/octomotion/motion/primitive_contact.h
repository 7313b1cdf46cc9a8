// Exact obstacles for the last step of a conservative query: does a moved source tree come near
// a primitive (box, ball, cylinder) itself, rather than near the primitive's voxels?
//
// A conservative voxel query carries two margins: the moved source's voxels reach up to a
// voxel diagonal beyond the object, and the obstacle's voxels up to one beyond the obstacle.
// When the obstacle is a primitive its exact shape is known, so a contact the voxel query
// reports can be confirmed against the shape with the source's own black leaves (which are
// finer than the world's voxels for the planner's link trees): the obstacle's margin is gone
// and only the leaves' remains. The test is conservative — a leaf that overlaps the shape is
// always found (its bounding sphere meets the shape) — so a caller that answers "in contact"
// only when both the voxel query and this test say so never misses a contact that either would
// have found.
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
  double a_[3];  // box: half extents; ball: radius; cylinder: radius, half length
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
