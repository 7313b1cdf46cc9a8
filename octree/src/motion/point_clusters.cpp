#include "octomotion/motion/point_clusters.h"

#include <algorithm>
#include <utility>

#include <Eigen/Geometry>

namespace octomotion {

std::vector<PointCluster> clusterPoints(const std::vector<Eigen::Vector3d>& points,
                                        std::size_t max_points, std::vector<std::uint32_t>& order) {
  order.resize(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::vector<PointCluster> clusters;
  if (points.empty()) return clusters;
  std::vector<std::pair<std::size_t, std::size_t>> todo = {{0, order.size()}};
  while (!todo.empty()) {
    const auto [begin, end] = todo.back();
    todo.pop_back();
    Eigen::AlignedBox3d box;
    for (std::size_t k = begin; k < end; ++k) box.extend(points[order[k]]);
    if (end - begin > std::max<std::size_t>(max_points, 1)) {
      Eigen::Index axis = 0;
      box.sizes().maxCoeff(&axis);
      const std::size_t middle = begin + (end - begin) / 2;
      std::nth_element(
          order.begin() + static_cast<std::ptrdiff_t>(begin),
          order.begin() + static_cast<std::ptrdiff_t>(middle),
          order.begin() + static_cast<std::ptrdiff_t>(end),
          [&](std::uint32_t a, std::uint32_t b) { return points[a][axis] < points[b][axis]; });
      todo.emplace_back(begin, middle);
      todo.emplace_back(middle, end);
      continue;
    }
    PointCluster cluster;
    cluster.centre = box.center();
    for (std::size_t k = begin; k < end; ++k) {
      cluster.radius = std::max(cluster.radius, (points[order[k]] - cluster.centre).norm());
    }
    cluster.begin = static_cast<std::uint32_t>(begin);
    cluster.end = static_cast<std::uint32_t>(end);
    clusters.push_back(cluster);
  }
  return clusters;
}

}  // namespace octomotion
