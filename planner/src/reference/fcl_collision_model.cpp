#include "octomotion/planner/reference/fcl_collision_model.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <string>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "../robot/internal/fcl_robot.h"
#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

using fcl_internal::Geom;

struct FclCollisionModel::Geometry {
  explicit Geometry(const RobotModel& model, bool keep_mesh_root_transform,
                    bool center_mesh_vertices)
      : robot(model, keep_mesh_root_transform, center_mesh_vertices) {}
  fcl_internal::RobotGeometry robot;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> environment;
  // Broad phase over the environment objects, built once; queries only read it.
  fcl::DynamicAABBTreeCollisionManagerd environment_manager;
  EnvironmentGeometry objects;  // parallel to `environment`: updates and explanations name them
  struct Attached {
    std::string name;
    std::size_t element = 0;  // in robot's elements
    EnvironmentGeometry::Item item;
    int link = -1;
  };
  std::vector<Attached> attached;
};

namespace {

std::unique_ptr<fcl::CollisionObjectd> environmentObject(const EnvironmentGeometry::Item& item) {
  Geom g;
  switch (item.spec.kind) {
    case EnvironmentObject::Kind::kPrimitive:
      g = fcl_internal::shapeOf(item.spec.primitive);
      break;
    case EnvironmentObject::Kind::kMesh:
      g = fcl_internal::meshOf(item.mesh);
      break;
    default:
      throw InvalidArgument(item.spec.name +
                            ": the FCL checker takes primitives and meshes only (use "
                            "fcl-octomap for maps and point clouds)");
  }
  auto object = std::make_unique<fcl::CollisionObjectd>(g, item.spec.X_WO.rotation(),
                                                        item.spec.X_WO.translation());
  fcl_internal::setTightAabb(*object);
  return object;
}

}  // namespace

struct FclCollisionModel::Scratch final : BackendScratch {
  fcl_internal::RobotScratch robot;
};

FclCollisionModel::FclCollisionModel(const RobotModel& robot,
                                     const EnvironmentGeometry& environment,
                                     bool keep_mesh_root_transform, bool center_mesh_vertices,
                                     const Eigen::Isometry3d& mount)
    : id_(nextModelId()),
      robot_(robot),
      mount_(mount),
      geometry_(
          std::make_unique<Geometry>(robot_, keep_mesh_root_transform, center_mesh_vertices)) {
  std::vector<fcl::CollisionObjectd*> objects;
  for (const EnvironmentGeometry::Item& item : environment.items()) {
    geometry_->environment.push_back(environmentObject(item));
    objects.push_back(geometry_->environment.back().get());
  }
  if (!objects.empty()) {
    geometry_->environment_manager.registerObjects(objects);
    geometry_->environment_manager.setup();
  }
  geometry_->objects = environment;
}

FclCollisionModel::~FclCollisionModel() = default;
FclCollisionModel::FclCollisionModel(FclCollisionModel&&) noexcept = default;

void FclCollisionModel::ScratchDeleter::operator()(Scratch* s) const {
  delete s;
}

FclCollisionModel::ScratchPtr FclCollisionModel::makeScratch() const {
  ScratchPtr s(new Scratch);
  geometry_->robot.initScratch(robot_, s->robot);
  s->owner = id_;
  return s;
}

std::unique_ptr<BackendScratch> FclCollisionModel::makeBackendScratch() const {
  return std::unique_ptr<BackendScratch>(makeScratch().release());
}

FclCollisionModel::Scratch& FclCollisionModel::scratchOf(BackendScratch& scratch) const {
  if (scratch.owner != id_) {
    throw InvalidArgument("FclCollisionModel: the scratch was made by another backend");
  }
  return static_cast<Scratch&>(scratch);
}

bool FclCollisionModel::inCollision(const double* q, std::size_t q_size,
                                    const Eigen::Isometry3d& X_WB, BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return inCollision(s);
}

bool FclCollisionModel::environmentInCollision(const double* q, std::size_t q_size,
                                               const Eigen::Isometry3d& X_WB,
                                               BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return environmentInCollision(s);
}

bool FclCollisionModel::selfInCollision(const double* q, std::size_t q_size,
                                        const Eigen::Isometry3d& X_WB,
                                        BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return selfInCollision(s);
}

double FclCollisionModel::clearance(BackendScratch& scratch) const {
  return environmentDistance(scratchOf(scratch));
}

