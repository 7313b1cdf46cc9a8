// Point cloud -> occupancy octree and clearance map.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "octomotion/error.h"
#include "octomotion/pointcloud/environment.h"

namespace octomotion::pointcloud {

std::vector<Eigen::Vector3f> downsample(const std::vector<Eigen::Vector3f>& points, double voxel) {
  if (!std::isfinite(voxel) || !(voxel > 0))
    throw InvalidArgument("downsample: voxel size must be finite and > 0");
  struct Sum {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t count = 0;
    std::size_t order = 0;
  };
  // Cube key: the three integer cube coordinates packed 21 bits each; coordinates beyond
  // +-2^20 cubes would alias, so they are rejected.
  std::unordered_map<std::uint64_t, Sum> cubes;
  cubes.reserve(points.size() / 4 + 16);
  std::vector<std::uint64_t> order;
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d c = (p.cast<double>() / voxel).array().floor();
    if ((c.array().abs() >= double(1 << 20)).any())
      throw InvalidArgument("downsample: point too far from the origin for this voxel size");
    const auto pack = [](double v) {
      return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + (1 << 20)) & 0x1fffffu;
    };
    const std::uint64_t key = pack(c.x()) | (pack(c.y()) << 21) | (pack(c.z()) << 42);
    Sum& s = cubes[key];
    if (s.count == 0) {
      s.order = order.size();
      order.push_back(key);
    }
    s.sum += p.cast<double>();
    ++s.count;
  }
  std::vector<Eigen::Vector3f> out;
  out.reserve(order.size());
  for (std::uint64_t key : order) {
    const Sum& s = cubes[key];
    out.push_back((s.sum / static_cast<double>(s.count)).cast<float>());
  }
  return out;
}

Octree environmentFromPoints(const WorldGrid& grid, const std::vector<Eigen::Vector3f>& points,
                             const EnvironmentOptions& options, EnvironmentStats* stats) {
  EnvironmentStats local;
  local.points_in = points.size();
  const std::vector<Eigen::Vector3f> thinned = options.downsample_voxel > 0
                                                   ? downsample(points, options.downsample_voxel)
                                                   : std::vector<Eigen::Vector3f>{};
  if (options.downsample_voxel < 0 || std::isnan(options.downsample_voxel))
    throw InvalidArgument("environmentFromPoints: downsample_voxel must be >= 0");
  const std::vector<Eigen::Vector3f>& source = options.downsample_voxel > 0 ? thinned : points;
  std::vector<Voxel> voxels;
  voxels.reserve(source.size());
  for (const Eigen::Vector3f& p : source) {
    Voxel v;
    if (!grid.voxelAt(p.cast<double>(), &v)) {  // NaN reports as outside too
      ++local.outside_universe;
      continue;
    }
    voxels.push_back(v);
    ++local.points_used;
  }
  // Deduplicate: many points share a voxel.
  std::sort(voxels.begin(), voxels.end(), [](const Voxel& a, const Voxel& b) {
    return a.z != b.z ? a.z < b.z : (a.y != b.y ? a.y < b.y : a.x < b.x);
  });
  voxels.erase(std::unique(voxels.begin(), voxels.end()), voxels.end());
  local.occupied_voxels = voxels.size();
  if (stats) *stats = local;
  return Octree::fromVoxels(grid, voxels);
}

namespace {

std::vector<Eigen::Vector3f> finitePoints(const std::vector<Eigen::Vector3f>& points,
                                          const EnvironmentOptions& options) {
  if (options.downsample_voxel > 0) return downsample(points, options.downsample_voxel);
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const Eigen::Vector3f& p : points)
    if (p.allFinite()) out.push_back(p);
  return out;
}

}  // namespace

ClearanceMap::ClearanceMap(const std::vector<Eigen::Vector3f>& points,
                           const EnvironmentOptions& options)
    : points_(PointOctree::build(finitePoints(points, options))) {}

}  // namespace octomotion::pointcloud
