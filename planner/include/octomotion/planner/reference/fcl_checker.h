// The exact reference: the same robot, self-collision pairs and environment checked with FCL
// (meshes as BVHModel<OBBRSS>, primitives as FCL shapes). Used to validate the octree checker
// and to measure the speed/accuracy trade against it in the same run, so it is written as a
// careful FCL user would (MoveIt's FCL plugin does the same): the environment in a broad phase
// (DynamicAABBTreeCollisionManager), tight world AABBs pre-tested before every narrow phase,
// nothing allocated per query once a thread's scratch exists.
//
// FCL treats meshes as surfaces: a mesh swallowed whole by another mesh does not collide.
// Primitives are solids.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <ompl/base/StateValidityChecker.h>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/octree_validity_checker.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

class FclCollisionModel {
 public:
  // Mesh conventions as in CollisionModelOptions.
  FclCollisionModel(const RobotModel& robot, const EnvironmentGeometry& environment,
                    bool keep_mesh_root_transform = false, bool center_mesh_vertices = false);
  ~FclCollisionModel();
  FclCollisionModel(FclCollisionModel&&) noexcept;

  struct Scratch;  // per-thread: FK results and the robot's FCL objects (opaque)
  struct ScratchDeleter {
    void operator()(Scratch* s) const;
  };
  using ScratchPtr = std::unique_ptr<Scratch, ScratchDeleter>;
  ScratchPtr makeScratch() const;

  // Link poses from q (and X_WB for free-flying robots) into the scratch.
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

  const RobotModel& robot() const { return robot_; }
  std::uint64_t id() const { return id_; }  // see OctreeCollisionModel::id

 private:
  struct Geometry;
  std::uint64_t id_;
  RobotModel robot_;
  std::unique_ptr<Geometry> geometry_;
};

class FclValidityChecker : public ompl::base::StateValidityChecker {
 public:
  FclValidityChecker(const ompl::base::SpaceInformationPtr& si,
                     std::shared_ptr<const FclCollisionModel> model);
  ~FclValidityChecker() override;
  bool isValid(const ompl::base::State* state) const override;
  // Exact distance to the environment (0 when invalid).
  double clearance(const ompl::base::State* state) const override;

 private:
  std::shared_ptr<const FclCollisionModel> model_;
  BoundsCheck in_bounds_;
};

}  // namespace octomotion
