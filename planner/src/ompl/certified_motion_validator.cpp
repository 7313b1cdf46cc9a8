#include "octomotion/planner/ompl/certified_motion_validator.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/state_space.h"

namespace octomotion {

namespace ob = ompl::base;

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
  std::vector<int> active_links;
  std::vector<std::size_t> active_pairs;
  std::vector<double> clearance, distance;  // per evaluated state: per link, per pair
  std::vector<Interval> todo;
  // Valid ends checked before (direct-mapped by a hash of the configuration): the values of the
  // links and pairs active then, NaN for the others.
  struct Remembered {
    std::uint64_t validator = 0;
    std::vector<double> key, clearance, distance;
  };
  static constexpr std::size_t kRemembered = 64;
  std::array<Remembered, kRemembered> remembered;
  std::vector<double> key;
  // Free-flying robots: an OMPL state for the interpolated ones (the space kept alive with it).
  ob::StateSpacePtr space;
  ob::State* state = nullptr;

  Scratch() = default;
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() { release(); }
  void useSpace(const ob::StateSpacePtr& s) {
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

namespace {

std::uint64_t nextSerial() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

CertifiedMotionValidator::CertifiedMotionValidator(const ob::SpaceInformationPtr& si,
                                                   std::shared_ptr<const CollisionBackend> backend,
                                                   std::shared_ptr<const LinkMotionBound> bound,
                                                   double resolution)
    : ob::MotionValidator(si),
      backend_(std::move(backend)),
      bound_(std::move(bound)),
      resolution_(resolution),
      serial_(nextSerial()) {
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
}

double CertifiedMotionValidator::motionBound(const ob::State* s1, const ob::State* s2) const {
  const RobotModel& robot = backend_->robot();
  const auto n = static_cast<std::size_t>(robot.variableCount());
  std::vector<double> q1(n), q2(n);  // stateToConfiguration fills them to their size
  Eigen::Isometry3d X1, X2;
  if (!stateToConfiguration(robot, s1, q1, X1) || !stateToConfiguration(robot, s2, q2, X2)) {
    return std::numeric_limits<double>::infinity();
  }
  if (robot.isFreeFlying()) {
    const double angle = Eigen::AngleAxisd(X1.linear().transpose() * X2.linear()).angle();
    return bound_->freeFlyingBound((X2.translation() - X1.translation()).norm(), angle);
  }
  for (std::size_t i = 0; i < q1.size(); ++i) q2[i] -= q1[i];
  return bound_->maxBound(q2.data());
}

void CertifiedMotionValidator::countMotion(bool free) const {
  // OMPL's counters are plain members, but checkMotion is const and may run on several threads
  // (parallel planners), so the increments are atomic.
  __atomic_fetch_add(free ? &valid_ : &invalid_, 1u, __ATOMIC_RELAXED);
}

bool CertifiedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  double last_valid = 0.0;
  const bool free = check(s1, s2, false, last_valid);
  countMotion(free);
  return free;
}

bool CertifiedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                           std::pair<ob::State*, double>& lastValid) const {
  double last_valid = 0.0;
  const bool free = check(s1, s2, true, last_valid);
  countMotion(free);
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
  // interval's is this times its length (the interpolation is linear in q, and in translation
  // and angle for SE(3)). Only links and pairs whose bound exceeds the resolution need more than
  // the ends ("active"); a link no joint moves never does.
  for (std::size_t i = 0; i < n; ++i) t.dq[i] = t.q2[i] - t.q1[i];
  double free_flying = 0.0;
  if (robot.isFreeFlying()) {
    const double angle = Eigen::AngleAxisd(t.X_WB1.linear().transpose() * t.X_WB2.linear()).angle();
    free_flying =
        bound_->freeFlyingBound((t.X_WB2.translation() - t.X_WB1.translation()).norm(), angle);
    if (!std::isfinite(free_flying)) return false;
  }
  t.link_bound.assign(links, 0.0);
  t.active_links.clear();
  double max_bound = 0.0, max_link = 0.0, max_pair = 0.0;
  for (int l : bound_->geometryLinks()) {
    const double b = free_flying + bound_->linkBound(l, t.dq.data());
    if (!std::isfinite(b)) return false;
    t.link_bound[static_cast<std::size_t>(l)] = b;
    if (b > resolution_) t.active_links.push_back(l);
    max_link = std::max(max_link, b);
  }
  t.pair_bound.assign(pairs, 0.0);
  t.active_pairs.clear();
  for (std::size_t p = 0; p < pairs; ++p) {
    const double b = bound_->pairBound(p, t.dq.data());
    if (!std::isfinite(b)) return false;
    t.pair_bound[p] = b;
    if (b > resolution_) t.active_pairs.push_back(p);
    max_pair = std::max(max_pair, b);
  }
  max_bound = std::max(max_link, max_pair);
  // Clearances above a link's whole-edge bound decide nothing more: capped (FCL stops early).
  t.caps.assign(links, 0.0);
  for (int l : t.active_links) t.caps[static_cast<std::size_t>(l)] = t.link_bound[l];
  const bool has_clearance = backend.clearanceBound() != ClearanceBound::kNone;
  const bool direct = !robot.isFreeFlying();  // q(t) without OMPL's interpolation
  const ob::SpaceInformation* si = si_;
  if (!direct) t.useSpace(si->getStateSpace());
  const std::size_t stride = std::max<std::size_t>(links, 1);
  t.clearance.clear();
  t.distance.clear();

  // Checks the state at t_edge into a new slot: the environment and/or the self pairs, then
  // the active links' clearances and the active pairs' distances when asked.
  // A slot's values stay 0 when its state is invalid.
  auto evaluate = [&](double t_edge, bool environment, bool self, bool clearances, bool distances,
                      std::size_t& slot) {
    (environment ? state_checks_ : self_checks_).fetch_add(1, std::memory_order_relaxed);
    slot = t.clearance.size() / stride;
    t.clearance.resize(t.clearance.size() + stride, 0.0);
    t.distance.resize(t.distance.size() + pairs, 0.0);
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
    BackendScratch& scratch = *t.backend;
    const bool collides = environment && self ? backend.inCollision(t.q.data(), n, t.X_WB, scratch)
                          : environment
                              ? backend.environmentInCollision(t.q.data(), n, t.X_WB, scratch)
                              : backend.selfInCollision(t.q.data(), n, t.X_WB, scratch);
    if (collides) return false;
    if (environment && clearances && has_clearance) {
      backend.motionClearances(scratch, t.caps.data(), t.clearance.data() + slot * stride);
    }
    if (self && distances && !t.active_pairs.empty()) {
      const RobotData* posed = backend.posedRobot(scratch);
      if (!posed) {
        robot.forwardKinematics(t.q.data(), n, t.data,
                                robot.isFreeFlying() ? t.X_WB : Eigen::Isometry3d::Identity());
        posed = &t.data;
      }
      double* d = t.distance.data() + slot * pairs;
      for (std::size_t p : t.active_pairs) d[p] = bound_->pairDistance(p, *posed, t.pair_bound[p]);
    }
    return true;
  };
  // Whether every active link (pair) is proven free over [a, b] or decided by its ends; the
  // bit of each one proven is set in `done` (the first 64; the others are tested again).
  auto linksFree = [&](const Interval& in, std::uint64_t& done) {
    const double s = in.b - in.a;
    const double* ca = t.clearance.data() + in.slot_a * stride;
    const double* cb = t.clearance.data() + in.slot_b * stride;
    bool all = true;
    for (std::size_t k = 0; k < t.active_links.size(); ++k) {
      if (k < 64 && (done >> k & 1)) continue;
      const auto l = static_cast<std::size_t>(t.active_links[k]);
      const double b = t.link_bound[l] * s;
      if (b <= resolution_ || b < ca[l] + cb[l]) {
        if (k < 64) done |= std::uint64_t{1} << k;
      } else {
        all = false;
      }
    }
    return all;
  };
  auto pairsFree = [&](const Interval& in, std::uint64_t& done) {
    const double s = in.b - in.a;
    const double* da = t.distance.data() + in.slot_a * pairs;
    const double* db = t.distance.data() + in.slot_b * pairs;
    bool all = true;
    for (std::size_t k = 0; k < t.active_pairs.size(); ++k) {
      if (k < 64 && (done >> k & 1)) continue;
      const std::size_t p = t.active_pairs[k];
      const double b = t.pair_bound[p] * s;
      if (b <= resolution_ || b < da[p] + db[p]) {
        if (k < 64) done |= std::uint64_t{1} << k;
      } else {
        all = false;
      }
    }
    return all;
  };

  try {
    // s1 is valid by contract; its clearances are still needed (0 if it is not valid after
    // all: the slot stays zero).
    const bool need_clearance = !t.active_links.empty();
    const bool need_distance = !t.active_pairs.empty();
    // An end: remembered, or checked (and remembered when valid).
    constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    auto evaluateEnd = [&](double t_edge, std::size_t& slot) {
      const std::vector<double>& q = t_edge == 0.0 ? t.q1 : t.q2;
      const Eigen::Isometry3d& X = t_edge == 0.0 ? t.X_WB1 : t.X_WB2;
      t.key.assign(q.begin(), q.end());
      if (robot.isFreeFlying()) {
        t.key.insert(t.key.end(), X.matrix().data(), X.matrix().data() + 12);
      }
      std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the values' bytes
      for (double v : t.key) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        hash = (hash ^ bits) * 1099511628211ull;
      }
      Scratch::Remembered& r = t.remembered[(hash ^ (hash >> 29)) % Scratch::kRemembered];
      if (r.validator == serial_ && r.key == t.key) {
        bool known = true;
        for (int l : t.active_links) known = known && !std::isnan(r.clearance[l]);
        for (std::size_t p : t.active_pairs) known = known && !std::isnan(r.distance[p]);
        if (known) {
          slot = t.clearance.size() / stride;
          t.clearance.resize(t.clearance.size() + stride, 0.0);
          t.distance.resize(t.distance.size() + pairs, 0.0);
          for (int l : t.active_links) t.clearance[slot * stride + l] = r.clearance[l];
          for (std::size_t p : t.active_pairs) t.distance[slot * pairs + p] = r.distance[p];
          return true;
        }
      }
      if (!evaluate(t_edge, true, true, need_clearance, need_distance, slot)) return false;
      r.validator = serial_;
      r.key = t.key;
      r.clearance.assign(stride, kUnknown);
      r.distance.assign(pairs, kUnknown);
      if (has_clearance) {
        for (int l : t.active_links) r.clearance[l] = t.clearance[slot * stride + l];
      } else {
        for (int l : t.active_links) r.clearance[l] = 0.0;
      }
      for (std::size_t p : t.active_pairs) r.distance[p] = t.distance[slot * pairs + p];
      return true;
    };
    // s2 first: an edge to an invalid state (most rejected edges) ends before s1 is looked at.
    std::size_t slot1 = 0, slot2 = 0;
    const bool s2_valid = evaluateEnd(1.0, slot2);
    if (!s2_valid && !want_last) return false;
    evaluateEnd(0.0, slot1);
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
      if (in.b_valid) {
        const bool links_free = linksFree(in, in.links_done);
        const bool pairs_free = pairsFree(in, in.pairs_done);
        if (links_free && pairs_free) {
          if (want_last) last_valid = in.b;
          continue;
        }
      } else if (max_bound * s <= resolution_) {
        last_valid = in.a;
        return false;
      }
      // Halves at the final resolution are decided by their ends: no clearance needed there.
      const bool environment = !in.b_valid || !linksFree(in, in.links_done);
      const bool self = !in.b_valid || !pairsFree(in, in.pairs_done);
      const double m = 0.5 * (in.a + in.b);
      // The midpoint's clearances serve only the halves and their parts: a clearance above a
      // link's bound over a half decides nothing more (and a capped value is still a bound).
      for (int l : t.active_links) t.caps[static_cast<std::size_t>(l)] = t.link_bound[l] * 0.5 * s;
      std::size_t sm = 0;
      const bool m_valid = evaluate(m, environment || !self, self, 0.5 * max_link * s > resolution_,
                                    0.5 * max_pair * s > resolution_, sm);
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
