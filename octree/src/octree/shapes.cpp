#include "octomotion/octree/shapes.h"

#include <cmath>
#include <string>

#include "octomotion/error.h"

namespace octomotion {
namespace {

void requirePositive(double value, const char* field) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw InvalidArgument(std::string(field) + " must be finite and > 0, got " +
                          std::to_string(value));
  }
}

}  // namespace

void validate(const Primitive& shape) {
  if (const Box* box = std::get_if<Box>(&shape)) {
    requirePositive(box->half_extents.x(), "Box.half_extents.x");
    requirePositive(box->half_extents.y(), "Box.half_extents.y");
    requirePositive(box->half_extents.z(), "Box.half_extents.z");
  } else if (const Sphere* sphere = std::get_if<Sphere>(&shape)) {
    requirePositive(sphere->radius, "Sphere.radius");
  } else if (const Cylinder* cylinder = std::get_if<Cylinder>(&shape)) {
    requirePositive(cylinder->radius, "Cylinder.radius");
    requirePositive(cylinder->length, "Cylinder.length");
  }
}

bool containsPoint(const Primitive& shape, const Eigen::Vector3d& p_S) {
  if (const Box* box = std::get_if<Box>(&shape)) {
    return (p_S.cwiseAbs().array() <= box->half_extents.array()).all();
  }
  if (const Sphere* sphere = std::get_if<Sphere>(&shape)) {
    return p_S.squaredNorm() <= sphere->radius * sphere->radius;
  }
  const Cylinder& cylinder = std::get<Cylinder>(shape);
  return std::abs(p_S.z()) <= 0.5 * cylinder.length &&
         p_S.x() * p_S.x() + p_S.y() * p_S.y() <= cylinder.radius * cylinder.radius;
}

Eigen::Vector3d boxHalfSides(const Primitive& shape) {
  if (const auto* box = std::get_if<Box>(&shape)) return box->half_extents;
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    return Eigen::Vector3d::Constant(ball->radius);
  }
  const auto& rod = std::get<Cylinder>(shape);
  return Eigen::Vector3d(rod.radius, rod.radius, rod.length / 2);
}

Eigen::Vector3d inscribedBoxHalfSides(const Primitive& shape) {
  if (const auto* box = std::get_if<Box>(&shape)) return box->half_extents;
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    return Eigen::Vector3d::Constant(ball->radius / std::sqrt(3.0));
  }
  const auto& rod = std::get<Cylinder>(shape);
  const double side = rod.radius / std::sqrt(2.0);
  return Eigen::Vector3d(side, side, rod.length / 2);
}

Eigen::AlignedBox3d boundingBox(const Primitive& shape, const Eigen::Isometry3d& X_WS) {
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    // A ball's box does not depend on the rotation.
    const Eigen::Vector3d c = X_WS.translation();
    return Eigen::AlignedBox3d(c.array() - ball->radius, c.array() + ball->radius);
  }
  // |R| h is the half-size of the rotated box's box.
  const Eigen::Vector3d world_half = X_WS.linear().cwiseAbs() * boxHalfSides(shape);
  return Eigen::AlignedBox3d(X_WS.translation() - world_half, X_WS.translation() + world_half);
}

}  // namespace octomotion
