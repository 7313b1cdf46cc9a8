#include "octomotion/planner/fcl_octomap_checker.h"

#include <chrono>

#include <fcl/geometry/octree/octree.h>
#include <fcl/narrowphase/collision.h>
#include <octomap/OcTree.h>
#include <ompl/base/SpaceInformation.h>

#include "fcl_robot.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/planner/collision_model.h"
#include "octomotion/planner/octree_validity_checker.h"

namespace octomotion {

namespace {

constexpr int kOctoMapDepth = 16;

// liboctomap makes a root only as a side effect of updating a voxel at full depth; inserting
// whole cubes at their own depth needs the bare root, which only a derived class can make.
class CubeOcTree : public octomap::OcTree {
 public:
  using octomap::OcTree::OcTree;
  octomap::OcTreeNode* ensureRoot() {
    if (root == nullptr) {
      root = new octomap::OcTreeNode();
      tree_size = 1;
      size_changed = true;
    }
    return root;
  }
};

// On the native grid our voxel coordinates are OctoMap keys and a level-L cube is the OctoMap
// node at depth 16 - L with the same keys (same child numbering, Ahuja & Nash Fig. 1), so each
// black leaf becomes one occupied node, reached by following its key bits from the root.
std::shared_ptr<CubeOcTree> toOctoMap(const Octree& tree, double resolution) {
  auto map = std::make_shared<CubeOcTree>(resolution);
  const float occupied = map->getClampingThresMaxLog();
  tree.forEachBlackLeaf([&](const Cube& c) {
    octomap::OcTreeNode* node = map->ensureRoot();
    const int depth = kOctoMapDepth - c.level;
    for (int d = 0; d < depth; ++d) {
      const int bit = kOctoMapDepth - 1 - d;
      const unsigned k = ((c.origin.x >> bit) & 1u) | (((c.origin.y >> bit) & 1u) << 1) |
                         (((c.origin.z >> bit) & 1u) << 2);
      node = map->nodeChildExists(node, k) ? map->getNodeChild(node, k)
                                           : map->createNodeChild(node, k);
    }
    node->setLogOdds(occupied);
  });
  if (map->getRoot() != nullptr) {
    map->updateInnerOccupancy();
    map->prune();
  }
  return map;
}

}  // namespace

struct FclOctomapCollisionModel::Geometry {
  Geometry(const RobotModel& model, bool keep_mesh_root_transform, bool center_mesh_vertices)
      : robot(model, keep_mesh_root_transform, center_mesh_vertices) {}
  fcl_internal::RobotGeometry robot;
  std::shared_ptr<CubeOcTree> map;
  std::unique_ptr<fcl::CollisionObjectd> environment;  // null when nothing is occupied
};

struct FclOctomapCollisionModel::Scratch {
  fcl_internal::RobotScratch robot;
};

FclOctomapCollisionModel::FclOctomapCollisionModel(const RobotModel& robot,
                                                   const EnvironmentGeometry& environment,
                                                   double resolution, bool keep_mesh_root_transform,
                                                   bool center_mesh_vertices)
    : id_(nextModelId()),
      robot_(robot),
      resolution_(resolution),
      geometry_(
          std::make_unique<Geometry>(robot_, keep_mesh_root_transform, center_mesh_vertices)) {
  const auto start = std::chrono::steady_clock::now();
  const WorldGrid grid = octomapNativeGrid(resolution);
  const Octree voxels = environment.voxelize(grid, Rounding::kConservative);
  geometry_->map = toOctoMap(voxels, resolution);
  octomap_bytes_ = geometry_->map->memoryUsage();
  if (const auto b = voxels.bounds()) {
    auto tree = std::make_shared<fcl::OcTreed>(
        std::static_pointer_cast<const octomap::OcTree>(geometry_->map));
    geometry_->environment = std::make_unique<fcl::CollisionObjectd>(tree);
    // FCL bounds an OcTree by its whole key range; the occupied voxels' box is the useful
    // pre-test for the links.
    fcl::AABBd& aabb = const_cast<fcl::AABBd&>(geometry_->environment->getAABB());
    aabb.min_ = grid.cubeMin(Cube{0, b->min});
    aabb.max_ = grid.cubeMax(Cube{0, b->max});
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
  return s;
}

void FclOctomapCollisionModel::setConfiguration(const double* q, std::size_t q_size,
                                                const Eigen::Isometry3d& X_WB, Scratch& s) const {
  geometry_->robot.pose(robot_, q, q_size, X_WB, s.robot);
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

bool FclOctomapCollisionModel::inCollision(Scratch& s) const {
  return environmentInCollision(s) || selfInCollision(s);
}

namespace {
struct OctomapThreadScratch {
  std::uint64_t owner = 0;
  FclOctomapCollisionModel::ScratchPtr scratch;
  std::vector<double> q;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};
OctomapThreadScratch& octomapScratch(const FclOctomapCollisionModel& model) {
  thread_local OctomapThreadScratch t;
  if (t.owner != model.id()) {
    t.scratch = model.makeScratch();
    t.q.assign(static_cast<std::size_t>(model.robot().variableCount()), 0.0);
    t.owner = model.id();
  }
  return t;
}
}  // namespace

FclOctomapValidityChecker::FclOctomapValidityChecker(
    const ompl::base::SpaceInformationPtr& si,
    std::shared_ptr<const FclOctomapCollisionModel> model)
    : ompl::base::StateValidityChecker(si), model_(std::move(model)) {}

FclOctomapValidityChecker::~FclOctomapValidityChecker() = default;

bool FclOctomapValidityChecker::isValid(const ompl::base::State* state) const {
  try {
    OctomapThreadScratch& t = octomapScratch(*model_);
    if (!si_->satisfiesBounds(state)) return false;
    if (!stateToConfiguration(model_->robot(), state, t.q, t.X_WB)) return false;
    model_->setConfiguration(t.q.data(), t.q.size(), t.X_WB, *t.scratch);
    return !model_->inCollision(*t.scratch);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace octomotion
