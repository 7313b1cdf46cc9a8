// Exact rotations of an octree by multiples of 90 degrees about the centre of the universe
// (Jackins & Tanimoto 1980, cited by Ahuja & Nash 1984 §5 and Weng & Ahuja 1987 §1).
//
// Such a rotation maps every cube of the tessellation onto a cube of the same level, and the
// octants of a cube onto the octants of its image by one fixed relabelling of 0..7. So the
// rotated tree has the same nodes, each with its child masks relabelled and its gray children
// reordered: no splitting, no rounding, node count unchanged.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "octomotion/octree/octree.h"

namespace octomotion {

// One of the 24 proper rotations that map the coordinate axes onto coordinate axes: a signed
// permutation matrix R with det R = +1. It acts on positions relative to the universe centre:
// p' = R p. Row i has its one nonzero entry, sign(i) = +-1, in column axis(i).
class AxisRotation {
 public:
  AxisRotation();  // the identity

  // Throws InvalidArgument naming the matrix when it is not a signed permutation with det +1.
  static AxisRotation fromMatrix(const Eigen::Matrix3i& R);
  // `quarter_turns` * 90 degrees about +x, +y or +z (axis 0, 1, 2), right-handed; any integer.
  static AxisRotation about(int axis, int quarter_turns);
  // All 24, the identity first.
  static const std::array<AxisRotation, 24>& all();

  Eigen::Matrix3i matrix() const;
  int axis(int i) const { return axis_[static_cast<std::size_t>(i)]; }
  int sign(int i) const { return sign_[static_cast<std::size_t>(i)]; }

  // The label of the image of octant `label` (Ahuja & Nash Fig. 1 labels) inside the image of
  // its parent, and the same applied to each bit of a child mask.
  int mapLabel(int label) const { return label_map_[static_cast<std::size_t>(label)]; }
  std::uint8_t mapMask(std::uint8_t mask) const { return mask_map_[mask]; }

  // Where a voxel or cube of a depth-`depth` universe goes.
  Voxel apply(const Voxel& v, int depth) const;
  Cube apply(const Cube& c, int depth) const;

  // (a * b) rotates by b, then by a (matrix product).
  friend AxisRotation operator*(const AxisRotation& a, const AxisRotation& b);
  AxisRotation inverse() const;
  friend bool operator==(const AxisRotation& a, const AxisRotation& b) {
    return a.axis_ == b.axis_ && a.sign_ == b.sign_;
  }
  friend bool operator!=(const AxisRotation& a, const AxisRotation& b) { return !(a == b); }

 private:
  AxisRotation(const std::array<std::int8_t, 3>& axis, const std::array<std::int8_t, 3>& sign);

  std::array<std::int8_t, 3> axis_;
  std::array<std::int8_t, 3> sign_;
  std::array<std::uint8_t, 8> label_map_;
  std::array<std::uint8_t, 256> mask_map_;
};

// The tree rotated by R about the universe centre; exact, same node count, compact.
Octree rotate90(const Octree& source, const AxisRotation& R);

}  // namespace octomotion
