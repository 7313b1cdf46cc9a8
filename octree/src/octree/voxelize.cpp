// Primitive and point-set builders. The top-down descent follows Weng & Ahuja (1987) §4: classify
// each upright cube against the object (inside / outside / partial), split partial cubes, decide
// voxels by the rounding rule, condense eight equal children at once.
#include "octomotion/octree/voxelize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

#include "internal/voxelize.h"

namespace octomotion {
namespace detail {

void validatePose(const Eigen::Isometry3d& X, const char* what) {
  if (!X.matrix().allFinite()) throw InvalidArgument(std::string(what) + ": pose is not finite");
  const Eigen::Matrix3d R = X.linear();
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= 1e-6) || !(R.determinant() > 0.0)) {
    throw InvalidArgument(std::string(what) +
                          ": linear part is not a rotation (orthonormal, determinant +1)");
  }
}

GridPose toGridPose(const WorldGrid& grid, const Eigen::Isometry3d& X_WS) {
  Eigen::Matrix3d R = X_WS.linear();
  // Already orthonormal to rounding (e.g. exact quarter turns): keep it bit for bit, so that
  // a face meant to lie on a voxel boundary stays on it.
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-15) {
    Eigen::Quaterniond q(R);
    q.normalize();
    R = q.toRotationMatrix();
  }
  const Eigen::Vector3d t = grid.toGrid(X_WS.translation());
  if (!t.allFinite()) throw InvalidArgument("pose: translation is too far out for this grid");
  return {R, t};
}

namespace {

// ---- Shapes in grid coordinates. Each offers:
//   touches(lo, hi)  closed box meets the solid (exact up to rounding);
//   inside(lo, hi)   closed box lies in the solid (exact or an under-estimate: only speed);
//   containsPoint(p) p on or in the solid.

// Oriented box: separating-axis test against the upright box (15 axes).
class GridBox {
 public:
  GridBox(const GridPose& pose, const Eigen::Vector3d& half) : R_(pose.R), c_(pose.t), h_(half) {
    // The tiny addition keeps near-parallel edge pairs (cross product ~ 0) from producing a
    // spurious separation out of rounding; it grows the box by < 1e-12 of its size.
    absR_ = R_.cwiseAbs().array() + 1e-12;
  }

  bool touches(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d e = 0.5 * (hi - lo);
    const Eigen::Vector3d T = c_ - 0.5 * (lo + hi);
    for (int i = 0; i < 3; ++i) {
      if (std::abs(T[i]) > e[i] + absR_.row(i).dot(h_)) return false;
    }
    const Eigen::Vector3d TB = R_.transpose() * T;
    for (int j = 0; j < 3; ++j) {
      if (std::abs(TB[j]) > absR_.col(j).dot(e) + h_[j]) return false;
    }
    for (int i = 0; i < 3; ++i) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      for (int j = 0; j < 3; ++j) {
        const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double ra = e[i1] * absR_(i2, j) + e[i2] * absR_(i1, j);
        const double rb = h_[j1] * absR_(i, j2) + h_[j2] * absR_(i, j1);
        if (std::abs(T[i2] * R_(i1, j) - T[i1] * R_(i2, j)) > ra + rb) return false;
      }
    }
    return true;
  }

  bool inside(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d e = 0.5 * (hi - lo);
    const Eigen::Vector3d q = R_.transpose() * (0.5 * (lo + hi) - c_);
    for (int j = 0; j < 3; ++j) {
      if (std::abs(q[j]) + R_.col(j).cwiseAbs().dot(e) > h_[j]) return false;
    }
    return true;
  }

  bool containsPoint(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = R_.transpose() * (p - c_);
    return std::abs(q.x()) <= h_.x() && std::abs(q.y()) <= h_.y() && std::abs(q.z()) <= h_.z();
  }

 private:
  Eigen::Matrix3d R_, absR_;
  Eigen::Vector3d c_, h_;
};

class GridSphere {
 public:
  GridSphere(const GridPose& pose, double radius) : c_(pose.t), r2_(radius * radius) {}

  bool touches(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d nearest = c_.cwiseMax(lo).cwiseMin(hi);
    return (nearest - c_).squaredNorm() <= r2_;
  }
  bool inside(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d far = (c_ - lo).cwiseAbs().cwiseMax((hi - c_).cwiseAbs());
    return far.squaredNorm() <= r2_;
  }
  bool containsPoint(const Eigen::Vector3d& p) const { return (p - c_).squaredNorm() <= r2_; }

 private:
  Eigen::Vector3d c_;
  double r2_;
};

