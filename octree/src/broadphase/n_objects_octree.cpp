// N-objects octree: construction, per-step membership update through neighbour finding, deferred
// split/merge, re-rooting and the invariant checker. See the header for the algorithm.
#include "octomotion/broadphase/n_objects_octree.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"

namespace octomotion::broadphase {

namespace {

// For each combination of "the box reaches beyond the node" bits (bit 2a: on the -a side, bit
// 2a+1: on the +a side) the set of directions (bit d) whose neighbour can touch the box.
struct ReachTable {
  std::uint32_t directions[64];
};

constexpr ReachTable makeReachTable() {
  ReachTable t{};
  for (int reach = 0; reach < 64; ++reach) {
    std::uint32_t mask = 0;
    for (int d = 0; d < kDirectionCount; ++d) {
      const Offset o = offset(static_cast<Direction>(d));
      const int c[3] = {o.dx, o.dy, o.dz};
      bool ok = true;
      for (int a = 0; a < 3; ++a) {
        if (c[a] < 0 && !(reach & (1 << (2 * a)))) ok = false;
        if (c[a] > 0 && !(reach & (1 << (2 * a + 1)))) ok = false;
      }
      if (ok) mask |= 1u << d;
    }
    t.directions[reach] = mask;
  }
  return t;
}
constexpr ReachTable kReach = makeReachTable();

void eraseValue(std::vector<std::uint32_t>& v, std::uint32_t value) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] == value) {
      v[i] = v.back();
      v.pop_back();
      return;
    }
  }
}

}  // namespace

const char* directionName(Direction d) {
  static const char* const kNames[27] = {
      "L",  "R",  "D",  "U",  "B",   "F",   "LD",  "LU",  "LB",  "LF",  "RD",  "RU",  "RB",   "RF",
      "DB", "DF", "UB", "UF", "LDB", "LDF", "LUB", "LUF", "RDB", "RDF", "RUB", "RUF", "Omega"};
  return kNames[static_cast<int>(d)];
}

NObjectsOctree::NObjectsOctree(const Aabb& root, Options options) : options_(options) {
  if (!root.valid()) throw InvalidArgument("NObjectsOctree: root box is not finite and ordered");
  if (options.max_depth < 0 || options.max_depth > kMaxDepth)
    throw InvalidArgument("NObjectsOctree: max_depth must be in [0, 21]");
  if (options.leaf_capacity == 0)
    throw InvalidArgument("NObjectsOctree: leaf_capacity (N) must be at least 1");
  const Eigen::Vector3d centre = 0.5 * (root.min + root.max);
  double side = (root.max - root.min).maxCoeff();
  if (!(side > 0)) side = 1.0;
  root_box_.min = centre - Eigen::Vector3d::Constant(0.5 * side);
  unit_ = side / std::ldexp(1.0, options_.max_depth);
  root_box_.max = root_box_.min + Eigen::Vector3d::Constant(side);
  initRoot();
}

