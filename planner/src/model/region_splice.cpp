#include "internal/region_splice.h"

#include <algorithm>
#include <cmath>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion::detail {

namespace {

// A tree at one cube: a leaf colour, or (kGray) a node.
struct At {
  Color color = Color::kWhite;
  std::uint32_t node = 0;
};

At childAt(const Octree& tree, At at, int k) {
  if (at.color != Color::kGray) return at;
  const OctreeNode& n = tree.nodes()[at.node];
  if (n.black & (1u << k)) return {Color::kBlack, 0};
  if (n.gray & (1u << k)) return {Color::kGray, n.childIndex(k)};
  return {Color::kWhite, 0};
}

At rootAt(const Octree& tree) {
  return {tree.rootColor(), 0};
}

enum class Relation { kOutside, kInside, kPartial };

Relation relation(const Cube& c, const VoxelBounds& r) {
  const std::uint32_t s = c.side() - 1;
  const std::uint32_t lo[3] = {c.origin.x, c.origin.y, c.origin.z};
  const std::uint32_t rlo[3] = {r.min.x, r.min.y, r.min.z};
  const std::uint32_t rhi[3] = {r.max.x, r.max.y, r.max.z};
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    if (lo[a] + s < rlo[a] || lo[a] > rhi[a]) return Relation::kOutside;
    inside = inside && lo[a] >= rlo[a] && lo[a] + s <= rhi[a];
  }
  return inside ? Relation::kInside : Relation::kPartial;
}

void copySubtree(const Octree& t, std::uint32_t from, OctreeBuilder& out, std::uint32_t to) {
  const OctreeNode& n = t.nodes()[from];
  out.node(to).black = n.black;
  for (unsigned g = n.gray; g; g &= g - 1) {
    const int k = lowestBit(g);
    copySubtree(t, n.childIndex(k), out, out.split(to, k));
  }
}

// Child k of builder node `to` becomes what `tree` holds there.
void put(const Octree& tree, At at, OctreeBuilder& out, std::uint32_t to, int k) {
  if (at.color == Color::kBlack) {
    out.node(to).black = static_cast<std::uint8_t>(out.node(to).black | (1u << k));
  } else if (at.color == Color::kGray) {
    copySubtree(tree, at.node, out, out.split(to, k));
  }
}

// Builder node `to` stands for `cube`, which the region cuts (level >= 1): fills its children.
void fill(const Octree& outside, At a, const Octree& inside, At b, const VoxelBounds& region,
          const Cube& cube, OctreeBuilder& out, std::uint32_t to) {
  for (int k = 0; k < 8; ++k) {
    const Cube child = cube.child(k);
    const At ca = childAt(outside, a, k);
    const At cb = childAt(inside, b, k);
    switch (relation(child, region)) {
      case Relation::kOutside:
        put(outside, ca, out, to, k);
        break;
      case Relation::kInside:
        put(inside, cb, out, to, k);
        break;
      case Relation::kPartial:
        if (ca.color != Color::kGray && ca.color == cb.color) {
          put(outside, ca, out, to, k);  // the same colour on both sides of the cut
        } else {
          fill(outside, ca, inside, cb, region, child, out, out.split(to, k));
          out.condense(to, k);
        }
        break;
    }
  }
}

}  // namespace

std::optional<VoxelBounds> touchedVoxels(const WorldGrid& grid, const Eigen::AlignedBox3d& box_W) {
  if (box_W.isEmpty()) return std::nullopt;
  const Eigen::Vector3d lo = grid.toGrid(box_W.min()).array().floor() - 1;
  const Eigen::Vector3d hi = grid.toGrid(box_W.max()).array().floor() + 1;
  const double last = static_cast<double>(grid.sideVoxels()) - 1;
  if ((hi.array() < 0).any() || (lo.array() > last).any()) return std::nullopt;
  auto clamp = [last](double v) { return static_cast<std::uint32_t>(std::clamp(v, 0.0, last)); };
  return VoxelBounds{{clamp(lo.x()), clamp(lo.y()), clamp(lo.z())},
                     {clamp(hi.x()), clamp(hi.y()), clamp(hi.z())}};
}

VoxelBounds merge(const VoxelBounds& a, const VoxelBounds& b) {
  return {{std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y), std::min(a.min.z, b.min.z)},
          {std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y), std::max(a.max.z, b.max.z)}};
}

bool overlap(const VoxelBounds& a, const VoxelBounds& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

Octree spliceRegion(const Octree& outside, const Octree& inside, const VoxelBounds& region) {
  if (outside.grid() != inside.grid()) {
    throw InvalidArgument("spliceRegion: the two trees are on different grids");
  }
  const Cube universe = outside.grid().universe();
  switch (relation(universe, region)) {
    case Relation::kOutside:
      return outside;
    case Relation::kInside:
      return inside;
    case Relation::kPartial:
      break;
  }
  OctreeBuilder out(outside.grid());
  out.reserve(outside.internalNodeCount() + inside.internalNodeCount() / 4 + 64);
  fill(outside, rootAt(outside), inside, rootAt(inside), region, universe, out,
       OctreeBuilder::kRoot);
  return out.build();
}

}  // namespace octomotion::detail
