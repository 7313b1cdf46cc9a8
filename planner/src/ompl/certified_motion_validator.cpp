#include "octomotion/planner/ompl/certified_motion_validator.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <vector>

#include "internal/certified_scratch.h"
#include "octomotion/error.h"
#include "octomotion/planner/ompl/state_space.h"

namespace octomotion {

namespace ob = ompl::base;

namespace {

std::uint64_t nextSerial() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

// The work of the edge at hand on this thread, added to the validator's counts when it ends.
struct EdgeTally {
  std::size_t screen_checks = 0, proof_checks = 0, clearance_states = 0, pair_distances = 0;
  std::size_t depth = 0, remembered_ends = 0, table_pairs = 0;
  double travel = 0.0;
  bool screened_out = false;
};
thread_local EdgeTally tally;

}  // namespace

void CertifiedMotionValidator::setScreenLevels(int levels) {
  if (levels < 0 || levels > 16) {
    throw InvalidArgument("CertifiedMotionValidator: the screen's levels must be within 0..16");
  }
  screen_levels_ = levels;
}

CertifiedMotionValidator::CertifiedMotionValidator(const ob::SpaceInformationPtr& si,
                                                   std::shared_ptr<const CollisionBackend> backend,
                                                   std::shared_ptr<const LinkMotionBound> bound,
                                                   double resolution)
    : ob::MotionValidator(si),
      backend_(std::move(backend)),
      bound_(std::move(bound)),
      resolution_(resolution),
      serial_(nextSerial()),
      counts_(std::make_shared<AtomicCounts>()) {
  if (!backend_) throw InvalidArgument("CertifiedMotionValidator: no collision backend");
  if (!bound_) throw InvalidArgument("CertifiedMotionValidator: no motion bound");
  const RobotModel& robot = backend_->robot();
  if (bound_->linkCount() != robot.linkCount() ||
      bound_->variableCount() != robot.variableCount()) {
    throw InvalidArgument("CertifiedMotionValidator: the motion bound was made for another robot");
  }
  if (!(resolution_ > 0) || !std::isfinite(resolution_)) {
    throw InvalidArgument("CertifiedMotionValidator: the resolution must be positive and finite");
  }
  if (bound_->pairs() != robot.checkedPairs()) {
    throw InvalidArgument(
        "CertifiedMotionValidator: the motion bound was made before the robot's self pairs "
        "changed");
  }
  // Exact answers on a fixed-base arm: the self pairs' distance table, from the backend's own
  // pair distances (exact for such backends) at the cells' centres. It is optional: a backend
  // that cannot pose or measure leaves the validator without it.
  if (!robot.isFreeFlying() && backend_->exactAnswers()) {
    try {
      std::unique_ptr<BackendScratch> scratch = backend_->makeBackendScratch();
      const auto n = static_cast<std::size_t>(robot.variableCount());
      const std::vector<std::pair<int, int>>& pairs = bound_->pairs();
      pair_table_ = std::make_shared<const PairDistanceTable>(
          robot, *bound_, [&](std::size_t p, const double* q, double cap) {
            backend_->setPose(q, n, Eigen::Isometry3d::Identity(), *scratch);
            return backend_->linkPairDistance(*scratch, pairs[p].first, pairs[p].second, cap);
          });
      pair_table_owner_ = backend_->id();
    } catch (const std::exception&) {
      pair_table_.reset();
    }
  }
}

double CertifiedMotionValidator::motionBound(const ob::State* s1, const ob::State* s2) const {
  const RobotModel& robot = backend_->robot();
  const auto n = static_cast<std::size_t>(robot.variableCount());
  std::vector<double> q1(n), q2(n);  // stateToConfiguration fills them to their size
  Eigen::Isometry3d X1, X2;
  if (!stateToConfiguration(robot, s1, q1, X1) || !stateToConfiguration(robot, s2, q2, X2)) {
    return std::numeric_limits<double>::infinity();
  }
  for (std::size_t i = 0; i < q1.size(); ++i) q2[i] -= q1[i];
  if (!robot.isFreeFlying()) return bound_->maxBound(q2.data());
  const LinkMotionBound::RootMotion root(X1, X2);
  double bound = 0.0;
  for (int l : bound_->geometryLinks()) {
    bound = std::max(bound, bound_->freeFlyingBound(l, root) + bound_->linkBound(l, q2.data()));
  }
  return bound;
}

void CertifiedMotionValidator::countMotion(bool free,
                                           std::chrono::steady_clock::time_point start) const {
  // OMPL's counters are plain members, but checkMotion is const and may run on several threads
  // (parallel planners), so the increments are atomic.
  __atomic_fetch_add(free ? &valid_ : &invalid_, 1u, __ATOMIC_RELAXED);
  const auto ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count();
  AtomicCounts::Edges& e = free ? counts_->accepted : counts_->rejected;
  constexpr auto relaxed = std::memory_order_relaxed;
  e.edges.fetch_add(1, relaxed);
  e.screen_checks.fetch_add(tally.screen_checks, relaxed);
  e.proof_checks.fetch_add(tally.proof_checks, relaxed);
  e.clearance_states.fetch_add(tally.clearance_states, relaxed);
  e.pair_distances.fetch_add(tally.pair_distances, relaxed);
  e.table_pairs.fetch_add(tally.table_pairs, relaxed);
  e.depth.fetch_add(tally.depth, relaxed);
  if (std::isfinite(tally.travel)) {
    e.micrometres.fetch_add(static_cast<std::size_t>(tally.travel * 1e6), relaxed);
  }
  e.nanoseconds.fetch_add(static_cast<std::size_t>(std::max<std::int64_t>(ns, 0)), relaxed);
  if (tally.screened_out) counts_->rejected_by_screen.fetch_add(1, relaxed);
  counts_->remembered_ends.fetch_add(tally.remembered_ends, relaxed);
}

bool CertifiedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const auto start = std::chrono::steady_clock::now();
  tally = {};
  double last_valid = 0.0;
  const bool free = check(s1, s2, false, last_valid);
  countMotion(free, start);
  return free;
}

