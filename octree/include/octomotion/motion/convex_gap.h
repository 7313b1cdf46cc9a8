// Certified separation of two convex sets, each the convex hull of its points grown by a radius
// (a mesh's vertices, a box's corners, a ball's centre), by GJK (Gilbert, Johnson & Keerthi
// 1988) on their Minkowski difference. GJK only proposes a direction; the answer "apart" rests
// on the two support values computed for that direction over every point, so a plane between
// the sets is proven whatever the iteration did. Used by exact refine mode to clear a robot
// link pair before any voxel or mesh test: two meshes whose vertex hulls are apart cannot share
// a triangle contact. The same certificate bounds their distance from below
// (convexDistanceBelow), with hulls of the scene's primitives (boxHull, ballHull, cylinderHull).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/motion/point_clusters.h"

namespace octomotion {

class ConvexPoints {
 public:
  ConvexPoints() = default;
  // The hull of `points` grown by `radius` (>= 0). Throws InvalidArgument when empty.
  explicit ConvexPoints(const std::vector<Eigen::Vector3d>& points, double radius = 0);
  // The same, with the edges of triangles over the points (a mesh's): support points are then
  // found by climbing along edges, which for a convex mesh visits a few points instead of all.
  // Any triangles are accepted (a non-convex mesh only makes the climb stop short, and
  // convexApart checks every answer over all points). Throws InvalidArgument for an index out
  // of range.
  ConvexPoints(const std::vector<Eigen::Vector3d>& points,
               const std::vector<std::array<std::uint32_t, 3>>& triangles, double radius = 0);

  bool empty() const { return x_.empty(); }
  std::size_t size() const { return x_.size(); }
  double radius() const { return radius_; }
  Eigen::Vector3d point(std::size_t i) const { return {x_[i], y_[i], z_[i]}; }
  // A point of the (ungrown) hull that maximises d . p: one of the points.
  std::size_t supportIndex(const Eigen::Vector3d& d) const;
  // From the support point of the cell of 384 fixed directions that d falls in (climbStart), the
  // neighbour that is highest along d, as long as one is higher than the current point: a support
  // point when the points are a convex mesh's vertices, a local maximum otherwise. supportIndex
  // when there are no edges.
  std::size_t climbSupport(const Eigen::Vector3d& d) const;
  bool hasEdges() const { return !neighbours_.empty(); }
  // The hull of `points` grown by `radius`, kept as its boundary's vertices and edges
  // (convexHullTriangles): a climb along them then finds the support exactly (a closed convex
  // surface), with no search over every point (exactClimb). Points inside are dropped; one that
  // rounding leaves outside the surface grows the radius by twice its distance to it. Without a
  // hull (flat sets, more than kMaxHullPoints) it is ConvexPoints(points, radius).
  static ConvexPoints hullOf(const std::vector<Eigen::Vector3d>& points, double radius = 0);
  // Whether climbSupport finds the support of every point (a hull, or no edges to climb).
  bool exactClimb() const { return exact_climb_ || neighbours_.empty(); }
  // A support point found exactly: by climbing when that is exact, else over every point.
  std::size_t exactSupport(const Eigen::Vector3d& d) const {
    return exact_climb_ ? climbSupport(d) : supportIndex(d);
  }
  const Eigen::Vector3d& centroid() const { return centroid_; }
  // The largest distance from the centroid to a point: the grown hull lies in the ball of
  // radius reach() + radius() around the centroid.
  double reach() const { return reach_; }

 private:
  std::vector<double> x_, y_, z_;  // split by coordinate: the support loop vectorises
  // Many points come in clusters of nearby ones (clusterPoints), contiguous in x_, y_, z_:
  // supportIndex skips a cluster whose bound d . centre + |d| radius cannot beat the best point
  // found.
  std::vector<PointCluster> clusters_;
  // Stores the points, clustered when many; returns each given point's index.
  std::vector<std::uint32_t> store(const std::vector<Eigen::Vector3d>& points);
  std::size_t supportIndexIn(const Eigen::Vector3d& d, std::size_t begin, std::size_t end,
                             double& value) const;
  // Neighbours of point i: neighbours_[first_[i] .. first_[i + 1]).
  std::vector<std::uint32_t> first_, neighbours_;
  // With edges: where climbs start (climbStart), by the cell of the cube of directions that
  // the direction crosses (6 faces of kStartCells x kStartCells cells): the support point of the
  // direction through the cell's centre, a few steps from the direction's own on a hull.
  static constexpr int kStartCells = 8;
  std::array<std::uint32_t, 6 * kStartCells * kStartCells> start_{};
  std::size_t climbStart(const Eigen::Vector3d& d) const;
  double radius_ = 0;
  bool exact_climb_ = false;
  // boxHull's corners, in boxCorners' order: the support's index is the signs of d.
  bool box_corners_ = false;
  friend ConvexPoints boxHull(const Eigen::Vector3d& half_extents);
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  double reach_ = 0;
};

// True only when a plane leaves `a` and `b` (b placed in a's frame by X_AB) more than `gap`
// apart: every point of a at least `gap` from every point of b along that plane's normal.
// False when they overlap, are closer than `gap`, or GJK gives up (it stops after a fixed number
// of iterations): false never claims a contact. `direction_A`, when given, starts the search
// (a direction from b towards a, e.g. the one a previous call returned) and receives the
// separating one on success.
bool convexApart(const ConvexPoints& a, const ConvexPoints& b, const Eigen::Isometry3d& X_AB,
                 double gap, Eigen::Vector3d* direction_A = nullptr);

// A certified lower bound (>= 0) on the distance between `a` and `b` (b placed in a's frame by
// X_AB): the width of the slab between them along the best of GJK's directions, taken over
// every point of both sets, less their radii and a nanometre for rounding. GJK only proposes the
// direction, so a wrong or unfinished run makes the bound smaller, never too large. 0 when they
// overlap. GJK stops early once the bound reaches `cap`; otherwise it runs until the distance is
// found to about `tolerance` relative (GJK's upper bound on the distance within that fraction of
// its lower one), so for convex sets the bound is their distance up to that. `direction_A`, when
// given and non-zero, is tried first (an earlier answer's direction: its slab over every point
// is the answer when it reaches `cap`, else GJK runs as without it) and receives the bound's
// direction.
double convexDistanceBelow(const ConvexPoints& a, const ConvexPoints& b,
                           const Eigen::Isometry3d& X_AB, double cap,
                           Eigen::Vector3d* direction_A = nullptr, double tolerance = 1e-9);

// The points of exact or outer hulls of primitive solids, in the solid's frame (centred, a
// cylinder along z), for convexDistanceBelow: a distance to them never exceeds the distance to
// the solid. A box: its 8 corners (exact, boxCorners). A ball: its centre grown by the radius
// (exact). A cylinder: two regular `sides`-gons circumscribing its end discs (an outer hull, wider
// than the cylinder by at most radius * (1 / cos(pi / sides) - 1)). Throw InvalidArgument for a
// non-finite or negative size, or fewer than 3 sides.
ConvexPoints boxHull(const Eigen::Vector3d& half_extents);
// The 8 corners of the box of these half extents about the origin, corner k at
// (+-x, +-y, +-z) with the sign of each axis from bit 0, 1, 2 of k (set: +).
std::array<Eigen::Vector3d, 8> boxCorners(const Eigen::Vector3d& half_extents);
ConvexPoints ballHull(double radius);
ConvexPoints cylinderHull(double radius, double length, int sides = 32);

}  // namespace octomotion
