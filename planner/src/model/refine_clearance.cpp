// RefineMode::kExact's distances for the certified motion validator
// (OctreeCollisionModel::refineClearancesPerLink, refinedPairDistance), on the links (and
// pairs) whose cheaper bound is below what the validator needs. The validator needs only lower
// bounds: the distance between convex hulls holding the geometry (a link's hull holds its
// triangles, a primitive obstacle is its own hull or lies in its outer hull) is one, certified
// by convexDistanceBelow, and costs a GJK run. It is the answer unless it is within a fraction
// of a voxel of contact: there FCL's distance between the meshes decides, where a hull wraps
// around an object (an open gripper around a grasped box) or the geometry nearly touches.
#include <algorithm>
#include <cstddef>
#include <variant>

#include "internal/refine.h"

namespace octomotion {

namespace detail {

ConvexPoints primitiveHull(const Primitive& shape) {
  if (const auto* box = std::get_if<Box>(&shape)) return boxHull(box->half_extents);
  if (const auto* ball = std::get_if<Sphere>(&shape)) return ballHull(ball->radius);
  const auto& cylinder = std::get<Cylinder>(shape);
  return cylinderHull(cylinder.radius, cylinder.length);
}

namespace {

// Hull bounds above this are the answer even below what was asked. Below it the validator is
// near its minimum travel (a sixteenth of the resolution), where a bound looser than FCL's
// distance (hulls overlapping around an object, concave links) would reject edges FCL proves.
double hullTrusted(const WorldGrid& grid) {
  return grid.voxelSize() / 8;
}
// Against a primitive obstacle, whose hull is the shape itself or tight around it, a link's
// hull distance differs from FCL's only where the link's hull is loose (a concave part facing
// the obstacle), and it is trusted down to a 64th of a voxel: nearer contact than the validator's
// minimum travel, where FCL's distance would cost more than the bisection it saves.
double hullTrusted(const WorldGrid& grid, const RefineObject& object) {
  return object.primitive ? grid.voxelSize() / 64 : hullTrusted(grid);
}

// GJK's stopping tolerance for the validator's hull distances (convexDistanceBelow): a bound
// within 1 % of the hulls' distance costs a little bisection, and GJK's last iterations
// (rounded shapes converge slowly) cost more.
constexpr double kHullTolerance = 1e-2;

// A lower bound on the distance from `link`'s elements to the environment's objects, or `cap`
// when at least `cap`: per object, the hulls' bound when it reaches the best so far or is above
// the object's hullTrusted, else FCL's distance.
double refineLinkDistance(const RefineData& data, RefineScratch& r, const RobotData& robot,
                          int link, double cap, const WorldGrid& grid) {
  const ConvexPoints& hull_L = data.link_hulls_L[static_cast<std::size_t>(link)];
  const Eigen::Isometry3d& X_WL = robot.linkPose(link);
  // The link's hull lies in this ball: most objects are farther than it is from what is asked.
  const Eigen::Vector3d centre_W = X_WL * hull_L.centroid();
  const double reach = hull_L.reach() + hull_L.radius();
  bool posed = false;
  double best = cap;
  const std::size_t objects = data.objects.size();
  for (std::size_t i = 0; i < objects; ++i) {
    const RefineObject& object = data.objects[i];
    if (object.shapes.empty()) continue;
    if (!hull_L.empty()) {
      if (distanceToBox(object.box_W, centre_W) - reach >= best) continue;
      if (!object.hull_O.empty()) {
        Eigen::Vector3d& direction_O =
            r.link_object_directions[static_cast<std::size_t>(link) * objects + i];
        const double h = convexDistanceBelow(object.hull_O, hull_L, object.X_OW * X_WL, best,
                                             &direction_O, kHullTolerance);
        if (h >= best || h > hullTrusted(grid, object)) {
          ++r.hull_distances;
          best = std::min(best, h);
          continue;
        }
      }
    }
    if (!posed) {
      refinePoseLink(data, r, robot, link);
      posed = true;
    }
    for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
      const fcl::CollisionObjectd& element = r.fcl.objects[e];
      if (object.box_W.distance(element.getAABB()) >= best) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        ++r.fcl_distances;
        best = fcl_internal::distanceBelow(element, shape, best);
        if (best <= 0) return 0;
      }
    }
  }
  return best;
}

}  // namespace
}  // namespace detail

void OctreeCollisionModel::refineClearancesPerLink(const CheckScratch& scratch, const double* caps,
                                                   double* per_link) const {
  if (!refine_) return;
  // Farther than two voxels the grid's bound is within its own looseness of the distance, and
  // a tighter bound costs more than the bisection the looser one asks for.
  const double near = 2 * grid().voxelSize();
  detail::RefineScratch* r = nullptr;  // made on the first link asked
  for (int l = 0; l < robot_.linkCount(); ++l) {
    if (caps[l] <= 0 || per_link[l] >= caps[l] || per_link[l] >= near ||
        !robot_.link(l).hasCollision()) {
      continue;
    }
    if (r == nullptr) r = &detail::refineScratch(*refine_, robot_, id_, scratch.refine);
    per_link[l] = std::max(
        per_link[l], detail::refineLinkDistance(*refine_, *r, scratch.robot, l, caps[l], grid()));
  }
}

double OctreeCollisionModel::refinedPairDistance(const CheckScratch& scratch, int link_a,
                                                 int link_b, double cap) const {
  if (!refine_) return 0.0;
  detail::RefineScratch& r = detail::refineScratch(*refine_, robot_, id_, scratch.refine);
  const ConvexPoints& hull_a = refine_->link_hulls_L[static_cast<std::size_t>(link_a)];
  const ConvexPoints& hull_b = refine_->link_hulls_L[static_cast<std::size_t>(link_b)];
  if (!hull_a.empty() && !hull_b.empty()) {
    const Eigen::Isometry3d X_AB =
        scratch.robot.linkPose(link_a).inverse() * scratch.robot.linkPose(link_b);
    const double h =
        convexDistanceBelow(hull_a, hull_b, X_AB, cap, nullptr, detail::kHullTolerance);
    if (h >= cap || h > detail::hullTrusted(grid())) {
      ++r.hull_distances;
      return std::min(h, cap);
    }
  }
  detail::refinePoseLink(*refine_, r, scratch.robot, link_a);
  detail::refinePoseLink(*refine_, r, scratch.robot, link_b);
  double best = cap;
  for (std::size_t a : refine_->link_elements[static_cast<std::size_t>(link_a)]) {
    for (std::size_t b : refine_->link_elements[static_cast<std::size_t>(link_b)]) {
      ++r.fcl_distances;
      best = fcl_internal::distanceBelow(r.fcl.objects[a], r.fcl.objects[b], best);
      if (best <= 0) return 0;
    }
  }
  return best;
}

}  // namespace octomotion