bool CertifiedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                           std::pair<ob::State*, double>& lastValid) const {
  const auto start = std::chrono::steady_clock::now();
  tally = {};
  double last_valid = 0.0;
  const bool free = check(s1, s2, true, last_valid);
  countMotion(free, start);
  if (free) return true;
  lastValid.second = last_valid;
  if (lastValid.first) si_->getStateSpace()->interpolate(s1, s2, last_valid, lastValid.first);
  return false;
}

bool CertifiedMotionValidator::check(const ob::State* s1, const ob::State* s2, bool want_last,
                                     double& last_valid) const {
  const CollisionBackend& backend = *backend_;
  const RobotModel& robot = backend.robot();
  using Interval = Scratch::Interval;
  thread_local Scratch t;
  if (t.owner != backend.id()) {
    t.backend = backend.makeBackendScratch();
    t.data = robot.makeData();
    t.owner = backend.id();
  }
  // stateToConfiguration fills q to its size.
  const auto n = static_cast<std::size_t>(robot.variableCount());
  const auto links = static_cast<std::size_t>(robot.linkCount());
  const std::size_t pairs = bound_->pairs().size();
  t.q.resize(n);
  t.q1.resize(n);
  t.q2.resize(n);
  t.dq.resize(n);
  last_valid = 0.0;
  if (!stateToConfiguration(robot, s1, t.q1, t.X_WB1) ||
      !stateToConfiguration(robot, s2, t.q2, t.X_WB2)) {
    return false;
  }
  // Each link's path-length bound over the whole edge, and each pair's relative one; an
  // interval's is this times its length (the interpolation is linear in q, and for SE(3) in
  // translation and in angle about one axis of the root frame). Only links and pairs whose bound
  // exceeds what the ends decide need more than the ends ("active"); a link no joint moves
  // never does.
  for (std::size_t i = 0; i < n; ++i) t.dq[i] = t.q2[i] - t.q1[i];
  const bool free_flying = robot.isFreeFlying();
  const LinkMotionBound::RootMotion root =
      free_flying ? LinkMotionBound::RootMotion(t.X_WB1, t.X_WB2) : LinkMotionBound::RootMotion();
  // Voxel answers carry a margin: a link or pair whose bound over an interval is at most the
  // resolution is decided by its valid ends. Exact answers carry none: only clearances prove.
  const bool has_clearance = backend.clearanceBound() != ClearanceBound::kNone;
  const bool exact = has_clearance && backend.exactAnswers();
  const double decided_by_ends = exact ? 0.0 : resolution_;
  t.link_bound.assign(links, 0.0);
  t.active_links.clear();
  double max_bound = 0.0, max_link = 0.0, max_pair = 0.0;
  for (int l : bound_->geometryLinks()) {
    const double b =
        (free_flying ? bound_->freeFlyingBound(l, root) : 0.0) + bound_->linkBound(l, t.dq.data());
    if (!std::isfinite(b)) return false;
    t.link_bound[static_cast<std::size_t>(l)] = b;
    if (b > decided_by_ends) t.active_links.push_back(static_cast<std::size_t>(l));
    max_link = std::max(max_link, b);
  }
  t.pair_bound.assign(pairs, 0.0);
  t.active_pairs.clear();
  for (std::size_t p = 0; p < pairs; ++p) {
    const double b = bound_->pairBound(p, t.dq.data());
    if (!std::isfinite(b)) return false;
    t.pair_bound[p] = b;
    if (b > decided_by_ends) t.active_pairs.push_back(p);
    max_pair = std::max(max_pair, b);
  }
  const PairDistanceTable* table = robot.isFreeFlying() ? nullptr : pairTable();
  max_bound = std::max(max_link, max_pair);
  tally.travel = max_bound;
  // Exact answers: the travel below which an unproven interval rejects the edge.
  const double min_travel = resolution_ * kExactMinTravel;
  t.caps.assign(links, 0.0);
  const bool direct = !robot.isFreeFlying();  // q(t) without OMPL's interpolation
  // Fixed-base robots: bounds from the poses at an interval's ends (LinkMotionBound's posed
  // bounds), tighter than the edge's where the arm is not stretched.
  const std::size_t arm_count = direct ? bound_->armCount() : 0;
  t.arms.resize(arm_count * LinkMotionBound::kArmValues);
  t.link_rate.clear();
  t.pair_rate.clear();
  t.link_speed.clear();
  t.pair_speed.clear();
  // Exact answers on fixed-base robots: the nearest obstacles' slabs prove links too.
  const bool slabs = t.slabs = exact && arm_count > 0;
  t.nearest.resize(links);
  constexpr double kNoRate = std::numeric_limits<double>::infinity();
  const ob::SpaceInformation* si = si_;
  if (!direct) t.useSpace(si->getStateSpace());
  const std::size_t stride = std::max<std::size_t>(links, 1);
  // What an evaluated state's (in `slot`) clearance (distance) of the k-th active link (pair) i
  // must reach, above which it decides nothing more: capped there, so the grid, the hulls and FCL
  // stop early. At an end (no interval), kEndCapShare of the edge's bound from it. At the
  // midpoint of [a, b], enough to prove both halves at once, each half's bound less the value at
  // its outer end, plus a 512th of the half's bound; 0 (not computed) for one already proven over
  // [a, b]. A half's bound is the edge's, or the posed bounds from its ends (Scratch::posedBound).
  // Link (pair) i's bound over a part of length s of the edge: the edge's times s, or less,
  // the posed bounds from the ends (slots) of the part.
  auto boundOver = [&](bool pair, std::size_t i, double s, std::size_t slot_a, std::size_t slot_b) {
    const double whole = (pair ? t.pair_bound[i] : t.link_bound[i]) * s;
    if (arm_count == 0) return whole;
    return std::min(whole, t.posedBound(pair, i, s, slot_a, slot_b, stride, pairs));
  };
  auto capOf = [&](const Scratch::Interval* in, std::size_t slot, std::size_t k, std::size_t i,
                   bool pair) {
    if (!in) return kEndCapShare * boundOver(pair, i, 1.0, slot, slot);
    if (k < 64 && ((pair ? in->pairs_done : in->links_done) >> k & 1)) return 0.0;
    const std::vector<double>& values = pair ? t.distance : t.clearance;
    const std::size_t width = pair ? pairs : stride;
    const double h = 0.5 * (in->b - in->a);
    double need = 0.0, most = 0.0;
    for (const std::size_t end : {in->slot_a, in->slot_b}) {
      const double half = boundOver(pair, i, h, slot, end);
      need = std::max(need, half - values[end * width + i]);
      most = std::max(most, half);
    }
    return need + most / 512;
  };
  t.clearance.clear();
  t.distance.clear();

  // The screen's levels when it passed (every state at t = k / 2^levels, and s2, was found free
  // by the checker), -1 when it did not run.
  int screened_levels = -1;
  // s2 was found free for every link and pair: by the screen, or before (a remembered end).
  bool s2_in_full = false;
  auto screenedFree = [&](double t_edge) {
    if (screened_levels < 0 || t_edge == 0.0) return false;
    const double k = std::ldexp(t_edge, screened_levels);
    return k == std::floor(k);
  };
  // The configuration at t_edge into t.q (and t.X_WB); false when it is out of bounds.
  auto place = [&](double t_edge) {
    if (direct) {
      const ob::State* s = t_edge == 0.0 ? s1 : t_edge == 1.0 ? s2 : nullptr;
      if (s) {
        if (!si->satisfiesBounds(s)) return false;
        t.q = t_edge == 0.0 ? t.q1 : t.q2;
      } else {
        // RealVectorStateSpace::interpolate's own expression; within the bounds between two
        // states that are.
        for (std::size_t i = 0; i < n; ++i) t.q[i] = t.q1[i] + (t.q2[i] - t.q1[i]) * t_edge;
      }
    } else {
      const ob::State* s = t_edge == 0.0 ? s1 : t_edge == 1.0 ? s2 : t.state;
      if (s == t.state) si->getStateSpace()->interpolate(s1, s2, t_edge, t.state);
      if (!si->satisfiesBounds(s) || !stateToConfiguration(robot, s, t.q, t.X_WB)) return false;
    }
    return true;
  };
  // A new evaluated state's slot: its values 0 (an invalid state's stay so), no rates yet.
  auto newSlot = [&] {
    const std::size_t slot = t.clearance.size() / stride;
    t.clearance.resize(t.clearance.size() + stride, 0.0);
    t.distance.resize(t.distance.size() + pairs, 0.0);
    if (arm_count > 0) {
      t.link_rate.resize(t.link_rate.size() + stride, kNoRate);
      t.pair_rate.resize(t.pair_rate.size() + pairs, kNoRate);
      t.link_speed.resize(t.link_speed.size() + stride, kNoRate);
      t.pair_speed.resize(t.pair_speed.size() + pairs, kNoRate);
    }
    if (slabs) t.clearSlabs(slot, stride);
    return slot;
  };
  // A proof's collision check of the state in t.q, of the halves asked (one at least).
  auto proofCollides = [&](bool environment, bool self) {
    (environment ? state_checks_ : self_checks_).fetch_add(1, std::memory_order_relaxed);
    ++tally.proof_checks;
    BackendScratch& scratch = *t.backend;
    return environment && self ? backend.inCollision(t.q.data(), n, t.X_WB, scratch)
           : environment       ? backend.environmentInCollision(t.q.data(), n, t.X_WB, scratch)
                               : backend.selfInCollision(t.q.data(), n, t.X_WB, scratch);
  };
  // Checks the state at t_edge into a new slot: the environment and/or the self pairs, then
  // the active links' clearances and the active pairs' distances when asked.
  // A slot's values stay 0 when its state is invalid.
  auto evaluate = [&](double t_edge, const Scratch::Interval* in, bool environment, bool self,
                      bool clearances, bool distances, std::size_t& slot) {
    slot = newSlot();
    if (!place(t_edge)) return false;
    BackendScratch& scratch = *t.backend;
    // Exact answers: a positive clearance (distance) is the link's (pair's) exact verdict, so
    // the values come first and the collision check runs only for a half they leave open. At s1
    // only when s2 was checked in full: the links and pairs the edge does not move are as there.
    const bool screened = screenedFree(t_edge);
    const bool values_first = exact && (t_edge != 0.0 || s2_in_full) && !screened;
    if (screened || values_first) {
      const RobotData* kept = screened ? t.screenPose(t_edge, screened_levels) : nullptr;
      if (!kept || !backend.setPosed(*kept, scratch)) {
        backend.setPose(t.q.data(), n, t.X_WB, scratch);  // its clearances only
      }
    } else if (proofCollides(environment, self)) {
      return false;
    }
    const RobotData* posed = nullptr;
    auto pose = [&] {
      if (posed) return;
      posed = backend.posedRobot(scratch);
      if (posed) return;
      robot.forwardKinematics(t.q.data(), n, t.data,
                              robot.isFreeFlying() ? t.X_WB : Eigen::Isometry3d::Identity());
      posed = &t.data;
    };
    if (arm_count > 0) {
      pose();
      t.setRates(*bound_, posed, slot, stride, in);
    }
    if (environment && clearances && has_clearance) {
      for (std::size_t k = 0; k < t.active_links.size(); ++k) {
        const std::size_t l = t.active_links[k];
        t.caps[l] = capOf(in, slot, k, l, false);
      }
      backend.motionClearances(scratch, t.caps.data(), t.clearance.data() + slot * stride,
                               slabs ? t.nearest.data() : nullptr);
      if (slabs) t.setSlabs(*bound_, slot, stride, in);
      ++tally.clearance_states;
    }
    if (self && distances && !t.active_pairs.empty()) {
      pose();
      double* d = t.distance.data() + slot * pairs;
      for (std::size_t k = 0; k < t.active_pairs.size(); ++k) {
        const std::size_t p = t.active_pairs[k];
        const double cap = capOf(in, slot, k, p, true);
        if (cap <= 0) continue;
        // The table's bound at this state, when it covers the pair, else the spheres'.
        const double looked_up = table ? table->at(p, t.q.data()) : 0.0;
        if (looked_up >= cap) {
          d[p] = cap;
          continue;
        }
        d[p] = std::max(looked_up, bound_->pairDistance(p, *posed, cap));
        // The spheres' bound is too small and near contact: the links' own distance (farther,
        // FCL's distance costs more than the bisection the looser bound asks for).
        if (exact && d[p] < cap && d[p] < kExactNear * resolution_) {
          ++tally.pair_distances;
          const auto& [link_a, link_b] = bound_->pairs()[p];
          d[p] = std::max(d[p], backend.linkPairDistance(scratch, link_a, link_b, cap));
        }
      }
    }
    if (values_first) {
      // A half is free when each of its active links (pairs) is proven over the interval or
      // has a positive value; the others do not move (relative to each other) along the edge,
      // and s1 was checked.
      auto allFree = [](const std::vector<std::size_t>& active, const double* values,
                        std::uint64_t done) {
        for (std::size_t k = 0; k < active.size(); ++k) {
          if (k < 64 && (done >> k & 1)) continue;
          if (!(values[active[k]] > 0)) return false;
        }
        return true;
      };
      const bool check_environment =
          environment &&
          !(clearances && has_clearance &&
            allFree(t.active_links, t.clearance.data() + slot * stride, in ? in->links_done : 0));
      const bool check_self =
          self && !(distances && allFree(t.active_pairs, t.distance.data() + slot * pairs,
                                         in ? in->pairs_done : 0));
      if ((check_environment || check_self) && proofCollides(check_environment, check_self)) {
        std::fill_n(t.clearance.data() + slot * stride, stride, 0.0);
        std::fill_n(t.distance.data() + slot * pairs, pairs, 0.0);
        return false;
      }
    }
    return true;
  };
  // The largest bound over [a, b] (of length s) of the active links or pairs not yet proven
  // free there, 0 when all are: one is proven when its bound is below the sum of its values
  // (clearances, distances) at the ends, or, for voxel answers, decided by its ends. The bound
  // is the edge's times s, or when that proves nothing (fixed-base robots) the posed bound from
  // the end with the smaller rate. The bit of each one proven is set in `done` (the first 64;
  // the others are tested again).
  auto unproven = [&](bool pair, const Interval& in, const double* va, const double* vb,
                      std::uint64_t& done) {
    const std::vector<std::size_t>& active = pair ? t.active_pairs : t.active_links;
    const double* bound = pair ? t.pair_bound.data() : t.link_bound.data();
    const double s = in.b - in.a;
    double open = 0.0;
    for (std::size_t k = 0; k < active.size(); ++k) {
      if (k < 64 && (done >> k & 1)) continue;
      const std::size_t i = active[k];
      double b = bound[i] * s;
      if (arm_count > 0 && b > decided_by_ends && b >= va[i] + vb[i]) {
        b = boundOver(pair, i, s, in.slot_a, in.slot_b);
      }
      if (b <= decided_by_ends || b < va[i] + vb[i] ||
          (slabs && !pair && t.provenBySlabs(i, in, va[i], vb[i], stride))) {
        if (k < 64) done |= std::uint64_t{1} << k;
      } else {
        open = std::max(open, b);
      }
    }
    return open;
  };
  auto unprovenLinks = [&](Scratch::Interval& in) {
    return unproven(false, in, t.clearance.data() + in.slot_a * stride,
                    t.clearance.data() + in.slot_b * stride, in.links_done);
  };
  auto unprovenPairs = [&](Scratch::Interval& in) {
    const double* da = t.distance.data() + in.slot_a * pairs;
    const double* db = t.distance.data() + in.slot_b * pairs;
    const double open = unproven(true, in, da, db, in.pairs_done);
    // A part of the edge: the table may prove a pair along it (not along the whole edge, which
    // it did not).
    if (open == 0.0 || !table || (in.a == 0.0 && in.b == 1.0)) return open;
    bool more = false;
    for (std::size_t k = 0; k < t.active_pairs.size() && k < 64; ++k) {
      const std::size_t p = t.active_pairs[k];
      if ((in.pairs_done >> k & 1) || !table->covers(p)) continue;
      if (table->along(p, t.q1.data(), t.q2.data(), in.a, in.b) > 0) {
        in.pairs_done |= std::uint64_t{1} << k;
        more = true;
      }
    }
    return more ? unproven(true, in, da, db, in.pairs_done) : open;
  };

  // Exact answers: the last valid state reported is a proven interval's end at least the minimum
  // travel from contact (every active link and pair), so that an edge to it can be proven
  // again; nearer ones are skipped.
  auto clearOfContact = [&](std::size_t slot) {
    for (std::size_t l : t.active_links) {
      if (t.clearance[slot * stride + l] < min_travel) return false;
    }
    for (std::size_t p : t.active_pairs) {
      if (t.distance[slot * pairs + p] < min_travel) return false;
    }
    return true;
  };

  try {
    // s1 is valid by OMPL's contract; it is checked all the same (most edges start at a
    // remembered end), with its clearances, which the proof needs.
    const bool need_clearance = !t.active_links.empty();
    bool need_distance = !t.active_pairs.empty();  // after the pair table, below
    // An end: remembered, or checked (and remembered when valid).
    constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    // The end's place in the remembered ends (its key in t.key): it is remembered when the
    // place holds its key.
    auto rememberedPlace = [&](double t_edge) -> Scratch::Remembered& {
      return t.rememberedPlace(t_edge == 0.0, robot.isFreeFlying());
    };
    auto evaluateEnd = [&](double t_edge, std::size_t& slot) {
      Scratch::Remembered& r = rememberedPlace(t_edge);
      if (r.holds(serial_, t.key)) {
        bool known = true;
        for (std::size_t l : t.active_links) known = known && !std::isnan(r.clearance[l]);
        for (std::size_t p : t.active_pairs) known = known && !std::isnan(r.distance[p]);
        if (known) {
          if (t_edge == 1.0) s2_in_full = true;
          ++tally.remembered_ends;
          slot = newSlot();
          if (arm_count > 0) {
            t.arms = r.arms;
            t.setRates(*bound_, nullptr, slot, stride, nullptr);
          }
          if (slabs) t.restoreSlabs(*bound_, r, slot, stride);
          for (std::size_t l : t.active_links) t.clearance[slot * stride + l] = r.clearance[l];
          for (std::size_t p : t.active_pairs) t.distance[slot * pairs + p] = r.distance[p];
          return true;
        }
      }
      if (!evaluate(t_edge, nullptr, true, true, need_clearance, need_distance, slot)) {
        return false;
      }
      r.validator = serial_;
      r.key = t.key;
      r.clearance.assign(stride, kUnknown);
      r.distance.assign(pairs, kUnknown);
      r.arms = t.arms;  // every link's at an end
      if (has_clearance) {
        for (std::size_t l : t.active_links) r.clearance[l] = t.clearance[slot * stride + l];
      } else {
        for (std::size_t l : t.active_links) r.clearance[l] = 0.0;
      }
      for (std::size_t p : t.active_pairs) r.distance[p] = t.distance[slot * pairs + p];
      t.keepSlabs(r, slot, stride);
      return true;
    };
    // The collision screen (the header's kScreenLevels): an edge through a colliding state is
    // rejected before any clearance is measured. Not when the last valid state is wanted: that
    // must end a proven part of the edge.
    // A free state's link poses are kept for the proof (Scratch::screenPose).
    int levels = 0;
    auto screenCollides = [&](double t_edge) {
      state_checks_.fetch_add(1, std::memory_order_relaxed);
      ++tally.screen_checks;
      if (!place(t_edge)) return true;
      if (backend.inCollision(t.q.data(), n, t.X_WB, *t.backend)) return true;
      if (const RobotData* posed = backend.posedRobot(*t.backend)) {
        t.keepScreenPose(t_edge, levels, *posed);
      }
      return false;
    };
    if (!want_last && screen_levels_ > 0) {
      while (levels < screen_levels_ &&
             std::ldexp(max_bound, -levels) > kScreenTravel * resolution_) {
        ++levels;
      }
      const std::size_t states = (std::size_t{1} << levels) + 1;
      if (t.screen_poses.size() < states) t.screen_poses.resize(states, robot.makeData());
      t.screen_posed.assign(states, 0);
      const Scratch::Remembered& r2 = rememberedPlace(1.0);
      bool collides = !r2.holds(serial_, t.key) && screenCollides(1.0);
      for (int level = 1; level <= levels && !collides; ++level) {
        const double step = std::ldexp(1.0, -level);
        for (double m = step; m < 1.0 && !collides; m += 2 * step) collides = screenCollides(m);
      }
      if (collides) {
        tally.screened_out = true;
        return false;
      }
      screened_levels = levels;
      s2_in_full = true;  // screened, or remembered
    }
    // After the screen, which rejects most edges without them: the posed bounds' terms, and the
    // pairs whose table bound is positive along the whole edge, proven free over it.
    if (direct) bound_->edgeTerms(t.dq.data(), t.terms);
    if (table) {
      std::size_t kept = 0;
      for (std::size_t p : t.active_pairs) {
        if (table->covers(p) && table->along(p, t.q1.data(), t.q2.data(), 0.0, 1.0) > 0) {
          ++tally.table_pairs;
        } else {
          t.active_pairs[kept++] = p;
        }
      }
      t.active_pairs.resize(kept);
      need_distance = kept > 0;
    }
    // s2 first: an edge to an invalid state (most rejected edges) ends before s1 is looked at.
    std::size_t slot1 = 0, slot2 = 0;
    const bool s2_valid = evaluateEnd(1.0, slot2);
    if (!s2_valid && !want_last) return false;
    // s1 is valid by OMPL's contract; one that is not rejects the edge. s2, remembered from its
    // values alone, is then forgotten: the links the edge does not move were checked nowhere.
    if (!evaluateEnd(0.0, slot1)) {
      Scratch::Remembered& r2 = rememberedPlace(1.0);
      if (!s2_in_full && r2.holds(serial_, t.key)) r2.validator = 0;
      return false;
    }
    t.todo.clear();
    t.todo.push_back({0.0, 1.0, slot1, slot2, s2_valid, 0, 0});
    // Breadth first (midpoints first, coarse to fine) finds a collision with few checks; depth
    // first, left half first, keeps everything before the interval at hand proven free (the
    // last valid state).
    std::size_t head = 0;
    while (want_last ? !t.todo.empty() : head < t.todo.size()) {
      Interval in{};
      if (want_last) {
        in = t.todo.back();
        t.todo.pop_back();
      } else {
        in = t.todo[head++];
      }
      const double s = in.b - in.a;
      double open_links = 0.0, open_pairs = 0.0;
      if (in.b_valid) {
        open_links = unprovenLinks(in);
        open_pairs = unprovenPairs(in);
        if (open_links == 0.0 && open_pairs == 0.0) {
          if (want_last && (!exact || clearOfContact(in.slot_b))) last_valid = in.b;
          continue;
        }
        // Exact answers: a link or pair still unproven when its bound over the interval is below
        // the minimum may graze an obstacle (or the other link); the edge is not proven, so it
        // is rejected, here.
        if (exact && std::max(open_links, open_pairs) < min_travel) return false;
      } else if (max_bound * s <= resolution_) {
        if (!exact) last_valid = in.a;
        return false;
      }
      // Voxel answers: halves at the final resolution are decided by their ends, no clearance
      // needed there.
      const bool environment = !in.b_valid || open_links > 0.0;
      const bool self = !in.b_valid || open_pairs > 0.0;
      const double m = 0.5 * (in.a + in.b);
      tally.depth = std::max(tally.depth, static_cast<std::size_t>(1 - std::ilogb(s)));
      std::size_t sm = 0;
      const bool m_valid =
          evaluate(m, &in, environment || !self, self, 0.5 * max_link * s > decided_by_ends,
                   0.5 * max_pair * s > decided_by_ends, sm);
      if (!m_valid && !want_last) return false;
      const Interval left{in.a, m, in.slot_a, sm, m_valid, in.links_done, in.pairs_done};
      const Interval right{m, in.b, sm, in.slot_b, in.b_valid, in.links_done, in.pairs_done};
      if (want_last) {
        if (m_valid) t.todo.push_back(right);
        t.todo.push_back(left);
      } else {
        t.todo.push_back(left);
        t.todo.push_back(right);
      }
    }
    return true;
  } catch (const std::exception&) {
    return false;  // never throw into OMPL: an edge that cannot be checked is not free
  }
}

}  // namespace octomotion
