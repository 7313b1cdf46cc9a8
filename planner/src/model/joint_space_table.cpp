#include "octomotion/planner/model/joint_space_table.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

#include "octomotion/error.h"

namespace octomotion {

JointSpaceTable JointSpaceTable::build(const std::vector<Dim>& dims, const Classifier& classify,
                                       const BuildLimits& limits) {
  if (dims.empty() || dims.size() > kMaxDims) {
    throw InvalidArgument("joint-space table: expected 1 to " + std::to_string(kMaxDims) +
                          " dimensions, got " + std::to_string(dims.size()));
  }
  if (limits.max_depth < 1 || limits.max_depth > kMaxDepth) {
    throw InvalidArgument("joint-space table: max_depth must be in [1, " +
                          std::to_string(kMaxDepth) + "], got " + std::to_string(limits.max_depth));
  }
  JointSpaceTable t;
  t.dims_count_ = static_cast<int>(dims.size());
  t.depth_ = limits.max_depth;
  t.cells_per_dim_ = std::ldexp(1.0, t.depth_);
  for (int d = 0; d < t.dims_count_; ++d) {
    const Dim& dim = dims[static_cast<std::size_t>(d)];
    if (!(std::isfinite(dim.lower) && std::isfinite(dim.upper) && dim.upper > dim.lower)) {
      throw InvalidArgument("joint-space table: dimension " + std::to_string(d) +
                            " needs a finite range with upper > lower");
    }
    if (dim.stretch < 0 || dim.stretch >= t.depth_) {
      throw InvalidArgument("joint-space table: dimension " + std::to_string(d) +
                            " needs a stretch in [0, " + std::to_string(t.depth_) + ")");
    }
    const auto s = static_cast<std::size_t>(d);
    t.dims_[s] = dim;
    t.range_cells_[s] = std::ldexp(t.cells_per_dim_, -dim.stretch);
    t.scale_[s] = t.range_cells_[s] / (dim.upper - dim.lower);
  }

  // A cell: `size` finest cells per side from integer corner ix; `slot` is where its verdict
  // goes (children_ index, or npos for the root).
  constexpr std::size_t kRootSlot = ~std::size_t{0};
  struct Pending {
    std::size_t slot;
    std::array<std::uint32_t, kMaxDims> ix;
    int level;  // side = 2^level finest cells; 0 cannot be split
  };
  const std::size_t fan = std::size_t{1} << t.dims_count_;
  std::deque<Pending> queue{{kRootSlot, {0, 0, 0}, t.depth_}}, later;
  double centre[kMaxDims] = {0, 0, 0};
  double half[kMaxDims] = {0, 0, 0};
  while (!queue.empty() || !later.empty()) {
    std::deque<Pending>& from = queue.empty() ? later : queue;
    const Pending p = from.front();
    from.pop_front();
    const double side = std::ldexp(1.0, p.level);
    double share = 1;  // of the box [lower, upper) in this cell
    for (int d = 0; d < t.dims_count_; ++d) {
      const auto s = static_cast<std::size_t>(d);
      half[d] = side / 2 / t.scale_[s];
      centre[d] = t.dims_[s].lower + (p.ix[s] + side / 2) / t.scale_[s];
      share *=
          std::max(0.0, std::min(p.ix[s] + side, t.range_cells_[s]) - p.ix[s]) / t.range_cells_[s];
    }
    Verdict v;
    if (share > 0 && t.classified_ < limits.max_cells) {  // beyond the range: never read
      v = classify(centre, half);
      ++t.classified_;
    }
    std::uint32_t value = v.cell;
    if (v.cell == kUnknown && v.split && p.level > 0 && t.classified_ < limits.max_cells) {
      const std::size_t node = t.children_.size() / fan;
      t.children_.resize(t.children_.size() + fan, kUnknown);
      value = kFirstNode + static_cast<std::uint32_t>(node);
      const std::uint32_t step = std::uint32_t{1} << (p.level - 1);
      for (std::size_t c = 0; c < fan; ++c) {
        Pending child{node * fan + c, p.ix, p.level - 1};
        for (int d = 0; d < t.dims_count_; ++d) {
          if (c & (std::size_t{1} << d)) child.ix[static_cast<std::size_t>(d)] += step;
        }
        (v.later ? later : queue).push_back(child);
      }
    } else {
      t.volume_[v.cell] += share;
    }
    if (p.slot == kRootSlot) {
      t.root_ = value;
    } else {
      t.children_[p.slot] = value;
    }
  }
  return t;
}

}  // namespace octomotion
