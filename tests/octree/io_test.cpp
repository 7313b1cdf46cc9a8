// The octomotion octree file (io.h): exact round trips, and every kind of damaged input is
// refused with an Error that names the file — never a crash, never a huge allocation.
#include "octomotion/octree/io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "dense_grid.h"
#include "octomotion/error.h"

namespace octomotion {
namespace {

using test::randomShape;

WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d(-1.25, 2.0, 0.1), 0.05, depth);
}

std::string toBytes(const Octree& t) {
  std::ostringstream out(std::ios::binary);
  writeOctree(t, out);
  return out.str();
}

Octree fromBytes(const std::string& bytes, const std::string& name = "<memory>") {
  std::istringstream in(bytes, std::ios::binary);
  return readOctree(in, name);
}

std::string tempPath(const std::string& stem) {
  return ::testing::TempDir() + "octomotion_io_test_" + stem + ".omt";
}

// The FNV-1a 64 of the header and node bytes, re-stamped after a deliberate edit so that the
// structural checks behind the checksum are reached.
std::string restamp(std::string bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  if (bytes.size() < 8) return bytes;
  for (std::size_t i = 0; i < bytes.size() - 8; ++i) {
    h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  }
  for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = static_cast<char>(h >> (8 * i));
  return bytes;
}

// A stream buffer that cannot seek, like a pipe: the reader cannot learn the input's size.
struct NoSeekBuf : std::stringbuf {
  using std::stringbuf::stringbuf;
  pos_type seekoff(off_type, std::ios::seekdir, std::ios::openmode) override {
    return pos_type(off_type(-1));
  }
  pos_type seekpos(pos_type, std::ios::openmode) override { return pos_type(off_type(-1)); }
};

void putU64(std::string& bytes, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) bytes[at + i] = static_cast<char>(v >> (8 * i));
}

TEST(OctreeIo, RoundTripsRandomTrees) {
  std::mt19937_64 rng(7301);
  for (int depth = 3; depth <= 7; ++depth) {
    for (int trial = 0; trial < 6; ++trial) {
      const Octree tree = randomShape(depth, rng).toTree(gridOfDepth(depth));
      const std::string bytes = toBytes(tree);
      ASSERT_EQ(bytes.size(), 64 + 8 * tree.internalNodeCount() + 8);
      const Octree back = fromBytes(bytes);
      EXPECT_EQ(back, tree);
      EXPECT_EQ(back.nodes(), tree.nodes());  // the layout itself survives, not just occupancy
      EXPECT_EQ(back.grid(), tree.grid());
      EXPECT_EQ(toBytes(back), bytes);  // writing is deterministic
    }
  }
}

TEST(OctreeIo, Version1LayoutIsAsDocumented) {
  // A depth-2 tree with voxel (0,0,0) black: root (gray child 0) + one node (black child 0).
  const WorldGrid grid(Eigen::Vector3d(1.0, -2.0, 0.5), 0.25, 2);
  const std::string bytes = toBytes(Octree::fromVoxels(grid, {{0, 0, 0}}));
  ASSERT_EQ(bytes.size(), 64u + 2 * 8 + 8);
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
      v |= std::uint32_t(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
    return v;
  };
  auto u64 = [&](std::size_t at) {
    return std::uint64_t(u32(at)) | (std::uint64_t(u32(at + 4)) << 32);
  };
  auto f64 = [&](std::size_t at) {
    const std::uint64_t bits = u64(at);
    double d;
    std::memcpy(&d, &bits, 8);
    return d;
  };
  EXPECT_EQ(bytes.substr(0, 8), "OMOCTREE");
  EXPECT_EQ(u32(8), 1u);    // version
  EXPECT_EQ(u32(12), 2u);   // depth
  EXPECT_EQ(f64(16), 1.0);  // origin
  EXPECT_EQ(f64(24), -2.0);
  EXPECT_EQ(f64(32), 0.5);
  EXPECT_EQ(f64(40), 0.25);  // voxel size
  EXPECT_EQ(u32(48), 2u);    // gray root
  EXPECT_EQ(u32(52), 0u);
  EXPECT_EQ(u64(56), 2u);  // node count
  // Root: first_child 1, black 0, gray 0b1; then node 1: black 0b1.
  EXPECT_EQ(u32(64), 1u);
  EXPECT_EQ(bytes[68], 0);
  EXPECT_EQ(bytes[69], 1);
  EXPECT_EQ(u32(72), 0u);
  EXPECT_EQ(bytes[76], 1);
  EXPECT_EQ(bytes[77], 0);
  EXPECT_EQ(restamp(bytes), bytes);  // the trailer is FNV-1a 64 of all bytes before it
}

