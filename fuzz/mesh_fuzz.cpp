// Fuzzes the mesh loader (assimp, then our checks) for one file format, chosen at build time
// (OCTOMOTION_FUZZ_EXT: ".stl", ".obj", ".dae"; assimp dispatches on the extension first). What
// is accepted is voxelized on a small grid, exercising the voxelizer on whatever geometry the
// loader lets through (huge, tiny, degenerate or open meshes).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/voxelize.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace octomotion;
  const std::string path = fuzz::writeInput(data, size, OCTOMOTION_FUZZ_EXT);
  try {
    const TriangleMesh mesh = loadMesh(path);
    validateMesh(mesh);  // the loader promises finite vertices and indices in range
    isClosedManifold(mesh);
    const WorldGrid grid(Eigen::Vector3d::Constant(-1.0), 1.0 / 16, 5);
    const Octree tree = voxelizeMesh(grid, mesh, Eigen::Isometry3d::Identity(),
                                     Rounding::kConservative, [](const std::string&) {});
    if (!tree.checkInvariants()) fuzz::fail("voxelized mesh breaks the octree invariants");
  } catch (const Error&) {
  }
  return 0;
}
