// A robot's collision meshes as a scene asks for them (the file's root transform kept or not,
// vertices centred on their mean or not — OMPL.app's convention), each (file, scale) loaded once.
// The one loader of a robot's geometry: every model built from a RobotModel (octree, FCL, glTF
// export, bounding boxes) reads its meshes through this, so they all see the same triangles in
// the same frame, and tests read them the same way to check what a model made of them.
#pragma once

#include <array>
#include <map>
#include <string>
#include <utility>

#include "octomotion/octree/mesh.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

class CollisionMeshes {
 public:
  CollisionMeshes(bool keep_root_transform, bool center_vertices)
      : keep_root_transform_(keep_root_transform), center_vertices_(center_vertices) {}

  // Loads on first use (throws what loadMesh throws); the reference stays valid as long as this
  // object lives.
  const TriangleMesh& get(const MeshRef& ref) {
    const Key key(ref.path, {ref.scale.x(), ref.scale.y(), ref.scale.z()});
    auto it = meshes_.find(key);
    if (it == meshes_.end()) {
      MeshLoadOptions options;
      options.keep_root_transform = keep_root_transform_;
      options.scale = ref.scale;
      TriangleMesh mesh = loadMesh(ref.path, options);
      if (center_vertices_) centerOnVertexMean(mesh);
      it = meshes_.emplace(key, std::move(mesh)).first;
    }
    return it->second;
  }

 private:
  using Key = std::pair<std::string, std::array<double, 3>>;
  bool keep_root_transform_;
  bool center_vertices_;
  std::map<Key, TriangleMesh> meshes_;
};

}  // namespace octomotion