TEST(OctreeIo, RoundTripsEmptyAndFullTrees) {
  for (int depth : {1, 4, kMaxDepth}) {
    const WorldGrid grid = gridOfDepth(depth);
    const Octree empty(grid);
    const Octree full = Octree::full(grid);
    EXPECT_EQ(fromBytes(toBytes(empty)), empty);
    EXPECT_EQ(fromBytes(toBytes(full)), full);
    EXPECT_EQ(toBytes(empty).size(), 72u);
  }
}

TEST(OctreeIo, PreservesGridBitsExactly) {
  // Origins and voxel sizes that are not short decimals must come back bit for bit.
  const WorldGrid grid(Eigen::Vector3d(-0.1 / 3.0, 1e-300, 12345.678901234567), 0.1 / 7.0, 5);
  const Octree t = Octree::fromVoxels(grid, {{1, 2, 3}, {31, 0, 17}});
  const Octree back = fromBytes(toBytes(t));
  EXPECT_EQ(back.grid().origin().x(), grid.origin().x());
  EXPECT_EQ(back.grid().origin().z(), grid.origin().z());
  EXPECT_EQ(back.grid().voxelSize(), grid.voxelSize());
  EXPECT_EQ(back, t);
}

TEST(OctreeIo, SaveAndLoadFiles) {
  std::mt19937_64 rng(99);
  const Octree tree = randomShape(6, rng).toTree(gridOfDepth(6));
  const std::string path = tempPath("save");
  saveOctree(tree, path);
  EXPECT_EQ(loadOctree(path), tree);
  // Trailing bytes after the checksum are refused by loadOctree.
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out << "x";
  }
  try {
    loadOctree(path);
    FAIL() << "trailing byte accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

TEST(OctreeIo, MissingFileNamesThePath) {
  const std::string path = tempPath("does_not_exist");
  std::remove(path.c_str());
  try {
    loadOctree(path);
    FAIL() << "missing file accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
  }
  EXPECT_THROW(saveOctree(Octree(gridOfDepth(3)), "/nonexistent-dir/x/y.omt"), FileError);
}

TEST(OctreeIo, EveryTruncationIsRejected) {
  std::mt19937_64 rng(5);
  const Octree tree = randomShape(4, rng, 2, 6).toTree(gridOfDepth(4));
  const std::string bytes = toBytes(tree);
  ASSERT_GT(bytes.size(), 80u);
  for (std::size_t len = 0; len < bytes.size(); ++len) {
    try {
      fromBytes(bytes.substr(0, len), "cut.omt");
      FAIL() << "a file cut to " << len << " of " << bytes.size() << " bytes was accepted";
    } catch (const FileError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.omt: ", 0), 0u) << e.what();
    }
  }
}

TEST(OctreeIo, TruncationIsRejectedOnUnseekableStreams) {
  // A stream that cannot report its size: the reader must still stop at the missing bytes.
  std::mt19937_64 rng(6);
  const std::string bytes = toBytes(randomShape(5, rng).toTree(gridOfDepth(5)));
  for (std::size_t len : {bytes.size() / 2, bytes.size() - 1, bytes.size()}) {
    NoSeekBuf buf(bytes.substr(0, len), std::ios::in);
    std::istream in(&buf);
    if (len == bytes.size()) {
      EXPECT_EQ(readOctree(in, "pipe"), fromBytes(bytes));
    } else {
      EXPECT_THROW(readOctree(in, "pipe"), FileError);
    }
  }
}

TEST(OctreeIo, SingleByteChangesAreAlwaysDetected) {
  // FNV-1a changes under any single-byte edit, so each one must be refused.
  std::mt19937_64 rng(11);
  const std::string bytes = toBytes(randomShape(4, rng, 2, 8).toTree(gridOfDepth(4)));
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (int bit : {0, 7}) {
      std::string bad = bytes;
      bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
      EXPECT_THROW(fromBytes(bad), Error) << "byte " << i << " bit " << bit;
    }
  }
}

