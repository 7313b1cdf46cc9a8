#include "octomotion/motion/translate.h"

#include <algorithm>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"
#include "octomotion/octree/octree_builder.h"

namespace octomotion {

void LabelPath::push(int label) {
  if (label < 0 || label > 7) {
    throw InvalidArgument("LabelPath::push: label " + std::to_string(label) + " is not in 0..7");
  }
  if (length >= kMaxDepth) {
    throw InvalidArgument(
        "LabelPath::push: path already has kMaxDepth = " + std::to_string(kMaxDepth) + " labels");
  }
  labels[static_cast<std::size_t>(length++)] = static_cast<std::uint8_t>(label);
}

LabelPath LabelPath::parse(const std::string& text) {
  if (text.empty() || text[0] != 'r' || text.size() > 1 + static_cast<std::size_t>(kMaxDepth)) {
    throw InvalidArgument("LabelPath::parse: \"" + text + "\" is not 'r' followed by at most " +
                          std::to_string(kMaxDepth) + " labels 0..7");
  }
  LabelPath path;
  for (std::size_t i = 1; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '7') {
      throw InvalidArgument("LabelPath::parse: \"" + text + "\" has '" + text[i] +
                            "' where a label 0..7 belongs");
    }
    path.push(text[i] - '0');
  }
  return path;
}

std::string LabelPath::toString() const {
  std::string s = "r";
  for (int i = 0; i < length; ++i) s += static_cast<char>('0' + (*this)[i]);
  return s;
}

LabelPath LabelPath::of(const Cube& cube, int depth) {
  if (depth < 1 || depth > kMaxDepth || cube.level < 0 || cube.level > depth) {
    throw InvalidArgument("LabelPath::of: a cube of level " + std::to_string(cube.level) +
                          " is not in a universe of depth " + std::to_string(depth));
  }
  LabelPath path;
  for (int bit = depth - 1; bit >= cube.level; --bit) {
    path.push(static_cast<int>(((cube.origin.x >> bit) & 1u) |
                               (((cube.origin.y >> bit) & 1u) << 1) |
                               (((cube.origin.z >> bit) & 1u) << 2)));
  }
  return path;
}

Cube LabelPath::cube(int depth) const {
  if (length > depth) {
    throw InvalidArgument("LabelPath::cube: a path of " + std::to_string(length) +
                          " labels is deeper than the universe depth " + std::to_string(depth));
  }
  Cube c{depth, {0, 0, 0}};
  for (int i = 0; i < length; ++i) c = c.child((*this)[i]);
  return c;
}

