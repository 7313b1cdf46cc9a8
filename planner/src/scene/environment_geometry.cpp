#include "octomotion/planner/scene/environment_geometry.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "octomotion/octree/octomap_io.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/voxelize.h"
#include "octomotion/pointcloud/environment.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Eigen::AlignedBox3d boxOfPoints(const std::vector<Eigen::Vector3d>& points_O,
                                const Eigen::Isometry3d& X_WO) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points_O) box.extend(X_WO * p);
  return box;
}

Eigen::AlignedBox3d octreeBounds(const Octree& tree) {
  Eigen::AlignedBox3d box;
  if (const auto b = tree.bounds()) {
    box.extend(tree.grid().cubeMin(Cube{0, b->min}));
    box.extend(tree.grid().cubeMax(Cube{0, b->max}));
  }
  return box;
}

}  // namespace

WorldGrid fitGrid(const Eigen::AlignedBox3d& region_W, double resolution) {
  if (!(std::isfinite(resolution) && resolution > 0)) {
    std::ostringstream what;
    what << "resolution must be finite and > 0, got " << resolution;
    throw InvalidArgument(what.str());
  }
  if (region_W.isEmpty() || !region_W.min().allFinite() || !region_W.max().allFinite()) {
    throw InvalidArgument("the region to model is empty or not finite");
  }
  const double longest = region_W.sizes().maxCoeff();
  int depth = 1;
  while (depth <= kMaxDepth && std::ldexp(resolution, depth) < longest) ++depth;
  if (depth > kMaxDepth) {
    std::ostringstream what;  // %g: a 1e-9 m resolution must not print as 0.000000
    what << "resolution " << resolution << " m over a region of " << longest
         << " m needs more than " << kMaxDepth << " octree levels; use a coarser resolution";
    throw InvalidArgument(what.str());
  }
  return WorldGrid(region_W.min(), resolution, depth);
}

EnvironmentGeometry EnvironmentGeometry::load(const std::vector<EnvironmentObject>& objects,
                                              const WarningSink& warnings) {
  EnvironmentGeometry env;
  for (const EnvironmentObject& spec : objects) {
    Item item{spec, {}, {}, {}};
    if (!spec.X_WO.matrix().allFinite()) {
      throw InvalidArgument(spec.name + ": pose is not finite");
    }
    if (!spec.frame.empty() || spec.robot_root_frame) {
      // Placing it needs the robot: resolveSceneFrames (scene_frames.h) first.
      throw InvalidArgument(spec.name + ": pose is relative to the robot's frame '" +
                            (spec.frame.empty() ? std::string("root") : spec.frame) +
                            "', not resolved to the world");
    }
    switch (spec.kind) {
      case EnvironmentObject::Kind::kPrimitive:
        validate(spec.primitive);
        item.bounds_W = boundingBox(spec.primitive, spec.X_WO);
        break;
      case EnvironmentObject::Kind::kMesh: {
        if (spec.mesh) {
          item.mesh = *spec.mesh;  // given inline (a MoveIt mesh)
        } else {
          MeshLoadOptions options;
          options.keep_root_transform = spec.keep_mesh_root_transform;
          options.scale = spec.scale;
          item.mesh = loadMesh(spec.file, options);
        }
        item.bounds_W = boxOfPoints(item.mesh.vertices, spec.X_WO);
        break;
      }
      case EnvironmentObject::Kind::kOctomap: {
        // A map is already in world coordinates: resampling it under another pose would blur it.
        if (!spec.X_WO.isApprox(Eigen::Isometry3d::Identity())) {
          throw InvalidArgument(spec.name +
                                ": an OctoMap is in world coordinates already; "
                                "its pose must be the identity");
        }
        item.bounds_W = octreeBounds(importOctoMap(spec.file));
        break;
      }
      case EnvironmentObject::Kind::kPointCloud: {
        pointcloud::PointCloud cloud = pointcloud::loadPointCloud(spec.file);
        if (cloud.skipped_non_finite > 0) {
          warn(warnings, spec.file + ": skipped " + std::to_string(cloud.skipped_non_finite) +
                             " points with a NaN or infinite coordinate");
        }
        const Eigen::Isometry3f X = spec.X_WO.cast<float>();
        item.points_W.reserve(cloud.points.size());
        for (const Eigen::Vector3f& p : cloud.points) {
          item.points_W.push_back(X * p);
          item.bounds_W.extend(item.points_W.back().cast<double>());
        }
        break;
      }
    }
    env.items_.push_back(std::move(item));
  }
  return env;
}

std::optional<Eigen::AlignedBox3d> EnvironmentGeometry::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Item& item : items_) {
    if (!item.bounds_W.isEmpty()) box.extend(item.bounds_W);
  }
  if (box.isEmpty()) return std::nullopt;
  return box;
}

EnvironmentGeometry EnvironmentGeometry::withoutPrimitives() const {
  EnvironmentGeometry rest;
  for (const Item& item : items_) {
    if (item.spec.kind != EnvironmentObject::Kind::kPrimitive) rest.items_.push_back(item);
  }
  return rest;
}

Octree EnvironmentGeometry::voxelize(const WorldGrid& grid, Rounding rounding,
                                     EnvironmentReport* report, const WarningSink& warnings) const {
  const auto start = std::chrono::steady_clock::now();
  Octree all(grid);
  for (const Item& item : items_) {
    const auto t0 = std::chrono::steady_clock::now();
    const Octree part =
        voxelizeObject(static_cast<std::size_t>(&item - items_.data()), grid, rounding, warnings);
    all = unite(all, part);
    if (report) {
      report->objects.push_back(
          {item.spec.name, part.blackLeafCount(), part.internalNodeCount(), secondsSince(t0)});
    }
  }
  if (report) {
    report->internal_nodes = all.internalNodeCount();
    report->bytes = all.bytes();
    report->build_seconds = secondsSince(start);
  }
  return all;
}

Octree EnvironmentGeometry::voxelizeObject(std::size_t i, const WorldGrid& grid, Rounding rounding,
                                           const WarningSink& warnings) const {
  const Item& item = items_.at(i);
  switch (item.spec.kind) {
    case EnvironmentObject::Kind::kPrimitive:
      return octomotion::voxelize(grid, item.spec.primitive, item.spec.X_WO, rounding);
    case EnvironmentObject::Kind::kMesh:
      return voxelizeMesh(grid, item.mesh, item.spec.X_WO, rounding, warnings);
    case EnvironmentObject::Kind::kOctomap:
      return importOctoMap(item.spec.file, grid, rounding, warnings);
    case EnvironmentObject::Kind::kPointCloud:
      return pointcloud::environmentFromPoints(grid, item.points_W);
  }
  return Octree(grid);
}

}  // namespace octomotion
