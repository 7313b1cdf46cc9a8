// Choosing and building a scene's motion validator (ompl/certified_motion_validator.h).
#include <memory>

#include <ompl/base/DiscreteMotionValidator.h>

#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

std::shared_ptr<const LinkMotionBound> makeLinkMotionBound(
    const RobotModel& robot, bool keep_mesh_root_transform, bool center_mesh_vertices,
    const std::vector<AttachedObject>& attached) {
  std::vector<LinkMotionBound::CarriedPoints> carried;
  for (const AttachedObject& a : attached) {
    // object.X_WO is the pose in the link, so the box is in the link's frame.
    const std::optional<Eigen::AlignedBox3d> box = EnvironmentGeometry::load({a.object}).bounds();
    if (!box) continue;
    LinkMotionBound::CarriedPoints c;
    c.link = robot.linkIndex(a.link);
    for (int corner = 0; corner < 8; ++corner) {
      c.points.push_back(box->corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
    }
    carried.push_back(std::move(c));
  }
  return std::make_shared<const LinkMotionBound>(robot, keep_mesh_root_transform,
                                                 center_mesh_vertices, carried);
}

void setMotionValidator(const ompl::base::SpaceInformationPtr& si, MotionValidatorKind kind,
                        std::shared_ptr<const CollisionBackend> backend,
                        std::shared_ptr<const LinkMotionBound> bound, double resolution) {
  if (kind != MotionValidatorKind::kCertified) {
    si->setMotionValidator(std::make_shared<ompl::base::DiscreteMotionValidator>(si));
    return;
  }
  si->setMotionValidator(std::make_shared<CertifiedMotionValidator>(si, std::move(backend),
                                                                    std::move(bound), resolution));
}

void installMotionValidator(PlanningScene& scene,
                            const std::shared_ptr<const CollisionBackend>& backend) {
  if (!scene.setup) return;
  const ompl::base::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const MotionValidatorKind kind = scene.spec.problem.motion_validator;
  std::shared_ptr<const LinkMotionBound> bound;
  if (kind == MotionValidatorKind::kCertified) {
    bound = makeLinkMotionBound(backend->robot(), scene.spec.robot.keep_mesh_root_transform,
                                scene.spec.robot.center_mesh_vertices, scene.attached);
  }
  setMotionValidator(si, kind, backend, std::move(bound), *scene.spec.octree.resolution);
}

ompl::geometric::SimpleSetupPtr makeSimpleSetup(const std::string& scene_path,
                                                const SceneOverrides& overrides,
                                                const WarningSink& warnings) {
  return loadPlanningScene(scene_path, overrides, warnings).setup;
}

}  // namespace octomotion
