// The certified motion validator's per-thread working memory (certified_motion_validator.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <ompl/base/StateSpace.h>
#include <Eigen/Geometry>

#include "octomotion/planner/ompl/certified_motion_validator.h"

namespace octomotion {

// The validator's counts, shared by the threads that check edges.
struct CertifiedMotionValidator::AtomicCounts {
  struct Edges {
    std::atomic<std::size_t> edges{0}, screen_checks{0}, proof_checks{0}, clearance_states{0},
        pair_distances{0}, table_pairs{0}, depth{0}, nanoseconds{0}, micrometres{0};
  };
  Edges accepted, rejected;
  std::atomic<std::size_t> rejected_by_screen{0}, remembered_ends{0};
};

// One thread's working memory, rebuilt when the thread turns to another backend; kept between
// edges so that checking one allocates nothing once the vectors have grown.
struct CertifiedMotionValidator::Scratch {
  // An interval [a, b] of the edge: its ends' slots (their clearances and pair distances); the
  // end b may be known invalid (only while looking for the last valid state); the active links
  // and pairs already proven over it (bit k: the k-th active one).
  struct Interval {
    double a, b;
    std::size_t slot_a, slot_b;
    bool b_valid;
    std::uint64_t links_done, pairs_done;
  };
  std::uint64_t owner = 0;
  std::unique_ptr<BackendScratch> backend;
  RobotData data;  // link poses for backends that keep none (posedRobot)
  std::vector<double> q, q1, q2, dq;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB1 = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB2 = Eigen::Isometry3d::Identity();
  std::vector<double> link_bound, pair_bound, caps;  // per link, per pair, per link
  std::vector<std::size_t> active_links;
  std::vector<std::size_t> active_pairs;
  std::vector<double> clearance, distance;  // per evaluated state: per link, per pair
  // Fixed-base robots, the posed bounds (LinkMotionBound): the edge's terms; per evaluated state,
  // the rates and speeds of the links and pairs it was evaluated for (+inf for the others); the
  // arms of the state at hand and, per link, whether they are computed.
  LinkMotionBound::EdgeTerms terms;
  std::vector<double> link_rate, pair_rate, link_speed, pair_speed, arms;
  std::vector<char> armed;
  // The state's speed sums (LinkMotionBound::speedSums) and, per link, whether they are made.
  std::vector<double> speed_sums;
  std::vector<char> summed;
  // Sets a slot's rates at the pose `posed`: of every active link and pair at an end (`in`
  // null; every link's arms computed, or already in `arms` when `posed` is null), else of those
  // not proven over the interval `in` it halves (all that its halves' descendants test).
  void setRates(const LinkMotionBound& bound, const RobotData* posed, std::size_t slot,
                std::size_t stride, const Interval* in);
  // Link (pair) i's posed bound over a part of length s whose ends are evaluated in slots a and
  // b: the smaller of the rates' and the speeds' (each from the end where it is smaller); +inf
  // when neither end has them.
  double posedBound(bool pair, std::size_t i, double s, std::size_t a, std::size_t b,
                    std::size_t stride, std::size_t pairs) const {
    const std::vector<double>& rate = pair ? pair_rate : link_rate;
    const std::vector<double>& speed = pair ? pair_speed : link_speed;
    const std::size_t width = pair ? pairs : stride;
    const double r = std::min(rate[a * width + i], rate[b * width + i]);
    const double v = std::min(speed[a * width + i], speed[b * width + i]);
    const double growth = pair ? terms.pair_growth[i] : terms.link_growth[i];
    const double speed_growth = pair ? terms.pair_speed_growth[i] : terms.link_speed_growth[i];
    return std::min(r * s + 0.5 * growth * s * s, v * s + 0.5 * speed_growth * s * s);
  }
  // Exact answers on fixed-base robots: per link, the nearest obstacles' slabs of the state at
  // hand (CollisionBackend::motionClearances); per evaluated state and link, kNear values: the
  // slabs' gaps (NaN: none), the others' bound, the slabs' directions (3 each), and how fast the
  // link approaches each slab's object along it as the edge runs forwards and backwards
  // (LinkMotionBound::linkApproach). An end is remembered with the first kNearKept.
  static constexpr std::size_t kSlabs = NearestObstacle::kSlabs;
  static constexpr std::size_t kNearKept = 1 + kSlabs * 4;
  static constexpr std::size_t kNear = kNearKept + 2 * kSlabs;
  std::vector<NearestObstacle> nearest;
  std::vector<double> link_near;  // its slots beyond the evaluated states' are stale
  bool slabs = false;             // the edge at hand uses them
  // A new slot without slabs (its other values are written with its slabs).
  void clearSlabs(std::size_t slot, std::size_t stride) {
    const std::size_t end = (slot + 1) * stride * kNear;
    if (link_near.size() < end) link_near.resize(end);
    for (std::size_t l = 0; l < stride; ++l) {
      link_near[(slot * stride + l) * kNear] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  // Fills a slot's slab values from `nearest` for the active links not proven over `in` (null:
  // every active link), with the rates from the speed sums setRates made for the slot.
  void setSlabs(const LinkMotionBound& bound, std::size_t slot, std::size_t stride,
                const Interval* in);
  // Whether link i is free over `in`, whose ends have the clearances ca and cb: the part of `in`
  // from each end over which no point can reach the clearance (the posed bounds), or, with a
  // slab, over which the link neither crosses the slab nor reaches the other objects, covers
  // `in` (docs/validation.md §4).
  bool provenBySlabs(std::size_t i, const Interval& in, double ca, double cb,
                     std::size_t stride) const {
    return stretch(i, in.slot_a, true, ca, stride) + stretch(i, in.slot_b, false, cb, stride) >
           in.b - in.a;
  }
  // The part of an edge, from the end in `slot` (forwards: towards the edge's end), over which
  // link i is proven free.
  double stretch(std::size_t i, std::size_t slot, bool forwards, double clear,
                 std::size_t stride) const;
  std::vector<Interval> todo;
  // The link poses of the states the collision screen found free, by k for t = k / 2^levels
  // (posed[k] when held), so a proof's evaluation there poses the robot without forward
  // kinematics (CollisionBackend::setPosed).
  std::vector<RobotData> screen_poses;
  std::vector<char> screen_posed;
  // Keeps the poses of the state at t_edge, screened at `levels`.
  void keepScreenPose(double t_edge, int levels, const RobotData& posed) {
    const std::size_t k = screenIndex(t_edge, levels);
    screen_poses[k] = posed;
    screen_posed[k] = 1;
  }
  // The screen's poses of the state at t_edge (screened at `levels`), or null.
  const RobotData* screenPose(double t_edge, int levels) const {
    const std::size_t k = screenIndex(t_edge, levels);
    return k < screen_posed.size() && screen_posed[k] ? &screen_poses[k] : nullptr;
  }
  static std::size_t screenIndex(double t_edge, int levels) {
    return static_cast<std::size_t>(std::ldexp(t_edge, levels));
  }
  // Valid ends checked before (direct-mapped by a hash of the configuration): the values of the
  // links and pairs active then, NaN for the others. Each was found free for every link and
  // pair: those its edge moved by their values or a check, the others at the edge's other end,
  // which was checked in full (or remembered).
  struct Remembered {
    std::uint64_t validator = 0;
    // near: per link, the first kNearKept of the slot's kNear values.
    std::vector<double> key, clearance, distance, arms, near;
    // It holds the end of this key, remembered by this validator.
    bool holds(std::uint64_t by, const std::vector<double>& end_key) const {
      return validator == by && key == end_key;
    }
  };
  static constexpr std::size_t kRemembered = 64;
  std::array<Remembered, kRemembered> remembered;
  std::vector<double> key;
  // The place of an edge's end (q1 or q2, with X_WB1 or X_WB2 for a free-flying robot) among
  // the remembered ends, its key in `key`: it is remembered when the place holds that key.
  Remembered& rememberedPlace(bool at_start, bool free_flying);
  // Keeps the slab values of the end in `slot` with it, or restores them into the slot (the
  // rates from the slot's speed sums).
  void keepSlabs(Remembered& r, std::size_t slot, std::size_t stride) const;
  void restoreSlabs(const LinkMotionBound& bound, const Remembered& r, std::size_t slot,
                    std::size_t stride);
  // Free-flying robots: an OMPL state for the interpolated ones (the space kept alive with it).
  ompl::base::StateSpacePtr space;
  ompl::base::State* state = nullptr;

  Scratch() = default;
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() { release(); }
  void useSpace(const ompl::base::StateSpacePtr& s) {
    if (space == s && state) return;
    release();
    space = s;
    state = space->allocState();
  }
  void release() {
    if (state) space->freeState(state);
    state = nullptr;
  }
};

}  // namespace octomotion
