// Certified separation of two convex sets, each the convex hull of its points grown by a radius
// (a mesh's vertices, a box's corners, a ball's centre), by GJK (Gilbert, Johnson & Keerthi
// 1988) on their Minkowski difference. GJK only proposes a direction; the answer "apart" rests
// on the two support values computed for that direction over every point, so a plane between
// the sets is proven whatever the iteration did. Used by exact refine mode to clear a robot
// link pair before any voxel or mesh test: two meshes whose vertex hulls are apart cannot share
// a triangle contact.
#pragma once

#include <vector>

#include <Eigen/Geometry>

namespace octomotion {

class ConvexPoints {
 public:
  ConvexPoints() = default;
  // The hull of `points` grown by `radius` (>= 0). Throws InvalidArgument when empty.
  explicit ConvexPoints(const std::vector<Eigen::Vector3d>& points, double radius = 0);

  bool empty() const { return x_.empty(); }
  std::size_t size() const { return x_.size(); }
  double radius() const { return radius_; }
  Eigen::Vector3d point(std::size_t i) const { return {x_[i], y_[i], z_[i]}; }
  // A point of the (ungrown) hull that maximises d . p: one of the points.
  std::size_t supportIndex(const Eigen::Vector3d& d) const;
  const Eigen::Vector3d& centroid() const { return centroid_; }

 private:
  std::vector<double> x_, y_, z_;  // split by coordinate: the support loop vectorises
  double radius_ = 0;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
};

// True only when a plane leaves `a` and `b` (b placed in a's frame by X_AB) more than `gap`
// apart: every point of a at least `gap` from every point of b along that plane's normal.
// False when they overlap, are closer than `gap`, or GJK gives up (it stops after a fixed number
// of iterations): false never claims a contact. `direction_A`, when given, starts the search
// (a direction from b towards a, e.g. the one a previous call returned) and receives the
// separating one on success.
bool convexApart(const ConvexPoints& a, const ConvexPoints& b, const Eigen::Isometry3d& X_AB,
                 double gap, Eigen::Vector3d* direction_A = nullptr);

}  // namespace octomotion
