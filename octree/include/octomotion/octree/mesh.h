// Triangle meshes: loading (via assimp) and the closed-manifold check that decides whether a
// mesh is voxelized solid or as a surface shell.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octomotion/input_limits.h"

namespace octomotion {

// Indexed triangles; the outward side is the counter-clockwise one (right-hand rule).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct MeshLoadOptions {
  // What assimp (5.2) puts in the root node's transform: for Collada, the file's <unit> scale
  // times the rotation taking its <up_axis> to assimp's Y-up (Z_UP: (x, y, z) -> (x, z, -y)).
  // true = apply it (the Collada reading). false = reset it to identity, as ROS RViz and MoveIt
  // (geometric_shapes) do for URDF meshes: vertices stay as written, which also ignores <unit>.
  bool keep_root_transform = true;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // URDF <mesh scale>, applied last
  // Larger files are refused before assimp reads them (its import takes ~40x the file size).
  std::uintmax_t max_file_bytes = kMaxMeshFileBytes;
};

// Loads every triangle of every mesh in the file (STL binary/ASCII, Collada, OBJ, ... whatever
// assimp reads), with the node hierarchy's transforms applied, then `scale`. Throws FileError
// naming the path when the file is missing, unreadable, not a mesh, has no triangles or has a
// non-finite vertex; InvalidArgument for a non-finite or zero scale.
TriangleMesh loadMesh(const std::string& path, const MeshLoadOptions& options = {});

// Shifts the vertices so that their mean is the origin (OMPL.app's convention for robots);
// returns the shift that was subtracted.
Eigen::Vector3d centerOnVertexMean(TriangleMesh& mesh);

// Throws InvalidArgument (naming `what`) for an index out of range or a non-finite vertex.
void validateMesh(const TriangleMesh& mesh, const std::string& what = "mesh");

// True when every edge is shared by exactly two triangles that traverse it in opposite
// directions. Vertices are identified by position (so unwelded STL meshes work); triangles
// with two identical corners are ignored. An empty mesh is not closed. Throws InvalidArgument
// like validateMesh for a bad index or vertex.
bool isClosedManifold(const TriangleMesh& mesh);

// Closed, outward-oriented tessellations, handy for tests and benchmarks.
// A box centred on the origin, each face split into n x n squares of two triangles (n >= 1).
TriangleMesh boxMesh(const Eigen::Vector3d& half_extents, int n = 1);
// A UV sphere with `segments` >= 3 around the z axis and `rings` >= 2 from pole to pole:
// 2 * segments * (rings - 1) triangles, vertices on the sphere (so it lies inside it).
TriangleMesh sphereMesh(double radius, int segments, int rings);
// A torus around the z axis (tube centre radius R > r), 2 * segments * sides triangles.
TriangleMesh torusMesh(double R, double r, int segments, int sides);

}  // namespace octomotion
