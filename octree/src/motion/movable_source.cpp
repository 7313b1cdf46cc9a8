// MovableSource: a source tree prepared for the fused query (see collides.h).
#include <algorithm>
#include <cmath>

#include "internal/kernel.h"
#include "octomotion/error.h"
#include "octomotion/motion/collides.h"

namespace octomotion {

namespace {

using Node = MovableSource::Node;

struct IntBox {
  std::uint32_t lo[3], hi[3];
  bool empty;
  double voxels;  // black voxels under the node
};

// Tight box of the black voxels under node i (bottom-up); fills the node geometry.
IntBox fillNode(const Octree& t, std::vector<Node>& out, std::uint32_t i, const Cube& cube,
                double expand_factor) {
  const OctreeNode& n = t.nodes()[i];
  Node& m = out[i];
  m.first_child = n.first_child;
  m.black = n.black;
  m.gray = n.gray;
  m.level = static_cast<std::int8_t>(cube.level);
  m.origin = cube.origin;
  IntBox box{{0xffffffffu, 0xffffffffu, 0xffffffffu}, {0, 0, 0}, true, 0.0};
  auto grow = [&box](const IntBox& c) {
    if (c.empty) return;
    box.voxels += c.voxels;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = box.empty ? c.lo[a] : std::min(box.lo[a], c.lo[a]);
      box.hi[a] = box.empty ? c.hi[a] : std::max(box.hi[a], c.hi[a]);
    }
    box.empty = false;
  };
  for (int k = 0; k < 8; ++k) {
    const Cube c = cube.child(k);
    if (n.black & (1u << k)) {
      const std::uint32_t s = c.side() - 1;
      const double side = static_cast<double>(c.side());
      grow({{c.origin.x, c.origin.y, c.origin.z},
            {c.origin.x + s, c.origin.y + s, c.origin.z + s},
            false,
            side * side * side});
    } else if (n.gray & (1u << k)) {
      grow(fillNode(t, out, n.childIndex(k), c, expand_factor));
    }
  }
  double volume = 1.0;
  for (int a = 0; a < 3; ++a) {  // `out` is never resized, so `m` is still valid
    const double lo = static_cast<double>(box.lo[a]);
    const double hi = static_cast<double>(box.hi[a]) + 1.0;
    m.centre[a] = 0.5 * (lo + hi);
    m.half[a] = 0.5 * (hi - lo);
    volume *= hi - lo;
  }
  const double expand = box.voxels < MovableSource::kSparseFill * volume
                            ? std::min(expand_factor, MovableSource::kExpandFactorSparse)
                            : expand_factor;
  m.split_half = std::max(m.half[0], std::max(m.half[1], m.half[2])) / expand;
  return box;
}

constexpr std::size_t kCoreLeaves = 3;

}  // namespace

MovableSource::MovableSource(const Octree& source, double expand_factor)
    : grid_(source.grid()), root_(source.rootColor()), expand_factor_(expand_factor) {
  if (!(expand_factor >= 1)) throw InvalidArgument("MovableSource: expand_factor must be >= 1");
  if (root_ == Color::kGray) {
    nodes_.resize(source.nodes().size());
    fillNode(source, nodes_, 0, grid_.universe(), expand_factor);
  } else if (root_ == Color::kBlack) {
    // A virtual parent one level above the universe whose child 0 is the black universe, so
    // the query handles every source the same way.
    const double h = detail::halfSide(grid_.depth());
    Node n{};
    n.centre[0] = n.centre[1] = n.centre[2] = h;
    n.half[0] = n.half[1] = n.half[2] = h;
    n.split_half = h / expand_factor;
    n.black = 1;
    n.level = static_cast<std::int8_t>(grid_.depth() + 1);
    nodes_.push_back(n);
  }
  // Core leaves: among the largest leaves (top two levels), greedily the farthest apart, so
  // the first guesses cover the object's length.
  std::vector<Cube> leaves = source.blackLeaves();
  int top = -1;
  for (const Cube& c : leaves) top = std::max(top, c.level);
  std::vector<Cube> candidates;
  for (const Cube& c : leaves) {
    if (c.level >= top - 1) candidates.push_back(c);
  }
  auto centre = [](const Cube& c) {
    double u[3];
    detail::cubeCentre(c, u);
    return Eigen::Vector3d(u[0], u[1], u[2]);
  };
  while (core_.size() < kCoreLeaves && core_.size() < candidates.size()) {
    double best = -1;
    Cube pick = candidates.front();
    for (const Cube& c : candidates) {
      double nearest = core_.empty() ? static_cast<double>(c.level) : 1e300;
      for (const Cube& k : core_) nearest = std::min(nearest, (centre(c) - centre(k)).norm());
      if (nearest > best) {
        best = nearest;
        pick = c;
      }
    }
    core_.push_back(pick);
  }
  // Grid probes: farthest-point sampling over every black leaf's centre, from the largest.
  if (!leaves.empty()) {
    std::vector<Eigen::Vector3d> centres;
    centres.reserve(leaves.size());
    std::size_t first = 0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      centres.push_back(centre(leaves[i]));
      if (leaves[i].level > leaves[first].level) first = i;
    }
    std::vector<double> nearest(leaves.size(), 1e300);
    std::size_t pick = first;
    for (std::size_t n = 0; n < kGridProbes && n < leaves.size(); ++n) {
      grid_probes_.push_back({centres[pick].x(), centres[pick].y(), centres[pick].z()});
      std::size_t next = pick;
      double far = -1.0;
      for (std::size_t i = 0; i < leaves.size(); ++i) {
        nearest[i] = std::min(nearest[i], (centres[i] - centres[pick]).squaredNorm());
        if (nearest[i] > far) {
          far = nearest[i];
          next = i;
        }
      }
      if (far <= 0.0) break;  // every leaf centre is taken
      pick = next;
    }
  }
}

}  // namespace octomotion
