// Point-cloud loaders: round trips through PCD/PLY (ascii and binary) and XYZ in a temp dir,
// extra fields and elements, NaN points skipped and counted, and malformed files rejected with a
// FileError naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion::pointcloud {
namespace {

namespace fs = std::filesystem;

class PointCloudIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("octomotion_pcio_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::mt19937_64 rng(555);
    std::uniform_real_distribution<float> u(-100.0f, 100.0f);
    for (int i = 0; i < 500; ++i) points_.emplace_back(u(rng), u(rng), u(rng));
    points_.emplace_back(1e-30f, -0.0f, 3.4e38f);  // extreme but finite values round-trip too
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream out(path(name), std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // Expects a FileError whose message starts with the path and mentions `words`.
  void expectRejected(const std::string& name, const std::string& words) const {
    try {
      loadPointCloud(path(name));
      FAIL() << name << " was accepted";
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path(name), 0), 0u) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  }

  fs::path dir_;
  std::vector<Eigen::Vector3f> points_;
};

std::string bytesOf(const void* p, std::size_t n) {
  return std::string(static_cast<const char*>(p), n);
}

TEST_F(PointCloudIo, RoundTripsEveryFormat) {
  savePcd(path("a.pcd"), points_, Encoding::kAscii);
  savePcd(path("b.pcd"), points_, Encoding::kBinary);
  savePly(path("a.ply"), points_, Encoding::kAscii);
  savePly(path("b.ply"), points_, Encoding::kBinary);
  saveXyz(path("a.xyz"), points_);
  for (const char* name : {"a.pcd", "b.pcd", "a.ply", "b.ply", "a.xyz"}) {
    const PointCloud cloud = loadPointCloud(path(name));
    EXPECT_EQ(cloud.points, points_) << name;
    EXPECT_EQ(cloud.skipped_non_finite, 0u) << name;
  }
  // Empty clouds are fine.
  savePcd(path("empty.pcd"), {}, Encoding::kBinary);
  EXPECT_TRUE(loadPcd(path("empty.pcd")).points.empty());
}

TEST_F(PointCloudIo, ReadsExtraFieldsElementsAndSkipsNaN) {
  // PCD ascii with rgb before x and an intensity after; a NaN point; CRLF line ends.
  write("extra.pcd",
        "# comment\r\nVERSION 0.7\r\nFIELDS rgb x y z intensity\r\nSIZE 4 4 4 4 4\r\n"
        "TYPE U F F F F\r\nCOUNT 1 1 1 1 1\r\nWIDTH 3\r\nHEIGHT 1\r\nPOINTS 3\r\nDATA ascii\r\n"
        "7 1 2 3 0.5\r\n8 nan nan nan 0\r\n9 -4 5.5 6e2 1\r\n");
  PointCloud c = loadPcd(path("extra.pcd"));
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_EQ(c.points[1], Eigen::Vector3f(-4, 5.5f, 600));
  EXPECT_EQ(c.skipped_non_finite, 1u);

  // PCD binary: x as double, a 3-wide normal field, organised 2x2 with one NaN point.
  std::string body;
  for (int i = 0; i < 4; ++i) {
    const double x = i == 2 ? NAN : i;
    const float yz[2] = {static_cast<float>(10 + i), static_cast<float>(20 + i)};
    const float normal[3] = {0, 0, 1};
    const std::uint8_t label = static_cast<std::uint8_t>(i);
    body += bytesOf(&label, 1) + bytesOf(&x, 8) + bytesOf(yz, 8) + bytesOf(normal, 12);
  }
  write("organised.pcd",
        "VERSION .7\nFIELDS label x y z normal\nSIZE 1 8 4 4 4\nTYPE U F F F F\nCOUNT 1 1 1 1 3\n"
        "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n" +
            body);
  c = loadPcd(path("organised.pcd"));
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.points[2], Eigen::Vector3f(3, 13, 23));
  EXPECT_EQ(c.skipped_non_finite, 1u);

