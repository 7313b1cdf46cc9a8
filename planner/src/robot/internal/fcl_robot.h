// Private to the planner library: the robot as FCL objects, shared by the two FCL references
// (FclCollisionModel, FclOctomapCollisionModel) and the self-pair tables' build-time oracle.
// Written the way a careful FCL user would: geometry built once, each query only poses the
// objects, pre-tests world AABBs before any narrow phase and reuses its request/result.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "octomotion/octree/mesh.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::fcl_internal {

using Geom = std::shared_ptr<fcl::CollisionGeometryd>;

// Primitives as FCL shapes, meshes as BVHModel<OBBRSS> (local AABB computed here, once).
Geom shapeOf(const Primitive& p);
Geom meshOf(const TriangleMesh& mesh);

// The world AABB of a posed object, tight for its local box (FCL's own computeAABB bounds a
// rotated object by the sphere around its local box, which is looser). Written into the object's
// AABB cache, which broad phases read.
void setTightAabb(fcl::CollisionObjectd& object);

// Narrow phase on two posed objects after an AABB pre-test. `result` is cleared first.
bool collidePair(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                 const fcl::CollisionRequestd& request, fcl::CollisionResultd& result);
// FCL's distance between two posed objects (0 in contact) when below `best`, else `best`
// (objects whose AABBs are `best` apart are not measured).
double distanceBelow(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b, double best);

struct RobotScratch {
  RobotData robot;
  std::vector<fcl::CollisionObjectd> objects;  // one per collision element, posed in the world
  fcl::CollisionRequestd request;              // yes/no: one contact, no contact points
  fcl::CollisionResultd result;
};

class RobotGeometry {
 public:
  // Loads each mesh file once, with the robot's mesh conventions (see CollisionModelOptions).
  RobotGeometry(const RobotModel& robot, bool keep_mesh_root_transform, bool center_mesh_vertices);

  void initScratch(const RobotModel& robot, RobotScratch& scratch) const;
  // Forward kinematics, then each element's pose and world AABB.
  void pose(const RobotModel& robot, const double* q, std::size_t q_size,
            const Eigen::Isometry3d& X_WB, RobotScratch& scratch) const;

  // Each element's pose and world AABB from link poses already in `data` (forwardKinematics).
  void poseElements(const RobotData& data, RobotScratch& scratch) const;
  // The same for one element (exact refine mode poses only the links it tests).
  void poseElement(const RobotData& data, std::size_t element, RobotScratch& scratch) const;

  // The robot's checked self pairs (RobotModel::checkedPairs), element by element.
  bool selfInCollision(RobotScratch& scratch) const;
  // For explanations: the checked link pairs (a < b) whose elements collide, in checkedPairs
  // order, the first only unless `all`; whether two links' elements collide; whether one of a
  // link's elements collides with `object`.
  std::vector<std::pair<int, int>> collidingPairs(RobotScratch& scratch, bool all) const;
  bool linksCollide(RobotScratch& scratch, int link_a, int link_b) const;
  bool linkCollides(RobotScratch& scratch, int link, const fcl::CollisionObjectd& object) const;
  // Smallest distance between the elements of checked pairs (0 in contact, +inf with no pairs);
  // pairs whose AABBs are at least `cap` apart are skipped (distances >= cap may read as cap).
  double selfDistance(RobotScratch& scratch, double cap) const;
  // The smallest distance between an element of link_a and one of link_b (0 in contact), or
  // `cap` when at least `cap` (or when a link has no elements).
  double linksDistance(RobotScratch& scratch, int link_a, int link_b, double cap) const;

  // World updates (FclCollisionModel::attachObject): an element carried by `link`, paired with
  // the elements of every link not in `allowed_links` (per robot link); returns its index. And
  // its removal (later elements move down by one).
  std::size_t addElement(int link, const Eigen::Isometry3d& X_LE, Geom geometry,
                         const std::vector<bool>& allowed_links);
  void removeElement(std::size_t element);

  std::size_t elementCount() const { return elements_.size(); }
  int elementLink(std::size_t element) const { return elements_[element].link; }

 private:
  struct Element {
    int link;
    Eigen::Isometry3d X_LE;
  };
  std::vector<Element> elements_;
  // One object per element, made once: FCL's CollisionObject constructor writes to the shared
  // geometry (computeLocalAABB), so scratches copy these instead of constructing their own.
  std::vector<fcl::CollisionObjectd> prototypes_;
  std::vector<std::pair<int, int>> element_pairs_;  // elements of the checked link pairs
};

}  // namespace octomotion::fcl_internal
