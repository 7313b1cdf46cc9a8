#include "octomotion/octree/io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion {

namespace {

constexpr std::size_t kHeaderBytes = 64;
constexpr std::size_t kNodeBytes = 8;
constexpr std::size_t kChecksumBytes = 8;
// Nodes are read and written in blocks of this many, so a stream of unknown length never makes
// us allocate more than it actually delivered plus one block.
constexpr std::size_t kBlockNodes = std::size_t{1} << 16;

// FNV-1a 64: every single-byte change alters the result (each step is a bijection of the state),
// which is what a storage checksum needs here; it is not meant to resist tampering.
class Fnv1a64 {
 public:
  void update(const unsigned char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      hash_ = (hash_ ^ data[i]) * 0x100000001b3ull;
    }
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

void putU32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void putU64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void putF64(unsigned char* p, double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  putU64(p, bits);
}
std::uint32_t getU32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{p[i]} << (8 * i);
  return v;
}
std::uint64_t getU64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t{p[i]} << (8 * i);
  return v;
}
double getF64(const unsigned char* p) {
  const std::uint64_t bits = getU64(p);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

void encodeNode(unsigned char* p, const OctreeNode& n) {
  putU32(p, n.first_child);
  p[4] = n.black;
  p[5] = n.gray;
  p[6] = 0;
  p[7] = 0;
}

// Bytes left in a seekable stream, or -1 when the stream cannot tell (pipes and the like).
long long remainingBytes(std::istream& in) {
  const std::istream::pos_type here = in.tellg();
  if (here == std::istream::pos_type(-1)) {
    in.clear();
    return -1;
  }
  in.seekg(0, std::ios::end);
  const std::istream::pos_type end = in.tellg();
  in.seekg(here);
  if (end == std::istream::pos_type(-1) || !in) {
    in.clear();
    in.seekg(here);
    return -1;
  }
  return static_cast<long long>(end - here);
}

// Reads exactly n bytes or throws, saying what was being read and how much was missing.
void readExact(std::istream& in, unsigned char* buf, std::size_t n, std::size_t offset,
               const char* what, const std::string& name) {
  in.read(reinterpret_cast<char*>(buf), static_cast<std::streamsize>(n));
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  if (got != n) {
    throw FileError(name, std::string("truncated: ") + what + " at byte " + std::to_string(offset) +
                              " needs " + std::to_string(n) + " bytes, only " +
                              std::to_string(got) + " left");
  }
}

// Largest node count a tree of this depth can have: a complete tree, (8^depth - 1) / 7.
std::uint64_t maxNodes(int depth) {
  std::uint64_t count = 0, level = 1;
  for (int d = 0; d < depth; ++d, level *= 8) count += level;
  return count;
}

}  // namespace

void writeOctree(const Octree& tree, std::ostream& out) {
  Fnv1a64 hash;
  unsigned char header[kHeaderBytes] = {};
  std::memcpy(header, kOctreeFileMagic, 8);
  putU32(header + 8, kOctreeFileVersion);
  const WorldGrid& grid = tree.grid();
  putU32(header + 12, static_cast<std::uint32_t>(grid.depth()));
  putF64(header + 16, grid.origin().x());
  putF64(header + 24, grid.origin().y());
  putF64(header + 32, grid.origin().z());
  putF64(header + 40, grid.voxelSize());
  putU32(header + 48, static_cast<std::uint32_t>(tree.rootColor()));
  putU32(header + 52, 0);
  const std::vector<OctreeNode>& nodes = tree.nodes();
  putU64(header + 56, nodes.size());
  hash.update(header, kHeaderBytes);
  out.write(reinterpret_cast<const char*>(header), kHeaderBytes);

  std::vector<unsigned char> block(std::min(nodes.size(), kBlockNodes) * kNodeBytes);
  for (std::size_t start = 0; start < nodes.size(); start += kBlockNodes) {
    const std::size_t count = std::min(kBlockNodes, nodes.size() - start);
    for (std::size_t i = 0; i < count; ++i) encodeNode(&block[i * kNodeBytes], nodes[start + i]);
    hash.update(block.data(), count * kNodeBytes);
    out.write(reinterpret_cast<const char*>(block.data()),
              static_cast<std::streamsize>(count * kNodeBytes));
  }
  unsigned char checksum[kChecksumBytes];
  putU64(checksum, hash.value());
  out.write(reinterpret_cast<const char*>(checksum), kChecksumBytes);
  if (!out) throw Error("writeOctree: the output stream failed");
}

