// An OMPL MotionValidator that accepts an edge only when it is proven free, by adaptive
// bisection (Schwarzer, Saha & Latombe, "Adaptive dynamic collision checking for single and
// multiple articulated robots", IEEE T-RO 2005): docs/validation.md §4.
//
// Link by link, an interval [a, b] of the edge, both ends valid, is free of the environment for
// link l when l's path-length bound over it (LinkMotionBound, robot/motion_bound.h; for a
// fixed-base robot the smaller of the levers' bound and the posed bounds from the interval's
// ends) is less than the sum of l's clearances at its ends (a lower bound on its distance,
// CollisionBackend::motionClearances). With exact answers on a fixed-base robot, a link whose
// clearance comes with its nearest objects' separating slabs is also free over the parts, from
// each end, in which it can neither cross those slabs (at the rate it approaches them) nor
// travel as far as the other objects; the interval is free when the two parts cover it. Pair by
// pair, it is free of self-collision when the
// bound on the change of the pair's distance (LinkMotionBound::pairBound: only the joints that
// move one link and not the other) is less than the sum of the pair's distance bounds at its
// ends (LinkMotionBound::pairDistance; for exact answers, the links' own distance,
// CollisionBackend::linkPairDistance, where the spheres' bound is too small). Otherwise the
// midpoint is checked (breadth first: coarse to fine, so a colliding edge fails early) and both
// halves are tried, each knowing which links and pairs are already proven over it; a midpoint
// needed by the self pairs alone is checked with selfInCollision.
//
// Termination depends on the checker's answer (CollisionBackend::exactAnswers):
// - voxel answers carry a margin: a link or pair whose bound over the interval is at most
//   `resolution` is decided by the checked ends (each of its points then stays within
//   resolution / 2 of a pose the checker found free, whose voxels hold the geometry);
// - exact answers carry none: a link or pair is proven only by the clearances, and an interval
//   whose unproven links' or pairs' bound falls below kExactMinTravel * resolution rejects the
//   edge, so every accepted edge is proven free for the exact geometry.
// Self pairs whose distance depends on at most two variables (a wrist's) are looked up in a
// PairDistanceTable (robot/pair_distance_table.h) built with the validator for exact answers: a
// pair whose table bound is positive along the whole edge (or an interval) is proven there
// without a distance, and the table's bound at a state stands in for one where it suffices.
// Before the proof, a collision screen (kScreenLevels) checks states of the edge for collision
// alone, coarse to fine: an edge through a colliding state is rejected without a clearance.
// Each thread remembers the last valid ends it checked (their clearances and pair distances), so
// an edge that starts where an earlier one ended (RRTConnect's connect steps, a tree node
// reused) does not check it again.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/robot/motion_bound.h"
#include "octomotion/planner/robot/pair_distance_table.h"
#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

class CertifiedMotionValidator : public ompl::base::MotionValidator {
 public:
  // Exact answers: the bound, as a fraction of the resolution, below which an interval whose
  // links or pairs are still unproven rejects the edge. Such an interval has an end within
  // half of it (0.3 mm at 1 cm voxels) of contact, so only an edge grazing an obstacle closer
  // than that is rejected, and bisecting there costs about two checks per halving of the
  // edge's bound down to it.
  static constexpr double kExactMinTravel = 1.0 / 16;
  // Exact answers: a self pair's exact distance (CollisionBackend::linkPairDistance) is asked
  // only where its sphere bound is below this many resolutions (and below what is needed).
  static constexpr double kExactNear = 2.0;
  // The share of the edge's bound from an end up to which the end's clearances and distances
  // are measured. The whole bound would let one end prove the edge alone, which it seldom does;
  // measuring that far costs more (more obstacles within the cap) than the deeper proofs the
  // smaller cap asks for now and then. The midpoint, evaluated next, proves the halves.
  static constexpr double kEndCapShare = 0.25;

  // `resolution` (metres, > 0): the final resolution above, usually the scene's voxel size.
  // Throws InvalidArgument for a null backend or bound, a bound made for another robot (or
  // other self pairs) or a resolution that is not positive and finite.
  CertifiedMotionValidator(const ompl::base::SpaceInformationPtr& si,
                           std::shared_ptr<const CollisionBackend> backend,
                           std::shared_ptr<const LinkMotionBound> bound, double resolution);

  // s1 is assumed valid (OMPL's contract); s2 is checked. Const and thread-safe.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  // On failure, lastValid.second is the end of the part of the edge proven free from s1 (its
  // state written to lastValid.first when not null); for exact answers, the last end of a proven
  // interval whose links and pairs are at least kExactMinTravel * resolution from contact.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  // The path-length bound of the whole edge: the largest over the robot's points.
  double motionBound(const ompl::base::State* s1, const ompl::base::State* s2) const;

