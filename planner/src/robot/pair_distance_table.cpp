#include "octomotion/planner/robot/pair_distance_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace octomotion {
namespace {

// How far beyond a cell (a fraction of the variable's range) its bound still holds: a point a
// rounding error outside the cell it is looked up in stays covered.
constexpr double kSlack = 1e-9;
// The smallest node (in fine cells along a variable) split though its centre is in contact.
constexpr int kContactCells = 4;

float roundedDown(double value) {
  const double v = std::max(value, 0.0);
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, 0.0f);
  return f;
}

}  // namespace

PairDistanceTable::PairDistanceTable(const RobotModel& robot, const LinkMotionBound& bound,
                                     const Distance& distance) {
  const std::size_t pairs = bound.pairs().size();
  const int n = bound.variableCount();
  index_.assign(pairs, -1);
  std::vector<double> q(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    const Variable& var = robot.variables()[static_cast<std::size_t>(v)];
    q[static_cast<std::size_t>(v)] = std::clamp(0.0, var.lower, var.upper);
  }
  for (std::size_t p = 0; p < pairs; ++p) {
    std::vector<int> vars;
    for (int v = 0; v < n; ++v) {
      if (bound.pairLever(p, v) > 0) vars.push_back(v);
    }
    if (vars.empty() || vars.size() > 2) continue;
    Table t;
    t.dims = static_cast<int>(vars.size());
    double lever[2] = {0, 0}, slack[2] = {0, 0};
    bool bounded = true;
    for (int k = 0; k < t.dims; ++k) {
      const Variable& var = robot.variables()[static_cast<std::size_t>(vars[k])];
      const double range = var.upper - var.lower;
      bounded = bounded && std::isfinite(range) && range > 0;
      t.var[k] = vars[k];
      t.lower[k] = var.lower;
      t.fine.cells[k] = 1 << kFineLog2;
      t.fine.width[k] = range / t.fine.cells[k];
      t.coarse.cells[k] = 1 << kCoarseLog2;
      t.coarse.width[k] = range / t.coarse.cells[k];
      lever[k] = bound.pairLever(p, vars[k]);
      slack[k] = kSlack * range;
    }
    if (!bounded) continue;
    Grid& fine = t.fine;
    const auto cells0 = static_cast<std::size_t>(fine.cells[0]);
    std::vector<double> best(cells0 * static_cast<std::size_t>(t.fine.cells[1]), 0.0);
    // Quadtree nodes (binary along one variable): the first cell along each variable and the
    // node's width in cells (1 along a missing second variable).
    struct Node {
      int first[2];
      int size;
    };
    std::vector<Node> todo;
    const int coarse = 1 << (kFineLog2 - kCoarseLog2);
    for (int i = 0; i < t.fine.cells[0]; i += coarse) {
      for (int j = 0; j < t.fine.cells[1]; j += (t.dims == 2 ? coarse : 1))
        todo.push_back({{i, j}, coarse});
    }
    while (!todo.empty()) {
      const Node node = todo.back();
      todo.pop_back();
      const int size[2] = {node.size, t.dims == 2 ? node.size : 1};
      double centre[2] = {0, 0};  // from the range's lower end
      for (int k = 0; k < t.dims; ++k) {
        centre[k] = (node.first[k] + 0.5 * size[k]) * t.fine.width[k];
        q[static_cast<std::size_t>(t.var[k])] = t.lower[k] + centre[k];
      }
      // Asked up to twice the node's reach: a node at least that far proves each of its cells
      // at least its reach apart, which is all a proof over a cell needs.
      double reach = 0.0;
      for (int k = 0; k < t.dims; ++k)
        reach += lever[k] * (0.5 * size[k] * t.fine.width[k] + slack[k]);
      const double d = distance(p, q.data(), 2 * reach);
      ++distance_calls_;
      // Each cell of the node: d less the levers times the farthest it reaches from the centre.
      for (int j = node.first[1]; j < node.first[1] + size[1]; ++j) {
        for (int i = node.first[0]; i < node.first[0] + size[0]; ++i) {
          const int cell[2] = {i, j};
          double lb = d;
          for (int k = 0; k < t.dims; ++k) {
            lb -= lever[k] * (std::abs((cell[k] + 0.5) * t.fine.width[k] - centre[k]) +
                              0.5 * t.fine.width[k] + slack[k]);
          }
          double& b = best[static_cast<std::size_t>(j) * cells0 + static_cast<std::size_t>(i)];
          b = std::max(b, lb);
        }
      }
      const double node_lb = d - reach;
      // A node whose centre is in contact is split only down to kContactCells: its cells near
      // the contact's edge keep a bound of 0 there (the validator then measures distances).
      if (node_lb > 0 || node.size == 1 || (d <= 0 && node.size <= kContactCells)) continue;
      const int half = node.size / 2;
      for (int di = 0; di < 2; ++di) {
        for (int dj = 0; dj < (t.dims == 2 ? 2 : 1); ++dj) {
          todo.push_back({{node.first[0] + di * half, node.first[1] + dj * half}, half});
        }
      }
    }
    fine.bound.resize(best.size());
    std::transform(best.begin(), best.end(), fine.bound.begin(), roundedDown);
    // The coarse grid: each cell the least of the fine cells it holds.
    Grid& coarse_grid = t.coarse;
    coarse_grid.bound.assign(static_cast<std::size_t>(coarse_grid.cells[0]) *
                                 static_cast<std::size_t>(coarse_grid.cells[1]),
                             std::numeric_limits<float>::infinity());
    const int per[2] = {fine.cells[0] / coarse_grid.cells[0], fine.cells[1] / coarse_grid.cells[1]};
    for (int j = 0; j < fine.cells[1]; ++j) {
      for (int i = 0; i < fine.cells[0]; ++i) {
        float& c = coarse_grid.bound[static_cast<std::size_t>(j / per[1]) *
                                         static_cast<std::size_t>(coarse_grid.cells[0]) +
                                     static_cast<std::size_t>(i / per[0])];
        c = std::min(
            c, fine.bound[static_cast<std::size_t>(j) * cells0 + static_cast<std::size_t>(i)]);
      }
    }
    index_[p] = static_cast<int>(tables_.size());
    tables_.push_back(std::move(t));
  }
}

