// Mesh topology helpers shared by mesh.cpp and voxelize_mesh.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "octomotion/octree/mesh.h"

namespace octomotion::detail {

// For each vertex, the index of the first vertex at exactly the same position.
std::vector<std::uint32_t> weldByPosition(const TriangleMesh& mesh);

// Edge statistics over the position-welded mesh, ignoring triangles with two equal corners.
struct EdgeCensus {
  std::size_t triangles = 0;  // triangles with three distinct corners
  // Every edge is traversed exactly once in each direction (closed, oriented 2-manifold).
  bool manifold = true;
  // Edges used by an odd number of triangles. Zero means the surface bounds a solid in the mod-2
  // sense, which is all ray parity needs (orientation and edges shared by four faces are fine).
  std::size_t odd_edges = 0;
};
EdgeCensus edgeCensus(const TriangleMesh& mesh);

}  // namespace octomotion::detail
