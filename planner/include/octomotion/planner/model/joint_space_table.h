// A 2^k-tree over the k <= 3 joint variables a self-collision pair depends on: each leaf cell of
// joint space is certified free, certified colliding, or unknown (the octree pair test decides).
// The octree check of a pair carries both link trees' voxel margins (docs/validation.md, δ_self),
// while a pair such as a wrist (link5–link7 on octo7: q6, q7 only) moves through a low-dimensional
// space that can be classified once, from the exact geometry, at model build time
// (docs/planner.md, "Self-pair tables"). Pointer-free layout: node n's 2^k children are
// children_[n * 2^k + c], each either a leaf kind (< kFirstNode) or kFirstNode + child node.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace octomotion {

class JointSpaceTable {
 public:
  enum Cell : std::uint32_t { kUnknown = 0, kFree = 1, kColliding = 2 };
  static constexpr int kMaxDims = 3;
  static constexpr int kMaxDepth = 20;  // cells of 2^-20 of a joint's range

  struct Dim {
    int joint = -1;    // index into RobotData::joint_values holding this variable's value
    double lower = 0;  // the table covers [lower, upper); values outside read kUnknown
    double upper = 0;
    // An angle whose pair looks the same a period on: values are first brought into
    // [lower, upper) by whole periods (upper - lower), so a joint with limits of +-2 pi is
    // classified over one turn and every value of it is in the table.
    bool periodic = false;
    // The tree's cells are cubes in joint space; a variable that moves the pair little needs
    // coarser cells than the others. Its side of the tree is (upper - lower) * 2^stretch, so
    // the first `stretch` splits along it only separate the range from the space beyond it,
    // whose cells are never classified (kUnknown). Values there read kUnknown or a cell whose
    // certificate covers them too.
    int stretch = 0;
  };
  // What the builder learns about one cell (centre and half-widths per dimension): a certified
  // kFree/kColliding, or kUnknown; `split` asks for the cell to be subdivided (when depth and
  // budget allow; otherwise it stays kUnknown).
  struct Verdict {
    Cell cell = kUnknown;
    bool split = false;
    // Split only once the budget has served every cell not marked so (a cell whose centre is
    // in contact: refining it serves speed, refining the others removes false positives).
    bool later = false;
  };
  using Classifier = std::function<Verdict(const double* centre, const double* half)>;

  struct BuildLimits {
    int max_depth = 12;             // per dimension; <= kMaxDepth
    std::size_t max_cells = 40000;  // classifier calls; cells left when it runs out stay kUnknown
  };

  JointSpaceTable() = default;
  // Breadth first from the whole box, so a budget that runs out leaves an evenly refined table
  // (cells split `later` after all others).
  // Throws InvalidArgument for 0 or more than kMaxDims dimensions, an empty or non-finite range,
  // a stretch outside [0, depth) or a depth outside [1, kMaxDepth].
  static JointSpaceTable build(const std::vector<Dim>& dims, const Classifier& classify,
                               const BuildLimits& limits);

  // The cell holding these joint values (joint_values indexed by Dim::joint). Branch-light: one
  // load per level.
  Cell lookup(const double* joint_values) const {
    std::uint32_t ix[kMaxDims] = {0, 0, 0};
    for (int d = 0; d < dims_count_; ++d) {
      double x = (joint_values[dims_[d].joint] - dims_[d].lower) * scale_[d];
      if (dims_[d].periodic) x -= range_cells_[d] * std::floor(x / range_cells_[d]);
      // Outside the range, or NaN or infinite (every comparison false): not in the table.
      if (!(x >= 0 && x < cells_per_dim_)) return kUnknown;
      ix[d] = static_cast<std::uint32_t>(x);
    }
    if (root_ < kFirstNode) return static_cast<Cell>(root_);
    std::uint32_t node = root_ - kFirstNode;
    for (int level = depth_ - 1;; --level) {
      std::uint32_t child = 0;
      for (int d = 0; d < dims_count_; ++d) child |= ((ix[d] >> level) & 1u) << d;
      const std::uint32_t v = children_[(static_cast<std::size_t>(node) << dims_count_) + child];
      if (v < kFirstNode) return static_cast<Cell>(v);
      node = v - kFirstNode;
    }
  }

  int dims() const { return dims_count_; }
  const Dim& dim(int d) const { return dims_[static_cast<std::size_t>(d)]; }
  int depth() const { return depth_; }
  std::size_t nodeCount() const { return children_.size() >> dims_count_; }
  std::size_t bytes() const { return sizeof(*this) + children_.size() * sizeof(std::uint32_t); }
  std::size_t classified() const { return classified_; }  // classifier calls made by build
  // Fraction of the joint box's volume in each kind of leaf (index by Cell).
  const std::array<double, 3>& volumeFractions() const { return volume_; }

 private:
  static constexpr std::uint32_t kFirstNode = 3;
  std::array<Dim, kMaxDims> dims_{};
  std::array<double, kMaxDims> scale_{};        // cells per unit of the variable
  std::array<double, kMaxDims> range_cells_{};  // finest cells in [lower, upper)
  int dims_count_ = 0;
  int depth_ = 1;
  double cells_per_dim_ = 2;
  std::uint32_t root_ = kUnknown;  // a leaf kind, or kFirstNode + 0
  std::vector<std::uint32_t> children_;
  std::size_t classified_ = 0;
  std::array<double, 3> volume_{};
};

}  // namespace octomotion
