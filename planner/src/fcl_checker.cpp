#include "octomotion/planner/fcl_checker.h"

#include <limits>
#include <map>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <ompl/base/SpaceInformation.h>

#include "octomotion/octree/mesh.h"
#include "octomotion/planner/octree_validity_checker.h"

namespace octomotion {

namespace {

using Geom = std::shared_ptr<fcl::CollisionGeometryd>;

Geom shapeOf(const Primitive& p) {
  if (const auto* b = std::get_if<Box>(&p)) {
    const Eigen::Vector3d size = 2 * b->half_extents;
    return std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z());
  }
  if (const auto* s = std::get_if<Sphere>(&p)) return std::make_shared<fcl::Sphered>(s->radius);
  const auto& c = std::get<Cylinder>(p);
  return std::make_shared<fcl::Cylinderd>(c.radius, c.length);
}

Geom meshOf(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

}  // namespace

struct FclCollisionModel::Geometry {
  struct Element {
    int link;
    Geom geometry;
    Eigen::Isometry3d X_LE;
  };
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> environment;
  std::vector<Element> elements;
  std::vector<std::vector<int>> link_elements;  // link -> indices into elements
  // One object per element, made once: FCL's CollisionObject constructor writes to the shared
  // geometry (computeLocalAABB), so threads copy these instead of constructing their own.
  std::vector<fcl::CollisionObjectd> prototypes;
};

struct FclCollisionModel::Scratch {
  RobotData robot;
  std::vector<fcl::CollisionObjectd> objects;  // one per element, posed in the world
};

FclCollisionModel::FclCollisionModel(const RobotModel& robot,
                                     const EnvironmentGeometry& environment,
                                     bool keep_mesh_root_transform, bool center_mesh_vertices)
    : id_(nextModelId()), robot_(robot), geometry_(std::make_unique<Geometry>()) {
  for (const EnvironmentGeometry::Item& item : environment.items()) {
    Geom g;
    switch (item.spec.kind) {
      case EnvironmentObject::Kind::kPrimitive:
        g = shapeOf(item.spec.primitive);
        break;
      case EnvironmentObject::Kind::kMesh:
        g = meshOf(item.mesh);
        break;
      default:
        throw InvalidArgument(item.spec.name +
                              ": the FCL checker takes primitives and meshes only (use "
                              "fcl-octomap for maps and point clouds)");
    }
    auto object = std::make_unique<fcl::CollisionObjectd>(g, item.spec.X_WO.rotation(),
                                                          item.spec.X_WO.translation());
    object->computeAABB();
    geometry_->environment.push_back(std::move(object));
  }
  std::map<std::string, Geom> meshes;
  geometry_->link_elements.resize(static_cast<std::size_t>(robot_.linkCount()));
  for (int l = 0; l < robot_.linkCount(); ++l) {
    for (const CollisionElement& e : robot_.link(l).collision) {
      Geom g;
      if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
        g = shapeOf(*p);
      } else {
        const auto& ref = std::get<MeshRef>(e.geometry);
        const std::string key = ref.path + "|" + std::to_string(ref.scale.x()) + "," +
                                std::to_string(ref.scale.y()) + "," + std::to_string(ref.scale.z());
        auto it = meshes.find(key);
        if (it == meshes.end()) {
          MeshLoadOptions options;
          options.keep_root_transform = keep_mesh_root_transform;
          options.scale = ref.scale;
          TriangleMesh mesh = loadMesh(ref.path, options);
          if (center_mesh_vertices) centerOnVertexMean(mesh);
          it = meshes.emplace(key, meshOf(mesh)).first;
        }
        g = it->second;
      }
      geometry_->link_elements[static_cast<std::size_t>(l)].push_back(
          static_cast<int>(geometry_->elements.size()));
      geometry_->elements.push_back({l, g, e.X_LE});
      geometry_->prototypes.emplace_back(g);
    }
  }
}