// Solid cylinder, exact. The box meets the cylinder iff the part of the box inside the slab
// |z| <= H (cylinder frame), projected along the axis, meets the disc of radius r. That part is
// a convex polytope whose vertices are the box corners in the slab and the crossings of box
// edges with the planes z = +-H, so its projection is the convex hull of those points in 2D.
class GridCylinder {
 public:
  GridCylinder(const GridPose& pose, double radius, double half_length)
      : Rt_(pose.R.transpose()), c_(pose.t), r_(radius), r2_(radius * radius), H_(half_length) {
    axis_abs_ = Rt_.row(2).transpose().cwiseAbs();
  }

  bool containsPoint(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = Rt_ * (p - c_);
    return std::abs(q.z()) <= H_ && q.x() * q.x() + q.y() * q.y() <= r2_;
  }

  bool inside(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d e = 0.5 * (hi - lo);
    const Eigen::Vector3d q = Rt_ * (0.5 * (lo + hi) - c_);
    if (std::abs(q.z()) + axis_abs_.dot(e) > H_) return false;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d corner = q + Rt_ * signedHalf(e, k);
      if (corner.x() * corner.x() + corner.y() * corner.y() > r2_) return false;
    }
    return true;
  }

  bool touches(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d e = 0.5 * (hi - lo);
    const Eigen::Vector3d q = Rt_ * (0.5 * (lo + hi) - c_);
    if (std::abs(q.z()) > H_ + axis_abs_.dot(e)) return false;
    const double rho = e.norm();  // the box's circumradius bounds its distance from its centre
    const double radial2 = q.x() * q.x() + q.y() * q.y();
    if (radial2 > (r_ + rho) * (r_ + rho)) return false;
    if (std::abs(q.z()) <= H_ && radial2 <= r2_) return true;

    std::array<Eigen::Vector3d, 8> corner;
    for (int k = 0; k < 8; ++k) corner[static_cast<std::size_t>(k)] = q + Rt_ * signedHalf(e, k);
    std::array<Eigen::Vector2d, 32> pts;
    std::size_t n = 0;
    for (const Eigen::Vector3d& p : corner) {
      if (std::abs(p.z()) <= H_) {
        if (p.x() * p.x() + p.y() * p.y() <= r2_) return true;
        pts[n++] = p.head<2>();
      }
    }
    for (int a = 0; a < 8; ++a) {
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (a & bit) continue;
        const Eigen::Vector3d& p0 = corner[static_cast<std::size_t>(a)];
        const Eigen::Vector3d& p1 = corner[static_cast<std::size_t>(a | bit)];
        for (const double plane : {-H_, H_}) {
          const double d0 = p0.z() - plane, d1 = p1.z() - plane;
          if ((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
            const double t = d0 / (d0 - d1);
            const Eigen::Vector2d x = p0.head<2>() + t * (p1.head<2>() - p0.head<2>());
            if (x.squaredNorm() <= r2_) return true;
            pts[n++] = x;
          }
        }
      }
    }
    if (n == 0) return false;
    return hullMeetsDisc(pts.data(), n);
  }

 private:
  static Eigen::Vector3d signedHalf(const Eigen::Vector3d& e, int k) {
    return {(k & 1) ? e.x() : -e.x(), (k & 2) ? e.y() : -e.y(), (k & 4) ? e.z() : -e.z()};
  }

  static double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  }

  // Does the convex hull of the points (none of them in the disc) meet the disc at the origin?
  // Then either the origin is in the hull or a hull edge passes within r of it.
  bool hullMeetsDisc(Eigen::Vector2d* pts, std::size_t n) const {
    std::sort(pts, pts + n, [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    // Andrew's monotone chain, counter-clockwise.
    std::array<Eigen::Vector2d, 64> hull;
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
      hull[k++] = pts[i];
    }
    for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) {
      while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
      hull[k++] = pts[i];
    }
    if (k > 1) --k;  // the last point repeats the first
    const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    if (k >= 3) {
      bool inside = true;
      for (std::size_t i = 0; i < k && inside; ++i) {
        inside = cross(hull[i], hull[(i + 1) % k], origin) >= 0.0;
      }
      if (inside) return true;
    }
    for (std::size_t i = 0; i < k; ++i) {
      const Eigen::Vector2d& a = hull[i];
      const Eigen::Vector2d& b = hull[(i + 1) % k];
      const Eigen::Vector2d ab = b - a;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp(-a.dot(ab) / len2, 0.0, 1.0) : 0.0;
      if ((a + t * ab).squaredNorm() <= r2_) return true;
    }
    return false;
  }

  Eigen::Matrix3d Rt_;
  Eigen::Vector3d c_, axis_abs_;
  double r_, r2_, H_;
};

// ---- The descent.

template <class Shape>
class PrimitiveDescent {
 public:
  PrimitiveDescent(const Shape& shape, Rounding rounding)
      : shape_(shape),
        conservative_(rounding == Rounding::kConservative),
        shrink_(shrinkOf(rounding)) {}

