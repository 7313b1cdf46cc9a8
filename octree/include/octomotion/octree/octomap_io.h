// Interoperation with OctoMap's binary occupancy files (".bt", liboctomap's OcTree::writeBinary).
// liboctomap is a private dependency: only toOctoMap names one of its types (declared, not
// included), for callers that link liboctomap themselves.
//
// OctoMap addresses voxels by 16-bit keys per axis: its tree always has depth 16 and key 32768
// is the voxel whose minimum corner is coordinate 0, so voxel key k spans
// [(k - 32768) * res, (k - 32767) * res). Its child numbering (bit 0 = +x, bit 1 = +y,
// bit 2 = +z) is the same as ours (Ahuja & Nash 1984 Fig. 1), so on the "native" grid below an
// OctoMap node and our cube of the same keys are the same region.
//
// Occupancy: a voxel is black iff it lies in an OctoMap leaf for which OctoMap's
// isNodeOccupied() holds. Free and unknown space both become white.
#pragma once

#include <memory>
#include <string>

#include "octomotion/error.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"

namespace octomap {
class OcTree;
}  // namespace octomap

namespace octomotion {

// The grid on which OctoMap keys are our voxel coordinates: depth 16, voxel size `resolution`,
// origin -32768 * resolution on each axis. Throws InvalidArgument for a bad resolution.
WorldGrid octomapNativeGrid(double resolution);

// Reads a .bt file onto its native grid: exact, one black voxel per occupied OctoMap voxel.
// The file is checked in full before liboctomap parses it (header, and that the bit stream is
// complete, no deeper than 16 levels and not followed by stray bytes): FileError naming the path
// and the defect otherwise.
Octree importOctoMap(const std::string& path);

// Reads a .bt file onto any grid. Each occupied OctoMap leaf is an upright box; with
// kConservative every voxel the (closed) box touches turns black, with kCenter every voxel whose
// centre lies in the closed box. On a grid aligned with the file's keys and of the same voxel
// size, kCenter reproduces the file exactly, while kConservative adds the voxels that only touch
// a leaf along a face, edge or corner. Parts outside the grid's universe are dropped, with one
// warning to `warnings`.
Octree importOctoMap(const std::string& path, const WorldGrid& grid, Rounding rounding,
                     const WarningSink& warnings = {});

// Writes the tree as a .bt file with resolution = the tree's voxel size. Black voxels become
// occupied OctoMap leaves (whole cubes, not voxel by voxel, then pruned); white space is left
// unknown, or written as free leaves when `write_free_space` (then the universe is all known).
// Throws InvalidArgument, saying why, unless the grid lies on OctoMap's key grid: origin / voxel
// size a whole number on every axis, and every voxel to be written within the 16-bit key range.
// Throws FileError when the file cannot be written. The resolution is stored at full precision,
// so importOctoMap(path) on the result reproduces the occupancy, key for key.
void exportOctoMap(const Octree& tree, const std::string& path, bool write_free_space = false);

// The same OctoMap in memory (black voxels as occupied leaves, white space unknown, pruned), for
// libraries that take an octomap::OcTree (e.g. fcl::OcTree). Same conditions and exceptions as
// exportOctoMap.
std::unique_ptr<octomap::OcTree> toOctoMap(const Octree& tree);

// What liboctomap's OcTree takes in memory for the same occupancy (black = occupied leaves, white
// = unknown, pruned), as its memoryUsage() reports: sizeof(OcTreeNode) (16 bytes: a pointer to a
// child-pointer array and a float) per node plus an array of 8 child pointers (64 bytes) per
// inner node, without heap headers. The tree is placed on OctoMap's keys with our cubes aligned to
// its cubes, so its nodes are ours plus the 16 - depth single-child inner nodes above our
// universe, plus one per black leaf. Throws InvalidArgument for a grid deeper than 16 levels.
struct OctoMapFootprint {
  std::size_t nodes = 0;        // all nodes liboctomap allocates, root and leaves included
  std::size_t inner_nodes = 0;  // nodes with a child array
  std::size_t bytes = 0;        // OcTree::memoryUsage(), including its fixed part
};
OctoMapFootprint octomapFootprint(const Octree& tree);

}  // namespace octomotion