NObjectsOctree NObjectsOctree::forBoxes(const std::vector<Aabb>& boxes, Options options) {
  Aabb all{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  if (!boxes.empty()) {
    all = boxes.front();
    for (const Aabb& b : boxes) {
      if (!b.valid())
        throw InvalidArgument("NObjectsOctree::forBoxes: a box is not finite/ordered");
      all.min = all.min.cwiseMin(b.min);
      all.max = all.max.cwiseMax(b.max);
    }
  }
  const Eigen::Vector3d centre = 0.5 * (all.min + all.max);
  const double half = 0.75 * std::max((all.max - all.min).maxCoeff(), 1e-9);
  NObjectsOctree tree(
      {centre - Eigen::Vector3d::Constant(half), centre + Eigen::Vector3d::Constant(half)},
      options);
  for (const Aabb& b : boxes) tree.add(b);
  tree.rebalance();
  return tree;
}

void NObjectsOctree::initRoot() {
  nodes_.clear();
  free_blocks_.clear();
  nodes_.emplace_back();
  nodes_[0].live = true;
  setNodeGeometry(0, Cube{options_.max_depth, {0, 0, 0}});
  live_nodes_ = 1;
}

void NObjectsOctree::setNodeGeometry(std::uint32_t n, const Cube& cube) {
  Node& node = nodes_[n];
  node.cube = cube;
  const std::uint32_t o[3] = {cube.origin.x, cube.origin.y, cube.origin.z};
  const std::uint32_t root_side = std::uint32_t{1} << options_.max_depth;
  node.at_root_max = 0;
  for (int a = 0; a < 3; ++a) {
    // Both faces from the same formula so neighbouring cubes share bit-identical boundaries.
    node.min[a] = root_box_.min[a] + static_cast<double>(o[a]) * unit_;
    node.max[a] = root_box_.min[a] + static_cast<double>(o[a] + cube.side()) * unit_;
    if (o[a] + cube.side() == root_side) node.at_root_max |= static_cast<std::uint8_t>(1u << a);
  }
}

Aabb NObjectsOctree::nodeBox(std::uint32_t n) const {
  const Node& node = nodes_[n];
  return {Eigen::Vector3d(node.min[0], node.min[1], node.min[2]),
          Eigen::Vector3d(node.max[0], node.max[1], node.max[2])};
}

std::size_t NObjectsOctree::leafCount() const {
  std::size_t count = 0;
  for (const Node& n : nodes_) count += n.live && n.first_child == kNone;
  return count;
}

std::uint32_t NObjectsOctree::allocateChildren(std::uint32_t parent) {
  std::uint32_t first;
  if (!free_blocks_.empty()) {
    first = free_blocks_.back();
    free_blocks_.pop_back();
  } else {
    first = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + 8);
  }
  const Cube cube = nodes_[parent].cube;
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t c = first + static_cast<std::uint32_t>(k);
    Node& node = nodes_[c];
    node.parent = parent;
    node.first_child = kNone;
    node.label = static_cast<std::uint8_t>(k);
    node.live = true;
    node.stamp = 0;
    node.objects.clear();  // keeps its capacity: recycled blocks do not allocate
    setNodeGeometry(c, cube.child(k));
  }
  nodes_[parent].first_child = first;
  live_nodes_ += 8;
  return first;
}

bool NObjectsOctree::nodeOverlaps(std::uint32_t n, const Aabb& b) const {
  const Node& node = nodes_[n];
  return node.min[0] <= b.max.x() && b.min.x() <= node.max[0] && node.min[1] <= b.max.y() &&
         b.min.y() <= node.max[1] && node.min[2] <= b.max.z() && b.min.z() <= node.max[2];
}

// Children of gray node n whose closed cubes touch b (bit k = child k). Assumes b touches n.
int NObjectsOctree::childMask(std::uint32_t n, const Aabb& b) const {
  const Node& low_child = nodes_[nodes_[n].first_child];
  int mask = 0xff;
  for (int a = 0; a < 3; ++a) {
    // The split plane is the max face of child 0 on this axis (computed, hence bit-identical).
    const double mid = low_child.max[a];
    const bool low = b.min[a] <= mid;
    const bool high = b.max[a] >= mid;
    // Children on the +a side have bit a set.
    static constexpr int kHighHalf[3] = {0xaa, 0xcc, 0xf0};
    if (!low) mask &= kHighHalf[a];
    if (!high) mask &= ~kHighHalf[a];
  }
  return mask;
}

void NObjectsOctree::addToLeaf(std::uint32_t leaf, std::uint32_t id) {
  Node& node = nodes_[leaf];
  node.objects.push_back(id);
  objects_[id].leaves.push_back(leaf);
  if (node.objects.size() == static_cast<std::size_t>(options_.leaf_capacity) + 1 &&
      options_.leaf_capacity != kUnlimited && node.cube.level > 0) {
    overfull_.push_back(leaf);
  }
}

