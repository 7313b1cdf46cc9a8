// Private to the planner library: what OctreeCollisionModel keeps for a world that changes
// between plans (world_updates.cpp): the world's objects (the environment tree is rebuilt from
// them region by region) and the attached objects, each a link-like entry of LinkModels.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::detail {

struct AttachedEntry {
  AttachedObject spec;
  EnvironmentGeometry::Item item;  // its geometry, loaded once (for leaving it in the world)
  int link = -1;                   // robot link index
  std::size_t slot = 0;            // in LinkModels::links
  Eigen::AlignedBox3d carried_W;   // where its link can carry it
};

struct WorldState {
  EnvironmentGeometry objects;
  std::vector<AttachedEntry> attached;
  // Every link with geometry has a slot: links the first build left out (they could reach
  // neither the environment nor a checked pair) are modelled at the first update.
  bool all_links_modelled = false;
  // Where attached objects can be carried (they may reach beyond CollisionModelReport::reach_W):
  // objects there must lie in the universe.
  Eigen::AlignedBox3d attached_reach_W;
  int clearance_grid_lowerings = 0;  // since the environment's ClearanceGrid was last rebuilt
  // Set by an update: the clearance levels (ClearanceMethod::kPointOctree) are built again by
  // the first clearance query after it, once, whichever thread asks.
  std::unique_ptr<std::once_flag> clearance_levels_once;
};

}  // namespace octomotion::detail
