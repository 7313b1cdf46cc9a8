// What a link's collision geometry is, independent of how it is voxelized later: a list of
// elements (one per URDF <collision>), each a primitive or a mesh file placed in the link frame.
#pragma once

#include <string>
#include <variant>

#include <Eigen/Geometry>

#include "octomotion/octree/shapes.h"

namespace octomotion {

// A mesh a collision element refers to. Loading it is left to the voxelizer, which loads each
// file once: robots use MeshLoadOptions{.keep_root_transform = false, .scale = scale}.
struct MeshRef {
  std::string path;                                 // absolute, resolved, existing file
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // URDF <mesh scale>; finite, non-zero
};

using CollisionGeometry = std::variant<Primitive, MeshRef>;

struct CollisionElement {
  Eigen::Isometry3d X_LE = Eigen::Isometry3d::Identity();  // element frame E in link frame L
  CollisionGeometry geometry;
  std::string name;  // the URDF <collision name="..."> attribute; often empty
};

}  // namespace octomotion
