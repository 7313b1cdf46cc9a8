// Why a state is invalid: what CollisionBackend::explain returns (model/collision_backend.h).
// Not a hot path: explanations name links, joints and environment objects as strings, for error
// messages (a start or goal in collision) and for `octomotion check --explain`.
#pragma once

#include <string>
#include <vector>

namespace octomotion {

// Whether the exact shapes behind a voxel contact touch. Octree checkers test voxels, which
// reach up to a voxel diagonal beyond the shapes (conservative rounding), so a contact may lie
// within that margin only.
enum class ExactContact {
  kTouching,  // the exact shapes touch (exact checkers always say so)
  kApart,     // they do not: the contact is the voxels' margin only
  kUnknown,   // no exact shape to test (point clouds, OctoMaps)
};

struct InvalidityReason {
  enum class Kind {
    kNonFinite,      // a joint value, the base pose or a link pose that is NaN or infinite
    kOutsideLimits,  // a joint value outside its limits
    kEnvironment,    // a link meets an environment object
    kSelf,           // a checked pair of links meet
  };
  Kind kind = Kind::kEnvironment;
  // kEnvironment, kSelf: the robot link; kOutsideLimits: the joint's variable; kNonFinite: the
  // variable, or what else is not finite ("base pose", "link 'name' pose").
  std::string link;
  // kEnvironment: the object's EnvironmentObject::name, empty when the checker cannot tell
  // which object (fcl-octomap, whose map fuses them all); kSelf: the other link.
  std::string other;
  ExactContact exact = ExactContact::kTouching;  // kEnvironment, kSelf
  // kEnvironment, kSelf: how far apart the exact shapes may be and still collide in this
  // checker: its voxel size (0 for exact checkers).
  double margin = 0;
  double value = 0, lower = 0, upper = 0;  // kOutsideLimits
};

struct StateExplanation {
  std::vector<InvalidityReason> reasons;  // none: the state is valid

  bool valid() const { return reasons.empty(); }
  // A contact (environment or self): what CollisionBackend::inCollision answers.
  bool inCollision() const;
  // Every contact lies within the voxels' margin (ExactContact::kApart): the exact shapes are
  // free, a finer resolution should accept the state. False without contacts.
  bool onlyVoxelMargin() const;
};

// One line per reason, e.g. "link panda_hand with object shelf_top", "link a with link b",
// "joint 'j1' = 3.2 is outside its limits [-2.9, 2.9]", "q[2] (j3) is not finite".
std::string describe(const InvalidityReason& reason);
// The reasons joined by "; " (empty for a valid state).
std::string describe(const StateExplanation& explanation);

// CollisionBackend::explain's options.
struct ExplainOptions {
  bool all = false;          // every contact (each link with each object, each pair), not the first
  bool check_limits = true;  // report joint values outside their limits (kOutsideLimits)
};

}  // namespace octomotion
