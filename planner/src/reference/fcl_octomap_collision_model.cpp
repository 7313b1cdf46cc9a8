#include "octomotion/planner/reference/fcl_octomap_collision_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fcl/geometry/octree/octree.h>
#include <fcl/narrowphase/collision.h>
#include <octomap/OcTree.h>

#include "../robot/internal/fcl_robot.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

struct FclOctomapCollisionModel::Geometry {
  Geometry(const RobotModel& model, bool keep_mesh_root_transform, bool center_mesh_vertices)
      : robot(model, keep_mesh_root_transform, center_mesh_vertices) {}
  fcl_internal::RobotGeometry robot;
  std::shared_ptr<const octomap::OcTree> map;
  std::unique_ptr<fcl::CollisionObjectd> environment;  // null when nothing is occupied
  // Each object's name and world box (explain: the map fuses the objects, so a contact is put
  // down to the objects whose box, grown by a voxel diagonal, meets the link element's box).
  std::vector<std::pair<std::string, Eigen::AlignedBox3d>> objects;
};

struct FclOctomapCollisionModel::Scratch final : BackendScratch {
  fcl_internal::RobotScratch robot;
};

FclOctomapCollisionModel::FclOctomapCollisionModel(const RobotModel& robot,
                                                   const EnvironmentGeometry& environment,
                                                   double resolution, bool keep_mesh_root_transform,
                                                   bool center_mesh_vertices,
                                                   const Eigen::Isometry3d& mount)
    : id_(nextModelId()),
      robot_(robot),
      mount_(mount),
      resolution_(resolution),
      geometry_(
          std::make_unique<Geometry>(robot_, keep_mesh_root_transform, center_mesh_vertices)) {
  const auto start = std::chrono::steady_clock::now();
  const WorldGrid grid = octomapNativeGrid(resolution);
  const Octree voxels = environment.voxelize(grid, Rounding::kConservative);
  // On the native grid our cubes are OctoMap's nodes of the same keys (octomap_io.h).
  geometry_->map = toOctoMap(voxels);
  octomap_bytes_ = geometry_->map->memoryUsage();
  if (const auto b = voxels.bounds()) {
    auto tree = std::make_shared<fcl::OcTreed>(geometry_->map);
    geometry_->environment = std::make_unique<fcl::CollisionObjectd>(tree);
    // FCL bounds an OcTree by its whole key range; the occupied voxels' box is the useful
    // pre-test for the links.
    fcl::AABBd& aabb = const_cast<fcl::AABBd&>(geometry_->environment->getAABB());
    aabb.min_ = grid.cubeMin(Cube{0, b->min});
    aabb.max_ = grid.cubeMax(Cube{0, b->max});
  }
  for (const EnvironmentGeometry::Item& item : environment.items()) {
    Eigen::AlignedBox3d box = item.bounds_W;
    if (!box.isEmpty()) {
      const Eigen::Vector3d grow = Eigen::Vector3d::Constant(std::sqrt(3.0) * resolution);
      box = Eigen::AlignedBox3d(box.min() - grow, box.max() + grow);
    }
    geometry_->objects.emplace_back(item.spec.name, box);
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

FclOctomapCollisionModel::~FclOctomapCollisionModel() = default;
FclOctomapCollisionModel::FclOctomapCollisionModel(FclOctomapCollisionModel&&) noexcept = default;

void FclOctomapCollisionModel::ScratchDeleter::operator()(Scratch* s) const {
  delete s;
}

FclOctomapCollisionModel::ScratchPtr FclOctomapCollisionModel::makeScratch() const {
  ScratchPtr s(new Scratch);
  geometry_->robot.initScratch(robot_, s->robot);
  s->owner = id_;
  return s;
}

std::unique_ptr<BackendScratch> FclOctomapCollisionModel::makeBackendScratch() const {
  return std::unique_ptr<BackendScratch>(makeScratch().release());
}

FclOctomapCollisionModel::Scratch& FclOctomapCollisionModel::scratchOf(
    BackendScratch& scratch) const {
  if (scratch.owner != id_) {
    throw InvalidArgument("FclOctomapCollisionModel: the scratch was made by another backend");
  }
  return static_cast<Scratch&>(scratch);
}

bool FclOctomapCollisionModel::inCollision(const double* q, std::size_t q_size,
                                           const Eigen::Isometry3d& X_WB,
                                           BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return inCollision(s);
}

bool FclOctomapCollisionModel::environmentInCollision(const double* q, std::size_t q_size,
                                                      const Eigen::Isometry3d& X_WB,
                                                      BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return environmentInCollision(s);
}

bool FclOctomapCollisionModel::selfInCollision(const double* q, std::size_t q_size,
                                               const Eigen::Isometry3d& X_WB,
                                               BackendScratch& scratch) const {
  Scratch& s = scratchOf(scratch);
  setConfiguration(q, q_size, X_WB, s);
  return selfInCollision(s);
}

void FclOctomapCollisionModel::setConfiguration(const double* q, std::size_t q_size,
                                                const Eigen::Isometry3d& X_WB, Scratch& s) const {
  geometry_->robot.pose(robot_, q, q_size, robot_.isFreeFlying() ? X_WB : mount_, s.robot);
}

bool FclOctomapCollisionModel::environmentInCollision(Scratch& s) const {
  if (!geometry_->environment) return false;
  for (const fcl::CollisionObjectd& link_object : s.robot.objects) {
    if (fcl_internal::collidePair(link_object, *geometry_->environment, s.robot.request,
                                  s.robot.result)) {
      return true;
    }
  }
  return false;
}

bool FclOctomapCollisionModel::selfInCollision(Scratch& s) const {
  return geometry_->robot.selfInCollision(s.robot);
}

void FclOctomapCollisionModel::explainContacts(const double* q, std::size_t q_size,
                                               const Eigen::Isometry3d& X_WB,
                                               BackendScratch& scratch, bool all,
                                               StateExplanation& explanation) const {
  Scratch& s = scratchOf(scratch);
  if (!poseForExplain(robot_, q, q_size, robot_.isFreeFlying() ? X_WB : mount_, s.robot.robot,
                      explanation)) {
    return;
  }
  geometry_->robot.poseElements(s.robot.robot, s.robot);
  auto add = [&](InvalidityReason::Kind kind, int link, const std::string& other) {
    InvalidityReason r;
    r.kind = kind;
    r.link = robot_.link(link).name;
    r.other = other;
    if (kind == InvalidityReason::Kind::kEnvironment) {
      r.exact = ExactContact::kUnknown;  // the map's voxels, not the objects' shapes
      r.margin = resolution_;
    }
    explanation.reasons.push_back(r);
  };
  if (geometry_->environment) {
    const fcl_internal::RobotGeometry& robot = geometry_->robot;
    for (int link = 0; link < robot_.linkCount(); ++link) {
      if (!robot_.link(link).hasCollision() ||
          !robot.linkCollides(s.robot, link, *geometry_->environment)) {
        continue;
      }
      // The objects near the link's colliding elements.
      std::vector<std::string> near;
      for (std::size_t e = 0; e < robot.elementCount(); ++e) {
        if (robot.elementLink(e) != link) continue;
        const fcl::AABBd& box = s.robot.objects[e].getAABB();
        for (const auto& [name, object_box] : geometry_->objects) {
          if (object_box.isEmpty() || (box.min_.array() > object_box.max().array()).any() ||
              (box.max_.array() < object_box.min().array()).any() ||
              std::find(near.begin(), near.end(), name) != near.end()) {
            continue;
          }
          near.push_back(name);
        }
      }
      if (near.empty()) near.emplace_back();  // cannot tell: "the environment"
      for (const std::string& name : near) {
        add(InvalidityReason::Kind::kEnvironment, link, name);
        if (!all) return;
      }
    }
  }
  for (const auto& [a, b] : geometry_->robot.collidingPairs(s.robot, all)) {
    add(InvalidityReason::Kind::kSelf, a, robot_.link(b).name);
  }
}

bool FclOctomapCollisionModel::inCollision(Scratch& s) const {
  return environmentInCollision(s) || selfInCollision(s);
}

}  // namespace octomotion
