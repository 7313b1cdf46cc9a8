#include "octomotion/octree/distance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/octree/bits.h"

namespace octomotion {

namespace {

double distanceToBox(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  return std::sqrt((p - p.cwiseMax(box.min()).cwiseMin(box.max())).squaredNorm());
}

}  // namespace

double distanceToBlack(const Octree& tree, const Eigen::Vector3d& p_W, double best) {
  if (tree.empty()) return best;
  const WorldGrid& g = tree.grid();
  auto cubeBox = [&](const Cube& c) { return Eigen::AlignedBox3d(g.cubeMin(c), g.cubeMax(c)); };
  if (tree.rootColor() == Color::kBlack) {
    return std::min(best, distanceToBox(p_W, cubeBox(g.universe())));
  }
  struct Item {
    std::uint32_t index;
    Cube cube;
  };
  std::vector<Item> stack{{0, g.universe()}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (distanceToBox(p_W, cubeBox(item.cube)) >= best) continue;
    const OctreeNode& n = tree.nodes()[item.index];
    for (unsigned m = n.occupied(); m; m &= m - 1) {
      const int k = lowestBit(m);
      const Cube child = item.cube.child(k);
      const double d = distanceToBox(p_W, cubeBox(child));
      if (d >= best) continue;
      if (n.black & (1u << k)) {
        best = d;
      } else {
        stack.push_back({n.childIndex(k), child});
      }
    }
  }
  return best;
}

}  // namespace octomotion
