// octomotion's own binary file for a compact Octree (extension ".omt" by convention): the node
// array is stored as it is in memory, so loading is one validated copy, no rebuilding.
//
// Layout, version 1. Every integer is little-endian, every real an IEEE-754 binary64 stored as
// its 64-bit pattern, little-endian; offsets in bytes.
//
//   0  magic          8 bytes  "OMOCTREE"
//   8  version        u32      1
//  12  depth          u32      grid depth, 1..kMaxDepth
//  16  origin         3 x f64  grid minimum corner x, y, z (metres)
//  40  voxel size     f64      > 0 (metres)
//  48  root colour    u32      0 white, 1 black, 2 gray (Color)
//  52  reserved       u32      0
//  56  node count     u64      0 unless the root is gray
//  64  nodes          count x 8 bytes, in array order (index 0 = root), each:
//                       u32 first_child, u8 black mask, u8 gray mask, 2 zero bytes
//  64 + 8*count       checksum u64: FNV-1a 64 over every byte before it
//
// A reader rejects (FileError naming the file, or "<stream>" for streams, and saying what is
// wrong): wrong magic, unknown version, invalid grid or root colour, a node count that cannot fit
// in what is left of the input (checked before allocating), truncation, checksum mismatch, and
// any structurally invalid tree (Octree::fromNodes validates).
#pragma once

#include <iosfwd>
#include <string>

#include "octomotion/octree/octree.h"

namespace octomotion {

inline constexpr char kOctreeFileMagic[8] = {'O', 'M', 'O', 'C', 'T', 'R', 'E', 'E'};
inline constexpr std::uint32_t kOctreeFileVersion = 1;

// Writes the layout above. Throws Error if the stream fails.
void writeOctree(const Octree& tree, std::ostream& out);
// Reads one tree written by writeOctree, leaving the stream just past its checksum.
// `name_for_errors` (a path, or e.g. "<memory>") starts every error message.
Octree readOctree(std::istream& in, const std::string& name_for_errors);

// Files: throw FileError(path, ...) when the file cannot be opened/written, and loadOctree also
// when bytes follow the checksum.
void saveOctree(const Octree& tree, const std::string& path);
Octree loadOctree(const std::string& path);

}  // namespace octomotion
