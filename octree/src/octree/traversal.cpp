#include "octomotion/octree/traversal.h"

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"

namespace octomotion {

namespace {

void requireSameGrid(const Octree& a, const Octree& b, const char* what) {
  if (a.grid() != b.grid()) {
    throw InvalidArgument(std::string(what) + ": the two trees are on different grids");
  }
}

// Both nodes stand for the same cube. A gray child always holds some black voxel (compaction),
// so a black child against any non-white child is a shared black region.
bool intersectsFrom(const OctreeNode* a_nodes, std::uint32_t ia, const OctreeNode* b_nodes,
                    std::uint32_t ib) {
  const OctreeNode& a = a_nodes[ia];
  const OctreeNode& b = b_nodes[ib];
  if ((a.black & b.occupied()) | (b.black & a.occupied())) return true;
  for (unsigned both = a.gray & b.gray; both; both &= both - 1) {
    const int k = lowestBit(both);
    if (intersectsFrom(a_nodes, a.childIndex(k), b_nodes, b.childIndex(k))) return true;
  }
  return false;
}

void collectLeaves(const Octree& t, std::uint32_t index, const Cube& cube, std::vector<Cube>& out) {
  const OctreeNode& n = t.nodes()[index];
  for (int k = 0; k < 8; ++k) {
    if (n.black & (1u << k)) {
      out.push_back(cube.child(k));
    } else if (n.gray & (1u << k)) {
      collectLeaves(t, n.childIndex(k), cube.child(k), out);
    }
  }
}

void overlapFrom(const Octree& a, std::uint32_t ia, const Octree& b, std::uint32_t ib,
                 const Cube& cube, std::vector<Cube>& out) {
  const OctreeNode& na = a.nodes()[ia];
  const OctreeNode& nb = b.nodes()[ib];
  for (unsigned m = na.occupied() & nb.occupied(); m; m &= m - 1) {
    const int k = lowestBit(m);
    const unsigned bit = 1u << k;
    const Cube child = cube.child(k);
    if ((na.black & bit) && (nb.black & bit)) {
      out.push_back(child);
    } else if (na.black & bit) {
      collectLeaves(b, nb.childIndex(k), child, out);
    } else if (nb.black & bit) {
      collectLeaves(a, na.childIndex(k), child, out);
    } else {
      overlapFrom(a, na.childIndex(k), b, nb.childIndex(k), child, out);
    }
  }
}

}  // namespace

bool intersects(const Octree& a, const Octree& b) {
  requireSameGrid(a, b, "intersects");
  if (a.empty() || b.empty()) return false;
  if (a.rootColor() == Color::kBlack || b.rootColor() == Color::kBlack) return true;
  return intersectsFrom(a.nodes().data(), 0, b.nodes().data(), 0);
}

std::vector<Cube> overlappingCubes(const Octree& a, const Octree& b) {
  requireSameGrid(a, b, "overlappingCubes");
  std::vector<Cube> out;
  if (a.empty() || b.empty()) return out;
  const Cube universe = a.grid().universe();
  if (a.rootColor() == Color::kBlack && b.rootColor() == Color::kBlack) {
    out.push_back(universe);
  } else if (a.rootColor() == Color::kBlack) {
    collectLeaves(b, 0, universe, out);
  } else if (b.rootColor() == Color::kBlack) {
    collectLeaves(a, 0, universe, out);
  } else {
    overlapFrom(a, 0, b, 0, universe, out);
  }
  return out;
}

}  // namespace octomotion
