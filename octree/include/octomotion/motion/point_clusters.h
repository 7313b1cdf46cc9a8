// Nearby points in clusters, for searches that skip a whole cluster by a bound on its ball (the
// support point of a convex set, the vertex nearest or farthest from a point, the largest
// distance from an axis): the points are split at the median along the longest side of their
// box until a part holds at most `max_points`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace octomotion {

struct PointCluster {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of the cluster's box
  double radius = 0;                                 // every point lies within it of the centre
  std::uint32_t begin = 0, end = 0;                  // its points: order[begin .. end)
};

// The clusters of `points` (max_points >= 1); `order` receives the points' indices so that each
// cluster's are contiguous.
std::vector<PointCluster> clusterPoints(const std::vector<Eigen::Vector3d>& points,
                                        std::size_t max_points, std::vector<std::uint32_t>& order);

}  // namespace octomotion
