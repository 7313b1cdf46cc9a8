// Solid primitives the builders voxelize, each centred on the origin of its own frame S.
// A primitive is placed in the world by a pose X_WS (see voxelize.h).
#pragma once

#include <variant>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace octomotion {

// An upright box in its frame: |x| <= half_extents.x() etc.
struct Box {
  Eigen::Vector3d half_extents;
};

// A ball of the given radius about the frame origin.
struct Sphere {
  double radius;
};

// A solid cylinder whose axis is the frame's z axis: x^2 + y^2 <= radius^2, |z| <= length / 2.
struct Cylinder {
  double radius;
  double length;
};

using Primitive = std::variant<Box, Sphere, Cylinder>;

// Throws InvalidArgument naming the field (e.g. "Box.half_extents.y") when a size is zero,
// negative, NaN or infinite.
void validate(const Primitive& shape);

// Half sides of the shape's own box, centred on its frame and along its axes: the box
// itself, a ball's cube, a cylinder's square prism.
Eigen::Vector3d boxHalfSides(const Primitive& shape);

// Half sides of a box inside the shape, centred on its frame and along its axes: the box
// itself, a ball's inscribed cube, a cylinder's full length over the square inscribed in its
// disc (the largest cross-section a box can have there).
Eigen::Vector3d inscribedBoxHalfSides(const Primitive& shape);

// World-frame axis-aligned box of the shape placed at X_WS (exact for boxes and balls; for a
// cylinder, the box of its bounding box).
Eigen::AlignedBox3d boundingBox(const Primitive& shape, const Eigen::Isometry3d& X_WS);

// True when the point (in the shape frame S) is on or inside the shape.
bool containsPoint(const Primitive& shape, const Eigen::Vector3d& p_S);

}  // namespace octomotion