bool operator==(const LabelPath& a, const LabelPath& b) {
  if (a.length != b.length) return false;
  for (int i = 0; i < a.length; ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
}

std::int64_t addToPathWithCarry(LabelPath& path, int axis, std::int64_t displacement, int level) {
  if (axis < 0 || axis > 2) {
    throw InvalidArgument("addToPath: axis must be 0, 1 or 2, got " + std::to_string(axis));
  }
  if (level < 0 || level > kMaxDepth || path.length < 0 || path.length > kMaxDepth) {
    throw InvalidArgument("addToPath: level " + std::to_string(level) + " with a path of " +
                          std::to_string(path.length) + " labels is not a node of a universe");
  }
  // Two's complement digits, as the paper writes a negative displacement (§3.1).
  const std::uint64_t digits = static_cast<std::uint64_t>(displacement);
  if (digits & ((std::uint64_t{1} << level) - 1u)) {
    throw InvalidArgument("addToPath: displacement " + std::to_string(displacement) +
                          " is not a multiple of the node side 2^" + std::to_string(level));
  }
  const std::size_t a = static_cast<std::size_t>(axis);
  int carry = 0;
  int bit = level;
  for (int i = path.length - 1; i >= 0; --i, ++bit) {
    int label = path.labels[static_cast<std::size_t>(i)];
    // The digit and the incoming carry are each one unit step of this label (Table 2); two
    // steps return the label to itself with exactly one carry, as in binary 1 + 1 = 10.
    int steps = static_cast<int>((digits >> bit) & 1u) + carry;
    carry = 0;
    for (; steps > 0; --steps) {
      const int t = kLabelTransition[a][static_cast<std::size_t>(label)];
      label = t & 7;
      carry += t >> 3;
    }
    path.labels[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(label);
  }
  // The digits above the root: floor(displacement / 2^bit), i.e. the sign extension for a small
  // negative displacement (-1 cancels the carry the paper throws away).
  const std::int64_t above = displacement >= 0 ? (displacement >> bit) : ~((~displacement) >> bit);
  return above + carry;
}

namespace {

// Per axis, the labels on the - side of it (Fig. 1): west, south, lower.
constexpr std::array<std::uint8_t, 3> kLowHalf{0x55, 0x33, 0x0f};

// One axial component of a translation (§3.2), from a compact source into a fresh builder.
// Nodes of level H are moved whole; gray nodes above H are only traversed, so the cost follows
// the nodes at levels >= H, the paths (O(n - H) each) and the copied subtrees below H.
class AxisMover {
 public:
  AxisMover(const Octree& source, int axis, std::int64_t d)
      : source_(source),
        out_(source.grid()),
        axis_(axis),
        d_(d),
        level_h_(lowestBit64(static_cast<std::uint64_t>(d))) {}

  Octree run(bool* clipped) {
    LabelPath path;
    if (source_.rootColor() == Color::kBlack) {
      moveBlackLeaf(path, source_.grid().depth());
    } else {
      traverse(0, path, source_.grid().depth());
    }
    paintPendingSlabs();
    *clipped = *clipped || clipped_;
    return out_.build();
  }

 private:
  // Children met in the direction of motion first (right to left for a positive displacement):
  // the order §3.2 needs when moving in place. Here the destination is a separate tree, so
  // the order is not needed for correctness, but it is kept to follow the paper.
  void traverse(std::uint32_t index, LabelPath& path, int level) {
    if (level == level_h_ + 1) {
      moveChildren(index, path);
      return;
    }
    const OctreeNode node = source_.nodes()[index];
    for (int i = 0; i < 8; ++i) {
      const int k = d_ > 0 ? 7 - i : i;
      const unsigned bit = 1u << k;
      if (!(node.occupied() & bit)) continue;
      path.push(k);
      if (node.black & bit) {
        moveBlackLeaf(path, level - 1);
      } else {
        traverse(node.childIndex(k), path, level - 1);
      }
      path.pop();
    }
  }

  // Moves the eight level-H children of a level-(H+1) node s at once. Child s.k goes to
  // (s.k) + d = (s + (d - 2^H)).k + 2^H: its label takes one unit step (Table 2), which is
  // k + a (a = 1, 2, 4 for x, y, z) with no carry for the children on the - side of the axis
  // and k - a with a carry for the others (Table 1). So all of them land in two level-(H+1)
  // nodes, A = s + (d - 2^H) and B = A + 2^(H+1), found by path arithmetic once for the eight,
  // and their masks move over by shifting bits a places.
  void moveChildren(std::uint32_t index, const LabelPath& path) {
    const OctreeNode node = source_.nodes()[index];
    const std::int64_t unit = std::int64_t{1} << level_h_;
    const std::uint8_t low = kLowHalf[static_cast<std::size_t>(axis_)];
    if (node.occupied() & low) {
      LabelPath a = path;
      if (addToPathWithCarry(a, axis_, d_ - unit, level_h_ + 1) == 0) {
        place(a, node, low, true);
      } else {
        clipped_ = true;
      }
    }
    if (node.occupied() & ~low) {
      LabelPath b = path;
      if (addToPathWithCarry(b, axis_, d_ + unit, level_h_ + 1) == 0) {
        place(b, node, static_cast<std::uint8_t>(~low), false);
      } else {
        clipped_ = true;
      }
    }
  }

  // Puts the children of `node` selected by `part`, relabelled k -> k + a (up) or k - a, into
  // the builder node named by `dest`, copying gray subtrees.
  void place(const LabelPath& dest, const OctreeNode& node, std::uint8_t part, bool up) {
    const int a = 1 << axis_;
    const std::uint32_t to = descend(dest, dest.length);
    const unsigned black = node.black & part;
    OctreeBuilder::Node& n = out_.node(to);
    n.black = static_cast<std::uint8_t>(n.black | (up ? black << a : black >> a));
    for (std::uint8_t g = static_cast<std::uint8_t>(node.gray & part); g;
         g &= static_cast<std::uint8_t>(g - 1)) {
      const int k = lowestBit(g);
      const std::uint32_t copy = out_.split(to, k ^ a);  // may move out_'s nodes: no refs kept
      copySubtree(node.childIndex(k), copy);
    }
  }

  // A black leaf of level L > H. §3.2 splits it into 8^(L-H) level-H leaves and moves each;
  // all of them land in two level-L cubes: P1 = s + (d rounded down to a multiple of 2^L) and
  // P2 = P1 + 2^L, both computed by path arithmetic. The leaf covers offsets [r, 2^L) of P1
  // and [0, r) of P2 along the axis (r = d mod 2^L), so painting those two slabs gives the
  // same tree at the cost of the leaf's face area instead of its volume.
  void moveBlackLeaf(const LabelPath& path, int level) {
    const std::int64_t side = std::int64_t{1} << level;
    const std::int64_t d_low = d_ - remainder(level);  // |d| < 2^depth: no overflow here
    LabelPath p1 = path, p2 = path;
    if (addToPathWithCarry(p1, axis_, d_low, level) == 0) {
      pending_.push_back(pathKey(p1) << 1 | kUpperPart);
    } else {
      clipped_ = true;
    }
    if (addToPathWithCarry(p2, axis_, d_low + side, level) == 0) {
      pending_.push_back(pathKey(p2) << 1 | kLowerPart);
    } else {
      clipped_ = true;
    }
  }

  // r = d mod 2^level, the offset of a moved level-`level` leaf inside its destination cubes.
  std::int64_t remainder(int level) const {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(d_) &
                                     ((std::uint64_t{1} << level) - 1u));
  }

  // A leaf's upper part in P1 and its -axis neighbour's lower part in the same cube (when that
  // neighbour is a black leaf of the same level) make the cube whole: painting them as one
  // black leaf saves building two slabs that compaction would merge again. So slabs are
  // collected by destination path first, then painted.
  static constexpr std::uint64_t kUpperPart = 0, kLowerPart = 1;

  // A leading 1 bit, then 3 bits per label: unique per path (black leaves above H are at
  // level >= 1, so paths have at most 20 labels and the key fits in 62 bits with the part).
  static std::uint64_t pathKey(const LabelPath& path) {
    std::uint64_t key = 1;
    for (int i = 0; i < path.length; ++i) key = key << 3 | static_cast<std::uint64_t>(path[i]);
    return key;
  }
  static LabelPath pathOfKey(std::uint64_t key) {
    LabelPath path;
    const int length = highestBit64(key) / 3;
    for (int i = length - 1; i >= 0; --i) {
      path.push(static_cast<int>((key >> (3 * i)) & 7u));
    }
    return path;
  }

  void paintPendingSlabs() {
    std::sort(pending_.begin(), pending_.end());
    const int depth = source_.grid().depth();
    for (std::size_t i = 0; i < pending_.size();) {
      const std::uint64_t key = pending_[i] >> 1;
      const bool both = i + 1 < pending_.size() && (pending_[i + 1] >> 1) == key;
      const LabelPath path = pathOfKey(key);
      const int level = depth - path.length;
      const std::int64_t r = remainder(level);
      if (both) {
        paintWhole(path);
      } else if ((pending_[i] & 1u) == kUpperPart) {
        paintSlab(path, level, r, std::int64_t{1} << level);
      } else {
        paintSlab(path, level, 0, r);
      }
      i += both ? 2 : 1;
    }
  }

  void paintWhole(const LabelPath& path) {
    if (path.length == 0) {
      out_.node(OctreeBuilder::kRoot).black = 0xff;  // build() turns this into a black universe
      return;
    }
    const std::uint32_t parent = descend(path, path.length - 1);
    OctreeBuilder::Node& p = out_.node(parent);
    p.black = static_cast<std::uint8_t>(p.black | (1u << path[path.length - 1]));
  }

  // Paints black the part of the level-`level` cube named by `path` whose offset along the axis
  // is in [lo, hi), a proper part of the cube (0 < r < 2^level).
  void paintSlab(const LabelPath& path, int level, std::int64_t lo, std::int64_t hi) {
    if (path.length == 0) {
      paintSlabIn(OctreeBuilder::kRoot, level, lo, hi);
      return;
    }
    const std::uint32_t parent = descend(path, path.length - 1);
    const std::uint32_t node = out_.split(parent, path[path.length - 1]);
    paintSlabIn(node, level, lo, hi);
  }

  void paintSlabIn(std::uint32_t index, int level, std::int64_t lo, std::int64_t hi) {
    const std::int64_t half = std::int64_t{1} << (level - 1);
    for (int k = 0; k < 8; ++k) {
      const std::int64_t base = ((k >> axis_) & 1) ? half : 0;
      const std::int64_t a = std::max(lo, base), b = std::min(hi, base + half);
      if (a >= b) continue;
      if (a == base && b == base + half) {
        OctreeBuilder::Node& n = out_.node(index);
        n.black = static_cast<std::uint8_t>(n.black | (1u << k));
      } else {
        const std::uint32_t child = out_.split(index, k);  // may move out_'s nodes: no refs kept
        paintSlabIn(child, level - 1, a - base, b - base);
      }
    }
  }

  // The builder node of the first `count` labels of `path`, created (white) where missing.
  // Destinations of distinct source nodes are disjoint, so no black leaf is ever in the way.
  std::uint32_t descend(const LabelPath& path, int count) {
    std::uint32_t index = OctreeBuilder::kRoot;
    for (int i = 0; i < count; ++i) index = out_.split(index, path[i]);
    return index;
  }

  void copySubtree(std::uint32_t from, std::uint32_t to) {
    const OctreeNode n = source_.nodes()[from];
    out_.node(to).black = n.black;
    for (std::uint8_t g = n.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
      const int k = lowestBit(g);
      copySubtree(n.childIndex(k), out_.split(to, k));
    }
  }

  const Octree& source_;
  OctreeBuilder out_;
  std::vector<std::uint64_t> pending_;  // slab keys: pathKey << 1 | part
  int axis_;
  std::int64_t d_;
  int level_h_;  // the paper's H: lowest set bit of the displacement
  bool clipped_ = false;
};

// The top-down alternative: every cube C of the result is filled from the window C - d of the
// source, which straddles two adjacent source cubes of C's level along the axis ("lo" and "hi",
// C starting at offset r inside lo). The window of child k of C lies in the children of lo and
// hi in k's row along the axis (labels k & ~a, k | a: the Table 1 pairs), so the recursion
// never needs coordinates, and it stops as soon as a window is uniform or aligned (r = 0:
// the source subtree is copied as it is). Nothing is built that compaction would remove.
class AxisWindow {
 public:
  AxisWindow(const Octree& source, int axis, std::int64_t d)
      : source_(source), axis_(axis), a_(1 << axis), d_(d) {}

  Octree run(bool* clipped) {
    const int depth = source_.grid().depth();
    const std::int64_t side = std::int64_t{1} << depth;
    const Ref root =
        source_.rootColor() == Color::kGray ? Ref{0, Color::kGray} : Ref{0, source_.rootColor()};
    const Ref outside{0, Color::kWhite};
    // The universe's window starts at -d: in the (white) cube before the universe for d > 0.
    const Ref lo = d_ > 0 ? outside : root, hi = d_ > 0 ? root : outside;
    const std::int64_t r = d_ > 0 ? side - d_ : -d_;
    std::uint32_t top = 0;
    const Color color = pull(lo, hi, r, depth, &top);
    // What leaves is the source's slab [side - d, side) (d > 0) or [0, -d) along the axis.
    if (d_ > 0 ? anyBlack(root, depth, side - d_, side) : anyBlack(root, depth, 0, -d_)) {
      *clipped = true;
    }
    if (color != Color::kGray)
      return color == Color::kBlack ? Octree::full(source_.grid()) : Octree(source_.grid());
    std::vector<OctreeNode> nodes(1);
    nodes.reserve(made_.size() + source_.internalNodeCount());
    emit(top, 0, nodes);
    return Octree::fromNodes(source_.grid(), Color::kGray, std::move(nodes));
  }

 private:
  struct Ref {  // a source cube: a gray node's index, or a uniform colour
    std::uint32_t index;
    Color color;
  };
  // A result node: children are indices into made_, or source node indices tagged kSource.
  struct Made {
    std::uint8_t black = 0, gray = 0;
    std::array<std::uint32_t, 8> child{};
  };
  static constexpr std::uint32_t kSource = 0x80000000u;

  struct Masks {
    unsigned black, gray;
  };
  Masks masks(const Ref& ref) const {
    if (ref.color == Color::kBlack) return {0xffu, 0u};
    if (ref.color == Color::kWhite) return {0u, 0u};
    const OctreeNode& n = source_.nodes()[ref.index];
    return {n.black, n.gray};
  }

  Ref child(const Ref& ref, int k) const {
    if (ref.color != Color::kGray) return ref;
    const OctreeNode& n = source_.nodes()[ref.index];
    if (n.black & (1u << k)) return {0, Color::kBlack};
    if (n.gray & (1u << k)) return {n.childIndex(k), Color::kGray};
    return {0, Color::kWhite};
  }

  // The result cube of level `level` whose window starts at offset r in lo and runs into hi.
  Color pull(const Ref& lo, const Ref& hi, std::int64_t r, int level, std::uint32_t* out) {
    if (r == 0 || (lo.color != Color::kGray && lo.color == hi.color)) {
      if (lo.color == Color::kGray) *out = lo.index | kSource;
      return lo.color;
    }
    const int shift = level - 1;
    const std::int64_t half = std::int64_t{1} << shift;
    Made made;
    if (r == half) {
      // Aligned children (e.g. every node of level H + 1): lo's + half becomes the - half and
      // hi's - half the + half, labels k + a -> k and k -> k + a (Table 1), nothing below.
      const unsigned low = kLowHalf[static_cast<std::size_t>(axis_)];
      const Masks l = masks(lo), h = masks(hi);
      made.black = static_cast<std::uint8_t>(((l.black & ~low) >> a_) | ((h.black & low) << a_));
      made.gray = static_cast<std::uint8_t>(((l.gray & ~low) >> a_) | ((h.gray & low) << a_));
      for (std::uint8_t g = made.gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
        const int k = lowestBit(g);
        const Ref c = (k & a_) ? child(hi, k ^ a_) : child(lo, k ^ a_);
        made.child[static_cast<std::size_t>(k)] = c.index | kSource;
      }
    } else {
      for (int row = 0; row < 8; ++row) {
        if (row & a_) continue;
        const Ref quarter[4] = {child(lo, row), child(lo, row | a_), child(hi, row),
                                child(hi, row | a_)};
        for (int k : {row, row | a_}) {
          const std::int64_t start = r + ((k & a_) ? half : 0);
          const std::size_t q = static_cast<std::size_t>(start >> shift);  // 0 or 1 (r != half)
          std::uint32_t index = 0;
          const Color c = pull(quarter[q], quarter[q + 1], start & (half - 1), shift, &index);
          if (c == Color::kBlack) {
            made.black = static_cast<std::uint8_t>(made.black | (1u << k));
          } else if (c == Color::kGray) {
            made.gray = static_cast<std::uint8_t>(made.gray | (1u << k));
            made.child[static_cast<std::size_t>(k)] = index;
          }
        }
      }
    }
    if (made.black == 0xff) return Color::kBlack;
    if ((made.black | made.gray) == 0) return Color::kWhite;
    *out = static_cast<std::uint32_t>(made_.size());
    made_.push_back(made);
    return Color::kGray;
  }

  // Canonical compact layout (as OctreeBuilder::build): each node's gray children in one block.
  void emit(std::uint32_t ref, std::uint32_t pos, std::vector<OctreeNode>& out) const {
    std::uint8_t black, gray;
    std::array<std::uint32_t, 8> children{};
    if (ref & kSource) {
      const OctreeNode& n = source_.nodes()[ref & ~kSource];
      black = n.black;
      gray = n.gray;
      for (std::uint8_t g = gray; g; g &= static_cast<std::uint8_t>(g - 1)) {
        const int k = lowestBit(g);
        children[static_cast<std::size_t>(k)] = n.childIndex(k) | kSource;
      }
    } else {
      const Made& m = made_[ref];
      black = m.black;
      gray = m.gray;
      children = m.child;
    }
    const std::uint32_t first = static_cast<std::uint32_t>(out.size());
    out[pos] = OctreeNode{gray ? first : 0u, black, gray};
    out.resize(out.size() + static_cast<std::size_t>(popcount8(gray)));
    std::uint32_t j = 0;
    for (std::uint8_t g = gray; g; g &= static_cast<std::uint8_t>(g - 1), ++j) {
      emit(children[static_cast<std::size_t>(lowestBit(g))], first + j, out);
    }
  }

  // Whether the source cube has a black voxel at axis offsets [lo, hi).
  bool anyBlack(const Ref& ref, int level, std::int64_t lo, std::int64_t hi) const {
    if (lo >= hi || ref.color == Color::kWhite) return false;
    if (ref.color == Color::kBlack) return true;
    const std::int64_t half = std::int64_t{1} << (level - 1);
    for (int k = 0; k < 8; ++k) {
      const std::int64_t base = (k & a_) ? half : 0;
      if (anyBlack(child(ref, k), level - 1, std::max(lo, base) - base,
                   std::min(hi, base + half) - base)) {
        return true;
      }
    }
    return false;
  }

  const Octree& source_;
  int axis_;
  int a_;  // the label bit of the axis: 1, 2, 4
  std::int64_t d_;
  std::vector<Made> made_;
};

// Applies the x, y and z components in turn with one per-axis mover (the paper's AxisMover or
// the top-down AxisWindow); both share the clipping shortcut.
template <class Mover>
TranslateResult translateAxisByAxis(const Octree& source,
                                    const Eigen::Matrix<std::int64_t, 3, 1>& d) {
  TranslateResult result{source, false};
  const std::int64_t side = std::int64_t{source.grid().sideVoxels()};
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t component = d[axis];
    if (component == 0 || result.tree.empty()) continue;
    // Everything leaves: no need to look at the nodes (and no int64 overflow below).
    if (component >= side || component <= -side) {
      result.tree = Octree(source.grid());
      result.clipped = true;
      break;
    }
    result.tree = Mover(result.tree, axis, component).run(&result.clipped);
  }
  return result;
}

}  // namespace

TranslateResult translate(const Octree& source, const Eigen::Matrix<std::int64_t, 3, 1>& d) {
  return translateAxisByAxis<AxisMover>(source, d);
}

TranslateResult translateTopDown(const Octree& source, const Eigen::Matrix<std::int64_t, 3, 1>& d) {
  return translateAxisByAxis<AxisWindow>(source, d);
}

}  // namespace octomotion