void FclCollisionModel::setConfiguration(const double* q, std::size_t q_size,
                                         const Eigen::Isometry3d& X_WB, Scratch& s) const {
  if (s.owner != id_) {  // made before a world update: the robot's elements may differ
    geometry_->robot.initScratch(robot_, s.robot);
    s.owner = id_;
  }
  geometry_->robot.pose(robot_, q, q_size, robot_.isFreeFlying() ? X_WB : mount_, s.robot);
}

namespace {

struct BroadPhaseQuery {
  const fcl::CollisionRequestd* request;
  fcl::CollisionResultd* result;
  bool hit = false;
};

// Called by the broad phase for each environment object whose AABB overlaps the link's.
bool narrowPhase(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto& query = *static_cast<BroadPhaseQuery*>(data);
  query.result->clear();
  query.hit = fcl::collide(a, b, *query.request, *query.result) > 0;
  return query.hit;  // stop at the first contact
}

}  // namespace

bool FclCollisionModel::environmentInCollision(Scratch& s) const {
  if (geometry_->environment.empty()) return false;
  BroadPhaseQuery query{&s.robot.request, &s.robot.result};
  for (fcl::CollisionObjectd& link_object : s.robot.objects) {
    geometry_->environment_manager.collide(&link_object, &query, narrowPhase);
    if (query.hit) return true;
  }
  return false;
}

bool FclCollisionModel::selfInCollision(Scratch& s) const {
  return geometry_->robot.selfInCollision(s.robot);
}

bool FclCollisionModel::inCollision(Scratch& s) const {
  return environmentInCollision(s) || selfInCollision(s);
}

namespace {

struct DistanceQuery {
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  double best;
};

// Called by the broad phase for each environment object whose AABB is nearer than the best
// distance so far (FCL's recursion prunes with the value written to `dist`).
bool distanceNarrowPhase(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data,
                         double& dist) {
  auto& query = *static_cast<DistanceQuery*>(data);
  if (a->getAABB().distance(b->getAABB()) < query.best) {
    query.result.clear();
    fcl::distance(a, b, query.request, query.result);
    query.best = std::min(query.best, std::max(0.0, query.result.min_distance));
  }
  dist = query.best;
  return query.best <= 0;  // stop at contact
}

}  // namespace

double FclCollisionModel::environmentDistance(Scratch& s, double cap) const {
  if (geometry_->environment.empty()) return std::numeric_limits<double>::infinity();
  DistanceQuery query;
  query.best = cap;
  for (fcl::CollisionObjectd& link_object : s.robot.objects) {
    geometry_->environment_manager.distance(&link_object, &query, distanceNarrowPhase);
    if (query.best <= 0) return 0;
  }
  return query.best;
}

void FclCollisionModel::motionClearances(BackendScratch& scratch, const double* caps,
                                         double* per_link, NearestObstacle* nearest) const {
  Scratch& s = scratchOf(scratch);
  if (nearest) std::fill_n(nearest, robot_.linkCount(), NearestObstacle{});
  for (int l = 0; l < robot_.linkCount(); ++l) {
    per_link[l] = std::numeric_limits<double>::infinity();
  }
  if (geometry_->environment.empty()) return;
  for (std::size_t e = 0; e < s.robot.objects.size(); ++e) {
    const int link = geometry_->robot.elementLink(e);
    if (caps[link] <= 0 || per_link[link] <= 0) continue;
    DistanceQuery query;
    query.best = std::min(per_link[link], caps[link]);
    geometry_->environment_manager.distance(&s.robot.objects[e], &query, distanceNarrowPhase);
    per_link[link] = std::min(per_link[link], query.best);
  }
}

double FclCollisionModel::linkPairDistance(BackendScratch& scratch, int link_a, int link_b,
                                           double cap) const {
  return geometry_->robot.linksDistance(scratchOf(scratch).robot, link_a, link_b, cap);
}

const RobotData* FclCollisionModel::posedRobot(BackendScratch& scratch) const {
  return &scratchOf(scratch).robot.robot;
}

void FclCollisionModel::explainContacts(const double* q, std::size_t q_size,
                                        const Eigen::Isometry3d& X_WB, BackendScratch& scratch,
                                        bool all, StateExplanation& explanation) const {
  Scratch& s = scratchOf(scratch);
  if (!poseForExplain(robot_, q, q_size, robot_.isFreeFlying() ? X_WB : mount_, s.robot.robot,
                      explanation)) {
    return;
  }
  geometry_->robot.poseElements(s.robot.robot, s.robot);
  // Every link against every object (no broad phase: not a hot path), link by link.
  for (int link = 0; link < robot_.linkCount(); ++link) {
    if (!robot_.link(link).hasCollision()) continue;
    for (std::size_t o = 0; o < geometry_->environment.size(); ++o) {
      if (!geometry_->robot.linkCollides(s.robot, link, *geometry_->environment[o])) continue;
      InvalidityReason r;
      r.kind = InvalidityReason::Kind::kEnvironment;
      r.link = robot_.link(link).name;
      r.other = geometry_->objects.items()[o].spec.name;
      explanation.reasons.push_back(r);
      if (!all) return;
    }
  }
  for (const auto& [a, b] : geometry_->robot.collidingPairs(s.robot, all)) {
    InvalidityReason r;
    r.kind = InvalidityReason::Kind::kSelf;
    r.link = robot_.link(a).name;
    r.other = robot_.link(b).name;
    explanation.reasons.push_back(r);
  }
}