TEST(OctreeIo, RandomCorruptionNeverCrashes) {
  // Several random bytes changed, with the checksum recomputed half of the time so that the
  // structural validation is exercised: either an Error, or a tree that passes its invariants.
  std::mt19937_64 rng(12);
  const Octree tree = randomShape(6, rng).toTree(gridOfDepth(6));
  const std::string bytes = toBytes(tree);
  std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 9);
  int accepted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bad = bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bad[where(rng)] = static_cast<char>(rng());
    if (trial % 2) bad = restamp(bad);
    try {
      const Octree t = fromBytes(bad);
      std::string why;
      EXPECT_TRUE(t.checkInvariants(&why)) << why;
      ++accepted;
    } catch (const Error&) {
    }
  }
  // Restamped edits of mask bits often still form a valid tree; that is expected.
  EXPECT_GT(accepted, 0);
}

TEST(OctreeIo, HeaderDefectsAreNamed) {
  const Octree tree = Octree::fromVoxels(gridOfDepth(4), {{1, 1, 1}, {9, 3, 12}});
  const std::string good = toBytes(tree);
  auto expectMessage = [](const std::string& bytes, const std::string& part) {
    try {
      fromBytes(bytes, "f.omt");
      ADD_FAILURE() << "accepted; expected \"" << part << "\"";
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("f.omt: ", 0), 0u) << e.what();
    }
  };
  std::string bad = good;
  bad[0] = 'X';
  expectMessage(bad, "wrong magic");
  bad = good;
  bad[8] = 2;
  expectMessage(restamp(bad), "unsupported format version 2");
  bad = good;
  bad[12] = 30;
  expectMessage(restamp(bad), "depth 30");
  bad = good;
  putU64(bad, 40, 0);  // voxel size 0
  expectMessage(restamp(bad), "invalid grid");
  bad = good;
  bad[48] = 5;
  expectMessage(restamp(bad), "invalid root colour 5");
  bad = good;
  bad[good.size() - 1] ^= 1;
  expectMessage(bad, "checksum mismatch");
  bad = good;
  bad[64 + 6] = 1;  // a reserved byte of node 0
  expectMessage(restamp(bad), "reserved bytes");
  bad = good;
  bad[64 + 4] = static_cast<char>(0xff);  // root: all eight children black, not compact
  bad[64 + 5] = 0;
  expectMessage(restamp(bad), "invalid tree");
  expectMessage("short", "truncated");
}

TEST(OctreeIo, HugeNodeCountIsRejectedBeforeAllocating) {
  // Counts that fit the depth limit but not the input, and counts beyond any tree; with and
  // without a correct checksum, on seekable and unseekable streams. If the reader allocated the
  // count first, the 2^40-node case would need 8 TB and die, under ASan too.
  const Octree tree =
      Octree::fromVoxels(WorldGrid(Eigen::Vector3d::Zero(), 1.0, kMaxDepth), {{5, 5, 5}});
  const std::string good = toBytes(tree);
  for (std::uint64_t count : {std::uint64_t{1} << 40, std::uint64_t{0xffffffffu}, ~std::uint64_t{0},
                              std::uint64_t{1000}}) {
    std::string bad = good;
    putU64(bad, 56, count);
    bad = restamp(bad);
    try {
      fromBytes(bad, "big.omt");
      FAIL() << "count " << count << " accepted";
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("node count") != std::string::npos ||
                  what.find("truncated") != std::string::npos)
          << what;
    }
    NoSeekBuf buf(bad, std::ios::in);
    std::istream in(&buf);
    EXPECT_THROW(readOctree(in, "pipe"), FileError);
  }
}

}  // namespace
}  // namespace octomotion
