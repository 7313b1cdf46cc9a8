// RefineMode::kExact's exact distances for the certified motion validator
// (OctreeCollisionModel::refineClearancesPerLink, refinedPairDistance): FCL on the links (and
// pairs) whose cheaper bound is below what the validator needs, nothing for the others.
#include <algorithm>
#include <cstddef>

#include "internal/refine.h"

namespace octomotion {

namespace detail {
namespace {

// FCL's distance from `link`'s elements to the environment's objects, or `cap` when at least
// `cap`.
double refineLinkDistance(const RefineData& data, RefineScratch& r, const RobotData& robot,
                          int link, double cap) {
  refinePoseLink(data, r, robot, link);
  double best = cap;
  for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
    const fcl::CollisionObjectd& element = r.fcl.objects[e];
    for (const RefineObject& object : data.objects) {
      if (object.shapes.empty() || object.box_W.distance(element.getAABB()) >= best) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
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
  // FCL's distance (a BVH traversal per element) is what costs: the bound stands there.
  const double near = 2 * grid().voxelSize();
  detail::RefineScratch* r = nullptr;  // made on the first link that needs FCL
  for (int l = 0; l < robot_.linkCount(); ++l) {
    if (caps[l] <= 0 || per_link[l] >= caps[l] || per_link[l] >= near ||
        !robot_.link(l).hasCollision()) {
      continue;
    }
    if (r == nullptr) r = &detail::refineScratch(*refine_, robot_, id_, scratch.refine);
    per_link[l] = detail::refineLinkDistance(*refine_, *r, scratch.robot, l, caps[l]);
  }
}

double OctreeCollisionModel::refinedPairDistance(const CheckScratch& scratch, int link_a,
                                                 int link_b, double cap) const {
  if (!refine_) return 0.0;
  detail::RefineScratch& r = detail::refineScratch(*refine_, robot_, id_, scratch.refine);
  detail::refinePoseLink(*refine_, r, scratch.robot, link_a);
  detail::refinePoseLink(*refine_, r, scratch.robot, link_b);
  double best = cap;
  for (std::size_t a : refine_->link_elements[static_cast<std::size_t>(link_a)]) {
    for (std::size_t b : refine_->link_elements[static_cast<std::size_t>(link_b)]) {
      best = fcl_internal::distanceBelow(r.fcl.objects[a], r.fcl.objects[b], best);
      if (best <= 0) return 0;
    }
  }
  return best;
}

}  // namespace octomotion
