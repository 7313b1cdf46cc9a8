#include "octomotion/motion/clearance_grid.h"

#include <algorithm>
#include <cmath>

namespace octomotion {

namespace {

constexpr double kFar = 1e20;  // "no occupied cell on this line yet" (squared cells)

// Squared Euclidean distance transform of one line (lower envelope of parabolas; Felzenszwalb
// & Huttenlocher 2012, "Distance transforms of sampled functions"): d[q] = min_p f[p] + (q-p)^2.
void transformLine(const double* f, std::size_t n, double* d, std::vector<std::size_t>& v,
                   std::vector<double>& z) {
  v.resize(n);
  z.resize(n + 1);
  std::size_t k = 0;
  v[0] = 0;
  z[0] = -kFar;
  z[1] = kFar;
  auto meet = [&](std::size_t q, std::size_t p) {
    const double fq = f[q] + static_cast<double>(q * q), fp = f[p] + static_cast<double>(p * p);
    return (fq - fp) / (2.0 * static_cast<double>(q) - 2.0 * static_cast<double>(p));
  };
  for (std::size_t q = 1; q < n; ++q) {
    double s = meet(q, v[k]);
    while (s <= z[k]) s = meet(q, v[--k]);
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kFar;
  }
  k = 0;
  for (std::size_t q = 0; q < n; ++q) {
    while (z[k + 1] < static_cast<double>(q)) ++k;
    const double dq = static_cast<double>(q) - static_cast<double>(v[k]);
    d[q] = dq * dq + f[v[k]];
  }
}

}  // namespace

ClearanceGrid::ClearanceGrid(const Octree& tree, std::size_t max_cells) {
  const int depth = tree.grid().depth();
  while (level_ < depth && (std::uint64_t{1} << (3 * (depth - level_))) > max_cells) ++level_;
  cells_ = std::uint64_t{1} << (depth - level_);
  side_ = static_cast<double>(tree.grid().sideVoxels());
  step_ = static_cast<double>(std::uint64_t{1} << level_) / kStepsPerCell;
  const std::size_t n = static_cast<std::size_t>(cells_);
  const std::size_t total = n * n * n;
  auto at = [n](std::size_t x, std::size_t y, std::size_t z) { return (z * n + y) * n + x; };

  // Cells holding a black voxel: a leaf at or above the grid's level covers whole cells, a
  // smaller one its cell.
  std::vector<std::uint8_t> occupied(total, 0);
  tree.forEachBlackLeaf([&](const Cube& leaf) {
    const int l = std::max(leaf.level, level_);
    const std::size_t w = std::size_t{1} << (l - level_);
    const std::size_t x0 = (leaf.origin.x >> l) << (l - level_),
                      y0 = (leaf.origin.y >> l) << (l - level_),
                      z0 = (leaf.origin.z >> l) << (l - level_);
    for (std::size_t z = z0; z < z0 + w; ++z) {
      for (std::size_t y = y0; y < y0 + w; ++y) {
        std::fill_n(occupied.begin() + static_cast<std::ptrdiff_t>(at(x0, y, z)), w, 1);
      }
    }
  });
  // The box-to-box distance between cells dx, dy, dz apart is sqrt(sum max(0, |d| - 1)^2) cells:
  // the centre-to-centre distance to the occupied set grown by one cell in all 26 directions.
  // Grow it one axis at a time.
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? n : n * n;
    std::vector<std::uint8_t> grown(occupied);
    for (std::size_t i = 0; i < total; ++i) {
      if (!occupied[i]) continue;
      const std::size_t c = (i / stride) % n;
      if (c > 0) grown[i - stride] = 1;
      if (c + 1 < n) grown[i + stride] = 1;
    }
    occupied.swap(grown);
  }
  // Squared distances, one axis at a time.
  std::vector<double> d2(total);
  for (std::size_t i = 0; i < total; ++i) d2[i] = occupied[i] ? 0.0 : kFar;
  std::vector<double> line(n), out(n), z;
  std::vector<std::size_t> v;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? n : n * n;
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < n; ++b) {
        const std::size_t base = axis == 0 ? at(0, a, b) : axis == 1 ? at(a, 0, b) : at(a, b, 0);
        for (std::size_t q = 0; q < n; ++q) line[q] = d2[base + q * stride];
        transformLine(line.data(), n, out.data(), v, z);
        for (std::size_t q = 0; q < n; ++q) d2[base + q * stride] = out[q];
      }
    }
  }
  // Round down to quarters of a cell (sqrt of an integer below 2^52 is correctly rounded, so a
  // whole number of quarters is never rounded up past the true distance).
  steps_.resize(total);
  for (std::size_t i = 0; i < total; ++i) {
    const double q = d2[i] >= kFar / 2 ? 255.0 : std::floor(kStepsPerCell * std::sqrt(d2[i]));
    steps_[i] = static_cast<std::uint8_t>(std::min(255.0, q));
  }
}

void ClearanceGrid::addBlack(const VoxelBounds& added) {
  // The cells holding `added`, grown by one cell as the constructor grows occupied cells; each
  // cell's centre-to-centre distance to that box (in cells) bounds its distance to every black
  // voxel there, rounded down to quarters as the constructor rounds.
  const std::int64_t n = static_cast<std::int64_t>(cells_);
  auto cell = [this](std::uint32_t v) { return static_cast<std::int64_t>(v >> level_); };
  const std::int64_t lo[3] = {cell(added.min.x) - 1, cell(added.min.y) - 1, cell(added.min.z) - 1};
  const std::int64_t hi[3] = {cell(added.max.x) + 1, cell(added.max.y) + 1, cell(added.max.z) + 1};
  auto gap = [](std::int64_t c, std::int64_t l, std::int64_t h) {
    const std::int64_t d = c < l ? l - c : c > h ? c - h : 0;
    return static_cast<double>(d * d);
  };
  std::size_t i = 0;
  for (std::int64_t z = 0; z < n; ++z) {
    const double dz = gap(z, lo[2], hi[2]);
    for (std::int64_t y = 0; y < n; ++y) {
      const double dyz = dz + gap(y, lo[1], hi[1]);
      for (std::int64_t x = 0; x < n; ++x, ++i) {
        const double d2 = dyz + gap(x, lo[0], hi[0]);
        const double s = steps_[i];
        if (kStepsPerCell * kStepsPerCell * d2 >= s * s) continue;  // no lower: skip the root
        const double q = std::floor(kStepsPerCell * std::sqrt(d2));
        if (q < s) steps_[i] = static_cast<std::uint8_t>(q);
      }
    }
  }
}

}  // namespace octomotion