  Overlap classify(const Cube& cube) const {
    const TestBox b = testBox(cube, shrink_, kInternalMargin);
    if (!shape_.touches(b.lo, b.hi)) return Overlap::kOutside;
    if (shape_.inside(b.lo, b.hi)) return Overlap::kInside;
    return Overlap::kPartial;
  }

  // The rounding rule for one voxel, exact.
  bool voxel(const Cube& v) const {
    const Eigen::Vector3d o(v.origin.x, v.origin.y, v.origin.z);
    if (conservative_) return shape_.touches(o.array() + kFaceTie, o.array() + (1.0 - kFaceTie));
    return shape_.containsPoint(o.array() + 0.5);
  }

  // `node` of `builder` stands for the partial cube `cube` (level >= 1); fills its children.
  void descend(OctreeBuilder& builder, std::uint32_t node, const Cube& cube) const {
    if (cube.level == 1) {
      std::uint8_t mask = 0;
      for (int k = 0; k < 8; ++k) {
        if (voxel(cube.child(k))) mask = static_cast<std::uint8_t>(mask | (1u << k));
      }
      builder.node(node).black = mask;
      return;
    }
    for (int k = 0; k < 8; ++k) {
      const Cube child = cube.child(k);
      const Overlap overlap = classify(child);
      if (overlap == Overlap::kInside) {
        OctreeBuilder::Node& n = builder.node(node);
        n.black = static_cast<std::uint8_t>(n.black | (1u << k));
      } else if (overlap == Overlap::kPartial) {
        const std::uint32_t c = builder.split(node, k);
        descend(builder, c, child);
        builder.condense(node, k);
      }
    }
  }

  Octree build(const WorldGrid& grid) const {
    const Cube universe = grid.universe();
    const Overlap overlap = classify(universe);
    if (overlap == Overlap::kOutside) return Octree(grid);
    if (overlap == Overlap::kInside) return Octree::full(grid);
    OctreeBuilder builder(grid);
    descend(builder, OctreeBuilder::kRoot, universe);
    return builder.build();
  }

 private:
  const Shape& shape_;
  bool conservative_;
  double shrink_;
};

// Calls f(shape-in-grid-coordinates) with the concrete shape class.
template <class F>
auto withGridShape(const WorldGrid& grid, const Primitive& shape, const Eigen::Isometry3d& X_WS,
                   F&& f) {
  const GridPose pose = toGridPose(grid, X_WS);
  const double inv = 1.0 / grid.voxelSize();
  if (const Box* box = std::get_if<Box>(&shape)) return f(GridBox(pose, box->half_extents * inv));
  if (const Sphere* sphere = std::get_if<Sphere>(&shape)) {
    return f(GridSphere(pose, sphere->radius * inv));
  }
  const Cylinder& cylinder = std::get<Cylinder>(shape);
  return f(GridCylinder(pose, cylinder.radius * inv, 0.5 * cylinder.length * inv));
}

}  // namespace
}  // namespace detail

Octree voxelize(const WorldGrid& grid, const Primitive& shape, const Eigen::Isometry3d& X_WS,
                Rounding rounding) {
  validate(shape);
  detail::validatePose(X_WS, "voxelize: X_WS");
  return detail::withGridShape(grid, shape, X_WS, [&](const auto& grid_shape) {
    using Shape = std::decay_t<decltype(grid_shape)>;
    return detail::PrimitiveDescent<Shape>(grid_shape, rounding).build(grid);
  });
}

bool voxelIsBlack(const WorldGrid& grid, const Primitive& shape, const Eigen::Isometry3d& X_WS,
                  Rounding rounding, const Voxel& voxel) {
  validate(shape);
  detail::validatePose(X_WS, "voxelIsBlack: X_WS");
  return detail::withGridShape(grid, shape, X_WS, [&](const auto& grid_shape) {
    using Shape = std::decay_t<decltype(grid_shape)>;
    return detail::PrimitiveDescent<Shape>(grid_shape, rounding).voxel(Cube{0, voxel});
  });
}

Octree voxelizePoints(const WorldGrid& grid, const std::vector<Eigen::Vector3d>& points_W) {
  std::vector<Voxel> voxels;
  voxels.reserve(points_W.size());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    if (!points_W[i].allFinite()) {
      throw InvalidArgument("voxelizePoints: points_W[" + std::to_string(i) + "] is not finite");
    }
    Voxel v;
    if (grid.voxelAt(points_W[i], &v)) voxels.push_back(v);
  }
  // Sorting first makes the builder's painting walk the tree in order and drops duplicates.
  std::sort(voxels.begin(), voxels.end(), [](const Voxel& a, const Voxel& b) {
    return a.z != b.z ? a.z < b.z : a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  voxels.erase(std::unique(voxels.begin(), voxels.end()), voxels.end());
  OctreeBuilder builder(grid);
  for (const Voxel& v : voxels) builder.setVoxel(v);
  return builder.build();
}

}  // namespace octomotion
