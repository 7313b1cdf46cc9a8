#include "octomotion/octree/octree.h"

#include <algorithm>
#include <string>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {

Octree::Octree(const WorldGrid& grid) : grid_(grid) {}

Octree Octree::full(const WorldGrid& grid) {
  return Octree(grid, Color::kBlack, {});
}

Octree Octree::fromVoxels(const WorldGrid& grid, const std::vector<Voxel>& voxels) {
  OctreeBuilder builder(grid);
  const std::uint32_t side = grid.sideVoxels();
  for (const Voxel& v : voxels) {
    if (v.x >= side || v.y >= side || v.z >= side) {
      throw InvalidArgument("Octree::fromVoxels: voxel (" + std::to_string(v.x) + ", " +
                            std::to_string(v.y) + ", " + std::to_string(v.z) +
                            ") is outside a universe of side " + std::to_string(side));
    }
    builder.setVoxel(v);
  }
  return builder.build();
}

namespace {

// Walks a node array from the root, checking what a compact, well-formed tree must satisfy.
bool validate(const std::vector<OctreeNode>& nodes, int depth, std::string* why) {
  auto fail = [&](std::uint32_t i, const std::string& what) {
    if (why) *why = "node " + std::to_string(i) + ": " + what;
    return false;
  };
  std::vector<std::uint8_t> seen(nodes.size(), 0);
  struct Item {
    std::uint32_t index;
    int level;
  };
  std::vector<Item> stack{{0, depth}};
  seen[0] = 1;
  std::size_t visited = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    ++visited;
    const OctreeNode& n = nodes[item.index];
    if (n.black & n.gray) return fail(item.index, "a child is both black and gray");
    if (n.black == 0xff) return fail(item.index, "not compact: all eight children black");
    if (n.occupied() == 0) return fail(item.index, "not compact: all eight children white");
    if (n.gray && item.level <= 1) return fail(item.index, "gray child below voxel level");
    const std::uint64_t count = static_cast<std::uint64_t>(popcount8(n.gray));
    if (n.gray && static_cast<std::uint64_t>(n.first_child) + count > nodes.size()) {
      return fail(item.index, "child index out of range");
    }
    for (std::uint32_t j = 0; j < count; ++j) {
      const std::uint32_t c = n.first_child + j;
      if (seen[c]) return fail(item.index, "child " + std::to_string(c) + " referenced twice");
      seen[c] = 1;
      stack.push_back({c, item.level - 1});
    }
  }
  if (visited != nodes.size()) {
    if (why) *why = std::to_string(nodes.size() - visited) + " nodes unreachable from the root";
    return false;
  }
  return true;
}

}  // namespace

Octree Octree::fromNodes(const WorldGrid& grid, Color root, std::vector<OctreeNode> nodes) {
  if (root != Color::kGray) {
    if (!nodes.empty()) throw Error("Octree::fromNodes: a uniform root cannot have nodes");
    return Octree(grid, root, {});
  }
  if (nodes.empty()) throw Error("Octree::fromNodes: a gray root needs nodes");
  std::string why;
  if (!validate(nodes, grid.depth(), &why)) throw Error("Octree::fromNodes: " + why);
  return Octree(grid, root, std::move(nodes));
}

bool Octree::checkInvariants(std::string* why) const {
  if (root_ != Color::kGray) {
    if (!nodes_.empty()) {
      if (why) *why = "uniform root with nodes";
      return false;
    }
    return true;
  }
  if (nodes_.empty()) {
    if (why) *why = "gray root without nodes";
    return false;
  }
  return validate(nodes_, grid_.depth(), why);
}

std::size_t Octree::blackLeafCount() const {
  if (root_ != Color::kGray) return root_ == Color::kBlack ? 1 : 0;
  std::size_t count = 0;
  for (const OctreeNode& n : nodes_) count += static_cast<std::size_t>(popcount8(n.black));
  return count;
}

std::uint64_t Octree::blackVoxelCount() const {
  std::uint64_t count = 0;
  forEachBlackLeaf([&](const Cube& c) { count += std::uint64_t{1} << (3 * c.level); });
  return count;
}

double Octree::volume() const {
  const double v = grid_.voxelSize();
  return static_cast<double>(blackVoxelCount()) * v * v * v;
}

bool Octree::occupied(const Voxel& v) const {
  const std::uint32_t side = grid_.sideVoxels();
  if (v.x >= side || v.y >= side || v.z >= side) return false;
  if (root_ != Color::kGray) return root_ == Color::kBlack;
  std::uint32_t index = 0;
  for (int bit = grid_.depth() - 1; bit >= 0; --bit) {
    const OctreeNode& n = nodes_[index];
    const int k = static_cast<int>(((v.x >> bit) & 1u) | (((v.y >> bit) & 1u) << 1) |
                                   (((v.z >> bit) & 1u) << 2));
    if (n.black & (1u << k)) return true;
    if (!(n.gray & (1u << k))) return false;
    index = n.childIndex(k);
  }
  return false;  // unreachable for a valid tree: level-1 nodes have no gray children
}

bool Octree::occupiedAt(const Eigen::Vector3d& p_W) const {
  Voxel v;
  return grid_.voxelAt(p_W, &v) && occupied(v);
}

std::optional<VoxelBounds> Octree::bounds() const {
  if (empty()) return std::nullopt;
  VoxelBounds b{{~0u, ~0u, ~0u}, {0, 0, 0}};
  forEachBlackLeaf([&](const Cube& c) {
    const std::uint32_t last = c.side() - 1;
    b.min.x = std::min(b.min.x, c.origin.x);
    b.min.y = std::min(b.min.y, c.origin.y);
    b.min.z = std::min(b.min.z, c.origin.z);
    b.max.x = std::max(b.max.x, c.origin.x + last);
    b.max.y = std::max(b.max.y, c.origin.y + last);
    b.max.z = std::max(b.max.z, c.origin.z + last);
  });
  return b;
}

std::vector<Cube> Octree::blackLeaves() const {
  std::vector<Cube> leaves;
  forEachBlackLeaf([&](const Cube& c) { leaves.push_back(c); });
  return leaves;
}

std::vector<Voxel> Octree::blackVoxels() const {
  std::vector<Voxel> voxels;
  forEachBlackLeaf([&](const Cube& c) {
    const std::uint32_t s = c.side();
    for (std::uint32_t z = 0; z < s; ++z)
      for (std::uint32_t y = 0; y < s; ++y)
        for (std::uint32_t x = 0; x < s; ++x)
          voxels.push_back({c.origin.x + x, c.origin.y + y, c.origin.z + z});
  });
  return voxels;
}

namespace {
bool sameSubtree(const std::vector<OctreeNode>& a, std::uint32_t ia,
                 const std::vector<OctreeNode>& b, std::uint32_t ib) {
  const OctreeNode& na = a[ia];
  const OctreeNode& nb = b[ib];
  if (na.black != nb.black || na.gray != nb.gray) return false;
  for (std::uint8_t g = na.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
    const int k = lowestBit(g);
    if (!sameSubtree(a, na.childIndex(k), b, nb.childIndex(k))) return false;
  }
  return true;
}
}  // namespace

bool operator==(const Octree& a, const Octree& b) {
  if (a.grid_ != b.grid_ || a.root_ != b.root_) return false;
  if (a.root_ != Color::kGray) return true;
  return sameSubtree(a.nodes_, 0, b.nodes_, 0);
}

}  // namespace octomotion
