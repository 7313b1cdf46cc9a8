// The octree model as a CollisionBackend: a shared OctreeCollisionModel and the query path
// (moveTree or fused) to check it with. The queries are inline so that code templated on
// OctreeBackend calls the model directly.
#pragma once

#include <algorithm>
#include <cmath>

#include <memory>

#include "octomotion/error.h"
#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

class OctreeBackend final : public CollisionBackend {
 public:
  struct Scratch final : BackendScratch {
    CheckScratch check;
  };

  // Throws InvalidArgument for a null model.
  OctreeBackend(std::shared_ptr<const OctreeCollisionModel> model, CheckerPath path);

  std::unique_ptr<BackendScratch> makeBackendScratch() const override;

  bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                   BackendScratch& scratch) const override {
    return model_->inCollision(q, q_size, X_WB, path_, scratchOf(scratch).check);
  }
  bool environmentInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                              BackendScratch& scratch) const override {
    CheckScratch& check = pose(q, q_size, X_WB, scratch);
    return model_->environmentInCollision(path_, check);
  }
  bool selfInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch) const override {
    CheckScratch& check = pose(q, q_size, X_WB, scratch);
    return model_->selfInCollision(path_, check);
  }
  // Forward kinematics alone: the clearances and pair distances read the link poses.
  void setPose(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
               BackendScratch& scratch) const override {
    pose(q, q_size, X_WB, scratch);
  }
  // OctreeCollisionModel::clearanceLowerBound.
  double clearance(BackendScratch& scratch) const override {
    return model_->clearanceLowerBound(scratchOf(scratch).check);
  }
  ClearanceBound clearanceBound() const override { return ClearanceBound::kLowerBound; }
  // OctreeCollisionModel::clearanceLowerBoundGrid: one grid lookup per clearance sphere. The
  // moveTree path re-voxelises each moved link on the environment's grid, which conservative
  // rounding grows by up to a voxel diagonal beyond the spheres: that much less.
  double motionClearance(BackendScratch& scratch) const override {
    const double c = model_->clearanceLowerBoundGrid(scratchOf(scratch).check);
    if (path_ != CheckerPath::kMoveTree) return c;
    return std::max(0.0, c - std::sqrt(3.0) * model_->grid().voxelSize());
  }
  // OctreeCollisionModel::clearanceLowerBoundGridPerLink, less the same voxel diagonal on the
  // moveTree path.
  // With RefineMode::kExact, the slabs of refineClearancesPerLink.
  void motionClearances(BackendScratch& scratch, const double* caps, double* per_link,
                        NearestObstacle* nearest) const override {
    const double slack =
        path_ == CheckerPath::kMoveTree ? std::sqrt(3.0) * model_->grid().voxelSize() : 0.0;
    model_->clearanceLowerBoundGridPerLink(scratchOf(scratch).check, caps, slack, per_link);
    if (nearest) std::fill_n(nearest, model_->robot().linkCount(), NearestObstacle{});
    if (model_->refine() == RefineMode::kExact) {
      model_->refineClearancesPerLink(scratchOf(scratch).check, caps, per_link, nearest);
    }
  }
  bool exactAnswers() const override { return model_->refine() == RefineMode::kExact; }
  // OctreeCollisionModel::refinedPairDistance (0 without RefineMode::kExact).
  double linkPairDistance(BackendScratch& scratch, int link_a, int link_b,
                          double cap) const override {
    return model_->refinedPairDistance(scratchOf(scratch).check, link_a, link_b, cap);
  }
  const RobotData* posedRobot(BackendScratch& scratch) const override {
    return &scratchOf(scratch).check.robot;
  }
  // The octree's queries read nothing of a pose but the link poses.
  bool setPosed(const RobotData& posed, BackendScratch& scratch) const override {
    scratchOf(scratch).check.robot = posed;
    return true;
  }

  const RobotModel& robot() const override { return model_->robot(); }
  std::uint64_t id() const override { return model_->id(); }  // scratch depends on the model only
  CheckerKind kind() const override;

  // The scratch behind one made by makeBackendScratch (InvalidArgument for another backend's).
  Scratch& scratchOf(BackendScratch& scratch) const {
    if (scratch.owner != model_->id()) throwForeignScratch();
    return static_cast<Scratch&>(scratch);
  }

  const OctreeCollisionModel& model() const { return *model_; }
  const std::shared_ptr<const OctreeCollisionModel>& sharedModel() const { return model_; }
  CheckerPath path() const { return path_; }

 private:
  void explainContacts(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch, bool all,
                       StateExplanation& explanation) const override;
  [[noreturn]] static void throwForeignScratch();
  // Forward kinematics into the scratch, as OctreeCollisionModel::inCollision does.
  CheckScratch& pose(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                     BackendScratch& scratch) const {
    CheckScratch& check = scratchOf(scratch).check;
    const RobotModel& robot = model_->robot();
    robot.forwardKinematics(q, q_size, check.robot,
                            robot.isFreeFlying() ? X_WB : model_->baseMount());
    return check;
  }

  std::shared_ptr<const OctreeCollisionModel> model_;
  CheckerPath path_;
};

}  // namespace octomotion
