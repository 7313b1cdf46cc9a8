#include "octomotion/planner/ompl/validity_checker.h"

namespace octomotion {

template class ValidityChecker<CollisionBackend>;
template class ValidityChecker<OctreeBackend>;
template class ValidityChecker<FclCollisionModel>;
template class ValidityChecker<FclOctomapCollisionModel>;

ompl::base::StateValidityCheckerPtr makeValidityChecker(
    const ompl::base::SpaceInformationPtr& si,
    const std::shared_ptr<const CollisionBackend>& backend) {
  if (!backend) throw InvalidArgument("makeValidityChecker: no collision backend");
  if (auto octree = std::dynamic_pointer_cast<const OctreeBackend>(backend)) {
    return std::make_shared<OctreeValidityChecker>(si, std::move(octree));
  }
  if (auto fcl = std::dynamic_pointer_cast<const FclCollisionModel>(backend)) {
    return std::make_shared<FclValidityChecker>(si, std::move(fcl));
  }
  if (auto octomap = std::dynamic_pointer_cast<const FclOctomapCollisionModel>(backend)) {
    return std::make_shared<FclOctomapValidityChecker>(si, std::move(octomap));
  }
  return std::make_shared<ValidityChecker<CollisionBackend>>(si, backend);
}

}  // namespace octomotion
