// An OMPL MotionValidator that accepts an edge only when it is proven free down to a stated
// resolution, by adaptive bisection (Schwarzer, Saha & Latombe, "Adaptive dynamic collision
// checking for single and multiple articulated robots", IEEE T-RO 2005): docs/validation.md §4.
//
// An interval [a, b] of the edge, both ends valid, is free of the environment when the
// path-length bound of every point of the robot over it (LinkMotionBound, robot/motion_bound.h)
// is less than the sum of the backend's clearances at its ends (a lower bound on the distance,
// ClearanceBound); otherwise its midpoint is checked and both halves are tried. An interval whose
// bound is at most `resolution` is decided by its checked ends: every point of the robot then
// stays within resolution / 2 of a pose the checker found free. Self pairs have no clearance:
// inside an interval accepted through the clearance they are checked (selfInCollision) at states
// at most `resolution` of travel apart, the same final resolution.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/robot/motion_bound.h"
#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

class CertifiedMotionValidator : public ompl::base::MotionValidator {
 public:
  // `resolution` (metres, > 0): the final resolution above, usually the scene's voxel size.
  // Throws InvalidArgument for a null backend or bound, a bound made for another robot or a
  // resolution that is not positive and finite.
  CertifiedMotionValidator(const ompl::base::SpaceInformationPtr& si,
                           std::shared_ptr<const CollisionBackend> backend,
                           std::shared_ptr<const LinkMotionBound> bound, double resolution);

  // s1 is assumed valid (OMPL's contract); s2 is checked. Const and thread-safe.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  // On failure, lastValid.second is the end of the part of the edge proven free from s1 (its
  // state written to lastValid.first when not null).
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  // The path-length bound of the whole edge: the largest over the robot's points.
  double motionBound(const ompl::base::State* s1, const ompl::base::State* s2) const;

  // Counters since construction (or resetCounts): full state checks (with clearance) and
  // self-pair-only checks.
  std::size_t stateChecks() const { return state_checks_.load(std::memory_order_relaxed); }
  std::size_t selfChecks() const { return self_checks_.load(std::memory_order_relaxed); }
  void resetCounts() const {
    state_checks_ = 0;
    self_checks_ = 0;
  }

  double resolution() const { return resolution_; }
  const CollisionBackend& backend() const { return *backend_; }

 private:
  void countMotion(bool free) const;
  struct Scratch;
  bool check(const ompl::base::State* s1, const ompl::base::State* s2, bool want_last,
             double& last_valid) const;

  std::shared_ptr<const CollisionBackend> backend_;
  std::shared_ptr<const LinkMotionBound> bound_;
  double resolution_;
  bool self_pairs_;  // the robot has checked self pairs
  mutable std::atomic<std::size_t> state_checks_{0};
  mutable std::atomic<std::size_t> self_checks_{0};
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
