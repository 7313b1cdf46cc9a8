// Integral translation of an octree by arithmetic on label paths (Ahuja & Nash 1984 §3).
//
// A node is named by the labels met on the way down from the root ("r057"). Moving a node one
// unit of its own size along +x, +y or +z changes its last label by the increment of Table 1 and,
// for half the labels, carries into the parent's label (Table 2). A displacement of any size is
// added to a path digit by digit like a binary number whose "digits" are the path's labels
// (§3.1); a negative one is added in two's complement. translate() moves whole subtrees this way
// (§3.2) and, unlike the paper, never wraps around: what leaves the universe is dropped.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "octomotion/octree/octree.h"

namespace octomotion {

// Table 1: the label increment (mod 8) of a unit step along +x, +y, +z, indexed [axis][label].
inline constexpr std::array<std::array<std::uint8_t, 8>, 3> kLabelIncrement{{
    {1, 7, 1, 7, 1, 7, 1, 7},  // +x: west octants move east; east ones wrap west and carry
    {2, 2, 6, 6, 2, 2, 6, 6},  // +y: south -> north; north wraps south and carries
    {4, 4, 4, 4, 4, 4, 4, 4},  // +z: lower -> upper; upper wraps lower and carries
}};

// Table 2: the label after a unit step, indexed [axis][label], written like the paper in octal:
// the "eights" digit is the carry into the parent's label (e.g. 7 +y -> 015: label 5, carry 1).
inline constexpr std::array<std::array<std::uint8_t, 8>, 3> kLabelTransition{{
    {01, 010, 03, 012, 05, 014, 07, 016},
    {02, 03, 010, 011, 06, 07, 014, 015},
    {04, 05, 06, 07, 010, 011, 012, 013},
}};

// One unit step of a label along +axis (Table 2): the new label and whether it carries.
struct LabelStep {
  int label;
  bool carry;
};
constexpr LabelStep stepLabel(int label, int axis) {
  const int t = kLabelTransition[static_cast<std::size_t>(axis)][static_cast<std::size_t>(label)];
  return {t & 7, (t >> 3) != 0};
}

// The labels from the root down to a node, root first: labels[0] picks a child of the root.
// A path of length m in a universe of depth n names a cube of level n - m.
struct LabelPath {
  std::array<std::uint8_t, kMaxDepth> labels{};
  int length = 0;

  // Throws InvalidArgument when the label is outside 0..7 or the path is already kMaxDepth long.
  void push(int label);
  void pop() { --length; }
  int operator[](int i) const { return labels[static_cast<std::size_t>(i)]; }

  // "r057" <-> {0, 5, 7}. parse throws InvalidArgument naming the text when it is not 'r'
  // followed by up to kMaxDepth digits 0..7.
  static LabelPath parse(const std::string& text);
  std::string toString() const;

  // The path of a cube of a depth-`depth` universe, and the cube a path names (for tests and
  // printing; the motion itself never converts paths to coordinates).
  static LabelPath of(const Cube& cube, int depth);
  Cube cube(int depth) const;

  friend bool operator==(const LabelPath& a, const LabelPath& b);
  friend bool operator!=(const LabelPath& a, const LabelPath& b) { return !(a == b); }
};

// Adds `displacement` (in voxels, along `axis` 0=x 1=y 2=z) to the path of a node of level
// `level` (side 2^level voxels), in place, digit by digit with Table 2: bit level+i of the
// displacement (two's complement for negatives) is added to the i-th label from the end, then
// the carry. Returns the root carry in signed form: the number of universe sides the node moved
// past, 0 when the moved node is still inside. For a displacement >= 0 that is just the carry out
// of the root; for a negative one, the two's complement sign bits above the root cancel a carry
// out of the root, so the paper's "carry lost" (r275 - 5 = r057) gives 0, and a missing carry
// means the node left on the negative side. The path keeps the low digits (the wrap-around).
// Throws InvalidArgument for a bad axis or level or a displacement that is not a multiple of
// 2^level (the node would straddle cubes: split it first, §3.2).
std::int64_t addToPathWithCarry(LabelPath& path, int axis, std::int64_t displacement,
                                int level = 0);

// addToPathWithCarry() == 0: false when the node leaves the universe ("carry out of the root").
inline bool addToPath(LabelPath& path, int axis, std::int64_t displacement, int level = 0) {
  return addToPathWithCarry(path, axis, displacement, level) == 0;
}

struct TranslateResult {
  Octree tree;
  // True iff some black voxel of the source left the universe and was dropped.
  bool clipped = false;
};

// The source translated by d voxels (any signs), by Ahuja & Nash's algorithm (§3.2). Each
// nonzero component is applied in turn (x, y, z): the tree is traversed down to level H (the
// lowest set bit of the component) in the paper's order, every level-H node is moved whole to
// the path addToPathWithCarry gives, and the result is compacted. One departure: a black leaf
// above H is not split into its 8^(L-H) level-H cubes; its image, two slabs of the two level-L
// cubes found by path arithmetic, is painted instead (face area instead of volume). The part
// that leaves the universe is dropped and `clipped` set; a component of magnitude >= the
// universe side clips everything.
TranslateResult translate(const Octree& source, const Eigen::Matrix<std::int64_t, 3, 1>& d);

// The same result computed top-down: each cube of the new tree is filled from the two source
// cubes its pre-image straddles (children paired by the Table 1 relabelling), stopping at
// uniform or aligned windows and copying aligned source subtrees whole. Its work follows the
// windows it opens (the result's nodes, plus the faces of source leaves that a uniform window
// straddles) and it builds nothing that compaction would remove; faster than translate() in
// bench/translate_bench.cpp, most of all for displacements with a low H.
TranslateResult translateTopDown(const Octree& source, const Eigen::Matrix<std::int64_t, 3, 1>& d);

}  // namespace octomotion
