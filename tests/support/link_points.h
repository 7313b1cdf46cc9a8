// Points of a link's collision geometry in its own frame, for tests that follow points through
// forward kinematics (motion bounds against the points' real paths).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <variant>
#include <vector>

#include "octomotion/octree/shapes.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::test {

// At most `max_points` points of the link's geometry (every k-th mesh vertex, every corner of a
// primitive's box), in the link frame. A point's path length is convex in the point (its speed
// is the norm of an affine function of it), so the hull's worst points are among these.
inline std::vector<Eigen::Vector3d> linkPoints(const Link& link, CollisionMeshes& meshes,
                                               std::size_t max_points) {
  std::vector<Eigen::Vector3d> all;
  for (const CollisionElement& e : link.collision) {
    if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
      const Eigen::AlignedBox3d box = boundingBox(*p, e.X_LE);
      for (int c = 0; c < 8; ++c) {
        all.push_back(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
      }
    } else {
      for (const Eigen::Vector3d& v : meshes.get(std::get<MeshRef>(e.geometry)).vertices) {
        all.push_back(e.X_LE * v);
      }
    }
  }
  if (all.size() <= max_points) return all;
  std::vector<Eigen::Vector3d> some;
  const std::size_t step = all.size() / max_points + 1;
  for (std::size_t i = 0; i < all.size(); i += step) some.push_back(all[i]);
  return some;
}

}  // namespace octomotion::test