void NObjectsOctree::removeFromLeaf(std::uint32_t leaf, std::uint32_t id) {
  Node& node = nodes_[leaf];
  eraseValue(node.objects, id);
  if (node.parent != kNone) merge_candidates_.push_back(node.parent);
}

// Puts object id into every leaf of n's subtree its box touches (n touches the box).
void NObjectsOctree::insertFrom(std::uint32_t n, std::uint32_t id) {
  if (nodes_[n].first_child == kNone) {
    addToLeaf(n, id);
    return;
  }
  int mask = childMask(n, objects_[id].box);
  const std::uint32_t first = nodes_[n].first_child;
  while (mask) {
    const int k = lowestBit(static_cast<unsigned>(mask));
    mask &= mask - 1;
    insertFrom(first + static_cast<std::uint32_t>(k), id);
  }
}

// Like insertFrom, but skips nodes already tested for this (object, step) and queues the leaves
// entered so their own neighbours get examined.
void NObjectsOctree::enter(std::uint32_t n, std::uint32_t id) {
  Node& node = nodes_[n];
  if (node.stamp == stamp_) return;
  node.stamp = stamp_;
  const Aabb& b = objects_[id].box;
  if (!nodeOverlaps(n, b)) return;
  if (node.first_child == kNone) {
    addToLeaf(n, id);
    worklist_.push_back(n);
    return;
  }
  int mask = childMask(n, b);
  const std::uint32_t first = node.first_child;
  while (mask) {
    const int k = lowestBit(static_cast<unsigned>(mask));
    mask &= mask - 1;
    enter(first + static_cast<std::uint32_t>(k), id);
  }
}

void NObjectsOctree::checkBox(const Aabb& box, const char* what) const {
  if (!box.valid()) {
    std::ostringstream s;
    s << "NObjectsOctree::" << what << ": box is not finite with min <= max";
    throw InvalidArgument(s.str());
  }
}

std::uint32_t NObjectsOctree::add(const Aabb& box) {
  checkBox(box, "add");
  const auto id = static_cast<std::uint32_t>(objects_.size());
  objects_.push_back({box, {}, 0});
  if (!root_box_.contains(box)) {
    needs_reroot_ = true;
    return id;
  }
  if (!needs_reroot_) insertFrom(0, id);
  return id;
}

