// Private to the planner library: the environment as OctreeCollisionModel tests links against
// it. One merged environment tree on a universe fitted to the robot's reach, with its
// BlackCellGrid and ClearanceGrid; the boxes of the environment pre-test (the black voxels' box,
// or each object's); the solid boxes of certain contacts; and, with exact primitives, the
// primitives themselves and a tree of the other objects.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "link_models.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/model/collision_model.h"

namespace octomotion::detail {

// A box inside a primitive obstacle (the box itself, a ball's inscribed cube, a cylinder's
// square prism), shrunk by kSolidShrink: every voxel it overlaps is black in the environment.
struct SolidBox {
  Eigen::Vector3d centre_W, half;
  Eigen::Matrix3d R_OW;      // world to the box's axes
  Eigen::Vector3d extent_W;  // half sides of its world AABB
};

// CollisionModelOptions::exact_primitives: a primitive obstacle in its own frame P, and its
// world AABB (EnvironmentGeometry::Item::bounds_W: centre_W, half sides extent_W).
struct ExactPrimitive {
  PrimitiveShape shape;
  Eigen::Isometry3d X_PW;
  Eigen::Vector3d centre_W, extent_W;
};
// A link is tested against an exact primitive when the world box of the link's black voxels
// grown by this many link voxels meets the primitive's AABB: a link voxel's bounding sphere
// reaches (√3 - 1)/2 of a voxel beyond the voxel.
inline constexpr double kExactReachVoxels = 1.0;

// A rotated primitive's own box, grown by a voxel diagonal (it holds the object's black voxels
// too, and is much tighter than the world box for a tilted bar): tested after the world box.
// `tilted` false for the other objects.
struct ObjectFrameBox {
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero(), half = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_OW = Eigen::Matrix3d::Identity();  // world to the object's axes
  bool tilted = false;
};

// Objects in a tree of their own (on the environment's grid) with its grids, queried like the
// environment tree.
struct VoxelObjects {
  Octree tree;
  std::unique_ptr<const BlackCellGrid> cells;
  std::unique_ptr<const ClearanceGrid> clearance;
};

class EnvironmentModel {
 public:
  Rounding rounding = Rounding::kConservative;
  Octree tree{WorldGrid(Eigen::Vector3d::Zero(), 1.0, 1)};
  // The tree's entirely black cells as a bit grid: the fused query tries a few points of each
  // link in it before any traversal.
  std::unique_ptr<const BlackCellGrid> cells;
  // Lower bounds on the distance to the tree per cell: the fused query drops the pieces of a
  // link that are clear of it before descending.
  std::unique_ptr<const ClearanceGrid> clearance;
  Eigen::AlignedBox3d box_W;  // world box of the environment's black voxels
  // kObjectBoxes: each object's box grown by a voxel (so it holds the object's black voxels).
  std::vector<Eigen::AlignedBox3d> object_boxes_W;
  // The same boxes for the pre-test's first three axes, one array per axis (centre, and half
  // side plus the tie margin), precomputed: most boxes are rejected there.
  std::array<std::vector<double>, 3> object_centre_W, object_reach_W;
  std::vector<ObjectFrameBox> object_frame_boxes;  // parallel to object_boxes_W
  std::vector<SolidBox> solid_boxes_W;
  std::vector<ExactPrimitive> exact_primitives;
  // With exact primitives in a scene that also has other objects: their tree.
  std::unique_ptr<const VoxelObjects> other_objects;
  // Per CheckerPath: a link whose pose never changes (CollisionModelOptions::fold_static) met
  // the environment at build time, so every state is in collision.
  std::array<bool, 2> always_hits{};

  // The environment half of a check: the links' tests in order, stopping at the first contact.
  bool inCollision(const LinkModels& links, CheckerPath path, const RobotData& robot,
                   CollisionScratch& fused) const {
    if (always_hits[static_cast<std::size_t>(path)]) return true;
    for (const EnvironmentLinkTest& t : links.environment_tests) {
      const Eigen::Isometry3d& X_WL = robot.linkPose(t.link);
      if (sphereMeetsBox(t, X_WL, box_W) &&
          linkHits(t, links.links[t.slot].voxels, X_WL, path, fused)) {
        return true;
      }
    }
    return false;
  }
  // The clearance grid's bound at the centre of the link's bounding sphere exceeds its radius:
  // the sphere, which holds the link's black voxels and so its geometry, meets no black voxel
  // and no object. One lookup, cheaper than any test of its hull or voxels. False without a
  // grid, and outside the universe (the grid's bound is 0 there).
  bool linkClearByGrid(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const {
    if (!clearance) return false;
    const WorldGrid& world = tree.grid();
    const Eigen::Vector3d g = world.toGrid(X_WL * v.center_L);
    const double c[3] = {g.x(), g.y(), g.z()};
    return clearance->clearance(c) * world.voxelSize() - v.radius - 1e-6 > 0;
  }
  // For a link whose bounding sphere reaches the environment's box (sphereMeetsBox): false
  // when its oriented box meets neither the environment's box nor (kObjectBoxes) any object's
  // box, so it cannot meet an environment voxel.
  bool linkNear(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL) const;
  // linkNear, then the link's certain contacts, then its query against the environment tree
  // (with exact primitives: against the primitives, then the other objects' tree).
  bool linkHits(const EnvironmentLinkTest& t, const LinkVoxels& v, const Eigen::Isometry3d& X_WL,
                CheckerPath path, CollisionScratch& fused) const;
  // One of the link's core boxes overlaps a solid box: the link's moved tree and the
  // environment share a black voxel.
  bool certainContact(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const;
  // A black voxel of the link's environment tree meets one of exact_primitives.
  bool leavesMeetPrimitives(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const;
};

}  // namespace octomotion::detail
