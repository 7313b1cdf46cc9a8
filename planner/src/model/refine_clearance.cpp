// RefineMode::kExact's distances for the certified motion validator
// (OctreeCollisionModel::refineClearancesPerLink, refinedPairDistance), on the links (and
// pairs) whose cheaper bound is below what the validator needs. The validator needs only lower
// bounds: the distance between convex hulls holding the geometry (a link's hull holds its
// triangles, a primitive obstacle is its own hull or lies in its outer hull) is one, certified
// by convexDistanceBelow, and costs a GJK run. It is the answer unless it is within a fraction
// of a voxel of contact: there FCL's distance between the meshes decides, where a hull wraps
// around an object (an open gripper around a grasped box) or the geometry nearly touches.
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <utility>
#include <variant>
#include <vector>

#include "internal/refine.h"
#include "octomotion/planner/model/collision_backend.h"

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
// the object's hullTrusted, else FCL's distance. With `nearest`: the slabs of the nearest
// objects by those bounds, while they have one (NearestObstacle), and the least bound on the
// others.
double refineLinkDistance(const RefineData& data, RefineScratch& r, const RobotData& robot,
                          int link, double cap, const WorldGrid& grid, NearestObstacle* nearest) {
  const ConvexPoints& hull_L = data.link_hulls_L[static_cast<std::size_t>(link)];
  const Eigen::Isometry3d& X_WL = robot.linkPose(link);
  // The link's hull lies in this ball: most objects are farther than it is from what is asked.
  const Eigen::Vector3d centre_W = X_WL * hull_L.centroid();
  const double reach = hull_L.reach() + hull_L.radius();
  bool posed = false;
  double best = cap;
  // The nearest objects so far, by their bounds (ascending; a slab's gap 0 when it has none),
  // and the least bound on the others.
  struct Near {
    double bound, gap;
    const RefineObject* object;
    Eigen::Vector3d direction_O;
  };
  constexpr std::size_t kSlabs = NearestObstacle::kSlabs;
  std::array<Near, kSlabs> near{};
  std::size_t kept = 0;
  double others = cap;  // every object is below the cap or at least as far
  auto record = [&](const RefineObject& object, double bound, double gap,
                    const Eigen::Vector3d* direction_O) {
    Near entry{bound, direction_O ? gap : 0.0, &object,
               direction_O ? *direction_O : Eigen::Vector3d::Zero()};
    for (std::size_t k = 0; k < kept; ++k) {
      if (entry.bound < near[k].bound) std::swap(entry, near[k]);
    }
    if (kept < kSlabs) {
      near[kept++] = entry;
    } else {
      others = std::min(others, entry.bound);
    }
  };
  const std::size_t objects = data.objects.size();
  // Nearest boxes first: the nearest object's distance lowers the running best early, and the
  // farther objects then stop at their box's bound without GJK.
  thread_local std::vector<std::pair<double, std::size_t>> order;
  order.clear();
  for (std::size_t i = 0; i < objects; ++i) {
    if (data.objects[i].shapes.empty()) continue;
    order.emplace_back(
        hull_L.empty() ? 0.0 : distanceToBox(data.objects[i].box_W, centre_W) - reach, i);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [boxed, i] : order) {
    const RefineObject& object = data.objects[i];
    double gap = 0.0;  // the hulls' bound, 0 when not measured
    Eigen::Vector3d* direction_O = nullptr;
    if (!hull_L.empty()) {
      if (boxed >= best) {
        if (nearest) record(object, boxed, 0.0, nullptr);
        continue;
      }
      if (!object.hull_O.empty()) {
        direction_O = &r.link_object_directions[static_cast<std::size_t>(link) * objects + i];
        gap = convexDistanceBelow(object.hull_O, hull_L, object.X_OW * X_WL, best, direction_O,
                                  kHullTolerance);
        if (gap >= best || gap > hullTrusted(grid, object)) {
          ++r.hull_distances;
          best = std::min(best, gap);
          if (nearest) record(object, gap, gap, direction_O);
          continue;
        }
      }
    }
    if (!posed) {
      refinePoseLink(data, r, robot, link);
      posed = true;
    }
    double object_best = best;
    for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
      const fcl::CollisionObjectd& element = r.fcl.objects[e];
      if (object.box_W.distance(element.getAABB()) >= object_best) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        ++r.fcl_distances;
        object_best = fcl_internal::distanceBelow(element, shape, object_best);
        if (object_best <= 0) return 0;
      }
    }
    best = std::min(best, object_best);
    // FCL's distance is below the running best, or the object is at least that far: either is a
    // lower bound on its distance. The hulls' slab, when measured, still separates them.
    if (nearest) record(object, object_best, gap, direction_O);
  }
  if (nearest && best < cap) {
    // The nearest objects with a slab, in order, up to the first without; that one and the rest
    // are held off by `others`. The slab's direction points from the link towards the object
    // (convexDistanceBelow's runs from its second set to its first).
    std::size_t slabs = 0;
    while (slabs < kept && near[slabs].gap > 0) ++slabs;
    if (slabs == 0) return best;
    for (std::size_t k = 0; k < kSlabs; ++k) {
      if (k < slabs) {
        nearest->gap[k] = near[k].gap;
        nearest->toward_W[k] =
            (near[k].object->X_OW.linear().transpose() * near[k].direction_O).normalized();
      } else if (k < kept) {
        others = std::min(others, near[k].bound);
      }
    }
    nearest->others = others;
  }
  return best;
}

}  // namespace
}  // namespace detail

void OctreeCollisionModel::refineClearancesPerLink(const CheckScratch& scratch, const double* caps,
                                                   double* per_link,
                                                   NearestObstacle* nearest) const {
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
    per_link[l] =
        std::max(per_link[l], detail::refineLinkDistance(*refine_, *r, scratch.robot, l, caps[l],
                                                         grid(), nearest ? nearest + l : nullptr));
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