Octree readOctree(std::istream& in, const std::string& name) {
  const long long remaining = remainingBytes(in);
  Fnv1a64 hash;
  unsigned char header[kHeaderBytes];
  // Magic first, on its own, so a file of another kind is named as such rather than "truncated".
  readExact(in, header, 8, 0, "magic", name);
  if (std::memcmp(header, kOctreeFileMagic, 8) != 0) {
    throw FileError(name, "not an octomotion octree file (wrong magic; expected \"OMOCTREE\")");
  }
  readExact(in, header + 8, kHeaderBytes - 8, 8, "header", name);
  hash.update(header, kHeaderBytes);

  const std::uint32_t version = getU32(header + 8);
  if (version != kOctreeFileVersion) {
    throw FileError(name, "unsupported format version " + std::to_string(version) +
                              " (this build reads version " + std::to_string(kOctreeFileVersion) +
                              ")");
  }
  const std::uint32_t depth = getU32(header + 12);
  const Eigen::Vector3d origin(getF64(header + 16), getF64(header + 24), getF64(header + 32));
  const double voxel_size = getF64(header + 40);
  if (depth < 1 || depth > static_cast<std::uint32_t>(kMaxDepth)) {
    throw FileError(name, "invalid grid: depth " + std::to_string(depth) + " is outside [1, " +
                              std::to_string(kMaxDepth) + "]");
  }
  std::optional<WorldGrid> grid;
  try {
    grid.emplace(origin, voxel_size, static_cast<int>(depth));
  } catch (const Error& e) {
    throw FileError(name, std::string("invalid grid: ") + e.what());
  }
  const std::uint32_t root_code = getU32(header + 48);
  if (root_code > static_cast<std::uint32_t>(Color::kGray)) {
    throw FileError(
        name, "invalid root colour " + std::to_string(root_code) + " (0 white, 1 black, 2 gray)");
  }
  const Color root = static_cast<Color>(root_code);
  if (getU32(header + 52) != 0) throw FileError(name, "reserved header field is not zero");
  const std::uint64_t count = getU64(header + 56);
  if ((root == Color::kGray) != (count > 0)) {
    throw FileError(name, "node count " + std::to_string(count) +
                              (root == Color::kGray ? " for a gray root (needs at least 1)"
                                                    : " for a uniform root (must be 0)"));
  }
  // Checked before anything is allocated: a corrupt count must not cost memory.
  const std::uint64_t limit = maxNodes(static_cast<int>(depth));
  if (count > limit || count > std::uint64_t{0xffffffffu}) {
    throw FileError(name, "node count " + std::to_string(count) + " is more than a depth-" +
                              std::to_string(depth) + " tree can have");
  }
  if (remaining >= 0) {
    const std::uint64_t need = count * kNodeBytes + kChecksumBytes;
    const std::uint64_t left = static_cast<std::uint64_t>(remaining) - kHeaderBytes;
    if (static_cast<std::uint64_t>(remaining) < kHeaderBytes || need > left) {
      throw FileError(name, "truncated: node count " + std::to_string(count) + " needs " +
                                std::to_string(need) + " bytes after the header, only " +
                                std::to_string(left) + " left");
    }
  }

  std::vector<OctreeNode> nodes;
  std::vector<unsigned char> block;
  for (std::uint64_t start = 0; start < count; start += kBlockNodes) {
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::uint64_t>(kBlockNodes, count - start));
    block.resize(n * kNodeBytes);
    readExact(in, block.data(), block.size(),
              kHeaderBytes + static_cast<std::size_t>(start) * kNodeBytes, "node records", name);
    hash.update(block.data(), block.size());
    nodes.reserve(nodes.size() + n);
    for (std::size_t i = 0; i < n; ++i) {
      const unsigned char* p = &block[i * kNodeBytes];
      if (p[6] != 0 || p[7] != 0) {
        throw FileError(name,
                        "node " + std::to_string(start + i) + ": reserved bytes are not zero");
      }
      OctreeNode node;
      node.first_child = getU32(p);
      node.black = p[4];
      node.gray = p[5];
      nodes.push_back(node);
    }
  }
  unsigned char checksum[kChecksumBytes];
  readExact(in, checksum, kChecksumBytes,
            kHeaderBytes + static_cast<std::size_t>(count) * kNodeBytes, "checksum", name);
  if (getU64(checksum) != hash.value()) {
    throw FileError(name, "checksum mismatch: the file is corrupt");
  }
  try {
    return Octree::fromNodes(*grid, root, std::move(nodes));
  } catch (const Error& e) {
    throw FileError(name, std::string("invalid tree: ") + e.what());
  }
}

void saveOctree(const Octree& tree, const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw FileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  try {
    writeOctree(tree, out);
  } catch (const Error&) {
    throw FileError(path, "write failed (disk full?)");
  }
  out.close();
  if (!out) throw FileError(path, "write failed when closing the file");
}

Octree loadOctree(const std::string& path) {
  requireRegularFile(path, "octree file", kMaxDataFileBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, std::string("cannot open: ") + std::strerror(errno));
  Octree tree = readOctree(in, path);
  if (in.peek() != std::char_traits<char>::eof()) {
    throw FileError(path, "unexpected bytes after the checksum");
  }
  return tree;
}

}  // namespace octomotion
