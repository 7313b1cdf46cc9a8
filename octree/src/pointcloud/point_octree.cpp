// Point-region octree: bucket pool, insert/split, remove/collapse, bulk build by per-level
// counting sort, and the pruned best-first k-NN / radius searches.
#include "octomotion/pointcloud/point_octree.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "octomotion/error.h"

namespace octomotion::pointcloud {

namespace {

constexpr int kMaxSupportedDepth = 30;
constexpr std::uint32_t kMaxBucket = 4096;
// Distances are computed in float like the stored points; cell bounds in double. Pruning keeps a
// relative slack so float rounding can never prune a point that belongs in the answer.
constexpr double kPruneSlack = 1.0 - 1e-5;

double minDistance2(const Eigen::Vector3f& q, double cx, double cy, double cz, double half) {
  const double dx = std::max(0.0, std::abs(static_cast<double>(q.x()) - cx) - half);
  const double dy = std::max(0.0, std::abs(static_cast<double>(q.y()) - cy) - half);
  const double dz = std::max(0.0, std::abs(static_cast<double>(q.z()) - cz) - half);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

PointOctree::PointOctree(const Eigen::Vector3d& min, double side, Options options)
    : options_(options), min_(min), side_(side) {
  if (!min.allFinite() || !std::isfinite(side) || !(side > 0))
    throw InvalidArgument("PointOctree: root cube needs a finite corner and a side > 0");
  if (options.bucket_size < 1 || options.bucket_size > kMaxBucket)
    throw InvalidArgument("PointOctree: bucket_size must be in [1, 4096]");
  if (options.max_depth < 0 || options.max_depth > kMaxSupportedDepth)
    throw InvalidArgument("PointOctree: max_depth must be in [0, 30]");
  nodes_.emplace_back();
  live_nodes_ = 1;
}

PointOctree::Cell PointOctree::rootCell() const {
  const double h = 0.5 * side_;
  return {min_.x() + h, min_.y() + h, min_.z() + h, h};
}

void PointOctree::checkPoint(const Eigen::Vector3f& p, const char* what) const {
  if (!p.allFinite())
    throw InvalidArgument(std::string("PointOctree::") + what + ": non-finite point");
  const Eigen::Vector3d d = p.cast<double>() - min_;
  if ((d.array() < 0).any() || (d.array() > side_).any())
    throw InvalidArgument(std::string("PointOctree::") + what + ": point outside the root cube");
}

std::uint32_t PointOctree::allocateChildren(std::uint32_t parent) {
  std::uint32_t first;
  if (!free_node_blocks_.empty()) {
    first = free_node_blocks_.back();
    free_node_blocks_.pop_back();
    for (std::uint32_t c = first; c < first + 8; ++c) nodes_[c] = Node{};
  } else {
    first = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + 8);
  }
  nodes_[parent].first_child = first;
  live_nodes_ += 8;
  return first;
}

std::uint32_t PointOctree::allocateBucket() {
  if (!free_buckets_.empty()) {
    const std::uint32_t b = free_buckets_.back();
    free_buckets_.pop_back();
    bucket_count_[b] = 0;
    bucket_next_[b] = kNone;
    return b;
  }
  const auto b = static_cast<std::uint32_t>(bucket_count_.size());
  bucket_count_.push_back(0);
  bucket_next_.push_back(kNone);
  entries_.resize(entries_.size() + kChunk);
  return b;
}

void PointOctree::freeChain(std::uint32_t bucket) {
  while (bucket != kNone) {
    const std::uint32_t next = bucket_next_[bucket];
    free_buckets_.push_back(bucket);
    bucket = next;
  }
}

// Appends to the leaf's first bucket, prepending a fresh bucket when it is full (the chain is
// longer than one bucket only at max_depth).
void PointOctree::appendToLeaf(std::uint32_t leaf, const Entry& e) {
  std::uint32_t b = nodes_[leaf].bucket;
  if (b == kNone || bucket_count_[b] == kChunk) {
    const std::uint32_t fresh = allocateBucket();
    bucket_next_[fresh] = b;
    nodes_[leaf].bucket = fresh;
    b = fresh;
  }
  entries_[static_cast<std::size_t>(b) * kChunk + bucket_count_[b]++] = e;
}

void PointOctree::splitLeaf(std::uint32_t leaf, const Cell& cell, int depth) {
  // Gather the leaf's points (at most bucket_size + 1 here), free its buckets, re-insert below.
  std::vector<Entry>& moving = scratch_;
  moving.clear();
  forEachEntryBelow(leaf, [&](const Entry& e) { moving.push_back(e); });
  freeChain(nodes_[leaf].bucket);
  nodes_[leaf].bucket = kNone;
  const std::uint32_t first = allocateChildren(leaf);
  for (const Entry& e : moving) {
    const std::uint32_t c = first + static_cast<std::uint32_t>(cell.octant(e));
    ++nodes_[c].count;
    appendToLeaf(c, e);
  }
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t c = first + static_cast<std::uint32_t>(k);
    if (nodes_[c].count > options_.bucket_size && depth + 1 < options_.max_depth)
      splitLeaf(c, cell.child(k), depth + 1);
  }
}

std::uint32_t PointOctree::insert(const Eigen::Vector3f& p) {
  checkPoint(p, "insert");
  const Entry e{p.x(), p.y(), p.z(), next_id_++};
  std::uint32_t n = 0;
  Cell cell = rootCell();
  int depth = 0;
  for (;;) {
    ++nodes_[n].count;
    if (nodes_[n].first_child == kNone) break;
    const int k = cell.octant(e);
    n = nodes_[n].first_child + static_cast<std::uint32_t>(k);
    cell = cell.child(k);
    ++depth;
  }
  appendToLeaf(n, e);
  if (nodes_[n].count > options_.bucket_size && depth < options_.max_depth)
    splitLeaf(n, cell, depth);
  return e.id;
}

bool PointOctree::contains(const Eigen::Vector3f& p) const {
  if (!p.allFinite()) return false;
  const Entry e{p.x(), p.y(), p.z(), 0};
  Cell cell = rootCell();
  const Eigen::Vector3d d = p.cast<double>() - min_;
  if ((d.array() < 0).any() || (d.array() > side_).any()) return false;
  std::uint32_t n = 0;
  while (nodes_[n].first_child != kNone) {
    const int k = cell.octant(e);
    n = nodes_[n].first_child + static_cast<std::uint32_t>(k);
    cell = cell.child(k);
  }
  for (std::uint32_t b = nodes_[n].bucket; b != kNone; b = bucket_next_[b]) {
    const Entry* es = &entries_[static_cast<std::size_t>(b) * kChunk];
    for (std::uint32_t i = 0; i < bucket_count_[b]; ++i)
      if (es[i].x == e.x && es[i].y == e.y && es[i].z == e.z) return true;
  }
  return false;
}

bool PointOctree::remove(const Eigen::Vector3f& p) {
  if (!p.allFinite()) return false;
  const Eigen::Vector3d d = p.cast<double>() - min_;
  if ((d.array() < 0).any() || (d.array() > side_).any()) return false;
  const Entry e{p.x(), p.y(), p.z(), 0};
  std::uint32_t path[kMaxSupportedDepth + 1];
  int depth = 0;
  Cell cell = rootCell();
  std::uint32_t n = 0;
  path[0] = 0;
  while (nodes_[n].first_child != kNone) {
    const int k = cell.octant(e);
    n = nodes_[n].first_child + static_cast<std::uint32_t>(k);
    cell = cell.child(k);
    path[++depth] = n;
  }
  // Find the point, then fill its slot with the last entry of the leaf's first bucket.
  const std::uint32_t head = nodes_[n].bucket;
  bool found = false;
  for (std::uint32_t b = head; b != kNone && !found; b = bucket_next_[b]) {
    Entry* es = &entries_[static_cast<std::size_t>(b) * kChunk];
    for (std::uint32_t i = 0; i < bucket_count_[b]; ++i) {
      if (es[i].x == e.x && es[i].y == e.y && es[i].z == e.z) {
        Entry* head_entries = &entries_[static_cast<std::size_t>(head) * kChunk];
        es[i] = head_entries[--bucket_count_[head]];
        found = true;
        break;
      }
    }
  }
  if (!found) return false;
  if (bucket_count_[head] == 0) {
    nodes_[n].bucket = bucket_next_[head];
    free_buckets_.push_back(head);
  }
  for (int i = 0; i <= depth; ++i) --nodes_[path[i]].count;
  // Collapse the highest ancestor that no longer needs its children.
  for (int i = 0; i < depth; ++i) {
    if (nodes_[path[i]].count <= options_.bucket_size) {
      collapse(path[i]);
      break;
    }
  }
  return true;
}

// Turns an internal node into a leaf holding all its subtree's points.
void PointOctree::collapse(std::uint32_t node) {
  std::vector<Entry>& moving = scratch_;
  moving.clear();
  forEachEntryBelow(node, [&](const Entry& e) { moving.push_back(e); });
  // Free the subtree (post-order over node blocks).
  std::uint32_t stack[8 * (kMaxSupportedDepth + 1)];
  int top = 0;
  stack[top++] = node;
  while (top > 0) {
    const std::uint32_t m = stack[--top];
    const std::uint32_t first = nodes_[m].first_child;
    if (first == kNone) {
      freeChain(nodes_[m].bucket);
      nodes_[m].bucket = kNone;
      continue;
    }
    for (std::uint32_t c = first; c < first + 8; ++c) stack[top++] = c;
    nodes_[m].first_child = kNone;
    free_node_blocks_.push_back(first);
    live_nodes_ -= 8;
  }
  for (const Entry& e : moving) appendToLeaf(node, e);
}

PointOctree PointOctree::build(const std::vector<Eigen::Vector3f>& points, Options options) {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Ones();
  if (!points.empty()) {
    lo = hi = points.front().cast<double>();
    for (const Eigen::Vector3f& p : points) {
      if (!p.allFinite()) throw InvalidArgument("PointOctree::build: non-finite point");
      lo = lo.cwiseMin(p.cast<double>());
      hi = hi.cwiseMax(p.cast<double>());
    }
  }
  if (points.size() >= kNone) throw InvalidArgument("PointOctree::build: too many points");
  const double extent = std::max((hi - lo).maxCoeff(), 1e-6);
  const double side = extent * (1.0 + 1e-4);
  const Eigen::Vector3d min = 0.5 * (lo + hi) - Eigen::Vector3d::Constant(0.5 * side);
  PointOctree tree(min, side, options);
  const std::size_t n = points.size();
  std::vector<Entry> entries(n), scratch(n);
  for (std::size_t i = 0; i < n; ++i)
    entries[i] = {points[i].x(), points[i].y(), points[i].z(), static_cast<std::uint32_t>(i)};
  tree.next_id_ = static_cast<std::uint32_t>(n);
  // Reserve roughly what the chunks will need so the pool grows a few times, not per leaf.
  tree.entries_.reserve(n + n / 2 + kChunk);
  tree.buildFrom(0, tree.rootCell(), 0, entries.data(), entries.data() + n, scratch.data());
  tree.entries_.shrink_to_fit();
  tree.nodes_.shrink_to_fit();
  return tree;
}

void PointOctree::buildFrom(std::uint32_t node, const Cell& cell, int depth, Entry* begin,
                            Entry* end, Entry* scratch) {
  const auto count = static_cast<std::uint32_t>(end - begin);
  nodes_[node].count = count;
  if (count <= options_.bucket_size || depth >= options_.max_depth) {
    for (Entry* e = begin; e != end; ++e) appendToLeaf(node, *e);
    return;
  }
  // Counting sort by octant through the scratch buffer.
  std::uint32_t counts[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (Entry* e = begin; e != end; ++e) ++counts[cell.octant(*e)];
  std::uint32_t offsets[9];
  offsets[0] = 0;
  for (int k = 0; k < 8; ++k) offsets[k + 1] = offsets[k] + counts[k];
  std::uint32_t fill[8];
  std::copy(offsets, offsets + 8, fill);
  for (Entry* e = begin; e != end; ++e) scratch[fill[cell.octant(*e)]++] = *e;
  std::memcpy(static_cast<void*>(begin), scratch, sizeof(Entry) * count);
  const std::uint32_t first = allocateChildren(node);
  for (int k = 0; k < 8; ++k) {
    buildFrom(first + static_cast<std::uint32_t>(k), cell.child(k), depth + 1, begin + offsets[k],
              begin + offsets[k + 1], scratch);
  }
}

// The one branch-and-bound descent of the three searches. `search` supplies
//   float bound(): squared distance beyond which a cell is pruned (it may shrink as points come);
//   void visit(std::uint32_t id, float distance2): a stored point and its squared distance;
// kNearestFirst: children are visited nearest first (the bound shrinks sooner), else in label
// order.
// An explicit stack: at most 8 frames per level.
template <bool kNearestFirst, class Search>
void PointOctree::descend(const Eigen::Vector3f& q, Search& search) const {
  const float qx = q.x(), qy = q.y(), qz = q.z();
  struct Frame {
    std::uint32_t node;
    Cell cell;
  };
  Frame stack[8 * (kMaxSupportedDepth + 1)];
  int top = 0;
  stack[top++] = {0, rootCell()};
  while (top > 0) {
    const Frame f = stack[--top];
    if (minDistance2(q, f.cell.cx, f.cell.cy, f.cell.cz, f.cell.half) * kPruneSlack >
        search.bound())
      continue;
    const Node& n = nodes_[f.node];
    if (n.first_child == kNone) {
      for (std::uint32_t b = n.bucket; b != kNone; b = bucket_next_[b]) {
        const Entry* es = &entries_[static_cast<std::size_t>(b) * kChunk];
        for (std::uint32_t i = 0; i < bucket_count_[b]; ++i) {
          const float dx = es[i].x - qx, dy = es[i].y - qy, dz = es[i].z - qz;
          search.visit(es[i].id, dx * dx + dy * dy + dz * dz);
        }
      }
      continue;
    }
    if constexpr (kNearestFirst) {
      // Pushed farthest first, so the nearest is popped first.
      double dist[8];
      int order[8];
      int m = 0;
      for (int c = 0; c < 8; ++c) {
        if (nodes_[n.first_child + static_cast<std::uint32_t>(c)].count == 0) continue;
        const Cell child = f.cell.child(c);
        const double d = minDistance2(q, child.cx, child.cy, child.cz, child.half);
        if (d * kPruneSlack > search.bound()) continue;
        int j = m++;
        while (j > 0 && dist[j - 1] < d) {
          dist[j] = dist[j - 1];
          order[j] = order[j - 1];
          --j;
        }
        dist[j] = d;
        order[j] = c;
      }
      for (int j = 0; j < m; ++j) {
        stack[top++] = {n.first_child + static_cast<std::uint32_t>(order[j]),
                        f.cell.child(order[j])};
      }
    } else {
      for (int c = 0; c < 8; ++c) {
        if (nodes_[n.first_child + static_cast<std::uint32_t>(c)].count == 0) continue;
        stack[top++] = {n.first_child + static_cast<std::uint32_t>(c), f.cell.child(c)};
      }
    }
  }
}

void PointOctree::kNearest(const Eigen::Vector3f& q, std::size_t k,
                           std::vector<Neighbour>* out) const {
  out->clear();
  if (k == 0 || empty() || !q.allFinite()) return;
  // `out` is kept sorted by distance and at most k long; once full, its last entry bounds.
  struct Search {
    std::vector<Neighbour>& out;
    std::size_t k;
    float worst = std::numeric_limits<float>::infinity();
    float bound() const { return out.size() == k ? worst : std::numeric_limits<float>::infinity(); }
    void visit(std::uint32_t id, float d2) {
      if (out.size() == k && !(d2 < worst)) return;
      if (out.size() < k) out.push_back({});
      std::size_t j = out.size() - 1;
      while (j > 0 && out[j - 1].distance2 > d2) {
        out[j] = out[j - 1];
        --j;
      }
      out[j] = {id, d2};
      if (out.size() == k) worst = out.back().distance2;
    }
  } search{*out, k};
  descend<true>(q, search);
}

void PointOctree::radiusSearch(const Eigen::Vector3f& q, float radius,
                               std::vector<Neighbour>* out) const {
  out->clear();
  if (empty() || !q.allFinite() || !(radius >= 0)) return;
  struct Search {
    std::vector<Neighbour>& out;
    float r2;
    float bound() const { return r2; }
    void visit(std::uint32_t id, float d2) {
      if (d2 <= r2) out.push_back({id, d2});
    }
  } search{*out, radius * radius};
  descend<false>(q, search);
}

double PointOctree::nearestDistance(const Eigen::Vector3f& q) const {
  return nearestDistance(q, std::numeric_limits<double>::infinity());
}

double PointOctree::nearestDistance(const Eigen::Vector3f& q, double upper_bound) const {
  if (empty() || !q.allFinite()) return std::numeric_limits<double>::infinity();
  // k = 1 without an output vector. Starting from the caller's bound prunes every cell farther
  // than it (the bound is rounded up to float so no point nearer than it is pruned).
  struct Search {
    float best = std::numeric_limits<float>::infinity();
    float bound() const { return best; }
    void visit(std::uint32_t, float d2) { best = std::min(best, d2); }
  } search;
  if (upper_bound < std::numeric_limits<double>::infinity()) {
    const double b2 = std::max(0.0, upper_bound) * std::max(0.0, upper_bound);
    search.best =
        b2 < static_cast<double>(std::numeric_limits<float>::max())
            ? std::nextafter(static_cast<float>(b2), std::numeric_limits<float>::infinity())
            : std::numeric_limits<float>::infinity();
  }
  descend<true>(q, search);
  return std::sqrt(static_cast<double>(search.best));
}

std::size_t PointOctree::leafCount() const {
  std::size_t count = 0;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    if (nodes_[n].first_child == kNone) {
      ++count;
    } else {
      for (std::uint32_t c = nodes_[n].first_child; c < nodes_[n].first_child + 8; ++c)
        stack.push_back(c);
    }
  }
  return count;
}

int PointOctree::height() const {
  int best = 0;
  std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [n, d] = stack.back();
    stack.pop_back();
    best = std::max(best, d);
    if (nodes_[n].first_child != kNone)
      for (std::uint32_t c = nodes_[n].first_child; c < nodes_[n].first_child + 8; ++c)
        stack.push_back({c, d + 1});
  }
  return best;
}

