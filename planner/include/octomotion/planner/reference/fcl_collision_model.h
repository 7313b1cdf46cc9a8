// The exact reference: the same robot, self-collision pairs and environment checked with FCL
// (meshes as BVHModel<OBBRSS>, primitives as FCL shapes). Used to validate the octree checker
// and to measure the speed/accuracy trade against it in the same run, so it is written as a
// careful FCL user would (MoveIt's FCL plugin does the same): the environment in a broad phase
// (DynamicAABBTreeCollisionManager), tight world AABBs pre-tested before every narrow phase,
// nothing allocated per query once a thread's scratch exists.
//
// FCL treats meshes as surfaces: a mesh swallowed whole by another mesh does not collide.
// Primitives are solids.
//
// A CollisionBackend with exact clearance; its OMPL checker is FclValidityChecker
// (ompl/validity_checker.h).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

class FclCollisionModel final : public CollisionBackend {
 public:
  // Mesh conventions as in CollisionModelOptions. `mount`: a fixed-base robot's root link pose
  // in the world (CollisionModelOptions::X_WB); free-flying robots ignore it.
  FclCollisionModel(const RobotModel& robot, const EnvironmentGeometry& environment,
                    bool keep_mesh_root_transform = false, bool center_mesh_vertices = false,
                    const Eigen::Isometry3d& mount = Eigen::Isometry3d::Identity());
  ~FclCollisionModel() override;
  FclCollisionModel(FclCollisionModel&&) noexcept;

  struct Scratch;  // per-thread: FK results and the robot's FCL objects (opaque BackendScratch)
  struct ScratchDeleter {
    void operator()(Scratch* s) const;
  };
  using ScratchPtr = std::unique_ptr<Scratch, ScratchDeleter>;
  ScratchPtr makeScratch() const;

  // Link poses from q (and X_WB for free-flying robots; fixed-base robots use baseMount()) into
  // the scratch.
  void setConfiguration(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                        Scratch& scratch) const;
  // Environment contacts and checked self pairs at the scratch's configuration.
  bool inCollision(Scratch& scratch) const;
  // Its two halves: links against the environment only, and the checked self pairs only.
  bool environmentInCollision(Scratch& scratch) const;
  bool selfInCollision(Scratch& scratch) const;
  // Exact distance from the robot to the environment (0 in contact, +inf without environment).
  // With a finite `cap`, any distance >= cap may be returned as cap: objects whose AABBs are
  // that far apart are skipped, so a cap makes "is it within cap?" cheap.
  double environmentDistance(Scratch& scratch,
                             double cap = std::numeric_limits<double>::infinity()) const;
  // Exact smallest distance between the links of the checked self pairs (0 in contact, +inf
  // without pairs); `cap` as above.
  double selfDistance(Scratch& scratch, double cap = std::numeric_limits<double>::infinity()) const;

  // CollisionBackend: setConfiguration, then the query above; clearance is environmentDistance.
  std::unique_ptr<BackendScratch> makeBackendScratch() const override;
  bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                   BackendScratch& scratch) const override;
  bool environmentInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                              BackendScratch& scratch) const override;
  bool selfInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch) const override;
  double clearance(BackendScratch& scratch) const override;
  // setConfiguration alone.
  void setPose(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
               BackendScratch& scratch) const override {
    setConfiguration(q, q_size, X_WB, scratchOf(scratch));
  }
  // environmentDistance link by link, each capped at caps[l]; no slabs.
  void motionClearances(BackendScratch& scratch, const double* caps, double* per_link,
                        NearestObstacle* nearest) const override;
  const RobotData* posedRobot(BackendScratch& scratch) const override;
  ClearanceBound clearanceBound() const override { return ClearanceBound::kExact; }
  bool exactAnswers() const override { return true; }
  // FCL's distance between the two links' elements (capped as CollisionBackend says).
  double linkPairDistance(BackendScratch& scratch, int link_a, int link_b,
                          double cap) const override;

  // The scratch behind one made by makeBackendScratch, for the queries above (InvalidArgument for
  // another backend's).
  Scratch& scratchOf(BackendScratch& scratch) const;

  const RobotModel& robot() const override { return robot_; }
  std::uint64_t id() const override { return id_; }  // see OctreeCollisionModel::id
  CheckerKind kind() const override { return CheckerKind::kFcl; }
  const Eigen::Isometry3d& baseMount() const { return mount_; }

  // ---- World updates, as OctreeCollisionModel's (the same names, rules and errors, less the
  // universe's: nothing is voxelized). Between queries only; each gives a new id(), so
  // BackendScratch made before must be remade (the Scratch API's setConfiguration remakes its
  // own). Primitives and meshes only.
  void addObject(EnvironmentGeometry::Item item);
  void removeObject(const std::string& name);
  void moveObject(const std::string& name, const Eigen::Isometry3d& X_WO);
  void attachObject(const AttachedObject& object, const WarningSink& warnings = {});
  void detachObject(const std::string& name,
                    const std::optional<Eigen::Isometry3d>& leave_at_W = std::nullopt);
  const EnvironmentGeometry& objects() const;

 private:
  void explainContacts(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch, bool all,
                       StateExplanation& explanation) const override;

  struct Geometry;
  std::uint64_t id_;
  RobotModel robot_;
  Eigen::Isometry3d mount_;
  std::unique_ptr<Geometry> geometry_;
};

}  // namespace octomotion