void NObjectsOctree::move(std::uint32_t id, const Aabb& box) {
  if (id >= objects_.size()) throw InvalidArgument("NObjectsOctree::move: unknown object id");
  // Fast acceptance: inside the (finite) root with min <= max; NaN fails every comparison.
  const bool inside = root_box_.contains(box) && box.min.x() <= box.max.x() &&
                      box.min.y() <= box.max.y() && box.min.z() <= box.max.z();
  if (!inside) checkBox(box, "move");
  const Aabb old = objects_[id].box;
  objects_[id].box = box;
  if (needs_reroot_) return;  // everything is re-inserted anyway
  if (!inside) {
    needs_reroot_ = true;
    return;
  }
  // Drop the leaves the box left; stamp the ones it still touches.
  ++stamp_;
  std::vector<std::uint32_t>& leaves = objects_[id].leaves;
  for (std::size_t i = 0; i < leaves.size();) {
    const std::uint32_t leaf = leaves[i];
    if (nodeOverlaps(leaf, box)) {
      nodes_[leaf].stamp = stamp_;
      ++i;
    } else {
      removeFromLeaf(leaf, id);
      leaves[i] = leaves.back();
      leaves.pop_back();
    }
  }
  if (leaves.empty()) {
    // A jump off every old leaf: no neighbour path is guaranteed, so descend from the root (the
    // report assumes small steps, §1.1).
    insertFrom(0, id);
    return;
  }
  // The sides (bit 2a: -a, bit 2a+1: +a) toward which the box grew: the direction of motion.
  // A leaf the box newly touches holds a point p of B \ A; the segment from p's closest point in
  // A (which lies in A and B when they overlap) to p runs only along those sides, crossing
  // leaves through faces/edges/vertices in those directions, so exploring neighbours in those
  // directions only reaches every new leaf. Disjoint boxes need every direction.
  int motion = 0x3f;
  if (overlaps(old, box)) {
    motion = 0;
    for (int a = 0; a < 3; ++a) {
      if (box.min[a] < old.min[a]) motion |= 1 << (2 * a);
      if (box.max[a] > old.max[a]) motion |= 1 << (2 * a + 1);
    }
    if (motion == 0) return;  // the box shrank or stayed: no new leaves
  }
  // Flood from the kept leaves into >=-size neighbours on the sides the box reaches beyond each
  // leaf, restricted to the direction of motion.
  worklist_.assign(leaves.begin(), leaves.end());
  while (!worklist_.empty()) {
    const std::uint32_t leaf = worklist_.back();
    worklist_.pop_back();
    const Node& node = nodes_[leaf];
    int reach = 0;
    for (int a = 0; a < 3; ++a) {
      if (box.min[a] <= node.min[a]) reach |= 1 << (2 * a);
      if (box.max[a] >= node.max[a]) reach |= 1 << (2 * a + 1);
    }
    std::uint32_t directions = kReach.directions[reach & motion];
    while (directions) {
      const int d = lowestBit(directions);
      directions &= directions - 1;
      ++counters_.neighbour_queries;
      const std::uint32_t q = gtEqNeighbour(leaf, static_cast<Direction>(d));
      if (q != kNone) enter(q, id);
    }
  }
}

std::uint32_t NObjectsOctree::gtEqNeighbour(std::uint32_t n, Direction d) const {
  // Samet's GTEQ_{FACE,EDGE,VERTEX}_NEIGHBOR in one: climb while the step leaves the parent,
  // switching to the parent's common edge/face when only part of the step leaves it, then
  // descend once by reflection.
  const Node& node = nodes_[n];
  if (node.parent == kNone || d == Direction::kOmega) return kNone;
  const int o = node.label;
  std::uint32_t q;
  if (adj(d, o)) {
    q = gtEqNeighbour(node.parent, d);
  } else if (commonEdge(d, o) != Direction::kOmega) {
    q = gtEqNeighbour(node.parent, commonEdge(d, o));
  } else if (commonFace(d, o) != Direction::kOmega) {
    q = gtEqNeighbour(node.parent, commonFace(d, o));
  } else {
    q = node.parent;
  }
  if (q != kNone && nodes_[q].first_child != kNone) {
    return nodes_[q].first_child + static_cast<std::uint32_t>(reflect(d, o));
  }
  return q;
}

std::uint32_t NObjectsOctree::gtEqFaceNeighbour(std::uint32_t n, Direction face) const {
  if (kindOf(face) != DirectionKind::kFace)
    throw InvalidArgument("gtEqFaceNeighbour: direction is not a face");
  return gtEqNeighbour(n, face);
}
std::uint32_t NObjectsOctree::gtEqEdgeNeighbour(std::uint32_t n, Direction edge) const {
  if (kindOf(edge) != DirectionKind::kEdge)
    throw InvalidArgument("gtEqEdgeNeighbour: direction is not an edge");
  return gtEqNeighbour(n, edge);
}
std::uint32_t NObjectsOctree::gtEqVertexNeighbour(std::uint32_t n, Direction vertex) const {
  if (kindOf(vertex) != DirectionKind::kVertex)
    throw InvalidArgument("gtEqVertexNeighbour: direction is not a vertex");
  return gtEqNeighbour(n, vertex);
}

