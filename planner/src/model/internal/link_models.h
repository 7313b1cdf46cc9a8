// Private to the planner library: the robot's links as OctreeCollisionModel tests them. Each
// modelled link is voxelized once, in its own frame, into a source tree (LinkVoxels) with its
// bounding sphere, box and core boxes; the links that can touch the environment get one flat
// EnvironmentLinkTest each, in the order the environment half tests them.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/motion/collides.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octree.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::detail {

class EnvironmentModel;

// Boxes of a certain contact (a link's core boxes, the environment's solid boxes) are shrunk by
// this share of the larger voxel size: a point of both then has a ball about it in both boxes,
// so the target voxel holding it overlaps the obstacle and a moved link voxel by far more than
// the colour rules' ties (1e-6 voxel).
inline constexpr double kSolidShrink = 1e-3;

// A link's black voxels at one resolution, in its own frame L, prepared for queries.
struct LinkVoxels {
  Octree source{WorldGrid(Eigen::Vector3d::Zero(), 1.0, 1)};
  std::unique_ptr<const MovableSource> movable;        // the source prepared for the fused query
  Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  // bounding sphere of the black voxels
  double radius = 0;
  Eigen::Vector3d half_L = Eigen::Vector3d::Zero();  // their box: centre center_L, half-sides
  double source_diagonal = 0;                        // of one source voxel (metres)
  // Boxes inside the black voxels (CollisionModelOptions::core_boxes), shrunk by kSolidShrink.
  struct CoreBox {
    Eigen::Vector3d centre_L, half_L;
  };
  std::vector<CoreBox> core_boxes;
};

// A link's collision elements (element_mesh[k]: element k's mesh, nullptr for a primitive)
// voxelized in its frame at `resolution` (box_L: their extent). Throws Error when the tree does
// not hold the whole link.
LinkVoxels voxelizeLink(const Link& link, const std::vector<const TriangleMesh*>& element_mesh,
                        Eigen::AlignedBox3d box_L, double resolution,
                        const CollisionModelOptions& options, bool for_self_pairs);

// Clearance spheres of a link: they circumscribe the coarse ancestors of its black leaves, cubes
// of at least eight `voxel`s (metres) a side.
std::vector<Eigen::Vector4d> clearanceSpheres(const Octree& source, double voxel);

// A sphere holding the clearance spheres [begin, end) of a link: a grid clearance at its centre,
// less its radius, bounds theirs from below, so a group whose bound is no lower than the best
// so far is skipped without looking at its members (a large body has thousands of spheres).
struct SphereGroup {
  Eigen::Vector4d sphere_L;  // centre, radius
  std::size_t begin = 0, end = 0;
};
// Sorts `spheres` into groups of neighbours (about 4 x 4 x 4 of the smallest) and returns them.
std::vector<SphereGroup> groupClearanceSpheres(std::vector<Eigen::Vector4d>& spheres);

struct LinkTree {
  int link = -1;
  LinkVoxels voxels;  // tested against the environment (and the other links, unless below)
  // At self_link_resolution when it differs from link_resolution: the self pairs' margin is
  // set by the link voxels alone, so finer trees here remove self false positives without
  // deepening the environment queries.
  std::unique_ptr<const LinkVoxels> self_voxels;
  const LinkVoxels& forSelf() const { return self_voxels ? *self_voxels : voxels; }
  bool touches_environment = true;  // false: cannot reach the modelled environment
  bool folded = false;  // its pose is constant: tested against the environment at build time
  // Covers of the black voxels for the clearance bounds: by cubes of eight link voxels (the
  // tree and point methods), and by cubes of eight environment voxels, in groups
  // (groupClearanceSpheres), for the ClearanceGrid.
  std::vector<Eigen::Vector4d> spheres_L;
  std::vector<Eigen::Vector4d> grid_spheres_L;
  std::vector<SphereGroup> grid_sphere_groups_L;
};
// Sets lt's clearance spheres (both covers, and the grid's groups) from its link voxels.
void setClearanceSpheres(LinkTree& lt, double environment_voxel);

// What the environment pre-test reads of a link, in one flat record per link that can touch
// the environment (a rejected link touches nothing else).
struct EnvironmentLinkTest {
  Eigen::Vector3d center_L;  // the link box's centre and half sides (LinkVoxels)
  Eigen::Vector3d half_L;
  double reach_squared = 0;         // (bounding radius + one environment voxel diagonal)^2
  double origin_reach_squared = 0;  // (that reach + |center_L|)^2, about the link's origin
  int link = -1;                    // robot link index
  std::size_t slot = 0;             // in LinkModels::links
};

inline double squaredDistanceToBox(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  return (p - p.cwiseMax(box.min()).cwiseMin(box.max())).squaredNorm();
}

// The link's bounding sphere, grown by a voxel diagonal, reaches `box`: the first stage of the
// environment pre-test. It rejects most links of most states, so it runs inline in the loops
// over links, on the link frame's origin alone (a sphere about it, of radius |center_L| plus
// the bounding sphere's reach, holds that sphere: no transform of the centre), then on the
// sphere itself.
inline bool sphereMeetsBox(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL,
                           const Eigen::AlignedBox3d& box) {
  return squaredDistanceToBox(X_WL.translation(), box) <= t.origin_reach_squared &&
         squaredDistanceToBox(X_WL * t.center_L, box) <= t.reach_squared;
}

// The modelled links (those that can touch the environment or another link) and how the
// environment half visits them.
struct LinkModels {
  std::vector<LinkTree> links;  // modelled links only; a link's index here is its slot
  // The links that can touch the environment, in the order the environment half tests them:
  // most often hit first (LinkReport::environment_hit_share), ties in model order. Free states
  // test them all either way; colliding ones stop sooner.
  std::vector<EnvironmentLinkTest> environment_tests;
  std::vector<const LinkVoxels*> self_voxels;  // per slot: links[slot].forSelf(), one load
  std::vector<int> link_slot;                  // robot link index -> slot, or -1
  // A lower bound on the environment distance of the links left out of the clearance queries
  // (those whose reach never meets the environment's box): the gap between the two boxes. The
  // clearance bounds take the minimum with it, so they stay below the whole robot's distance.
  double unreachable_clearance = std::numeric_limits<double>::infinity();

  // The environment test record of the link in `slot`: its voxels placed on a grid of
  // `environment_voxel` (or, with exact primitives, tested against primitives) reach at most
  // that far beyond its bounding sphere.
  EnvironmentLinkTest environmentTest(std::size_t slot, double environment_voxel,
                                      bool exact_primitives) const;
  // Fills environment_tests: the links that touch the environment, most often hit in
  // kEnvironmentOrderSamples uniform joint states first (arms; model order otherwise). Writes
  // each link's hit share and the order into `report`.
  void orderEnvironmentTests(const EnvironmentModel& environment, const RobotModel& robot,
                             const Eigen::Isometry3d& X_WB, CollisionModelReport& report);
};

}  // namespace octomotion::detail