  // PLY binary: a face element *before* the vertices (lists skipped), double coordinates, extra
  // uchar colour properties.
  std::string ply_body;
  const std::uint8_t n3 = 3;
  const std::int32_t idx[3] = {0, 1, 0};
  ply_body += bytesOf(&n3, 1) + bytesOf(idx, 12);
  for (int i = 0; i < 2; ++i) {
    const double xyz[3] = {0.25 * i, -1.0, 1e3};
    const std::uint8_t rgb[3] = {1, 2, 3};
    ply_body += bytesOf(rgb, 3) + bytesOf(xyz, 24);
  }
  write("faces_first.ply",
        "ply\nformat binary_little_endian 1.0\ncomment test\nelement face 1\n"
        "property list uchar int vertex_indices\nelement vertex 2\nproperty uchar red\n"
        "property uchar green\nproperty uchar blue\nproperty double x\nproperty double y\n"
        "property double z\nend_header\n" +
            ply_body);
  c = loadPly(path("faces_first.ply"));
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_EQ(c.points[1], Eigen::Vector3f(0.25f, -1, 1000));

  // PLY ascii with trailing faces, NaN vertex skipped.
  write("ascii.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "1 2 3\nnan 0 0\n4 5 6\n3 0 1 2\n");
  c = loadPly(path("ascii.ply"));
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_EQ(c.skipped_non_finite, 1u);

  // XYZ: comments, blank lines, commas, extra columns.
  write("cloud.txt", "# x y z\n\n1,2,3\n4 5 6 255 0 0\n\t7\t8\t9\n");
  c = loadPointCloud(path("cloud.txt"));
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.points[2], Eigen::Vector3f(7, 8, 9));
}

TEST_F(PointCloudIo, RejectsMalformedFiles) {
  const std::string header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\nPOINTS 4\n";
  write("compressed.pcd", header + "DATA binary_compressed\n" + std::string(40, '\0'));
  expectRejected("compressed.pcd", "binary_compressed");
  write("short.pcd", header + "DATA binary\n" + std::string(47, '\0'));  // needs 48
  expectRejected("short.pcd", "truncated");
  write("short_ascii.pcd", header + "DATA ascii\n1 2 3\n4 5 6\n");
  expectRejected("short_ascii.pcd", "truncated");
  write("no_data.pcd", header);
  expectRejected("no_data.pcd", "DATA");
  write(
      "no_z.pcd",
      "FIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n");
  expectRejected("no_z.pcd", "x, y or z");
  write("int_x.pcd",
        "FIELDS x y z\nSIZE 4 4 4\nTYPE I F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
        "DATA ascii\n1 2 3\n");
  expectRejected("int_x.pcd", "FLOAT");
  write("mismatch.pcd",
        "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  expectRejected("mismatch.pcd", "different lengths");
  write("wh.pcd",
        "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 2\nPOINTS 5\nDATA ascii\n");
  expectRejected("wh.pcd", "POINTS");
  write("badnum.pcd", header + "DATA ascii\n1 2 3\n4 x 6\n1 1 1\n2 2 2\n");
  expectRejected("badnum.pcd", "line 10");
  write("cols.pcd", header + "DATA ascii\n1 2 3\n4 5\n1 1 1\n2 2 2\n");
  expectRejected("cols.pcd", "expected 3 values");
  write("garbage.pcd", "hello world\n");
  expectRejected("garbage.pcd", "unknown header keyword");

  write("magic.ply", "plx\nformat ascii 1.0\nend_header\n");
  expectRejected("magic.ply", "magic");
  write("big.ply",
        "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n" +
            std::string(12, '\0'));
  expectRejected("big.ply", "big_endian");
  write("short.ply",
        "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n" +
            std::string(23, '\0'));
  expectRejected("short.ply", "truncated");
  write("short_ascii.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n1 2 3\n");
  expectRejected("short_ascii.ply", "truncated");
  write("int.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty float y\n"
        "property float z\nend_header\n1 2 3\n");
  expectRejected("int.ply", "float or double");
  write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  expectRejected("noend.ply", "end_header");
  write("badtype.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n");
  expectRejected("badtype.ply", "bad property");
  write("novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n");
  expectRejected("novertex.ply", "no vertex");

  write("two.xyz", "1 2 3\n4 5\n");
  expectRejected("two.xyz", "line 2");
  write("word.xyz", "1 2 three\n");
  expectRejected("word.xyz", "bad number");
  write("cloud.obj", "v 1 2 3\n");
  expectRejected("cloud.obj", "extension");
  expectRejected("missing.pcd", "cannot open");
}

}  // namespace
}  // namespace octomotion::pointcloud
