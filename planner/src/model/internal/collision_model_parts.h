// Private to the planner library: the parts an OctreeCollisionModel is made of, each with one
// job; the facade owns them together (built once by CollisionModelBuilder, then constant).
#pragma once

#include "clearance.h"
#include "environment_model.h"
#include "link_models.h"
#include "self_collision.h"
#include "world_state.h"

namespace octomotion::detail {

struct CollisionModelParts {
  EnvironmentModel environment;  // what links are tested against
  LinkModels links;              // the links' source trees and environment tests
  SelfCollision self;            // the checked pairs and how they are found
  ClearanceLevels clearance;     // ClearanceMethod::kPointOctree (empty otherwise)
  WorldState world;              // what world updates need (world_updates.cpp)
};

}  // namespace octomotion::detail
