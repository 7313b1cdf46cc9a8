#include "octomotion/motion/primitive_contact.h"

#include <array>
#include <cmath>
#include <variant>

#include "octomotion/error.h"
#include "octomotion/motion/box_overlap.h"

namespace octomotion {

PrimitiveShape::PrimitiveShape(const Primitive& primitive)
    : kind_(std::holds_alternative<Box>(primitive)      ? Kind::kBox
            : std::holds_alternative<Sphere>(primitive) ? Kind::kBall
                                                        : Kind::kCylinder) {
  validate(primitive);
  const Eigen::Vector3d half = boxHalfSides(primitive);
  for (int i = 0; i < 3; ++i) a_[i] = half[i];
}

double PrimitiveShape::squaredDistance(const double p[3]) const {
  switch (kind_) {
    case Kind::kBox: {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) {
        const double d = std::fabs(p[i]) - a_[i];
        if (d > 0) d2 += d * d;
      }
      return d2;
    }
    case Kind::kBall: {
      const double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
      if (r2 <= a_[0] * a_[0]) return 0;
      const double d = std::sqrt(r2) - a_[0];
      return d * d;
    }
    case Kind::kCylinder:
    default: {
      const double dz = std::fabs(p[2]) - a_[2];
      const double axial = dz > 0 ? dz * dz : 0.0;
      const double rho2 = p[0] * p[0] + p[1] * p[1];
      if (rho2 <= a_[0] * a_[0]) return axial;
      const double d = std::sqrt(rho2) - a_[0];
      return d * d + axial;
    }
  }
}

namespace {

// A sphere's reach, grown by a relative 1e-9 so that rounding in the transform can only make
// the test say "meets" (the conservative side).
constexpr double kReachSlack = 1.0 + 1e-9;
// Deepest stack: at most 7 siblings wait on each of kMaxDepth + 1 levels, plus the node popped.
constexpr std::size_t kStackSize = 8 * (static_cast<std::size_t>(kMaxDepth) + 2);

// A black cube of `level` (centre p_P, axes the columns of R_PS, half side `half` metres) meets
// a ball or cylinder: at level 0 when its bounding sphere does; above, when its centre is in the
// shape (then so is a point of the voxel holding it) or one of its eight sub-cubes meets it.
// Every voxel of a black cube is black, so a yes is always a voxel's: the margin is a voxel's
// diagonal whatever the size of the leaf (a large leaf's sphere would reach much farther).
bool roundShapeMeetsCube(const PrimitiveShape& shape, const Eigen::Vector3d& p_P,
                         const Eigen::Matrix3d& R_PS, double half, int level) {
  const double d2 = shape.squaredDistance(p_P.data());
  const double reach = std::sqrt(3.0) * half * kReachSlack;
  if (d2 > reach * reach) return false;
  if (level == 0 || d2 == 0) return true;
  const double q = 0.5 * half;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d offset((k & 1) ? q : -q, (k & 2) ? q : -q, (k & 4) ? q : -q);
    if (roundShapeMeetsCube(shape, p_P + R_PS * offset, R_PS, q, level - 1)) return true;
  }
  return false;
}

}  // namespace

bool blackLeafMeetsPrimitive(const MovableSource& source, const Eigen::Isometry3d& X_PS,
                             const PrimitiveShape& shape) {
  const std::vector<MovableSource::Node>& nodes = source.nodes();
  if (nodes.empty()) return false;  // an empty (white) source
  // p_P = A u + b for u in the source's grid coordinates (voxels from its origin corner).
  const double s = source.grid().voxelSize();
  const Eigen::Matrix3d A = X_PS.linear() * s;
  const Eigen::Vector3d b = X_PS * source.grid().origin();
  auto place = [&](const double u[3], double p[3]) {
    for (int i = 0; i < 3; ++i) p[i] = A(i, 0) * u[0] + A(i, 1) * u[1] + A(i, 2) * u[2] + b[i];
  };
  auto nodeMeets = [&](const MovableSource::Node& n) {
    double p[3];
    place(n.centre, p);
    const double reach =
        s * std::sqrt(n.half[0] * n.half[0] + n.half[1] * n.half[1] + n.half[2] * n.half[2]) *
        kReachSlack;
    return shape.squaredDistance(p) <= reach * reach;
  };
  // A box obstacle is met exactly by a leaf whose sphere reaches it: the two boxes' separating
  // axes (with a margin of 1e-9 of the leaf, on the conservative side). A ball or cylinder by a
  // voxel-sized leaf whose sphere reaches it, or a larger leaf by roundShapeMeetsCube.
  auto leafMeetsBox = [&](const double p[3], const Eigen::Vector3d& half) {
    return boxesOverlap(Eigen::Vector3d::Zero(), shape.boxHalfExtents(), X_PS.linear(),
                        Eigen::Vector3d(p[0], p[1], p[2]), half, 1e-9 * half[0]);
  };
  if (!nodeMeets(nodes[0])) return false;
  std::array<std::uint32_t, kStackSize> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const MovableSource::Node& n = nodes[stack[--top]];
    const std::uint32_t child_side = std::uint32_t{1} << (n.level - 1);
    const double h = 0.5 * static_cast<double>(child_side);
    // A child cube's half diagonal is √3 h voxels.
    const double leaf_reach = s * h * std::sqrt(3.0) * kReachSlack;
    const double leaf_reach2 = leaf_reach * leaf_reach;
    const Eigen::Vector3d leaf_half = Eigen::Vector3d::Constant(s * h);
    for (int k = 0; k < 8; ++k) {
      const unsigned bit = 1u << k;
      if (!((n.black | n.gray) & bit)) continue;
      if (n.black & bit) {
        const double u[3] = {static_cast<double>(n.origin.x + ((k & 1) ? child_side : 0u)) + h,
                             static_cast<double>(n.origin.y + ((k & 2) ? child_side : 0u)) + h,
                             static_cast<double>(n.origin.z + ((k & 4) ? child_side : 0u)) + h};
        double p[3];
        place(u, p);
        if (shape.squaredDistance(p) > leaf_reach2) continue;
        if (shape.kind() == PrimitiveShape::Kind::kBox) {
          if (leafMeetsBox(p, leaf_half)) return true;
        } else if (n.level == 1 || roundShapeMeetsCube(shape, Eigen::Vector3d(p[0], p[1], p[2]),
                                                       X_PS.linear(), s * h, n.level - 1)) {
          return true;
        }
      } else {
        const std::uint32_t c = n.childIndex(k);
        if (nodeMeets(nodes[c])) stack[top++] = c;
      }
    }
  }
  return false;
}

}  // namespace octomotion
