// Ahuja & Nash (1984) §3 step by step: a node's label path plus a displacement's binary digits,
// added with the label transitions of Table 2, gives the node's path after the move. Prints the
// paper's worked examples (r057 +1 and +5 along y, and -5 in two's complement back again), then
// translates a small block and prints its octree before and after as indented node lists, in
// the manner of the paper's Figs. 3 and 4.
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "octomotion/motion/translate.h"
#include "octomotion/octree/octree_builder.h"

namespace {

using octomotion::Color;
using octomotion::Cube;
using octomotion::LabelPath;
using octomotion::Octree;
using octomotion::OctreeNode;
using Displacement = Eigen::Matrix<std::int64_t, 3, 1>;

const char* kAxisNames[] = {"x", "y", "z"};

// The displacement's low `digits` bits in two's complement, most significant first.
std::string binary(std::int64_t d, int digits) {
  std::string s;
  for (int bit = digits - 1; bit >= 0; --bit) {
    s += ((static_cast<std::uint64_t>(d) >> bit) & 1u) ? '1' : '0';
  }
  return s;
}

// Adds d to a path of a voxel, printing each digit's Table 2 steps, and checks the library's
// addToPath agrees. Returns the path after the move.
LabelPath addAndShow(const LabelPath& path, int axis, std::int64_t d) {
  const int n = path.length;
  std::cout << "    " << path.toString() << "\n  + " << std::string(1, ' ') << binary(d, n)
            << "   (" << (d < 0 ? "two's complement of " : "") << d << " along +"
            << kAxisNames[axis] << ")\n";
  LabelPath sum = path;
  int carry = 0;
  for (int i = n - 1, bit = 0; i >= 0; --i, ++bit) {
    int label = sum[i];
    const int digit = static_cast<int>((static_cast<std::uint64_t>(d) >> bit) & 1u);
    std::cout << "      label " << label << " + digit " << digit << " + carry " << carry << ":";
    int out = 0;
    for (int steps = digit + carry; steps > 0; --steps) {
      const octomotion::LabelStep step = octomotion::stepLabel(label, axis);
      std::cout << "  " << label << " -> " << (step.carry ? "1" : "") << step.label;
      label = step.label;
      out += step.carry ? 1 : 0;
    }
    if (digit + carry == 0) std::cout << "  unchanged";
    std::cout << "\n";
    sum.labels[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(label);
    carry = out;
  }
  std::cout << "  = " << (carry ? "1" : " ") << sum.toString();
  LabelPath checked = path;
  const std::int64_t root_carry = octomotion::addToPathWithCarry(checked, axis, d);
  if (carry && d < 0) {
    std::cout << "   carry lost: the two's complement sign cancels it, the node stays inside";
  } else if (carry) {
    std::cout << "   carry out of the root: the node left the universe (dropped, not wrapped)";
  }
  std::cout << "\n    (addToPathWithCarry: " << checked.toString() << ", root carry " << root_carry
            << ")\n\n";
  if (checked != sum) {
    std::cerr << "error: the library disagrees with the trace\n";
    std::exit(1);
  }
  return sum;
}

void printNode(const Octree& tree, std::uint32_t index, const std::string& indent) {
  const OctreeNode& n = tree.nodes()[index];
  for (int k = 0; k < 8; ++k) {
    if (n.black & (1u << k)) {
      std::cout << indent << k << " black\n";
    } else if (n.gray & (1u << k)) {
      std::cout << indent << k << " gray\n";
      printNode(tree, n.childIndex(k), indent + "  ");
    }
  }
}

// White children are left out, as in the paper's figures ("nodes not shown are white").
void printTree(const Octree& tree) {
  if (tree.rootColor() == Color::kGray) {
    std::cout << "  r gray\n";
    printNode(tree, 0, "    ");
  } else {
    std::cout << "  r " << (tree.rootColor() == Color::kBlack ? "black" : "white") << "\n";
  }
}

void printLeaves(const Octree& tree) {
  std::cout << "  black leaves:";
  const int depth = tree.grid().depth();
  tree.forEachBlackLeaf(
      [&](const Cube& c) { std::cout << " " << LabelPath::of(c, depth).toString(); });
  std::cout << "\n";
}

}  // namespace

int main() {
  std::cout << "Table 2 of Ahuja & Nash (1984): label after a unit step (1x = carry)\n"
            << "  label    +x   +y   +z\n";
  for (int label = 0; label < 8; ++label) {
    std::cout << "    " << label;
    for (int axis = 0; axis < 3; ++axis) {
      const int t = octomotion::kLabelTransition[static_cast<std::size_t>(axis)]
                                                [static_cast<std::size_t>(label)];
      std::cout << "   " << (t >> 3 ? "1" : " ") << (t & 7) << " ";
    }
    std::cout << "\n";
  }
  std::cout << "\n§3.1 worked examples in a universe of 8x8x8 voxels (depth 3):\n\n";
  const LabelPath r057 = LabelPath::parse("r057");
  const LabelPath r075 = addAndShow(r057, 1, 1);
  const LabelPath r275 = addAndShow(r057, 1, 5);
  const LabelPath back = addAndShow(r275, 1, -5);
  addAndShow(r275, 1, 3);  // the same digits 011 as a positive move do leave the universe
  if (r075.toString() != "r075" || r275.toString() != "r275" || back != r057) {
    std::cerr << "error: the worked examples do not come out as in the paper\n";
    return 1;
  }

  // Fig. 3 as trees.
  const octomotion::WorldGrid small(Eigen::Vector3d::Zero(), 1.0, 3);
  octomotion::OctreeBuilder fig3(small);
  fig3.paint(r057.cube(3), true);
  const Octree block = fig3.build();
  std::cout << "Fig. 3a: the unit block r057\n";
  printTree(block);
  std::cout << "Fig. 3c: translated by (0, 5, 0)\n";
  printTree(octomotion::translate(block, Displacement(0, 5, 0)).tree);

  // A small parallelepiped, as in Fig. 4, moved by an odd amount along each axis.
  const octomotion::WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, 4);
  octomotion::OctreeBuilder builder(grid);
  for (std::uint32_t z = 4; z < 8; ++z)
    for (std::uint32_t y = 8; y < 12; ++y)
      for (std::uint32_t x = 0; x < 8; ++x) builder.setVoxel({x, y, z});
  const Octree before = builder.build();
  std::cout << "\nFig. 4 style: an 8x4x4 block in a 16^3 universe\n(a) original\n";
  printTree(before);
  printLeaves(before);
  // H = 2: the lowest set bit of 4, so the two 4^3 leaves move whole, by one step of their size.
  const octomotion::TranslateResult aligned = octomotion::translate(before, Displacement(4, -4, 0));
  std::cout << "(b) translated by (4, -4, 0): H = 2, the level-2 leaves move whole\n";
  printTree(aligned.tree);
  // H = 0: the leaves are (virtually) split to voxels; what lands in the neighbouring cube is
  // the slab of width 1, the rest stays in place.
  const octomotion::TranslateResult odd = octomotion::translate(before, Displacement(1, 0, 0));
  std::cout << "(c) translated by (1, 0, 0): H = 0, the leaves split along x\n";
  printTree(odd.tree);
  printLeaves(odd.tree);
  // Moving (b) 10 further along +x pushes part of it out of the universe: dropped, flagged.
  const octomotion::TranslateResult out =
      octomotion::translate(aligned.tree, Displacement(10, 0, 0));
  std::cout << "(d) (b) then by (10, 0, 0): part of it leaves the universe\n";
  printTree(out.tree);
  std::cout << "  voxels " << aligned.tree.blackVoxelCount() << " -> " << out.tree.blackVoxelCount()
            << ", clipped: " << (out.clipped ? "yes" : "no") << "\n";
  // The top-down variant (each new cube pulled from the source cubes its pre-image straddles)
  // must agree.
  const bool same =
      octomotion::translateTopDown(before, Displacement(1, 0, 0)).tree == odd.tree &&
      octomotion::translateTopDown(aligned.tree, Displacement(10, 0, 0)).tree == out.tree;
  std::cout << "translateTopDown gives the same trees: " << (same ? "yes" : "NO") << "\n";
  if (!same || aligned.clipped || odd.clipped || !out.clipped ||
      aligned.tree.blackVoxelCount() != before.blackVoxelCount() ||
      odd.tree.blackVoxelCount() != before.blackVoxelCount() ||
      out.tree.blackVoxelCount() != 2 * 4 * 4 ||  // x in [14, 16) is left
      !aligned.tree.checkInvariants() || !odd.tree.checkInvariants() ||
      !out.tree.checkInvariants()) {
    std::cerr << "error: unexpected translation result\n";
    return 1;
  }
  return 0;
}
