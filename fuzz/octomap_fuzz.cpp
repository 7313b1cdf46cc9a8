// Fuzzes the OctoMap .bt importer (our pre-check of the whole file, then liboctomap's parser):
// both the native import and the import onto another grid give a valid tree or an
// octomotion::Error, and on a grid aligned with the file's keys kCenter reproduces the native
// import (octomap_io.h).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/octree/octomap_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace octomotion;
  const std::string path = fuzz::writeInput(data, size, ".bt");
  try {
    const Octree native = importOctoMap(path);
    if (!native.checkInvariants()) fuzz::fail("imported tree breaks the invariants");
    // A small grid near the key origin, on the file's voxel size.
    const double res = native.grid().voxelSize();
    const WorldGrid grid(Eigen::Vector3d::Constant(-8 * res), res, 4);
    const WarningSink quiet = [](const std::string&) {};
    const Octree center = importOctoMap(path, grid, Rounding::kCenter, quiet);
    const Octree conservative = importOctoMap(path, grid, Rounding::kConservative, quiet);
    if (!center.checkInvariants() || !conservative.checkInvariants()) {
      fuzz::fail("re-gridded tree breaks the invariants");
    }
    // Voxel by voxel: kCenter on the aligned grid is the native import, conservative covers it.
    const std::uint32_t side = grid.sideVoxels();
    for (std::uint32_t z = 0; z < side; ++z) {
      for (std::uint32_t y = 0; y < side; ++y) {
        for (std::uint32_t x = 0; x < side; ++x) {
          const std::uint32_t k = 32768 - 8;
          const bool in_file = native.occupied(Voxel{k + x, k + y, k + z});
          if (center.occupied(Voxel{x, y, z}) != in_file)
            fuzz::fail("kCenter differs from the file");
          if (in_file && !conservative.occupied(Voxel{x, y, z})) {
            fuzz::fail("kConservative misses an occupied voxel");
          }
        }
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
