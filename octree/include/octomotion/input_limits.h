// What every file reader checks before it reads (docs/robustness.md §5, "Input limits"): the
// path names a regular file (not a FIFO, a device or a directory, which would block or never
// end) no larger than the reader's limit, and XML nests no deeper than kMaxXmlDepth before a
// recursive parser (TinyXML, assimp's Collada importer) sees it. Each limit bounds what a reader
// may allocate, so a hostile file is refused with a message naming it and the limit instead of
// exhausting memory or the stack.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>

namespace octomotion {

inline constexpr std::uintmax_t kMiB = std::uintmax_t{1} << 20;
// YAML scenes and OMPL.app .cfg problems (yaml-cpp's node graph takes ~80x the text).
inline constexpr std::uintmax_t kMaxSceneFileBytes = 4 * kMiB;
// URDF, SRDF and package.xml.
inline constexpr std::uintmax_t kMaxXmlFileBytes = 16 * kMiB;
// Meshes (assimp's import peaks at ~40x the file: 32 MB of binary STL is ~650,000 triangles).
inline constexpr std::uintmax_t kMaxMeshFileBytes = 32 * kMiB;
// Point clouds, OctoMap .bt and octree .omt files (their memory is about their size).
inline constexpr std::uintmax_t kMaxDataFileBytes = 2048 * kMiB;
// Element nesting of any XML document (a URDF needs 5 levels, Collada scenes a few dozen).
inline constexpr int kMaxXmlDepth = 256;
// Links of a robot (the self-collision filter is a links x links matrix).
inline constexpr int kMaxRobotLinks = 4096;

// Throws FileError naming `path` unless it is an existing regular file (symlinks followed) of at
// most `max_bytes` bytes. `what` says what the file is for ("scene file", "mesh file").
void requireRegularFile(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// requireRegularFile, then the file's bytes (never more than max_bytes, even if it grows).
std::string readWholeFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes);

// Throws FileError naming `source_name` and the line when XML elements in `text` nest deeper
// than `max_depth`. A linear scan that only counts start and end tags (comments, CDATA,
// processing instructions, declarations and quoted attribute values are skipped); whether the
// document is well-formed is left to the parser.
void requireXmlDepth(const std::string& text, const std::string& source_name,
                     int max_depth = kMaxXmlDepth);

// v / |v| with |v| computed from v scaled by its largest component, so huge and tiny vectors
// normalise without overflow or underflow. Empty when v is not finite or is zero. Every reader
// of a quaternion or rotation axis uses it.
template <int N>
std::optional<Eigen::Matrix<double, N, 1>> scaledUnitVector(const Eigen::Matrix<double, N, 1>& v) {
  if (!v.allFinite()) return std::nullopt;
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;
  const Eigen::Matrix<double, N, 1> scaled = v / largest;
  return Eigen::Matrix<double, N, 1>(scaled / scaled.norm());
}

}  // namespace octomotion
