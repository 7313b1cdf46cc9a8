#include "octomotion/octree/octomap_io.h"

#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>

#include "octomotion/input_limits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {

namespace {

constexpr int kOctoMapDepth = 16;
constexpr std::int64_t kKeyCentre = 32768;  // OctoMap's tree_max_val: key of coordinate 0
constexpr std::int64_t kKeyCount = 65536;
const char* const kBtFirstLine = "# Octomap OcTree binary file";

using KeyBox = std::array<std::uint32_t, 6>;  // inclusive lo x, y, z, hi x, y, z

// ---------------------------------------------------------------------------------------------
// Reading

struct BtFile {
  std::string bytes;
  double resolution = 0;
  std::size_t node_count = 0;  // the "size" header field, checked against the data
  std::size_t data_offset = 0;
};

bool nextLine(const std::string& s, std::size_t* pos, std::string* line) {
  if (*pos >= s.size()) return false;
  const std::size_t end = s.find('\n', *pos);
  if (end == std::string::npos) return false;  // a header line must end with a newline
  *line = s.substr(*pos, end - *pos);
  if (!line->empty() && line->back() == '\r') line->pop_back();
  *pos = end + 1;
  return true;
}

// Checks the whole file before liboctomap sees it: its binary reader trusts the bit stream (it
// reads past the end and recurses as deep as the bits say), so only well-formed data reaches it.
BtFile readBtFile(const std::string& path) {
  BtFile file;
  file.bytes = readWholeFile(path, "OctoMap file", kMaxDataFileBytes);
  const std::string& s = file.bytes;

  std::size_t pos = 0;
  std::string line;
  if (!nextLine(s, &pos, &line) || line.rfind(kBtFirstLine, 0) != 0) {
    throw FileError(path,
                    std::string("not an OctoMap binary (.bt) file: the first line is not \"") +
                        kBtFirstLine + "\"");
  }
  std::string id;
  bool have_res = false, have_size = false, have_data = false;
  while (nextLine(s, &pos, &line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key == "data") {
      have_data = true;
      break;
    } else if (key == "id") {
      fields >> id;
    } else if (key == "res") {
      have_res = static_cast<bool>(fields >> file.resolution);
    } else if (key == "size") {
      long long size = -1;
      have_size = static_cast<bool>(fields >> size) && size >= 0;
      file.node_count = static_cast<std::size_t>(std::max(size, 0LL));
    }
    // Other keys are ignored, as liboctomap does.
  }
  if (!have_data) throw FileError(path, "truncated header: no \"data\" line");
  if (id != "OcTree") {
    throw FileError(path, "tree type \"" + id + "\" is not OcTree (only OcTree .bt files)");
  }
  if (!have_size) throw FileError(path, "header has no valid \"size\" line");
  // The upper bound keeps every key's coordinate (|key - 32768| * res) far from overflow.
  if (!have_res || !std::isfinite(file.resolution) || file.resolution <= 0 ||
      file.resolution > 1e100) {
    throw FileError(path, "header has no valid \"res\" line (a resolution in (0, 1e100] m)");
  }

  // The data: one 2-byte record per inner node in depth-first order, 2 bits per child
  // (00 unknown, 01 occupied leaf, 10 free leaf, 11 inner node whose record follows).
  file.data_offset = pos;
  std::size_t nodes = 0;
  if (pos < s.size() || file.node_count > 0) {
    nodes = 1;  // the root
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const int depth = stack.back();
      stack.pop_back();
      if (s.size() - pos < 2) {
        throw FileError(path, "truncated: the node data ends at byte " + std::to_string(s.size()));
      }
      const unsigned bits = static_cast<unsigned char>(s[pos]) |
                            (static_cast<unsigned>(static_cast<unsigned char>(s[pos + 1])) << 8);
      pos += 2;
      for (int k = 7; k >= 0; --k) {  // reversed so that child 0's record is read first
        const unsigned code = (bits >> (2 * k)) & 3u;
        if (code != 0) ++nodes;
        if (code == 3) {
          if (depth + 1 >= kOctoMapDepth) {
            throw FileError(path, "corrupt node data: inner node below OctoMap's 16 levels");
          }
          stack.push_back(depth + 1);
        }
      }
    }
  }
  if (pos != s.size()) {
    throw FileError(path, std::to_string(s.size() - pos) + " unexpected bytes after the node data");
  }
  if (nodes != file.node_count) {
    throw FileError(path, "header says size " + std::to_string(file.node_count) +
                              " but the data holds " + std::to_string(nodes) + " nodes");
  }
  return file;
}