double FclCollisionModel::selfDistance(Scratch& s, double cap) const {
  return geometry_->robot.selfDistance(s.robot, cap);
}

// ---- World updates.

const EnvironmentGeometry& FclCollisionModel::objects() const {
  return geometry_->objects;
}

void FclCollisionModel::addObject(EnvironmentGeometry::Item item) {
  for (const Geometry::Attached& a : geometry_->attached) {
    if (a.name == item.spec.name) {
      throw InvalidArgument("environment: '" + item.spec.name + "' names an attached object");
    }
  }
  auto object = environmentObject(item);
  geometry_->objects.add(std::move(item));
  geometry_->environment_manager.registerObject(object.get());
  geometry_->environment.push_back(std::move(object));
  id_ = nextModelId();
}

namespace {

std::size_t indexOf(const EnvironmentGeometry& objects, const std::string& name) {
  const auto& items = objects.items();
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].spec.name == name) return i;
  }
  throw InvalidArgument("environment: no object named '" + name + "'");
}

}  // namespace

void FclCollisionModel::removeObject(const std::string& name) {
  const std::size_t i = indexOf(geometry_->objects, name);
  geometry_->objects.remove(name);  // items keep their order: `environment` stays parallel
  geometry_->environment_manager.unregisterObject(geometry_->environment[i].get());
  geometry_->environment.erase(geometry_->environment.begin() + static_cast<std::ptrdiff_t>(i));
  id_ = nextModelId();
}

void FclCollisionModel::moveObject(const std::string& name, const Eigen::Isometry3d& X_WO) {
  const std::size_t i = indexOf(geometry_->objects, name);
  geometry_->objects.setPose(name, X_WO);
  fcl::CollisionObjectd& object = *geometry_->environment[i];
  object.setTransform(X_WO.rotation(), X_WO.translation());
  fcl_internal::setTightAabb(object);
  geometry_->environment_manager.update(&object);
  id_ = nextModelId();
}

void FclCollisionModel::attachObject(const AttachedObject& object, const WarningSink& warnings) {
  const std::string& name = object.object.name;
  if (geometry_->objects.find(name) != nullptr) {
    throw InvalidArgument("attach: '" + name + "' names an object of the world");
  }
  for (const Geometry::Attached& a : geometry_->attached) {
    if (a.name == name) {
      throw InvalidArgument("attach: an object named '" + name + "' is attached already");
    }
  }
  std::vector<bool> allowed;
  const int link = attachmentLinks(robot_, object, allowed);
  EnvironmentGeometry::Item item = EnvironmentGeometry::loadItem(object.object, warnings);
  Geom g = item.spec.kind == EnvironmentObject::Kind::kPrimitive
               ? fcl_internal::shapeOf(item.spec.primitive)
               : fcl_internal::meshOf(item.mesh);
  const std::size_t element =
      geometry_->robot.addElement(link, object.object.X_WO, std::move(g), allowed);
  geometry_->attached.push_back({name, element, std::move(item), link});
  id_ = nextModelId();
}

void FclCollisionModel::detachObject(const std::string& name,
                                     const std::optional<Eigen::Isometry3d>& leave_at_W) {
  auto& attached = geometry_->attached;
  const auto it = std::find_if(attached.begin(), attached.end(),
                               [&](const Geometry::Attached& a) { return a.name == name; });
  if (it == attached.end()) throw InvalidArgument("detach: no attached object '" + name + "'");
  std::optional<EnvironmentGeometry::Item> left;
  if (leave_at_W) {
    EnvironmentGeometry one;
    one.add(it->item);
    one.setPose(name, *leave_at_W);
    left = one.remove(name);
  }
  const std::size_t element = it->element;
  attached.erase(it);
  geometry_->robot.removeElement(element);
  for (Geometry::Attached& a : attached) {
    if (a.element > element) --a.element;
  }
  id_ = nextModelId();
  if (left) addObject(std::move(*left));
}

}  // namespace octomotion
