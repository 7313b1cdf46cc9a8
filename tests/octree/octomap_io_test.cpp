// OctoMap interoperation (octomap_io.h), checked against liboctomap itself: maps are built and
// queried with octomap::OcTree, written with its own writer, and our exports are read back with
// its own reader.
#include "octomotion/octree/octomap_io.h"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "dense_grid.h"
#include "octomotion/octree/io.h"
#include "octomotion/octree/set_ops.h"

namespace octomotion {
namespace {

using test::randomShape;

constexpr int kCentre = 32768;

std::string tempPath(const std::string& stem) {
  return ::testing::TempDir() + "octomotion_octomap_io_test_" + stem + ".bt";
}

// A map near the origin with scattered occupied and free voxels, a solid 8^3 occupied block and a
// 4^3 free block (both pruned into single leaves), and some voxels whose evidence cancels out.
octomap::OcTree randomOctoMap(std::mt19937_64& rng, double res) {
  octomap::OcTree t(res);
  std::uniform_int_distribution<int> key(kCentre - 20, kCentre + 19);
  for (int i = 0; i < 400; ++i) {
    const octomap::OcTreeKey k(static_cast<octomap::key_type>(key(rng)),
                               static_cast<octomap::key_type>(key(rng)),
                               static_cast<octomap::key_type>(key(rng)));
    t.updateNode(k, rng() % 3 != 0);
  }
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        t.setNodeValue(octomap::OcTreeKey(static_cast<octomap::key_type>(kCentre + 8 + x),
                                          static_cast<octomap::key_type>(kCentre - 16 + y),
                                          static_cast<octomap::key_type>(kCentre + z)),
                       t.getClampingThresMaxLog());
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        t.setNodeValue(octomap::OcTreeKey(static_cast<octomap::key_type>(kCentre - 8 + x),
                                          static_cast<octomap::key_type>(kCentre + y),
                                          static_cast<octomap::key_type>(kCentre - 4 + z)),
                       t.getClampingThresMinLog());
  t.prune();
  return t;
}

bool octomapOccupied(const octomap::OcTree& t, int kx, int ky, int kz) {
  const octomap::OcTreeNode* n = t.search(octomap::OcTreeKey(static_cast<octomap::key_type>(kx),
                                                             static_cast<octomap::key_type>(ky),
                                                             static_cast<octomap::key_type>(kz)));
  return n != nullptr && t.isNodeOccupied(n);
}

// Occupied leaves of an OctoMap as world boxes (min, max).
struct Box {
  Eigen::Vector3d min, max;
};
std::vector<Box> occupiedBoxes(const octomap::OcTree& t) {
  std::vector<Box> boxes;
  for (auto it = t.begin_leafs(); it != t.end_leafs(); ++it) {
    if (!t.isNodeOccupied(*it)) continue;
    // Exact corners from the key (the iterator's float coordinates would blur them).
    const octomap::OcTreeKey k = it.getKey();
    const int size = 1 << (16 - static_cast<int>(it.getDepth()));
    Eigen::Vector3d min;
    for (int a = 0; a < 3; ++a) {
      const int key_min = size == 1 ? k[a] : k[a] - size / 2;
      min[a] = (key_min - kCentre) * t.getResolution();
    }
    boxes.push_back({min, min + Eigen::Vector3d::Constant(size * t.getResolution())});
  }
  return boxes;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

TEST(OctoMapIo, NativeImportMatchesOctoMapVoxelByVoxel) {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 3; ++trial) {
    octomap::OcTree map = randomOctoMap(rng, 0.05);
    const std::string path = tempPath("native");
    ASSERT_TRUE(map.writeBinary(path));
    const Octree tree = importOctoMap(path);
    EXPECT_EQ(tree.grid(), octomapNativeGrid(0.05));
    std::string why;
    ASSERT_TRUE(tree.checkInvariants(&why)) << why;
    std::uint64_t occupied = 0;
    for (int z = kCentre - 24; z < kCentre + 24; ++z)
      for (int y = kCentre - 24; y < kCentre + 24; ++y)
        for (int x = kCentre - 24; x < kCentre + 24; ++x) {
          const bool expected = octomapOccupied(map, x, y, z);
          occupied += expected;
          ASSERT_EQ(tree.occupied(Voxel{std::uint32_t(x), std::uint32_t(y), std::uint32_t(z)}),
                    expected)
              << x << " " << y << " " << z;
        }
    EXPECT_GE(occupied, 512u);
    EXPECT_EQ(tree.blackVoxelCount(), occupied);  // nothing black outside the checked region
    // Same point queries in world coordinates.
    const octomap::point3d p(0.4125f, -0.7875f, 0.0125f);  // inside the solid block
    EXPECT_TRUE(tree.occupiedAt(Eigen::Vector3d(p.x(), p.y(), p.z())));
    std::remove(path.c_str());
  }
}

TEST(OctoMapIo, ImportOntoAnyGridFollowsTheRoundingRule) {
  std::mt19937_64 rng(32);
  octomap::OcTree map = randomOctoMap(rng, 0.1);
  const std::string path = tempPath("any_grid");
  ASSERT_TRUE(map.writeBinary(path));
  const std::vector<Box> boxes = occupiedBoxes(map);
  ASSERT_FALSE(boxes.empty());
  // A coarser, a finer and an odd voxel size, at origins off the key grid (no exact ties).
  for (double voxel : {0.23, 0.071, 0.1313}) {
    const WorldGrid grid(Eigen::Vector3d(-2.0113, -1.9371, -2.0237), voxel, 5);
    const double v = grid.voxelSize();
    for (Rounding rounding : {Rounding::kConservative, Rounding::kCenter}) {
      const Octree tree = importOctoMap(path, grid, rounding, [](const std::string&) {});
      std::size_t mismatches = 0, black = 0;
      const std::uint32_t side = grid.sideVoxels();
      for (std::uint32_t z = 0; z < side; ++z)
        for (std::uint32_t y = 0; y < side; ++y)
          for (std::uint32_t x = 0; x < side; ++x) {
            const Voxel vox{x, y, z};
            const Eigen::Vector3d lo = grid.toWorld(Eigen::Vector3d(x, y, z));
            const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(v);
            const Eigen::Vector3d c = grid.voxelCenter(vox);
            bool expected = false;
            for (const Box& b : boxes) {
              expected =
                  rounding == Rounding::kCenter
                      ? (c.array() >= b.min.array()).all() && (c.array() <= b.max.array()).all()
                      : (hi.array() >= b.min.array()).all() && (lo.array() <= b.max.array()).all();
              if (expected) break;
            }
            black += expected;
            mismatches += tree.occupied(vox) != expected;
          }
      EXPECT_EQ(mismatches, 0u) << "voxel " << voxel << " " << toString(rounding);
      EXPECT_GT(black, 0u);
    }
  }
  // The centre rule on a grid aligned with the keys reproduces the file exactly.
  const Octree native = importOctoMap(path);
  const WorldGrid aligned(Eigen::Vector3d(-3.2, -3.2, -3.2), 0.1, 6);  // key 32768 - 32
  const Octree centred = importOctoMap(path, aligned, Rounding::kCenter);
  EXPECT_EQ(centred.blackVoxelCount(), native.blackVoxelCount());
  for (const Voxel& v : centred.blackVoxels()) {
    ASSERT_TRUE(native.occupied(Voxel{v.x + kCentre - 32, v.y + kCentre - 32, v.z + kCentre - 32}));
  }
  // The conservative rule there also takes every voxel sharing a face, edge or corner point.
  const Octree touching = importOctoMap(path, aligned, Rounding::kConservative);
  EXPECT_EQ(intersect(touching, centred), centred);
  EXPECT_GT(touching.blackVoxelCount(), centred.blackVoxelCount());
  std::remove(path.c_str());
}

TEST(OctoMapIo, WarnsWhenTheMapReachesOutsideTheGrid) {
  std::mt19937_64 rng(33);
  octomap::OcTree map = randomOctoMap(rng, 0.1);
  const std::string path = tempPath("clip");
  ASSERT_TRUE(map.writeBinary(path));
  std::vector<std::string> warnings;
  const WorldGrid small(Eigen::Vector3d(0, 0, 0), 0.1, 3);  // 0.8 m: part of the map
  const Octree t = importOctoMap(path, small, Rounding::kCenter,
                                 [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("outside the grid"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find(path), std::string::npos) << warnings[0];
  std::remove(path.c_str());
}

TEST(OctoMapIo, ExportRoundTripsRandomTrees) {
  std::mt19937_64 rng(34);
  // One origin on a coarse key boundary, one an odd number of voxels off, so our cubes straddle
  // OctoMap's and have to be split on export.
  const Eigen::Vector3d origins[] = {Eigen::Vector3d(-1.6, 0.8, -6.4),
                                     Eigen::Vector3d(-1.55, 0.35, 0.05)};
  for (int depth = 3; depth <= 7; ++depth) {
    for (const Eigen::Vector3d& origin : origins) {
      for (bool free_space : {false, true}) {
        const WorldGrid grid(origin, 0.05, depth);
        const Octree tree = randomShape(depth, rng).toTree(grid);
        const std::string path = tempPath("export");
        exportOctoMap(tree, path, free_space);
        // Our importer, onto the same grid: identical.
        EXPECT_EQ(importOctoMap(path, grid, Rounding::kCenter), tree);
        // And on the native grid: same voxels, shifted by the key offset.
        const Octree native = importOctoMap(path);
        EXPECT_EQ(native.blackVoxelCount(), tree.blackVoxelCount());
        // liboctomap's own reader agrees, voxel by voxel, and sees free space when written.
        octomap::OcTree map(0.1);
        ASSERT_TRUE(map.readBinary(path));
        EXPECT_DOUBLE_EQ(map.getResolution(), 0.05);
        const int off[3] = {static_cast<int>(std::lround(origin.x() / 0.05)) + kCentre,
                            static_cast<int>(std::lround(origin.y() / 0.05)) + kCentre,
                            static_cast<int>(std::lround(origin.z() / 0.05)) + kCentre};
        const std::uint32_t side = grid.sideVoxels();
        const std::uint32_t step = depth <= 5 ? 1 : 3;  // sample the larger grids
        for (std::uint32_t z = 0; z < side; z += step)
          for (std::uint32_t y = 0; y < side; y += step)
            for (std::uint32_t x = 0; x < side; x += step) {
              const int kx = off[0] + int(x), ky = off[1] + int(y), kz = off[2] + int(z);
              ASSERT_EQ(octomapOccupied(map, kx, ky, kz), tree.occupied(Voxel{x, y, z}));
              const octomap::OcTreeNode* n = map.search(octomap::OcTreeKey(
                  octomap::key_type(kx), octomap::key_type(ky), octomap::key_type(kz)));
              ASSERT_EQ(n != nullptr, free_space || tree.occupied(Voxel{x, y, z}));
            }
        std::remove(path.c_str());
      }
    }
  }
}

TEST(OctoMapIo, NativeImportExportImportIsIdentity) {
  std::mt19937_64 rng(35);
  octomap::OcTree map = randomOctoMap(rng, 0.05);
  const std::string a = tempPath("a"), b = tempPath("b");
  ASSERT_TRUE(map.writeBinary(a));
  const Octree first = importOctoMap(a);
  exportOctoMap(first, b);
  EXPECT_EQ(importOctoMap(b), first);
  // Occupied leaves are written as whole cubes and pruned: the solid block stays one leaf, so
  // the export is no bigger than liboctomap's own file of the same occupancy.
  octomap::OcTree reread(0.1);
  ASSERT_TRUE(reread.readBinary(b));
  EXPECT_LE(reread.size(), map.size());
  std::remove(a.c_str());
  std::remove(b.c_str());
}

TEST(OctoMapIo, EmptyAndFullTrees) {
  const WorldGrid grid(Eigen::Vector3d(-0.4, 0, 0.8), 0.1, 4);
  const std::string path = tempPath("uniform");
  for (bool free_space : {false, true}) {
    exportOctoMap(Octree(grid), path, free_space);
    EXPECT_TRUE(importOctoMap(path).empty());
    EXPECT_TRUE(importOctoMap(path, grid, Rounding::kCenter).empty());
    exportOctoMap(Octree::full(grid), path, free_space);
    EXPECT_EQ(importOctoMap(path, grid, Rounding::kCenter), Octree::full(grid));
    EXPECT_EQ(importOctoMap(path).blackVoxelCount(), 4096u);
  }
  // The whole of OctoMap's key space: the root cannot be a leaf in a .bt file, so it is written
  // as eight occupied children, and comes back as the full native universe.
  const Octree full_native = Octree::full(octomapNativeGrid(0.25));
  exportOctoMap(full_native, path);
  EXPECT_EQ(importOctoMap(path), full_native);
  std::remove(path.c_str());
}

TEST(OctoMapIo, ExportRejectsGridsOffTheKeyGrid) {
  const std::string path = tempPath("reject");
  const Octree off_grid =
      Octree::fromVoxels(WorldGrid(Eigen::Vector3d(0.025, 0, 0), 0.05, 3), {{1, 1, 1}});
  try {
    exportOctoMap(off_grid, path);
    FAIL() << "misaligned origin accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("not a whole number"), std::string::npos) << e.what();
  }
  // Keys beyond 65535: a depth-17 grid from 0 holds voxels up to key 32768 + 131071.
  const WorldGrid wide(Eigen::Vector3d(0, 0, 0), 0.01, 17);
  try {
    exportOctoMap(Octree::fromVoxels(wide, {{40000, 0, 0}}), path);
    FAIL() << "out-of-range key accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("key range"), std::string::npos) << e.what();
  }
  // Only what is written must fit: black voxels near the origin export fine...
  EXPECT_NO_THROW(exportOctoMap(Octree::fromVoxels(wide, {{4, 5, 6}}), path));
  EXPECT_TRUE(importOctoMap(path).occupiedAt(Eigen::Vector3d(0.045, 0.055, 0.065)));
  // ...but the whole universe as free space does not.
  EXPECT_THROW(exportOctoMap(Octree::fromVoxels(wide, {{4, 5, 6}}), path, true), InvalidArgument);
  EXPECT_THROW(
      exportOctoMap(Octree(WorldGrid(Eigen::Vector3d::Zero(), 0.1, 3)), "/nonexistent-dir/x.bt"),
      FileError);
  std::remove(path.c_str());
}

TEST(OctoMapIo, BadFilesAreRejectedWithThePath) {
  const std::string path = tempPath("bad");
  std::remove(path.c_str());
  try {
    importOctoMap(path);
    FAIL() << "missing file accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
  }
  // A valid file to damage.
  std::mt19937_64 rng(36);
  octomap::OcTree map = randomOctoMap(rng, 0.1);
  ASSERT_TRUE(map.writeBinary(path));
  const std::string good = readFile(path);
  const std::size_t data = good.find("\ndata\n") + 6;
  ASSERT_LT(data, good.size());

  auto expectRejected = [&](const std::string& bytes, const std::string& part) {
    writeFile(path, bytes);
    try {
      importOctoMap(path);
      ADD_FAILURE() << "accepted; expected \"" << part << "\"";
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
    }
  };
  // Every truncation of a small map, in the header and in the node data.
  {
    octomap::OcTree small(0.1);
    small.updateNode(octomap::point3d(0.05f, 0.05f, 0.05f), true);
    small.updateNode(octomap::point3d(-0.35f, 0.15f, 0.05f), false);
    const std::string small_path = tempPath("small");
    ASSERT_TRUE(small.writeBinary(small_path));
    const std::string bytes = readFile(small_path);
    for (std::size_t len = 0; len < bytes.size(); ++len) {
      writeFile(path, bytes.substr(0, len));
      EXPECT_THROW(importOctoMap(path), FileError) << "cut to " << len;
    }
    std::remove(small_path.c_str());
  }
  expectRejected(good + "xy", "unexpected bytes");
  expectRejected("not an octomap", "not an OctoMap binary");
  std::ostringstream omt;
  writeOctree(Octree(WorldGrid(Eigen::Vector3d::Zero(), 1, 2)), omt);
  expectRejected(omt.str(), "not an OctoMap binary");
  std::string bad = good;
  bad.replace(bad.find("id OcTree"), 9, "id CoTree");
  expectRejected(bad, "tree type");
  bad = good;
  bad.replace(bad.find("res 0.1"), 7, "res -.1");
  expectRejected(bad, "res");
  bad = good;
  bad.replace(bad.find("res 0.1"), 7, "res 1e200");
  expectRejected(bad, "res");
  bad = good;
  bad.replace(bad.find("size "), 5, "size 9");  // prefixes a digit: the wrong count
  expectRejected(bad, "size");
  // Inner-node bits all the way down: liboctomap alone would recurse past its 16 levels.
  expectRejected(good.substr(0, data) + std::string(64, '\xff'), "16 levels");
  // Random byte changes in the node data: rejected or read, never a crash.
  std::uniform_int_distribution<std::size_t> where(data, good.size() - 1);
  for (int trial = 0; trial < 100; ++trial) {
    bad = good;
    bad[where(rng)] = static_cast<char>(rng());
    writeFile(path, bad);
    try {
      const Octree t = importOctoMap(path);
      std::string why;
      EXPECT_TRUE(t.checkInvariants(&why)) << why;
    } catch (const FileError&) {
    }
  }
  std::remove(path.c_str());
}

TEST(OctoMapIo, FootprintCountsLiboctomapsNodes) {
  std::mt19937_64 rng(37);
  for (int depth = 3; depth <= 7; ++depth) {
    const Octree tree =
        randomShape(depth, rng).toTree(WorldGrid(Eigen::Vector3d::Zero(), 0.1, depth));
    const OctoMapFootprint f = octomapFootprint(tree);
    // Same inner nodes as ours plus the chain above our universe; one leaf per black leaf.
    EXPECT_EQ(f.inner_nodes, tree.internalNodeCount() + std::size_t(16 - depth));
    EXPECT_EQ(f.nodes, f.inner_nodes + tree.blackLeafCount());
    EXPECT_EQ(
        f.bytes,
        sizeof(octomap::OcTreeBaseImpl<octomap::OcTreeNode, octomap::AbstractOccupancyOcTree>) +
            f.nodes * sizeof(octomap::OcTreeNode) + f.inner_nodes * 8 * sizeof(void*));
  }
  EXPECT_EQ(octomapFootprint(Octree(WorldGrid(Eigen::Vector3d::Zero(), 0.1, 4))).nodes, 0u);
  EXPECT_THROW(octomapFootprint(Octree(WorldGrid(Eigen::Vector3d::Zero(), 0.1, 17))),
               InvalidArgument);
}

}  // namespace
}  // namespace octomotion
