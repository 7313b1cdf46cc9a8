// Private to the planner library: what RefineMode::kExact keeps besides the octree model. The
// octree certifies freedom (no shared voxel under conservative rounding); a link whose voxels
// meet the environment's, or a checked pair whose voxels meet, is decided by FCL on the original
// geometry: the robot's links as FCL objects (fcl_robot.h), each object of the scene as a posed
// FCL shape (meshes and primitives) or, for point clouds and OctoMaps, whose geometry is their
// voxels, one FCL box per black leaf on the model's grid. Built once with the model, then
// constant and shared by threads; each thread poses the robot in its own RefineScratch.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "../../robot/internal/fcl_robot.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::detail {

struct RefineObject {
  std::vector<fcl::CollisionObjectd> shapes;  // one (primitive, mesh) or one box per voxel
  fcl::AABBd box_W;                           // of all shapes
};

struct RefineData {
  RefineData(const RobotModel& robot, const EnvironmentGeometry& objects, const WorldGrid& grid,
             const CollisionModelOptions& options);

  std::unique_ptr<const fcl_internal::RobotGeometry> robot;
  std::vector<RefineObject> objects;
  // Per robot link: its elements (indices in RobotGeometry's order).
  std::vector<std::vector<std::size_t>> link_elements;
};

struct RefineScratch {
  std::uint64_t owner = 0;  // id() of the model it was made for
  fcl_internal::RobotScratch fcl;
  bool posed = false;  // fcl's objects are at the current query's link poses
};

// The scratch's FCL objects at the link poses in `robot`, posing them on the query's first use.
fcl_internal::RobotScratch& posedRefineScratch(const RefineData& data, const RobotModel& model,
                                               std::uint64_t owner, const RobotData& robot,
                                               RefineScratchHolder& holder);

// FCL: one of `link`'s elements touches one of the objects' shapes.
bool refineLinkHits(const RefineData& data, fcl_internal::RobotScratch& s, int link);
// FCL: an element of link_a touches one of link_b.
bool refinePairHits(const RefineData& data, fcl_internal::RobotScratch& s, int link_a, int link_b);
// FCL's exact distance from the robot's elements to the objects (0 in contact).
double refineEnvironmentDistance(const RefineData& data, fcl_internal::RobotScratch& s);

}  // namespace octomotion::detail