int PairDistanceTable::cellOf(const Table& t, const Grid& grid, int k, double x) {
  const double u = (x - t.lower[k]) / grid.width[k];
  const double slack = kSlack * grid.cells[k];
  if (!(u >= -slack && u <= grid.cells[k] + slack)) return -1;  // NaN too
  return std::clamp(static_cast<int>(std::floor(u)), 0, grid.cells[k] - 1);
}

double PairDistanceTable::at(std::size_t p, const double* q) const {
  if (!covers(p)) return 0.0;
  const Table& t = tables_[static_cast<std::size_t>(index_[p])];
  int cell[2] = {0, 0};
  for (int k = 0; k < t.dims; ++k) {
    cell[k] = cellOf(t, t.fine, k, q[t.var[k]]);
    if (cell[k] < 0) return 0.0;
  }
  return t.fine
      .bound[static_cast<std::size_t>(cell[1]) * static_cast<std::size_t>(t.fine.cells[0]) +
             static_cast<std::size_t>(cell[0])];
}

double PairDistanceTable::along(std::size_t p, const double* q1, const double* q2, double a,
                                double b, double enough) const {
  if (!covers(p)) return 0.0;
  const Table& t = tables_[static_cast<std::size_t>(index_[p])];
  // The coarse cells first (fewer, each the least of its fine ones): most motions far from
  // contact are settled there.
  const double coarse = walk(t, t.coarse, q1, q2, a, b, enough);
  if (coarse > enough) return coarse;
  return walk(t, t.fine, q1, q2, a, b, enough);
}

double PairDistanceTable::walk(const Table& t, const Grid& grid, const double* q1, const double* q2,
                               double a, double b, double enough) {
  auto coordinate = [&](int k, double s) {
    const int v = t.var[k];
    return q1[v] + (q2[v] - q1[v]) * s;  // as the validator interpolates
  };
  // Pieces short enough to span at most two cells along each variable: each lies in the box of
  // its ends (a straight segment), which the cells from its least to its largest corner hold.
  double pieces = 1.0;
  for (int k = 0; k < t.dims; ++k) {
    pieces =
        std::max(pieces, std::ceil(std::abs(coordinate(k, b) - coordinate(k, a)) / grid.width[k]));
  }
  if (!(pieces <= 4.0 * (1 << kFineLog2))) return 0.0;  // not finite
  const int count = static_cast<int>(pieces);
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double s0 = a + (b - a) * i / count;
    const double s1 = i + 1 == count ? b : a + (b - a) * (i + 1) / count;
    int lo[2] = {0, 0}, hi[2] = {0, 0};
    for (int k = 0; k < t.dims; ++k) {
      const double x0 = coordinate(k, s0), x1 = coordinate(k, s1);
      lo[k] = cellOf(t, grid, k, std::min(x0, x1));
      hi[k] = cellOf(t, grid, k, std::max(x0, x1));
      if (lo[k] < 0 || hi[k] < 0) return 0.0;
    }
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int c = lo[0]; c <= hi[0]; ++c) {
        least = std::min<double>(
            least,
            grid.bound[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.cells[0]) +
                       static_cast<std::size_t>(c)]);
        if (least <= enough) return least;
      }
    }
  }
  return least;
}

}  // namespace octomotion