FclCollisionModel::~FclCollisionModel() = default;
FclCollisionModel::FclCollisionModel(FclCollisionModel&&) noexcept = default;

void FclCollisionModel::ScratchDeleter::operator()(Scratch* s) const {
  delete s;
}

FclCollisionModel::ScratchPtr FclCollisionModel::makeScratch() const {
  ScratchPtr s(new Scratch);
  s->robot = robot_.makeData();
  s->objects = geometry_->prototypes;
  return s;
}

void FclCollisionModel::setConfiguration(const double* q, std::size_t q_size,
                                         const Eigen::Isometry3d& X_WB, Scratch& s) const {
  robot_.forwardKinematics(q, q_size, s.robot, X_WB);
  for (std::size_t i = 0; i < geometry_->elements.size(); ++i) {
    const Geometry::Element& e = geometry_->elements[i];
    const Eigen::Isometry3d X_WE = s.robot.linkPose(e.link) * e.X_LE;
    s.objects[i].setTransform(X_WE.rotation(), X_WE.translation());
    s.objects[i].computeAABB();
  }
}

bool FclCollisionModel::inCollision(Scratch& s) const {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  for (fcl::CollisionObjectd& link_object : s.objects) {
    for (const auto& env : geometry_->environment) {
      result.clear();
      if (fcl::collide(&link_object, env.get(), request, result) > 0) return true;
    }
  }
  for (const auto& [a, b] : robot_.checkedPairs()) {
    for (int ea : geometry_->link_elements[static_cast<std::size_t>(a)]) {
      for (int eb : geometry_->link_elements[static_cast<std::size_t>(b)]) {
        result.clear();
        if (fcl::collide(&s.objects[static_cast<std::size_t>(ea)],
                         &s.objects[static_cast<std::size_t>(eb)], request, result) > 0) {
          return true;
        }
      }
    }
  }
  return false;
}

double FclCollisionModel::environmentDistance(Scratch& s) const {
  double best = std::numeric_limits<double>::infinity();
  fcl::DistanceRequestd request;
  for (fcl::CollisionObjectd& link_object : s.objects) {
    for (const auto& env : geometry_->environment) {
      fcl::DistanceResultd result;
      fcl::distance(&link_object, env.get(), request, result);
      best = std::min(best, std::max(0.0, result.min_distance));
      if (best <= 0) return 0;
    }
  }
  return best;
}

namespace {
struct FclThreadScratch {
  std::uint64_t owner = 0;
  FclCollisionModel::ScratchPtr scratch;
  std::vector<double> q;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};
FclThreadScratch& fclScratch(const FclCollisionModel& model) {
  thread_local FclThreadScratch t;
  if (t.owner != model.id()) {
    t.scratch = model.makeScratch();
    t.q.assign(static_cast<std::size_t>(model.robot().variableCount()), 0.0);
    t.owner = model.id();
  }
  return t;
}
}  // namespace

FclValidityChecker::FclValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                       std::shared_ptr<const FclCollisionModel> model)
    : ompl::base::StateValidityChecker(si), model_(std::move(model)) {
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
}

FclValidityChecker::~FclValidityChecker() = default;

bool FclValidityChecker::isValid(const ompl::base::State* state) const {
  try {
    FclThreadScratch& t = fclScratch(*model_);
    if (!si_->satisfiesBounds(state)) return false;
    if (!stateToConfiguration(model_->robot(), state, t.q, t.X_WB)) return false;
    model_->setConfiguration(t.q.data(), t.q.size(), t.X_WB, *t.scratch);
    return !model_->inCollision(*t.scratch);
  } catch (const std::exception&) {
    return false;
  }
}

double FclValidityChecker::clearance(const ompl::base::State* state) const {
  if (!isValid(state)) return 0.0;
  FclThreadScratch& t = fclScratch(*model_);
  return model_->environmentDistance(*t.scratch);
}

}  // namespace octomotion