std::size_t PointOctree::bytes() const {
  return sizeof(*this) + nodes_.capacity() * sizeof(Node) + entries_.capacity() * sizeof(Entry) +
         (bucket_count_.capacity() + bucket_next_.capacity() + free_buckets_.capacity() +
          free_node_blocks_.capacity()) *
             sizeof(std::uint32_t);
}

bool PointOctree::checkInvariants(std::string* why) const {
  auto fail = [&](const std::string& s) {
    if (why) *why = s;
    return false;
  };
  struct Frame {
    std::uint32_t node;
    Cell cell;
    int depth;
  };
  std::vector<Frame> stack{{0, rootCell(), 0}};
  std::size_t live = 0;
  while (!stack.empty()) {
    const Frame f = stack.back();
    stack.pop_back();
    ++live;
    const Node& n = nodes_[f.node];
    if (n.first_child != kNone) {
      if (n.bucket != kNone) return fail("internal node holds a bucket");
      if (n.count <= options_.bucket_size)
        return fail("node " + std::to_string(f.node) + " should have collapsed");
      std::uint32_t sum = 0;
      for (int k = 0; k < 8; ++k) {
        const std::uint32_t c = n.first_child + static_cast<std::uint32_t>(k);
        sum += nodes_[c].count;
        stack.push_back({c, f.cell.child(k), f.depth + 1});
      }
      if (sum != n.count) return fail("node count differs from its children's");
      continue;
    }
    if (n.count > options_.bucket_size && f.depth < options_.max_depth)
      return fail("leaf " + std::to_string(f.node) + " exceeds the bucket size above max depth");
    std::uint32_t total = 0;
    for (std::uint32_t b = n.bucket; b != kNone; b = bucket_next_[b]) {
      if (bucket_count_[b] == 0 || bucket_count_[b] > kChunk)
        return fail("bucket with a bad count");
      total += bucket_count_[b];
    }
    if (total != n.count) return fail("leaf count differs from its buckets'");
    bool inside = true;
    forEachEntryBelow(f.node, [&](const Entry& e) {
      const double d[3] = {e.x - f.cell.cx, e.y - f.cell.cy, e.z - f.cell.cz};
      for (double v : d) inside = inside && v >= -f.cell.half && v <= f.cell.half;
    });
    if (!inside) return fail("a point lies outside its leaf's cell");
  }
  if (live != live_nodes_) return fail("live node count is off");
  return true;
}

}  // namespace octomotion::pointcloud