// Decodes a checked file's node data with liboctomap's own reader. The header was parsed above;
// an empty tree (no data) is never handed to it.
std::unique_ptr<octomap::OcTree> parseWithOctoMap(const BtFile& file) {
  auto tree = std::make_unique<octomap::OcTree>(file.resolution);
  if (file.node_count == 0) return tree;
  std::istringstream in(file.bytes.substr(file.data_offset));
  tree->readBinaryData(in);
  return tree;
}

// Calls f(depth, key_min) for every occupied leaf. The root's record only describes its
// children, so the root itself is never taken as a leaf (liboctomap would call a childless
// root occupied).
template <class F>
void forEachOccupiedLeaf(const octomap::OcTree& tree, const octomap::OcTreeNode* node, int depth,
                         const std::array<std::uint32_t, 3>& key_min, F& f) {
  const std::uint32_t half = std::uint32_t{1} << (kOctoMapDepth - 1 - depth);
  for (unsigned k = 0; k < 8; ++k) {
    if (!tree.nodeChildExists(node, k)) continue;
    const octomap::OcTreeNode* child = tree.getNodeChild(node, k);
    const std::array<std::uint32_t, 3> child_min{key_min[0] + ((k & 1u) ? half : 0u),
                                                 key_min[1] + ((k & 2u) ? half : 0u),
                                                 key_min[2] + ((k & 4u) ? half : 0u)};
    if (tree.nodeHasChildren(child)) {
      forEachOccupiedLeaf(tree, child, depth + 1, child_min, f);
    } else if (tree.isNodeOccupied(child)) {
      f(depth + 1, child_min);
    }
  }
}

template <class F>
void forEachOccupiedLeaf(const octomap::OcTree& tree, F&& f) {
  if (tree.getRoot() == nullptr) return;
  forEachOccupiedLeaf(tree, tree.getRoot(), 0, {0, 0, 0}, f);
}

// Paints the voxels of an inclusive integer box as few aligned cubes as cover it exactly.
void paintBox(OctreeBuilder& builder, const Cube& cube, const KeyBox& box) {
  const std::uint32_t last = cube.side() - 1;
  const std::uint32_t lo[3] = {cube.origin.x, cube.origin.y, cube.origin.z};
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    const std::uint32_t a_lo = box[static_cast<std::size_t>(a)];
    const std::uint32_t a_hi = box[static_cast<std::size_t>(a + 3)];
    if (lo[a] > a_hi || lo[a] + last < a_lo) return;  // disjoint
    inside = inside && lo[a] >= a_lo && lo[a] + last <= a_hi;
  }
  if (inside) {
    builder.paint(cube, true);
    return;
  }
  for (int k = 0; k < 8; ++k) paintBox(builder, cube.child(k), box);
}

}  // namespace

WorldGrid octomapNativeGrid(double resolution) {
  if (!std::isfinite(resolution) || resolution <= 0) {
    throw InvalidArgument("octomapNativeGrid: resolution " + std::to_string(resolution) +
                          " is not a finite value > 0");
  }
  const double o = -static_cast<double>(kKeyCentre) * resolution;
  return WorldGrid(Eigen::Vector3d(o, o, o), resolution, kOctoMapDepth);
}

