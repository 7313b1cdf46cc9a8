#include "octomotion/octree/set_ops.h"

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {

namespace {

enum class Op { kUnite, kIntersect };

// Copies the compact subtree at `from` into builder node `to`.
void copySubtree(const Octree& t, std::uint32_t from, OctreeBuilder& out, std::uint32_t to) {
  const OctreeNode& n = t.nodes()[from];
  out.node(to).black = n.black;
  for (unsigned g = n.gray; g; g &= g - 1) {
    const int k = lowestBit(g);
    copySubtree(t, n.childIndex(k), out, out.split(to, k));
  }
}

// Combines two gray nodes standing for the same cube into builder node `to`.
void combine(Op op, const Octree& a, std::uint32_t ia, const Octree& b, std::uint32_t ib,
             OctreeBuilder& out, std::uint32_t to) {
  const OctreeNode& na = a.nodes()[ia];
  const OctreeNode& nb = b.nodes()[ib];
  const unsigned black = op == Op::kUnite ? (na.black | nb.black) : (na.black & nb.black);
  out.node(to).black = static_cast<std::uint8_t>(black);
  // Children whose result is a copy of one side's gray subtree.
  const unsigned a_only = op == Op::kUnite ? (na.gray & ~nb.occupied()) : (na.gray & nb.black);
  const unsigned b_only = op == Op::kUnite ? (nb.gray & ~na.occupied()) : (nb.gray & na.black);
  for (unsigned m = a_only; m; m &= m - 1) {
    const int k = lowestBit(m);
    copySubtree(a, na.childIndex(k), out, out.split(to, k));
  }
  for (unsigned m = b_only; m; m &= m - 1) {
    const int k = lowestBit(m);
    copySubtree(b, nb.childIndex(k), out, out.split(to, k));
  }
  for (unsigned m = na.gray & nb.gray; m; m &= m - 1) {
    const int k = lowestBit(m);
    combine(op, a, na.childIndex(k), b, nb.childIndex(k), out, out.split(to, k));
  }
}

Octree apply(Op op, const Octree& a, const Octree& b) {
  if (a.grid() != b.grid()) {
    throw InvalidArgument(op == Op::kUnite ? "unite: the two trees are on different grids"
                                           : "intersect: the two trees are on different grids");
  }
  const Color ca = a.rootColor();
  const Color cb = b.rootColor();
  if (op == Op::kUnite) {
    if (ca == Color::kBlack || cb == Color::kWhite) return a;
    if (cb == Color::kBlack || ca == Color::kWhite) return b;
  } else {
    if (ca == Color::kWhite || cb == Color::kBlack) return a;
    if (cb == Color::kWhite || ca == Color::kBlack) return b;
  }
  OctreeBuilder out(a.grid());
  combine(op, a, 0, b, 0, out, OctreeBuilder::kRoot);
  return out.build();
}

}  // namespace

Octree unite(const Octree& a, const Octree& b) {
  return apply(Op::kUnite, a, b);
}
Octree intersect(const Octree& a, const Octree& b) {
  return apply(Op::kIntersect, a, b);
}

}  // namespace octomotion
