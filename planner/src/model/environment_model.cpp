#include "internal/environment_model.h"

#include <cmath>

#include "octomotion/motion/box_overlap.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/traversal.h"

namespace octomotion::detail {

bool EnvironmentModel::linkNear(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL) const {
  // The box of the link's black voxels, oriented with the link: a link voxel can only meet an
  // environment voxel inside the environment's (or an object's) box. The margin, a millionth of
  // a voxel, is the overlap the colour rule itself demands (kMotionTieTolerance).
  const Eigen::Vector3d c_W = X_WL * t.center_L;
  const double margin = kMotionTieTolerance * tree.grid().voxelSize();
  const Eigen::Matrix3d& R_WL = X_WL.linear();
  if (object_boxes_W.empty()) {
    return boxesOverlap(box_W.center(), box_W.sizes() / 2, R_WL, c_W, t.half_L, margin);
  }
  // The link box's half extents along the world axes (with boxesOverlap's 1e-12 padding): its
  // first three axes, tested on their own first, reject most object boxes without the other
  // twelve or the sphere's distance.
  const Eigen::Vector3d h_W = (R_WL.cwiseAbs().array() + 1e-12).matrix() * t.half_L;
  const double* centre[3] = {object_centre_W[0].data(), object_centre_W[1].data(),
                             object_centre_W[2].data()};
  const double* reach[3] = {object_reach_W[0].data(), object_reach_W[1].data(),
                            object_reach_W[2].data()};
  const std::size_t n = object_boxes_W.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (std::fabs(c_W[0] - centre[0][i]) > reach[0][i] + h_W[0] ||
        std::fabs(c_W[1] - centre[1][i]) > reach[1][i] + h_W[1] ||
        std::fabs(c_W[2] - centre[2][i]) > reach[2][i] + h_W[2]) {
      continue;
    }
    const Eigen::AlignedBox3d& box = object_boxes_W[i];
    if (squaredDistanceToBox(c_W, box) <= t.reach_squared &&
        boxesOverlap(box.center(), box.sizes() / 2, R_WL, c_W, t.half_L, margin)) {
      const ObjectFrameBox& o = object_frame_boxes[i];
      if (!o.tilted) return true;
      if (boxesOverlap(Eigen::Vector3d::Zero(), o.half, o.R_OW * R_WL, o.R_OW * (c_W - o.centre_W),
                       t.half_L, margin)) {
        return true;
      }
    }
  }
  return false;
}

bool EnvironmentModel::certainContact(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const {
  if (v.core_boxes.empty()) return false;
  const Eigen::Matrix3d& R_WL = X_WL.linear();
  // The link box's extent along the world axes, to skip far obstacles with three comparisons.
  const Eigen::Vector3d c_W = X_WL * v.center_L;
  const Eigen::Vector3d h_W = R_WL.cwiseAbs() * v.half_L;
  for (const SolidBox& solid : solid_boxes_W) {
    if (((c_W - solid.centre_W).cwiseAbs() - solid.extent_W - h_W).maxCoeff() > 0) continue;
    const Eigen::Matrix3d R_OL = solid.R_OW * R_WL;
    for (const LinkVoxels::CoreBox& core : v.core_boxes) {
      const Eigen::Vector3d t_O = solid.R_OW * (X_WL * core.centre_L - solid.centre_W);
      if (boxesOverlap(Eigen::Vector3d::Zero(), solid.half, R_OL, t_O, core.half_L)) return true;
    }
  }
  return false;
}

bool EnvironmentModel::leavesMeetPrimitives(const LinkVoxels& v,
                                            const Eigen::Isometry3d& X_WL) const {
  const Eigen::Vector3d c_W = X_WL * v.center_L;
  const Eigen::Vector3d h_W =
      X_WL.linear().cwiseAbs() * v.half_L +
      Eigen::Vector3d::Constant(kExactReachVoxels * v.source.grid().voxelSize());
  for (const ExactPrimitive& p : exact_primitives) {
    if (((c_W - p.centre_W).cwiseAbs() - p.extent_W - h_W).maxCoeff() > 0) continue;
    if (blackLeafMeetsPrimitive(*v.movable, p.X_PW * X_WL, p.shape)) return true;
  }
  return false;
}

bool EnvironmentModel::linkHits(const EnvironmentLinkTest& t, const LinkVoxels& v,
                                const Eigen::Isometry3d& X_WL, CheckerPath path,
                                CollisionScratch& fused) const {
  if (!linkNear(t, X_WL)) return false;
  // A certain contact has a point inside a primitive and inside a black link leaf: the exact
  // primitives' answer too.
  if (certainContact(v, X_WL)) return true;
  // The voxels left to query: the environment tree, or with exact primitives the tree of the
  // other objects, if any.
  auto voxelsHit = [&](const Octree& voxels, const BlackCellGrid* voxel_cells,
                       const ClearanceGrid* voxel_clearance) {
    if (path == CheckerPath::kFused) {
      return collides(*v.movable, X_WL, voxels, rounding, fused, nullptr, voxel_cells,
                      voxel_clearance);
    }
    return intersects(moveTree(v.source, X_WL, voxels.grid(), rounding), voxels);
  };
  if (exact_primitives.empty()) return voxelsHit(tree, cells.get(), clearance.get());
  if (leavesMeetPrimitives(v, X_WL)) return true;
  return other_objects &&
         voxelsHit(other_objects->tree, other_objects->cells.get(), other_objects->clearance.get());
}

}  // namespace octomotion::detail
