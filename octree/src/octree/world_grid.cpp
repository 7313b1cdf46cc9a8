#include "octomotion/octree/world_grid.h"

#include <cmath>
#include <string>

#include "octomotion/error.h"

namespace octomotion {

WorldGrid::WorldGrid(const Eigen::Vector3d& origin, double voxel_size, int depth)
    : origin_(origin), voxel_size_(voxel_size), depth_(depth) {
  if (!origin.allFinite()) throw InvalidArgument("WorldGrid: origin must be finite");
  if (!std::isfinite(voxel_size) || !(voxel_size > 0.0)) {
    throw InvalidArgument("WorldGrid: voxel size must be finite and > 0, got " +
                          std::to_string(voxel_size));
  }
  if (depth < 1 || depth > kMaxDepth) {
    throw InvalidArgument("WorldGrid: depth must be in [1, " + std::to_string(kMaxDepth) +
                          "], got " + std::to_string(depth));
  }
}

bool WorldGrid::voxelAt(const Eigen::Vector3d& p_W, Voxel* voxel) const {
  const Eigen::Vector3d g = toGrid(p_W);
  const double side = static_cast<double>(sideVoxels());
  // Written so that NaN fails every comparison and is reported as outside.
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.z() >= 0.0 && g.x() < side && g.y() < side &&
        g.z() < side)) {
    return false;
  }
  voxel->x = static_cast<std::uint32_t>(g.x());
  voxel->y = static_cast<std::uint32_t>(g.y());
  voxel->z = static_cast<std::uint32_t>(g.z());
  return true;
}

Eigen::Vector3d WorldGrid::voxelCenter(const Voxel& v) const {
  return toWorld(Eigen::Vector3d(v.x + 0.5, v.y + 0.5, v.z + 0.5));
}

Eigen::Vector3d WorldGrid::cubeMin(const Cube& c) const {
  return toWorld(Eigen::Vector3d(c.origin.x, c.origin.y, c.origin.z));
}

Eigen::Vector3d WorldGrid::cubeMax(const Cube& c) const {
  const double s = static_cast<double>(c.side());
  return toWorld(Eigen::Vector3d(c.origin.x + s, c.origin.y + s, c.origin.z + s));
}

}  // namespace octomotion
