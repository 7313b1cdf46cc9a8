// Private to the planner library: the boxes an EnvironmentModel derives from its objects (the
// pre-test's object boxes, the solid boxes of certain contacts), made by CollisionModelBuilder
// once and again after every world update.
#pragma once

#include <Eigen/Geometry>

#include "environment_model.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::detail {

// The world box of a tree's black voxels (empty for an empty tree).
Eigen::AlignedBox3d blackBox(const Octree& tree);

// Object boxes for the environment pre-test (appended to environment.object_boxes_W and
// object_frame_boxes): every voxel an object marks lies within one voxel of its box.
void buildObjectBoxes(EnvironmentModel& environment, const EnvironmentGeometry& objects,
                      const WorldGrid& grid, double link_resolution, bool exact_primitives);
// Resolves kAuto, drops the object boxes unless kObjectBoxes, and fills the per-axis arrays.
EnvironmentPreTest resolveEnvironmentPreTest(EnvironmentModel& environment,
                                             EnvironmentPreTest option, const WorldGrid& grid);
// Solid boxes for the links' core boxes (conservative rounding, options.core_boxes).
void buildSolidBoxes(EnvironmentModel& environment, const EnvironmentGeometry& objects,
                     const WorldGrid& grid, const CollisionModelOptions& options,
                     double link_resolution);

}  // namespace octomotion::detail
