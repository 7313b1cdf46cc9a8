// EnvironmentGeometry's changes between plans: one object loaded, added, removed or moved.
#include <algorithm>

#include "octomotion/octree/shapes.h"
#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

namespace {

Eigen::AlignedBox3d meshBox(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WO) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(X_WO * v);
  return box;
}

// Updates voxelize the object at once: a pose that is not rigid is refused before anything
// changes.
void requireRigid(const std::string& name, const Eigen::Isometry3d& X_WO) {
  if (!X_WO.matrix().allFinite()) throw InvalidArgument(name + ": pose is not finite");
  const Eigen::Matrix3d R = X_WO.linear();
  if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6) ||
      !(R.determinant() > 0)) {
    throw InvalidArgument(name + ": pose's linear part is not a rotation");
  }
}

}  // namespace

EnvironmentGeometry::Item EnvironmentGeometry::loadItem(const EnvironmentObject& object,
                                                        const WarningSink& warnings) {
  EnvironmentGeometry one = load({object}, warnings);
  return std::move(one.items_.front());
}

const EnvironmentGeometry::Item* EnvironmentGeometry::find(const std::string& name) const {
  for (const Item& item : items_) {
    if (item.spec.name == name) return &item;
  }
  return nullptr;
}

void EnvironmentGeometry::add(Item item) {
  requireRigid(item.spec.name, item.spec.X_WO);
  if (find(item.spec.name)) {
    throw InvalidArgument("environment: an object named '" + item.spec.name +
                          "' exists already (names identify objects for updates)");
  }
  items_.push_back(std::move(item));
}

EnvironmentGeometry::Item EnvironmentGeometry::remove(const std::string& name) {
  const auto it = std::find_if(items_.begin(), items_.end(),
                               [&](const Item& item) { return item.spec.name == name; });
  if (it == items_.end()) throw InvalidArgument("environment: no object named '" + name + "'");
  Item item = std::move(*it);
  items_.erase(it);
  return item;
}

void EnvironmentGeometry::setPose(const std::string& name, const Eigen::Isometry3d& X_WO) {
  const auto it = std::find_if(items_.begin(), items_.end(),
                               [&](const Item& item) { return item.spec.name == name; });
  if (it == items_.end()) throw InvalidArgument("environment: no object named '" + name + "'");
  requireRigid(name, X_WO);
  switch (it->spec.kind) {
    case EnvironmentObject::Kind::kPrimitive:
      it->bounds_W = boundingBox(it->spec.primitive, X_WO);
      break;
    case EnvironmentObject::Kind::kMesh:
      it->bounds_W = meshBox(it->mesh, X_WO);
      break;
    case EnvironmentObject::Kind::kOctomap:
      throw InvalidArgument(name + ": an OctoMap is in world coordinates and cannot be moved");
    case EnvironmentObject::Kind::kPointCloud:
      throw InvalidArgument(name +
                            ": a point cloud's points are stored in the world; remove it and add "
                            "it at the new pose");
  }
  it->spec.X_WO = X_WO;
}

int attachmentLinks(const RobotModel& robot, const AttachedObject& object,
                    std::vector<bool>& allowed) {
  if (object.object.kind != EnvironmentObject::Kind::kPrimitive &&
      object.object.kind != EnvironmentObject::Kind::kMesh) {
    throw InvalidArgument("attach: '" + object.object.name + "' must be a primitive or a mesh");
  }
  const int link = robot.linkIndex(object.link);
  allowed.assign(static_cast<std::size_t>(robot.linkCount()), false);
  allowed[static_cast<std::size_t>(link)] = true;
  for (const std::string& touch : object.touch_links) {
    allowed[static_cast<std::size_t>(robot.linkIndex(touch))] = true;
  }
  return link;
}

}  // namespace octomotion
