// Lower-bound tables of self-pair distances (docs/validation.md §4), for the certified motion
// validator (ompl/certified_motion_validator.h).
//
// A checked self pair whose relative pose depends on at most two variables (its pair levers,
// LinkMotionBound::pairLever, are non-zero for at most two: on a serial arm, the links of a
// wrist) has a distance d that is a function of those variables alone, and that is Lipschitz
// in them: along a straight-line motion it changes by at most sum_v pairLever(p, v) |dq_v|
// (LinkMotionBound::pairBound). Over a grid of those variables' ranges, a cell whose centre c has
// the distance bound d(c) therefore keeps the pair at least d(c) - sum_v pairLever(p, v) h_v
// apart at every configuration in it (h_v: the cell's half-width, from c to its farthest point
// along v). The table holds, per cell, the largest such bound over the cells' centres evaluated
// (a quadtree: coarse cells first, each split while its bound is not positive, down to the
// finest; one whose centre is in contact only down to a few cells), clamped at 0. A lookup is O(1);
// a straight-line motion's bound is the least over the cells its projection crosses.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "octomotion/planner/robot/motion_bound.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

class PairDistanceTable {
 public:
  // A lower bound (>= 0) on the distance between the geometry of pair p's links with the robot
  // at q (variableCount() values), or `cap` when that bound is at least `cap`.
  using Distance = std::function<double(std::size_t pair, const double* q, double cap)>;
  // Cells per variable at the finest level (2^kFineLog2), and at the coarsest (2^kCoarseLog2).
  static constexpr int kFineLog2 = 7;
  static constexpr int kCoarseLog2 = 4;

  // Tables for the pairs of `bound` (a fixed-base robot's) with one or two variables of
  // non-zero pair lever, each bounded (lower < upper); `distance` is called at cells' centres,
  // the other variables within their limits.
  PairDistanceTable(const RobotModel& robot, const LinkMotionBound& bound,
                    const Distance& distance);

  bool covers(std::size_t p) const { return p < index_.size() && index_[p] >= 0; }
  std::size_t tableCount() const { return tables_.size(); }
  // How many times `distance` was called to build the tables.
  std::size_t distanceCalls() const { return distance_calls_; }
  // A lower bound (>= 0) on pair p's distance at q; 0 when p has no table or q is outside its
  // variables' ranges.
  double at(std::size_t p, const double* q) const;
  // A lower bound (>= 0) on pair p's distance over the motion q1 + (q2 - q1) t, t in [a, b]
  // (within [0, 1]): the least over the cells its projection crosses; 0 when p has no table or
  // the motion leaves the ranges. Stops at the first cell not above `enough` (its value, or
  // less, is returned then).
  double along(std::size_t p, const double* q1, const double* q2, double a, double b,
               double enough = 0.0) const;

 private:
  // Cells of one resolution: per cell, a lower bound on the pair's distance over it.
  struct Grid {
    int cells[2] = {1, 1};
    double width[2] = {1, 1};  // a cell's width along each variable
    std::vector<float> bound;  // cells[0] x cells[1], the first variable fastest
  };
  struct Table {
    int dims = 0;              // 1 or 2
    int var[2] = {-1, -1};     // the variables
    double lower[2] = {0, 0};  // their ranges' lower ends
    Grid fine, coarse;  // coarse: kCoarseLog2 cells per variable, the least of its fine cells
  };
  // Cell index of x along axis k of `grid`, or -1 when outside the range (beyond rounding).
  static int cellOf(const Table& t, const Grid& grid, int k, double x);
  // along() on one grid.
  static double walk(const Table& t, const Grid& grid, const double* q1, const double* q2, double a,
                     double b, double enough);
  std::vector<int> index_;  // per pair: its table, or -1
  std::vector<Table> tables_;
  std::size_t distance_calls_ = 0;
};

}  // namespace octomotion
