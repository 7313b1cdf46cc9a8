// PlanningScene's world updates between plans: the octree model changes in place, the exact
// references are rebuilt on next use from the updated objects (with the attached ones), and the
// OMPL setup gets the current checker with its planner data cleared.
#include <algorithm>

#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {

namespace {

// After an update: the references from the current objects, then the checker and the planner.
void refresh(PlanningScene& scene) {
  scene.environment = std::make_shared<const EnvironmentGeometry>(scene.model->objects());
  const std::shared_ptr<const OctreeCollisionModel> octree_model = scene.model;
  const std::shared_ptr<const EnvironmentGeometry> objects = scene.environment;
  const std::vector<AttachedObject> attached = scene.attached;
  const bool keep = scene.spec.robot.keep_mesh_root_transform;
  const bool center = scene.spec.robot.center_mesh_vertices;
  const double resolution = *scene.spec.octree.resolution;
  scene.fcl_model = LazyModel<FclCollisionModel>([octree_model, objects, attached, keep, center]() {
    auto model = std::make_shared<FclCollisionModel>(octree_model->robot(), *objects, keep, center);
    for (const AttachedObject& a : attached) model->attachObject(a);
    return std::shared_ptr<const FclCollisionModel>(std::move(model));
  });
  scene.fcl_octomap_model = LazyModel<FclOctomapCollisionModel>(
      [octree_model, objects, attached, keep, center, resolution]() {
        if (!attached.empty()) {
          throw InvalidArgument(
              "the fcl-octomap reference does not model attached objects; use fcl or an octree "
              "checker");
        }
        return std::make_shared<const FclOctomapCollisionModel>(octree_model->robot(), *objects,
                                                                resolution, keep, center);
      });
  if (!scene.setup) return;
  const ompl::base::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  std::shared_ptr<const CollisionBackend> backend;
  if (scene.checker == CheckerKind::kFcl) {
    backend = scene.fclModel();
  } else if (scene.checker == CheckerKind::kFclOctomap) {
    backend = scene.fclOctomapModel();
  } else {
    backend = std::make_shared<const OctreeBackend>(scene.model, octreeCheckerPath(scene.checker));
  }
  scene.setup->setStateValidityChecker(makeValidityChecker(si, backend));
  installMotionValidator(scene, backend);  // attached objects change the links' reach
  scene.setup->clear();                    // roadmaps and trees were checked against the old world
}

}  // namespace

void PlanningScene::addObject(const EnvironmentObject& object, const WarningSink& warnings) {
  model->addObject(object, warnings);
  refresh(*this);
}

void PlanningScene::removeObject(const std::string& name) {
  model->removeObject(name);
  refresh(*this);
}

void PlanningScene::moveObject(const std::string& name, const Eigen::Isometry3d& X_WO) {
  model->moveObject(name, X_WO);
  refresh(*this);
}

void PlanningScene::attachObject(const AttachedObject& object, const WarningSink& warnings) {
  if (checker == CheckerKind::kFclOctomap) {
    throw InvalidArgument("attach: the fcl-octomap checker does not model attached objects");
  }
  model->attachObject(object, warnings);
  attached.push_back(object);
  refresh(*this);
}

void PlanningScene::detachObject(const std::string& name, const std::vector<double>* leave_at_q) {
  std::optional<Eigen::Isometry3d> leave_at_W;
  if (leave_at_q) {
    leave_at_W = model->attachedObjectPose(name, leave_at_q->data(), leave_at_q->size(),
                                           Eigen::Isometry3d::Identity());
  }
  model->detachObject(name, leave_at_W);
  attached.erase(std::remove_if(attached.begin(), attached.end(),
                                [&](const AttachedObject& a) { return a.object.name == name; }),
                 attached.end());
  refresh(*this);
}

}  // namespace octomotion
