#include "octomotion/planner/model/octree_backend.h"

namespace octomotion {

OctreeBackend::OctreeBackend(std::shared_ptr<const OctreeCollisionModel> model, CheckerPath path)
    : model_(std::move(model)), path_(path) {
  if (!model_) throw InvalidArgument("OctreeBackend: no model");
}

std::unique_ptr<BackendScratch> OctreeBackend::makeBackendScratch() const {
  auto scratch = std::make_unique<Scratch>();
  scratch->check = model_->makeScratch();
  scratch->owner = model_->id();
  return scratch;
}

CheckerKind OctreeBackend::kind() const {
  return path_ == CheckerPath::kFused ? CheckerKind::kOctreeFused : CheckerKind::kOctree;
}

void OctreeBackend::explainContacts(const double* q, std::size_t q_size,
                                    const Eigen::Isometry3d& X_WB, BackendScratch& scratch,
                                    bool all, StateExplanation& explanation) const {
  CheckScratch& check = scratchOf(scratch).check;
  const RobotModel& robot = model_->robot();
  if (!poseForExplain(robot, q, q_size, robot.isFreeFlying() ? X_WB : model_->baseMount(),
                      check.robot, explanation)) {
    return;
  }
  model_->explainContacts(path_, check, all, explanation);
}

void OctreeBackend::throwForeignScratch() {
  throw InvalidArgument("OctreeBackend: the scratch was made by another backend");
}

}  // namespace octomotion
