// Private to the planner library: OctreeCollisionModel's clearance lower bounds, from the
// links' clearance spheres to the environment's black voxels (docs/planner.md, "Clearance").
#pragma once

#include <vector>

#include "link_models.h"
#include "octomotion/octree/octree.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/pointcloud/point_octree.h"

namespace octomotion::detail {

// ClearanceMethod::kPointOctree: the environment's black leaves' centres, one PointOctree per
// leaf level, so a nearest centre at distance d bounds the distance to its cube by d - half
// diagonal.
class ClearanceLevels {
 public:
  // The levels of `environment`'s black leaves (none for an empty environment).
  static ClearanceLevels build(const Octree& environment);
  bool empty() const { return levels_.empty(); }
  // The bound over the links that touch the environment (at the poses in `robot`); 0 in
  // contact. Requires !empty().
  double lowerBound(const LinkModels& links, const RobotData& robot) const;

 private:
  struct Level {
    double half_diagonal = 0;  // of that level's cubes (metres)
    pointcloud::PointOctree centres;
  };
  std::vector<Level> levels_;
  double float_slack_ = 0;  // covers float rounding of centres and distances
};

// ClearanceMethod::kEnvironmentTree: branch and bound over the environment tree's black leaves.
double clearanceLowerBoundTree(const LinkModels& links, const Octree& environment,
                               const RobotData& robot);

}  // namespace octomotion::detail
