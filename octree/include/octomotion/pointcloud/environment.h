// Turning a point cloud (a scan of the obstacles) into planning structures: the occupancy region
// octree at the world grid's resolution, and a point octree answering "how far is the nearest
// obstacle point" (clearance).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "octomotion/octree/octree.h"
#include "octomotion/octree/world_grid.h"
#include "octomotion/pointcloud/point_octree.h"

namespace octomotion::pointcloud {

struct EnvironmentOptions {
  // > 0: first thin the cloud to one point (the centroid) per cube of this side, in metres, like
  // a voxel-grid filter. 0 keeps every point.
  double downsample_voxel = 0.0;
};

struct EnvironmentStats {
  std::size_t points_in = 0;         // points given
  std::size_t points_used = 0;       // after downsampling, inside the universe
  std::size_t outside_universe = 0;  // dropped: outside the grid's universe (or non-finite)
  std::size_t occupied_voxels = 0;
};

// Voxel-grid downsampling: one centroid per occupied cube of side `voxel` (> 0, finite; else
// InvalidArgument). Non-finite points are dropped. Output order follows the cubes' first points.
std::vector<Eigen::Vector3f> downsample(const std::vector<Eigen::Vector3f>& points, double voxel);

// Occupancy octree: every voxel of `grid` containing a point is black. Points outside the
// universe are dropped (counted in stats).
Octree environmentFromPoints(const WorldGrid& grid, const std::vector<Eigen::Vector3f>& points,
                             const EnvironmentOptions& options = {},
                             EnvironmentStats* stats = nullptr);

// Clearance queries against the (optionally downsampled) cloud.
class ClearanceMap {
 public:
  explicit ClearanceMap(const std::vector<Eigen::Vector3f>& points,
                        const EnvironmentOptions& options = {});
  // Distance (metres) from p to the nearest obstacle point; +infinity for an empty cloud.
  double clearance(const Eigen::Vector3d& p) const {
    return points_.nearestDistance(p.cast<float>());
  }
  const PointOctree& points() const { return points_; }

 private:
  PointOctree points_;
};

}  // namespace octomotion::pointcloud
