#include "internal/clearance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "octomotion/octree/distance.h"

namespace octomotion::detail {

ClearanceLevels ClearanceLevels::build(const Octree& environment) {
  ClearanceLevels result;
  if (environment.empty()) return result;
  const WorldGrid& grid = environment.grid();
  std::vector<std::vector<Eigen::Vector3f>> centres(static_cast<std::size_t>(grid.depth()) + 1);
  environment.forEachBlackLeaf([&](const Cube& c) {
    centres[static_cast<std::size_t>(c.level)].push_back(
        ((grid.cubeMin(c) + grid.cubeMax(c)) / 2).cast<float>());
  });
  for (std::size_t level = 0; level < centres.size(); ++level) {
    if (centres[level].empty()) continue;
    const double side = grid.voxelSize() * static_cast<double>(std::uint64_t{1} << level);
    result.levels_.push_back(
        {side * std::sqrt(3.0) / 2, pointcloud::PointOctree::build(centres[level])});
  }
  // Centres rounded to float move by at most |coordinate| * 2^-24 per axis, and float
  // distances carry a few ulps of relative error: 1e-6 of the largest coordinate (plus 1 um)
  // covers both with a wide margin.
  const double extent = std::max(grid.origin().cwiseAbs().maxCoeff(),
                                 (grid.origin().array() + grid.sideMetres()).abs().maxCoeff());
  result.float_slack_ = 1e-6 * (1 + 4 * extent);
  return result;
}

double ClearanceLevels::lowerBound(const LinkModels& links, const RobotData& robot) const {
  // For a clearance sphere (centre c, radius r) and a black cube of half diagonal h whose centre
  // is at distance d from c, every point of the cube is at least d - h from c, so at least
  // d - h - r from the sphere, which covers the link's black voxels. The minimum over levels and
  // spheres, less the float slack, is therefore a lower bound on the distance between the links'
  // voxels and the environment's; it is below kEnvironmentTree's by at most the nearest cube's h.
  double best = std::numeric_limits<double>::infinity();
  for (const LinkTree& lt : links.links) {
    if (!lt.touches_environment) continue;
    const Eigen::Isometry3d& X_WL = robot.linkPose(lt.link);
    for (const Eigen::Vector4d& s : lt.spheres_L) {
      const Eigen::Vector3f c_W = (X_WL * Eigen::Vector3d(s.head<3>())).cast<float>();
      for (const Level& level : levels_) {
        // Only centres nearer than `beat` can lower the bound: the search prunes the rest.
        const double margin = level.half_diagonal + s[3] + float_slack_;
        const double d = level.centres.nearestDistance(c_W, best + margin) - margin;
        best = std::min(best, d);
      }
      if (best <= 0) return 0;
    }
  }
  return best;
}

double clearanceLowerBoundTree(const LinkModels& links, const Octree& environment,
                               const RobotData& robot) {
  double best = std::numeric_limits<double>::infinity();
  for (const LinkTree& lt : links.links) {
    if (!lt.touches_environment) continue;
    const Eigen::Isometry3d& X_WL = robot.linkPose(lt.link);
    for (const Eigen::Vector4d& s : lt.spheres_L) {
      // Distance to beat is best + r: a sphere can only lower the bound below `best` if its
      // centre is nearer than that.
      const double d =
          distanceToBlack(environment, X_WL * Eigen::Vector3d(s.head<3>()), best + s[3]);
      best = std::min(best, d - s[3]);
      if (best <= 0) return 0;
    }
  }
  return best;
}

}  // namespace octomotion::detail
