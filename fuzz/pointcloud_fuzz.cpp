// Fuzzes the point-cloud loaders (PCD ascii/binary, PLY ascii/binary, XYZ) for one format chosen
// at build time (OCTOMOTION_FUZZ_EXT; loadPointCloud dispatches on the extension): a cloud of
// finite points or an octomotion::Error. Accepted clouds are turned into an environment tree.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/pointcloud/environment.h"
#include "octomotion/pointcloud/point_cloud_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace octomotion;
  const std::string path = fuzz::writeInput(data, size, OCTOMOTION_FUZZ_EXT);
  try {
    const pointcloud::PointCloud cloud = pointcloud::loadPointCloud(path);
    for (const Eigen::Vector3f& p : cloud.points) {
      if (!p.allFinite()) fuzz::fail("a non-finite point was kept");
    }
    const WorldGrid grid(Eigen::Vector3d::Constant(-1.0), 1.0 / 16, 5);
    pointcloud::EnvironmentStats stats;
    const Octree tree = pointcloud::environmentFromPoints(grid, cloud.points, {}, &stats);
    if (!tree.checkInvariants()) fuzz::fail("cloud tree breaks the invariants");
    if (stats.points_used + stats.outside_universe != cloud.points.size()) {
      fuzz::fail("points lost between loading and the tree");
    }
    pointcloud::EnvironmentOptions thinned;
    thinned.downsample_voxel = 0.05;
    const Octree coarse = pointcloud::environmentFromPoints(grid, cloud.points, thinned);
    if (!coarse.checkInvariants()) fuzz::fail("downsampled cloud tree breaks the invariants");
  } catch (const Error&) {
  }
  return 0;
}