void NObjectsOctree::split(std::uint32_t leaf) {
  ++counters_.splits;
  const std::uint32_t first = allocateChildren(leaf);
  std::vector<std::uint32_t> moving;
  moving.swap(nodes_[leaf].objects);
  for (std::uint32_t id : moving) {
    eraseValue(objects_[id].leaves, leaf);
    int mask = childMask(leaf, objects_[id].box);
    while (mask) {
      const int k = lowestBit(static_cast<unsigned>(mask));
      mask &= mask - 1;
      addToLeaf(first + static_cast<std::uint32_t>(k), id);  // queues overfull children
    }
  }
  moving.clear();
  nodes_[leaf].objects.swap(moving);  // give the capacity back to the (now gray) node
}

bool NObjectsOctree::tryMerge(std::uint32_t n) {
  Node& node = nodes_[n];
  if (!node.live || node.first_child == kNone) return false;
  const std::uint32_t first = node.first_child;
  std::size_t total = 0;
  for (std::uint32_t c = first; c < first + 8; ++c) {
    if (nodes_[c].first_child != kNone) return false;
    total += nodes_[c].objects.size();
  }
  // Count distinct objects (one may live in several siblings).
  ++mark_;
  std::size_t distinct = 0;
  if (total > options_.leaf_capacity) {
    for (std::uint32_t c = first; c < first + 8; ++c) {
      for (std::uint32_t id : nodes_[c].objects) {
        if (objects_[id].mark != mark_) {
          objects_[id].mark = mark_;
          if (++distinct > options_.leaf_capacity) return false;
        }
      }
    }
    ++mark_;
  }
  ++counters_.merges;
  std::vector<std::uint32_t>& merged = nodes_[n].objects;
  merged.clear();
  for (std::uint32_t c = first; c < first + 8; ++c) {
    for (std::uint32_t id : nodes_[c].objects) {
      eraseValue(objects_[id].leaves, c);
      if (objects_[id].mark != mark_) {
        objects_[id].mark = mark_;
        merged.push_back(id);
        objects_[id].leaves.push_back(n);
      }
    }
    nodes_[c].objects.clear();
    nodes_[c].live = false;
    nodes_[c].first_child = kNone;
  }
  nodes_[n].first_child = kNone;
  free_blocks_.push_back(first);
  live_nodes_ -= 8;
  return true;
}

void NObjectsOctree::reroot() {
  ++counters_.reroots;
  Aabb all = objects_.front().box;
  for (const Object& o : objects_) {
    all.min = all.min.cwiseMin(o.box.min);
    all.max = all.max.cwiseMax(o.box.max);
  }
  // Keep the old root inside the new one so the tree does not shrink on every excursion.
  all.min = all.min.cwiseMin(root_box_.min);
  all.max = all.max.cwiseMax(root_box_.max);
  const Eigen::Vector3d centre = 0.5 * (all.min + all.max);
  const double side = 1.5 * (all.max - all.min).maxCoeff();
  if (!std::isfinite(side) || !centre.allFinite())
    throw InvalidArgument("NObjectsOctree: the boxes span a region too large to represent");
  root_box_.min = centre - Eigen::Vector3d::Constant(0.5 * side);
  unit_ = side / std::ldexp(1.0, options_.max_depth);
  root_box_.max = root_box_.min + Eigen::Vector3d::Constant(side);
  initRoot();
  overfull_.clear();
  merge_candidates_.clear();
  needs_reroot_ = false;
  for (std::uint32_t id = 0; id < objects_.size(); ++id) {
    objects_[id].leaves.clear();
    insertFrom(0, id);
  }
}

void NObjectsOctree::rebalance() {
  if (needs_reroot_) reroot();
  // Merges first (they never overfill a leaf), cascading upwards.
  for (std::size_t i = 0; i < merge_candidates_.size(); ++i) {
    std::uint32_t n = merge_candidates_[i];
    while (n != kNone && tryMerge(n)) n = nodes_[n].parent;
  }
  merge_candidates_.clear();
  // Splits: split() may queue more overfull children; the loop picks them up.
  for (std::size_t i = 0; i < overfull_.size(); ++i) {
    const std::uint32_t n = overfull_[i];
    if (nodes_[n].live && nodes_[n].first_child == kNone &&
        nodes_[n].objects.size() > options_.leaf_capacity && nodes_[n].cube.level > 0) {
      split(n);
    }
  }
  overfull_.clear();
}

