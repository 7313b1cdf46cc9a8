// A downstream program: builds two small trees on one grid and tests them for overlap, and
// parses a scene with the planner library.
#include <iostream>

#include <octomotion/octree/octree.h>
#include <octomotion/octree/traversal.h>
#include <octomotion/planner/scene/scene.h>

int main() {
  using namespace octomotion;
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.01, 5);
  const Octree a = Octree::fromVoxels(grid, {{1, 2, 3}, {4, 4, 4}});
  const Octree b = Octree::fromVoxels(grid, {{4, 4, 4}});
  const SceneSpec scene = parseSceneYaml("robot: {mesh: body.stl}", "/scenes/s.yaml");
  std::cout << "intersects=" << intersects(a, b) << " robot=" << scene.robot.mesh << "\n";
  return intersects(a, b) && scene.robot.mesh == "/scenes/body.stl" ? 0 : 1;
}
