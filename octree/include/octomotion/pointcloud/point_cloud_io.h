// Loading and saving point clouds: PCD (DATA ascii or binary), PLY (ascii or
// binary_little_endian) and plain XYZ text. Only the x, y, z coordinates are read; other fields
// and elements are skipped.
//
// Policy for bad input: anything malformed — missing or inconsistent header, unsupported
// encoding (PCD binary_compressed, PLY big endian), x/y/z of a type other than float/double,
// truncated data, unparsable numbers — throws FileError naming the file and the problem.
// Points with a NaN or infinite coordinate are NOT an error (PCL writes NaN for invalid points
// of organised clouds): they are skipped and counted in PointCloud::skipped_non_finite, as are
// points with a coordinate beyond float's range (they would be infinite as floats).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace octomotion::pointcloud {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::size_t skipped_non_finite = 0;  // points dropped for a NaN/inf coordinate
};

PointCloud loadPcd(const std::string& path);
PointCloud loadPly(const std::string& path);
// One point per line: x y z [more columns], separated by spaces, tabs or commas; empty lines and
// lines starting with '#' are ignored.
PointCloud loadXyz(const std::string& path);
// By extension (.pcd, .ply, .xyz/.txt/.pts, case-insensitive); FileError for anything else.
PointCloud loadPointCloud(const std::string& path);

enum class Encoding { kAscii, kBinary };
// Writers (x y z only) for tests and tools; FileError when the file cannot be written.
void savePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points,
             Encoding encoding);
void savePly(const std::string& path, const std::vector<Eigen::Vector3f>& points,
             Encoding encoding);
void saveXyz(const std::string& path, const std::vector<Eigen::Vector3f>& points);

}  // namespace octomotion::pointcloud
