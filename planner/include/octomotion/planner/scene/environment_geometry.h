// The static environment of a scene: its objects loaded once, the universe fitted to what the
// robot can reach, and the environment octree built on that universe (parts outside it are not
// modelled: nothing the robot can reach lies there).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octree.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// The smallest universe of cubic voxels of side `resolution` that covers `region_W`: origin at
// the region's minimum corner, depth = ceil(log2(longest side / resolution)) (at least 1).
// Throws InvalidArgument when that needs a depth above kMaxDepth or the inputs are not finite.
WorldGrid fitGrid(const Eigen::AlignedBox3d& region_W, double resolution);

struct EnvironmentObjectReport {
  std::string name;
  std::size_t black_leaves = 0;
  std::size_t internal_nodes = 0;
  double build_seconds = 0;
};

struct EnvironmentReport {
  std::vector<EnvironmentObjectReport> objects;
  std::size_t internal_nodes = 0;
  std::size_t bytes = 0;
  double build_seconds = 0;
};

class EnvironmentGeometry {
 public:
  // Reads every file an object names (meshes, point clouds, OctoMaps) once. Throws FileError
  // naming the file, and InvalidArgument for an object still in a robot frame
  // (EnvironmentObject::frame: resolveSceneFrames places it). A point cloud's points each mark
  // their voxel (whatever the rounding); non-finite points are skipped with a warning.
  static EnvironmentGeometry load(const std::vector<EnvironmentObject>& objects,
                                  const WarningSink& warnings = {});

  // World-frame bounding box of every object; empty when there are none.
  std::optional<Eigen::AlignedBox3d> bounds() const;
  // The same objects less the primitives (for a tree of what has no exact shape to test).
  EnvironmentGeometry withoutPrimitives() const;
  // The union of every object's octree on `grid`.
  Octree voxelize(const WorldGrid& grid, Rounding rounding, EnvironmentReport* report = nullptr,
                  const WarningSink& warnings = {}) const;
  // Object i's octree on `grid` (voxelize unites these).
  Octree voxelizeObject(std::size_t i, const WorldGrid& grid, Rounding rounding,
                        const WarningSink& warnings = {}) const;

  struct Item {
    EnvironmentObject spec;
    TriangleMesh mesh;                      // kMesh, in the object's frame
    std::vector<Eigen::Vector3f> points_W;  // kPointCloud, posed in the world
    Eigen::AlignedBox3d bounds_W;
  };
  std::size_t size() const { return items_.size(); }
  // The loaded objects, for reference checkers that use the exact geometry.
  const std::vector<Item>& items() const { return items_; }

  // Changes between plans (environment_updates.cpp). One object loaded (its file read) as load()
  // does.
  static Item loadItem(const EnvironmentObject& object, const WarningSink& warnings = {});
  // The object named `name`, or null.
  const Item* find(const std::string& name) const;
  // Appends an object; InvalidArgument when an object of that name exists.
  void add(Item item);
  // Removes the named object and returns it; InvalidArgument naming it when there is none.
  Item remove(const std::string& name);
  // Moves the named object to X_WO (its bounds follow); InvalidArgument for an unknown name, a
  // pose that is not finite, an OctoMap (in world coordinates) or a point cloud (its points are
  // stored posed: remove it and add it at the new pose).
  void setPose(const std::string& name, const Eigen::Isometry3d& X_WO);

 private:
  std::vector<Item> items_;
};

}  // namespace octomotion
