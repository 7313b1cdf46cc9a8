#include "octomotion/octree/octree_builder.h"

#include <string>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"

namespace octomotion {

OctreeBuilder::OctreeBuilder(const WorldGrid& grid) : grid_(grid) {
  allocate();
}

OctreeBuilder::OctreeBuilder(const Octree& tree) : OctreeBuilder(tree.grid()) {
  if (tree.rootColor() == Color::kBlack) {
    nodes_[kRoot].black = 0xff;
    return;
  }
  if (tree.rootColor() == Color::kWhite) return;
  // Copy the compact tree, node by node, into index form.
  struct Item {
    std::uint32_t from, to;
  };
  std::vector<Item> stack{{0, kRoot}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const OctreeNode& src = tree.nodes()[item.from];
    nodes_[item.to].black = src.black;
    for (std::uint8_t g = src.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
      const int k = lowestBit(g);
      const std::uint32_t child = split(item.to, k);
      stack.push_back({src.childIndex(k), child});
    }
  }
}

std::uint32_t OctreeBuilder::allocate() {
  std::uint32_t i;
  if (!free_.empty()) {
    i = free_.back();
    free_.pop_back();
    nodes_[i] = Node{};
  } else {
    i = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
  }
  if (++live_ > peak_) peak_ = live_;
  return i;
}

void OctreeBuilder::release(std::uint32_t i) {
  Node& n = nodes_[i];
  for (std::uint8_t g = n.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
    release(n.child[static_cast<std::size_t>(lowestBit(g))]);
  }
  n = Node{};
  free_.push_back(i);
  --live_;
}

std::uint32_t OctreeBuilder::split(std::uint32_t parent, int k) {
  const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
  if (nodes_[parent].gray & bit) return nodes_[parent].child[static_cast<std::size_t>(k)];
  const bool was_black = nodes_[parent].black & bit;
  const std::uint32_t c = allocate();  // may reallocate nodes_: index again below
  nodes_[c].black = was_black ? 0xff : 0;
  Node& p = nodes_[parent];
  p.black = static_cast<std::uint8_t>(p.black & ~bit);
  p.gray = static_cast<std::uint8_t>(p.gray | bit);
  p.child[static_cast<std::size_t>(k)] = c;
  return c;
}

bool OctreeBuilder::condense(std::uint32_t parent, int k) {
  const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
  Node& p = nodes_[parent];
  if (!(p.gray & bit)) return false;
  const std::uint32_t c = p.child[static_cast<std::size_t>(k)];
  const Node& n = nodes_[c];
  const bool all_black = n.black == 0xff;
  if (!all_black && (n.black | n.gray) != 0) return false;
  p.gray = static_cast<std::uint8_t>(p.gray & ~bit);
  if (all_black) p.black = static_cast<std::uint8_t>(p.black | bit);
  p.child[static_cast<std::size_t>(k)] = kNone;
  release(c);
  return true;
}

void OctreeBuilder::paint(const Cube& cube, bool black) {
  const std::uint32_t side = grid_.sideVoxels();
  if (cube.level < 0 || cube.level > grid_.depth() || cube.origin.x >= side ||
      cube.origin.y >= side || cube.origin.z >= side ||
      (cube.origin.x | cube.origin.y | cube.origin.z) & (cube.side() - 1)) {
    throw InvalidArgument("OctreeBuilder::paint: cube of level " + std::to_string(cube.level) +
                          " is not a cube of this grid");
  }
  if (cube.level == grid_.depth()) {
    Node& root = nodes_[kRoot];
    for (std::uint8_t g = root.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
      release(root.child[static_cast<std::size_t>(lowestBit(g))]);
    }
    nodes_[kRoot] = Node{};
    nodes_[kRoot].black = black ? 0xff : 0;
    return;
  }
  paintFrom(kRoot, grid_.universe(), cube, black);
}

void OctreeBuilder::paintFrom(std::uint32_t index, const Cube& cell, const Cube& target,
                              bool black) {
  const int shift = cell.level - 1;
  const int k = static_cast<int>(((target.origin.x >> shift) & 1u) |
                                 (((target.origin.y >> shift) & 1u) << 1) |
                                 (((target.origin.z >> shift) & 1u) << 2));
  const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
  if (cell.level - 1 == target.level) {
    Node& n = nodes_[index];
    if (n.gray & bit) {
      const std::uint32_t c = n.child[static_cast<std::size_t>(k)];
      n.gray = static_cast<std::uint8_t>(n.gray & ~bit);
      n.child[static_cast<std::size_t>(k)] = kNone;
      release(c);
    }
    Node& m = nodes_[index];
    m.black = static_cast<std::uint8_t>(black ? (m.black | bit) : (m.black & ~bit));
    return;
  }
  const Node& n = nodes_[index];
  if (!(n.gray & bit) && static_cast<bool>(n.black & bit) == black) return;  // already that colour
  const std::uint32_t c = split(index, k);
  paintFrom(c, cell.child(k), target, black);
  condense(index, k);
}

namespace {

// Effective masks of every builder node after condensation, computed bottom-up.
struct Masks {
  std::uint8_t black = 0, gray = 0;
};

Masks compactMasks(const std::vector<OctreeBuilder::Node>& nodes, std::uint32_t i,
                   std::vector<Masks>& out) {
  const OctreeBuilder::Node& n = nodes[i];
  Masks m{n.black, 0};
  for (std::uint8_t g = n.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
    const int k = lowestBit(g);
    const Masks c = compactMasks(nodes, n.child[static_cast<std::size_t>(k)], out);
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
    if (c.black == 0xff) {
      m.black = static_cast<std::uint8_t>(m.black | bit);
    } else if ((c.black | c.gray) != 0) {
      m.gray = static_cast<std::uint8_t>(m.gray | bit);
    }
  }
  out[i] = m;
  return m;
}

// Canonical layout: a node's gray children form one block, allocated when the node is laid
// out; blocks follow depth-first pre-order, so a subtree is contiguous after its root's block.
void layout(const std::vector<OctreeBuilder::Node>& nodes, const std::vector<Masks>& masks,
            std::uint32_t i, std::uint32_t pos, std::vector<OctreeNode>& out) {
  const Masks m = masks[i];
  const std::uint32_t first = static_cast<std::uint32_t>(out.size());
  out[pos] = OctreeNode{m.gray ? first : 0u, m.black, m.gray};
  out.resize(out.size() + static_cast<std::size_t>(popcount8(m.gray)));
  std::uint32_t j = 0;
  for (std::uint8_t g = m.gray; g; g &= static_cast<std::uint8_t>(g - 1), ++j) {
    layout(nodes, masks, nodes[i].child[static_cast<std::size_t>(lowestBit(g))], first + j, out);
  }
}

}  // namespace

Octree OctreeBuilder::build() const {
  std::vector<Masks> masks(nodes_.size());
  const Masks root = compactMasks(nodes_, kRoot, masks);
  if (root.black == 0xff) return Octree(grid_, Color::kBlack, {});
  if ((root.black | root.gray) == 0) return Octree(grid_, Color::kWhite, {});
  std::vector<OctreeNode> out(1);
  out.reserve(live_);
  layout(nodes_, masks, kRoot, 0, out);
  return Octree(grid_, Color::kGray, std::move(out));
}

}  // namespace octomotion