  // Collision screen: before the proof, states of the edge are checked for collision alone (no
  // clearance, no distance) in breadth-first order (the end s2, then 1/2, 1/4, 3/4, 1/8, ...),
  // down to the level where the edge's bound between them is at most kScreenTravel resolutions
  // and at most kScreenLevels levels (2^kScreenLevels - 1 midpoints): a colliding edge is
  // rejected there, cheaply; the proof is spent only on edges that pass it.
  static constexpr int kScreenLevels = 2;
  static constexpr double kScreenTravel = 4.0;

  // Counters since construction (or resetCounts): state checks that test the environment (with
  // clearances) and self-pair-only checks.
  std::size_t stateChecks() const { return state_checks_.load(std::memory_order_relaxed); }
  std::size_t selfChecks() const { return self_checks_.load(std::memory_order_relaxed); }
  // Where the work goes, edge by edge (for benches and profiling; the clock is read twice per
  // edge): accepted and rejected edges, each with its state checks (screen, environment and
  // self-only checks), states whose clearances were measured, exact pair distances asked, the
  // deepest bisection level reached, and the time spent.
  struct EdgeCounts {
    std::size_t edges = 0;
    std::size_t screen_checks = 0;     // collision-only checks of the screen
    std::size_t proof_checks = 0;      // checks of the proof (environment and self-only)
    std::size_t clearance_states = 0;  // states whose link clearances were measured
    std::size_t pair_distances = 0;    // CollisionBackend::linkPairDistance calls
    std::size_t table_pairs = 0;       // pairs proven over the whole edge by the pair table
    std::size_t depth = 0;             // sum over the edges of their deepest bisection level
    double travel = 0.0;               // sum over the edges of their bound (metres)
    double seconds = 0.0;
  };
  struct Counts {
    EdgeCounts accepted, rejected;
    std::size_t rejected_by_screen = 0;  // of `rejected`: a screened state collides
    std::size_t remembered_ends = 0;     // ends whose clearances were remembered
  };
  Counts counts() const;
  // The screen's depth in levels (0: no screen, the proof alone; kScreenLevels by default). Set
  // before planning (not thread-safe against checks in flight).
  void setScreenLevels(int levels);
  int screenLevels() const { return screen_levels_; }
  void resetCounts() const;

  double resolution() const { return resolution_; }
  // The self pairs' distance table (built at construction for exact answers on a fixed-base
  // robot, with the backend's linkPairDistance), or null: none, or the backend's model changed
  // since (its id differs: an object was attached or the world updated).
  const PairDistanceTable* pairTable() const {
    return pair_table_ && backend_->id() == pair_table_owner_ ? pair_table_.get() : nullptr;
  }
  const CollisionBackend& backend() const { return *backend_; }

 private:
  void countMotion(bool free, std::chrono::steady_clock::time_point start) const;
  struct Scratch;
  bool check(const ompl::base::State* s1, const ompl::base::State* s2, bool want_last,
             double& last_valid) const;

  std::shared_ptr<const CollisionBackend> backend_;
  std::shared_ptr<const LinkMotionBound> bound_;
  double resolution_;
  std::shared_ptr<const PairDistanceTable> pair_table_;
  std::uint64_t pair_table_owner_ = 0;  // the backend's id when the table was built
  std::uint64_t serial_;  // process-unique: a thread's remembered states belong to one validator
  int screen_levels_ = kScreenLevels;
  mutable std::atomic<std::size_t> state_checks_{0};
  mutable std::atomic<std::size_t> self_checks_{0};
  struct AtomicCounts;
  std::shared_ptr<AtomicCounts> counts_;  // defined in the source; shared_ptr: no destructor here
};

// The path-length bound of the robot's links and of what they carry (attached objects, by their
// bounding box in the link's frame), with the scene's mesh conventions.
std::shared_ptr<const LinkMotionBound> makeLinkMotionBound(
    const RobotModel& robot, bool keep_mesh_root_transform, bool center_mesh_vertices,
    const std::vector<AttachedObject>& attached = {});

// Installs a motion validator of `kind` on si: CertifiedMotionValidator over the backend at
// `resolution` with `bound`, or OMPL's DiscreteMotionValidator (which steps at si's state
// validity checking resolution; `bound` unused, may be null).
void setMotionValidator(const ompl::base::SpaceInformationPtr& si, MotionValidatorKind kind,
                        std::shared_ptr<const CollisionBackend> backend,
                        std::shared_ptr<const LinkMotionBound> bound, double resolution);

}  // namespace octomotion
