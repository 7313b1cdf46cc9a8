#include "octomotion/planner/ompl/certified_motion_validator.h"

#include <cmath>
#include <cstdint>
#include <deque>
#include <exception>
#include <limits>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/state_space.h"

namespace octomotion {

namespace ob = ompl::base;

// One thread's working memory, rebuilt when the thread turns to another backend.
struct CertifiedMotionValidator::Scratch {
  std::uint64_t owner = 0;
  std::unique_ptr<BackendScratch> backend;
  std::vector<double> q, q1, q2, dq;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB1 = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB2 = Eigen::Isometry3d::Identity();
};

namespace {

// An interval [a, b] of the edge with its ends' clearances; the end b may be known invalid
// (only while looking for the last valid state).
struct Interval {
  double a, b;
  double clearance_a, clearance_b;
  bool b_valid;
};

// An OMPL state freed on every way out.
class ScopedState {
 public:
  explicit ScopedState(const ob::SpaceInformation* si) : si_(si), state_(si->allocState()) {}
  ~ScopedState() { si_->freeState(state_); }
  ScopedState(const ScopedState&) = delete;
  ScopedState& operator=(const ScopedState&) = delete;
  ob::State* get() const { return state_; }

 private:
  const ob::SpaceInformation* si_;
  ob::State* state_;
};

}  // namespace

CertifiedMotionValidator::CertifiedMotionValidator(const ob::SpaceInformationPtr& si,
                                                   std::shared_ptr<const CollisionBackend> backend,
                                                   std::shared_ptr<const LinkMotionBound> bound,
                                                   double resolution)
    : ob::MotionValidator(si),
      backend_(std::move(backend)),
      bound_(std::move(bound)),
      resolution_(resolution),
      self_pairs_(false) {
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
  self_pairs_ = !robot.checkedPairs().empty();
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
  thread_local Scratch t;
  if (t.owner != backend.id()) {
    t.backend = backend.makeBackendScratch();
    t.owner = backend.id();
  }
  // stateToConfiguration fills q to its size.
  const auto n = static_cast<std::size_t>(robot.variableCount());
  t.q.resize(n);
  t.q1.resize(n);
  t.q2.resize(n);
  last_valid = 0.0;
  // The whole edge's path-length bound; an interval's is this times its length (the
  // interpolation is linear in q, and in translation and angle for SE(3)).
  double edge_bound = 0.0;
  if (!stateToConfiguration(robot, s1, t.q1, t.X_WB1) ||
      !stateToConfiguration(robot, s2, t.q2, t.X_WB2)) {
    return false;
  }
  if (robot.isFreeFlying()) {
    const double angle = Eigen::AngleAxisd(t.X_WB1.linear().transpose() * t.X_WB2.linear()).angle();
    edge_bound =
        bound_->freeFlyingBound((t.X_WB2.translation() - t.X_WB1.translation()).norm(), angle);
  } else {
    t.dq.resize(t.q1.size());
    for (std::size_t i = 0; i < t.q1.size(); ++i) t.dq[i] = t.q2[i] - t.q1[i];
    edge_bound = bound_->maxBound(t.dq.data());
  }
  if (!std::isfinite(edge_bound)) return false;

  const ob::SpaceInformation* si = si_;
  const ScopedState state(si);
  const bool has_clearance = backend.clearanceBound() != ClearanceBound::kNone;
  // Checks the state at t_edge; its clearance (0 without one) when valid.
  auto evaluate = [&](double t_edge, double& clearance, bool need_clearance = true) {
    state_checks_.fetch_add(1, std::memory_order_relaxed);
    const ob::State* s = t_edge == 0.0 ? s1 : t_edge == 1.0 ? s2 : state.get();
    if (s == state.get()) si->getStateSpace()->interpolate(s1, s2, t_edge, state.get());
    if (!si->satisfiesBounds(s) || !stateToConfiguration(robot, s, t.q, t.X_WB)) return false;
    if (backend.inCollision(t.q.data(), t.q.size(), t.X_WB, *t.backend)) return false;
    clearance = has_clearance && need_clearance ? backend.motionClearance(*t.backend) : 0.0;
    return true;
  };
  // Self pairs inside [a, b] at states at most `resolution` of travel apart; on a collision,
  // `last_valid` is the state before it.
  auto selfFree = [&](const Interval& in, double length_bound) {
    if (!self_pairs_ || length_bound <= resolution_) return true;
    const double steps = std::ceil(length_bound / resolution_);
    for (double i = 1; i < steps; ++i) {
      const double t_edge = in.a + (in.b - in.a) * i / steps;
      self_checks_.fetch_add(1, std::memory_order_relaxed);
      si->getStateSpace()->interpolate(s1, s2, t_edge, state.get());
      if (!stateToConfiguration(robot, state.get(), t.q, t.X_WB) ||
          backend.selfInCollision(t.q.data(), t.q.size(), t.X_WB, *t.backend)) {
        last_valid = in.a + (in.b - in.a) * (i - 1) / steps;
        return false;
      }
    }
    return true;
  };

  try {
    double clearance1 = 0.0, clearance2 = 0.0;
    // s1 is valid by contract; its clearance is still needed (0 if it is not valid after all).
    if (!evaluate(0.0, clearance1)) clearance1 = 0.0;
    const bool s2_valid = evaluate(1.0, clearance2);
    if (!s2_valid && !want_last) return false;
    // Breadth first finds a collision with few checks; depth first, left half first, keeps
    // everything before the interval at hand proven free (the last valid state).
    std::deque<Interval> todo{{0.0, 1.0, clearance1, s2_valid ? clearance2 : 0.0, s2_valid}};
    while (!todo.empty()) {
      Interval in{};
      if (want_last) {
        in = todo.back();
        todo.pop_back();
      } else {
        in = todo.front();
        todo.pop_front();
      }
      const double length_bound = edge_bound * (in.b - in.a);
      if (in.b_valid && length_bound < in.clearance_a + in.clearance_b) {
        if (!selfFree(in, length_bound)) return false;
        if (want_last) last_valid = in.b;
        continue;
      }
      if (length_bound <= resolution_) {
        if (!in.b_valid) {
          last_valid = in.a;
          return false;
        }
        if (want_last) last_valid = in.b;
        continue;
      }
      const double m = 0.5 * (in.a + in.b);
      double clearance_m = 0.0;
      // Halves at the final resolution are decided by their ends: no clearance needed there.
      const bool m_valid = evaluate(m, clearance_m, 0.5 * length_bound > resolution_);
      if (!m_valid && !want_last) return false;
      if (want_last) {
        if (m_valid) todo.push_back({m, in.b, clearance_m, in.clearance_b, in.b_valid});
        todo.push_back({in.a, m, in.clearance_a, m_valid ? clearance_m : 0.0, m_valid});
      } else {
        todo.push_back({in.a, m, in.clearance_a, clearance_m, true});
        todo.push_back({m, in.b, clearance_m, in.clearance_b, true});
      }
    }
    return true;
  } catch (const std::exception&) {
    return false;  // never throw into OMPL: an edge that cannot be checked is not free
  }
}

}  // namespace octomotion