bool NObjectsOctree::checkInvariants(std::string* why) const {
  auto fail = [&](const std::string& s) {
    if (why) *why = s;
    return false;
  };
  if (needs_reroot_ || !overfull_.empty() || !merge_candidates_.empty())
    return fail("rebalance() pending");
  // Structure: parents, labels, geometry; count live nodes.
  std::size_t live = 0;
  std::vector<std::uint64_t> seen(objects_.size(), 0);
  std::uint64_t tag = 0;
  for (std::uint32_t n = 0; n < nodes_.size(); ++n) {
    const Node& node = nodes_[n];
    if (!node.live) continue;
    ++live;
    if (n != 0) {
      if (node.parent == kNone || !nodes_[node.parent].live ||
          nodes_[node.parent].first_child + node.label != n)
        return fail("node " + std::to_string(n) + " is not its parent's child");
      if (!(nodes_[node.parent].cube.child(node.label) == node.cube))
        return fail("node " + std::to_string(n) + " has the wrong cube");
    }
    if (node.first_child == kNone) {
      if (node.objects.size() > options_.leaf_capacity && node.cube.level > 0)
        return fail("leaf " + std::to_string(n) + " holds more than N objects");
      ++tag;
      for (std::uint32_t id : node.objects) {
        if (id >= objects_.size()) return fail("leaf holds an unknown object");
        if (seen[id] == tag) return fail("leaf " + std::to_string(n) + " holds an object twice");
        seen[id] = tag;
        if (!nodeOverlaps(n, objects_[id].box))
          return fail("object " + std::to_string(id) + " in leaf it does not touch");
        const auto& l = objects_[id].leaves;
        if (std::find(l.begin(), l.end(), n) == l.end())
          return fail("object " + std::to_string(id) + " does not list its leaf");
      }
    } else {
      if (!node.objects.empty()) return fail("gray node holds objects");
      // A gray node holds more than N distinct objects, or siblings should have merged.
      ++tag;
      std::size_t distinct = 0;
      std::vector<std::uint32_t> stack{n};
      while (!stack.empty()) {
        const std::uint32_t m = stack.back();
        stack.pop_back();
        if (nodes_[m].first_child != kNone) {
          for (int k = 0; k < 8; ++k)
            stack.push_back(nodes_[m].first_child + static_cast<std::uint32_t>(k));
        } else {
          for (std::uint32_t id : nodes_[m].objects) {
            if (seen[id] != tag) {
              seen[id] = tag;
              ++distinct;
            }
          }
        }
      }
      if (distinct <= options_.leaf_capacity)
        return fail("gray node " + std::to_string(n) + " holds only " + std::to_string(distinct) +
                    " objects: its children should have merged");
    }
  }
  if (live != live_nodes_) return fail("live node count is off");
  // Membership: each object is in exactly the leaves its box touches.
  for (std::uint32_t id = 0; id < objects_.size(); ++id) {
    const Aabb& b = objects_[id].box;
    if (!root_box_.contains(b)) return fail("object " + std::to_string(id) + " outside the root");
    std::vector<std::uint32_t> expected;
    for (std::uint32_t n = 0; n < nodes_.size(); ++n) {
      if (nodes_[n].live && nodes_[n].first_child == kNone && nodeOverlaps(n, b))
        expected.push_back(n);
    }
    std::vector<std::uint32_t> actual = objects_[id].leaves;
    std::sort(actual.begin(), actual.end());
    if (actual != expected)
      return fail("object " + std::to_string(id) + " is not in exactly the leaves it touches");
  }
  return true;
}

}  // namespace octomotion::broadphase