Octree importOctoMap(const std::string& path) {
  const BtFile file = readBtFile(path);
  const auto tree = parseWithOctoMap(file);
  OctreeBuilder builder(octomapNativeGrid(file.resolution));
  forEachOccupiedLeaf(*tree, [&](int depth, const std::array<std::uint32_t, 3>& key_min) {
    builder.paint(Cube{kOctoMapDepth - depth, {key_min[0], key_min[1], key_min[2]}}, true);
  });
  return builder.build();
}

Octree importOctoMap(const std::string& path, const WorldGrid& grid, Rounding rounding,
                     const WarningSink& warnings) {
  const BtFile file = readBtFile(path);
  const auto tree = parseWithOctoMap(file);
  const double res = file.resolution;
  const double side = static_cast<double>(grid.sideVoxels());
  OctreeBuilder builder(grid);
  std::size_t leaves = 0, clipped = 0;
  forEachOccupiedLeaf(*tree, [&](int depth, const std::array<std::uint32_t, 3>& key_min) {
    ++leaves;
    const double size = static_cast<double>(std::uint32_t{1} << (kOctoMapDepth - depth));
    KeyBox box;
    bool was_clipped = false;
    for (int a = 0; a < 3; ++a) {
      // The leaf's extent in continuous grid coordinates (voxel units from the grid origin).
      const double min_W = (static_cast<double>(key_min[static_cast<std::size_t>(a)]) -
                            static_cast<double>(kKeyCentre)) *
                           res;
      const double lo = (min_W - grid.origin()[a]) / grid.voxelSize();
      const double hi = (min_W + size * res - grid.origin()[a]) / grid.voxelSize();
      // Voxel i spans [i, i + 1]: it touches [lo, hi] iff i in [lo - 1, hi]; its centre is in
      // it iff i in [lo - 0.5, hi - 0.5].
      double first = rounding == Rounding::kConservative ? std::ceil(lo - 1) : std::ceil(lo - 0.5);
      double last = rounding == Rounding::kConservative ? std::floor(hi) : std::floor(hi - 0.5);
      if (lo < 0 || hi > side) was_clipped = true;  // the leaf itself leaves the universe
      first = std::max(first, 0.0);
      last = std::min(last, side - 1);
      if (first > last) {  // nothing of this leaf inside the universe (or between centres)
        if (was_clipped) ++clipped;
        return;
      }
      box[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(first);
      box[static_cast<std::size_t>(a + 3)] = static_cast<std::uint32_t>(last);
    }
    if (was_clipped) ++clipped;
    paintBox(builder, grid.universe(), box);
  });
  if (clipped > 0) {
    warn(warnings, path + ": " + std::to_string(clipped) + " of " + std::to_string(leaves) +
                       " occupied OctoMap leaves reach outside the grid; those parts are dropped");
  }
  return builder.build();
}

// ---------------------------------------------------------------------------------------------
// Writing

namespace {

// liboctomap creates a root only as a side effect of updating a voxel (which also makes a path
// down to it); the export needs the bare root, which only a derived class can make.
class ExportTree : public octomap::OcTree {
 public:
  using octomap::OcTree::OcTree;
  octomap::OcTreeNode* ensureRoot() {
    if (root == nullptr) {
      root = new octomap::OcTreeNode();
      tree_size = 1;
      size_changed = true;
    }
    return root;
  }
};

// Makes the box's region of `node` (which spans 2^(16 - depth) keys from key_min and is only
// partly covered) a set of leaves with the given log-odds, creating nodes on the way.
void insertBox(octomap::OcTree& tree, octomap::OcTreeNode* node, int depth,
               const std::array<std::uint32_t, 3>& key_min, const KeyBox& box, float log_odds) {
  const std::uint32_t half = std::uint32_t{1} << (kOctoMapDepth - 1 - depth);
  for (unsigned k = 0; k < 8; ++k) {
    const std::array<std::uint32_t, 3> child_min{key_min[0] + ((k & 1u) ? half : 0u),
                                                 key_min[1] + ((k & 2u) ? half : 0u),
                                                 key_min[2] + ((k & 4u) ? half : 0u)};
    bool disjoint = false, inside = true;
    for (std::size_t a = 0; a < 3; ++a) {
      const std::uint32_t lo = child_min[a], hi = child_min[a] + half - 1;
      if (lo > box[a + 3] || hi < box[a]) disjoint = true;
      inside = inside && lo >= box[a] && hi <= box[a + 3];
    }
    if (disjoint) continue;
    if (inside) {
      // Our leaves are disjoint, so this region has not been touched yet.
      if (tree.nodeChildExists(node, k))
        throw Error("exportOctoMap: internal error: boxes overlap");
      tree.createNodeChild(node, k)->setLogOdds(log_odds);
    } else {
      octomap::OcTreeNode* child = tree.nodeChildExists(node, k) ? tree.getNodeChild(node, k)
                                                                 : tree.createNodeChild(node, k);
      insertBox(tree, child, depth + 1, child_min, box, log_odds);
    }
  }
}

struct Alignment {
  std::int64_t offset[3];  // OctoMap key of our voxel 0 on each axis
};

Alignment alignToOctoMap(const WorldGrid& grid) {
  Alignment al{};
  const char* axis = "xyz";
  for (int a = 0; a < 3; ++a) {
    const double q = grid.origin()[a] / grid.voxelSize();
    const double n = std::round(q);
    if (!(std::fabs(q - n) <= 1e-6) || std::fabs(n) > 1e12) {
      std::ostringstream why;
      why << std::setprecision(17) << "exportOctoMap: the grid origin " << axis[a] << " = "
          << grid.origin()[a] << " is " << q << " voxels from 0, not a whole number, so the "
          << "voxels do not lie on OctoMap's key grid (cells at multiples of the resolution "
          << grid.voxelSize() << "); use a grid whose origin is a multiple of the voxel size";
      throw InvalidArgument(why.str());
    }
    al.offset[a] = static_cast<std::int64_t>(n) + kKeyCentre;
  }
  return al;
}

// Builds the OctoMap of `tree` whose voxel 0 has keys `offset` (already checked to keep every
// written voxel in range): black leaves become occupied leaves, white ones free leaves when
// `write_free_space`, unknown otherwise; then inner values are set and the tree pruned.
void fillOctoMap(ExportTree& out, const Octree& tree, const std::int64_t offset[3],
                 bool write_free_space) {
  const float occupied = out.getClampingThresMaxLog();
  const float free = out.getClampingThresMinLog();
  auto keyBoxOf = [&](const Cube& c) {
    const std::uint32_t last = c.side() - 1;
    const std::uint32_t o[3] = {c.origin.x, c.origin.y, c.origin.z};
    KeyBox box;
    for (std::size_t a = 0; a < 3; ++a) {
      box[a] = static_cast<std::uint32_t>(offset[a] + o[a]);
      box[a + 3] = box[a] + last;
    }
    return box;
  };
  auto insert = [&](const Cube& c, float log_odds) {
    insertBox(out, out.ensureRoot(), 0, {0, 0, 0}, keyBoxOf(c), log_odds);
  };

  // Our leaves, each whole: an aligned cube may still straddle OctoMap's cube boundaries when the
  // offset is not a multiple of its side; insertBox splits it into OctoMap cubes then.
  if (tree.rootColor() != Color::kGray) {
    if (tree.rootColor() == Color::kBlack || write_free_space) {
      insert(tree.grid().universe(), tree.rootColor() == Color::kBlack ? occupied : free);
    }
  } else {
    struct Item {
      std::uint32_t index;
      Cube cube;
    };
    std::vector<Item> stack{{0, tree.grid().universe()}};
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      const OctreeNode& n = tree.nodes()[item.index];
      for (int k = 0; k < 8; ++k) {
        const unsigned bit = 1u << k;
        if (n.black & bit) {
          insert(item.cube.child(k), occupied);
        } else if (n.gray & bit) {
          stack.push_back({n.childIndex(k), item.cube.child(k)});
        } else if (write_free_space) {
          insert(item.cube.child(k), free);
        }
      }
    }
  }
  if (out.getRoot() != nullptr) {
    out.updateInnerOccupancy();
    out.toMaxLikelihood();
    out.prune();
  }
}

}  // namespace

