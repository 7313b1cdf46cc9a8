// One interface over the collision checkers a scene can plan with: the octree model (through
// OctreeBackend, model/octree_backend.h) and the two FCL references
// (reference/fcl_collision_model.h, reference/fcl_octomap_collision_model.h), so that consumers
// (the OMPL checker, tests, benches) write one measurement path. A backend is constant and shared
// by every thread; each thread queries it with its own scratch. The concrete backends are final, so
// code templated on them (ValidityChecker<Backend>, ompl/validity_checker.h) calls them without a
// virtual call.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>

#include <Eigen/Geometry>

#include "octomotion/planner/model/state_explanation.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// One thread's working memory for one backend's queries (link poses, narrow-phase buffers).
// Opaque: each backend derives its own. Made by CollisionBackend::makeBackendScratch and usable
// only with the backend that made it (the queries throw InvalidArgument for another's).
struct BackendScratch {
  virtual ~BackendScratch() = default;
  std::uint64_t owner = 0;  // id() of the backend that made it
};

// What CollisionBackend::clearance returns (and OMPL's StateValidityCheckerSpecs says).
enum class ClearanceBound {
  kNone,        // no clearance: always 0
  kLowerBound,  // a lower bound on the distance to the environment
  kExact,       // the exact distance to the environment
};

// A link's nearest environment objects as separating slabs certify them (motionClearances):
// along the unit direction toward_W[k] (world frame, from the link towards the k-th nearest
// object) every point of that object lies at least gap[k] beyond every point of the link, and
// every object not given a slab is at least `others` from the link. The certified motion
// validator bounds how fast the link approaches each slab's object along its direction, which
// for a link sliding past it is far below the link's speed (docs/validation.md §4). A NaN gap:
// no slab (the first NaN ends the list).
struct NearestObstacle {
  static constexpr std::size_t kSlabs = 2;
  std::array<double, kSlabs> gap{std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::quiet_NaN()};
  std::array<Eigen::Vector3d, kSlabs> toward_W{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double others = 0.0;
  bool valid(std::size_t k = 0) const { return gap[k] > 0; }
};

class CollisionBackend {
 public:
  virtual ~CollisionBackend() = default;

  virtual std::unique_ptr<BackendScratch> makeBackendScratch() const = 0;

