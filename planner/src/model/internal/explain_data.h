// Private to the planner library: what OctreeCollisionModel::explainContacts needs besides the
// model's parts. The environment tree fuses every object, so naming the object a link meets
// takes per-object data: each object's own tree on the environment's grid (the same voxels the
// fused tree has of it), built on the first explanation that needs it and kept, so memory grows
// only with the objects explanations have met. Whether the exact shapes touch is asked of FCL
// (the robot's links and the objects' shapes, also built on first use). Everything is per object,
// indexed like EnvironmentGeometry::items(), so an object can be replaced on its own.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "../../robot/internal/fcl_robot.h"
#include "octomotion/octree/octree.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::detail {

struct ExplainData {
  explicit ExplainData(std::shared_ptr<const EnvironmentGeometry> environment)
      : objects(std::move(environment)),
        object_trees(objects->size()),
        object_shapes(objects->size()),
        shape_built(objects->size(), false) {}

  std::shared_ptr<const EnvironmentGeometry> objects;
  std::mutex mutex;  // guards the lazily built members below
  std::vector<std::shared_ptr<const Octree>> object_trees;
  // The object as a posed FCL object; null for point clouds and OctoMaps (no exact shape).
  std::vector<std::shared_ptr<const fcl::CollisionObjectd>> object_shapes;
  std::vector<bool> shape_built;
  std::unique_ptr<const fcl_internal::RobotGeometry> robot;
};

}  // namespace octomotion::detail
