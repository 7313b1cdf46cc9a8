#include "octomotion/planner/reference/fcl_collision_model.h"

#include <limits>
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
  std::vector<std::string> environment_names;  // parallel to environment (explain)
  // Broad phase over the environment objects, built once; queries only read it.
  fcl::DynamicAABBTreeCollisionManagerd environment_manager;
};

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
    objects.push_back(object.get());
    geometry_->environment.push_back(std::move(object));
    geometry_->environment_names.push_back(item.spec.name);
  }
  if (!objects.empty()) {
    geometry_->environment_manager.registerObjects(objects);
    geometry_->environment_manager.setup();
  }
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
      r.other = geometry_->environment_names[o];
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

}  // namespace octomotion