  // Poses the robot at q (joint values in RobotModel::variables() order) and X_WB (the base pose
  // of a free-flying robot; a fixed-base robot ignores it: every backend uses the mount it was
  // built with, CollisionModelOptions::X_WB or the references' `mount`) in the scratch, then
  // tests the links against the environment and the checked self pairs against each other. Throws
  // InvalidArgument for a non-finite input or a scratch made by another backend.
  virtual bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                           BackendScratch& scratch) const = 0;
  // Its two halves, each posing the robot first: the environment only, the self pairs only.
  virtual bool environmentInCollision(const double* q, std::size_t q_size,
                                      const Eigen::Isometry3d& X_WB,
                                      BackendScratch& scratch) const = 0;
  virtual bool selfInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                               BackendScratch& scratch) const = 0;
  // Poses the robot only, for the queries below on a state already known free (the certified
  // motion validator's screened states). Default: inCollision, its answer dropped.
  virtual void setPose(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch) const {
    inCollision(q, q_size, X_WB, scratch);
  }

  // Why the state (q, X_WB as for inCollision) is invalid: non-finite values, joints outside
  // their limits (options.check_limits), and the contacts — each link with the environment
  // object it meets, each checked pair that meets — with whether the exact shapes touch and the
  // checker's margin. explain(...).inCollision() == inCollision(...) for every finite state; a
  // non-finite one is explained instead of thrown. The first contact only unless options.all.
  // Not a hot path (it allocates; octree models build per-object data on first use). Throws
  // InvalidArgument for a wrong q size or a scratch made by another backend.
  StateExplanation explain(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                           BackendScratch& scratch, const ExplainOptions& options = {}) const;

  // Distance from the robot, posed by the scratch's last query, to the environment, as
  // clearanceBound() says (0 in contact).
  virtual double clearance(BackendScratch& scratch) const = 0;
  virtual ClearanceBound clearanceBound() const = 0;
  // The lower bound the certified motion validator uses (same contract as clearance, in
  // kLowerBound or kExact terms): clearance() unless the backend has a cheaper bound.
  virtual double motionClearance(BackendScratch& scratch) const { return clearance(scratch); }
  // The same bound per link (robot link order) into per_link[robot().linkCount()]: a link's own
  // distance to the environment, so that a link that barely moves is not held to the clearance
  // of another. caps[l] > 0: a value at or above it may be written as caps[l]; caps[l] <= 0: the
  // link's value is not needed (unspecified). `nearest`, when not null, receives per link the
  // nearest objects' slabs (NearestObstacle) where the backend has them, for links with
  // caps[l] > 0 and a value below it, and no slab (a NaN gap) for the others. Default:
  // motionClearance() for every link, no slab.
  virtual void motionClearances(BackendScratch& scratch, const double* caps, double* per_link,
                                NearestObstacle* nearest) const;
  // Whether a state this backend finds free is free for the exact geometry with no margin (the
  // FCL checker; octree models with RefineMode::kExact), rather than by voxels that hold the
  // geometry with up to a voxel to spare. The certified motion validator then proves each edge
  // from exact clearances alone (docs/validation.md §4): motionClearances and linkPairDistance
  // are exact below their caps.
  virtual bool exactAnswers() const { return false; }
  // A lower bound on the distance between the geometry of links a and b at the scratch's last
  // pose (0 in contact), or `cap` when it is at least `cap`. Exact for exactAnswers() backends;
  // default 0 (no bound).
  virtual double linkPairDistance(BackendScratch& /*scratch*/, int /*link_a*/, int /*link_b*/,
                                  double /*cap*/) const {
    return 0.0;
  }
  // The link poses of the scratch's last query (after any of the queries above), or null when
  // the backend keeps none.
  virtual const RobotData* posedRobot(BackendScratch& /*scratch*/) const { return nullptr; }
  // Poses the robot as setPose would, from link poses that posedRobot gave after an earlier
  // query of this backend (a copy), without forward kinematics again. False when the backend
  // cannot (the default): call setPose instead.
  virtual bool setPosed(const RobotData& /*posed*/, BackendScratch& /*scratch*/) const {
    return false;
  }

  virtual const RobotModel& robot() const = 0;
  // Unique for the process's lifetime (nextModelId), so per-thread scratch can tell which
  // backend it belongs to. Backends over the same model may share it (and their scratch).
  virtual std::uint64_t id() const = 0;
  // Which checker this is, and its name in scene files and results.
  virtual CheckerKind kind() const = 0;
  const char* name() const { return checkerKindName(kind()); }

 protected:
  // explain's contacts, for a finite q of the right size: poses the robot (poseForExplain
  // turns a non-finite link pose into a kNonFinite reason) and appends a reason per contact.
  // The default, for backends that cannot name links: one reason per colliding half
  // (environmentInCollision, selfInCollision) with empty names and an unknown exact contact.
  virtual void explainContacts(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                               BackendScratch& scratch, bool all,
                               StateExplanation& explanation) const;
  // forwardKinematics into `data`; false (and a kNonFinite reason) when a link pose is not
  // finite.
  static bool poseForExplain(const RobotModel& robot, const double* q, std::size_t q_size,
                             const Eigen::Isometry3d& X_WB, RobotData& data,
                             StateExplanation& explanation);

  CollisionBackend() = default;
  CollisionBackend(const CollisionBackend&) = default;
  CollisionBackend(CollisionBackend&&) = default;
  CollisionBackend& operator=(const CollisionBackend&) = default;
  CollisionBackend& operator=(CollisionBackend&&) = default;
};

}  // namespace octomotion
