// A downstream program: builds two small trees on one grid and tests them for overlap.
#include <iostream>

#include <octomotion/octree/octree.h>
#include <octomotion/octree/traversal.h>

int main() {
  using namespace octomotion;
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.01, 5);
  const Octree a = Octree::fromVoxels(grid, {{1, 2, 3}, {4, 4, 4}});
  const Octree b = Octree::fromVoxels(grid, {{4, 4, 4}});
  std::cout << "intersects=" << intersects(a, b) << "\n";
  return intersects(a, b) ? 0 : 1;
}