namespace {

// Builds the OctoMap of `tree` (see exportOctoMap for the conditions it checks, and throws for).
std::unique_ptr<ExportTree> buildOctoMap(const Octree& tree, bool write_free_space) {
  const WorldGrid& grid = tree.grid();
  const Alignment al = alignToOctoMap(grid);

  // The voxels to be written must have keys in [0, 65535].
  std::optional<VoxelBounds> region;
  if (write_free_space) {
    const std::uint32_t last = grid.sideVoxels() - 1;
    region = VoxelBounds{{0, 0, 0}, {last, last, last}};
  } else {
    region = tree.bounds();
  }
  if (region) {
    const std::uint32_t lo[3] = {region->min.x, region->min.y, region->min.z};
    const std::uint32_t hi[3] = {region->max.x, region->max.y, region->max.z};
    for (int a = 0; a < 3; ++a) {
      if (al.offset[a] + lo[a] < 0 || al.offset[a] + hi[a] >= kKeyCount) {
        std::ostringstream why;
        why << "exportOctoMap: voxels " << lo[a] << ".." << hi[a] << " along "
            << "xyz"[a] << " map to OctoMap keys " << al.offset[a] + lo[a] << ".."
            << al.offset[a] + hi[a]
            << ", outside OctoMap's 16-bit key range [0, 65535] (+/- 32768 voxels of "
            << grid.voxelSize() << " m about 0)";
        throw InvalidArgument(why.str());
      }
    }
  }

  auto out = std::make_unique<ExportTree>(grid.voxelSize());
  fillOctoMap(*out, tree, al.offset, write_free_space);
  return out;
}

}  // namespace

std::unique_ptr<octomap::OcTree> toOctoMap(const Octree& tree) {
  return buildOctoMap(tree, false);
}

void exportOctoMap(const Octree& tree, const std::string& path, bool write_free_space) {
  const std::unique_ptr<ExportTree> built = buildOctoMap(tree, write_free_space);
  const ExportTree& out = *built;
  const WorldGrid& grid = tree.grid();

  // The header is written here rather than by liboctomap so that the resolution keeps all its
  // digits (liboctomap prints 6 significant ones); the node data is liboctomap's own encoding.
  std::ostringstream data(std::ios::binary);
  data << kBtFirstLine << "\n# Written by octomotion::exportOctoMap\n#\nid OcTree\nsize "
       << out.size() << "\nres " << std::setprecision(17) << grid.voxelSize() << "\ndata\n";
  out.writeBinaryData(data);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw FileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  const std::string bytes = data.str();
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) throw FileError(path, "write failed");
}

}  // namespace octomotion

namespace octomotion {

OctoMapFootprint octomapFootprint(const Octree& tree) {
  const int depth = tree.grid().depth();
  if (depth > kOctoMapDepth) {
    throw InvalidArgument("octomapFootprint: depth " + std::to_string(depth) +
                          " exceeds OctoMap's fixed 16 levels");
  }
  // Voxel 0 at key 32768 (or 0 for depth 16) keeps every cube of ours an OctoMap cube.
  const std::int64_t o = depth == kOctoMapDepth ? 0 : kKeyCentre;
  const std::int64_t offset[3] = {o, o, o};
  ExportTree out(tree.grid().voxelSize());
  fillOctoMap(out, tree, offset, false);
  OctoMapFootprint f;
  f.nodes = out.size();
  f.inner_nodes = out.size() - (out.getRoot() ? out.getNumLeafNodes() : 0);
  f.bytes = out.memoryUsage();
  return f;
}

}  // namespace octomotion
