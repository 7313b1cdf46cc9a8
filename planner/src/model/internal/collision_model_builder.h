// Private to the planner library: builds the parts of an OctreeCollisionModel, one function per
// step, in the order they depend on each other: the links' geometry and reach, the universe
// fitted to it, the link trees, the environment tree and its boxes, the clearance levels, then
// the modelled links, their environment order and the self pairs.
#pragma once

#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "collision_model_parts.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/scene/environment_geometry.h"
#include "self_pair_tables.h"

namespace octomotion::detail {

class CollisionModelBuilder {
 public:
  // Writes what it models into `report` (which must outlive the builder), except its
  // build_seconds.
  CollisionModelBuilder(const RobotModel& robot, const EnvironmentGeometry& environment,
                        const CollisionModelOptions& options, CollisionModelReport& report);
  // Throws InvalidArgument for bad options, or a scene too large for the resolution.
  std::unique_ptr<CollisionModelParts> build();

 private:
  // A self pair whose joint-space table is classified on the worker threads: each job owns its
  // FCL objects and robot data and only reads shared state.
  struct TableJob {
    std::size_t pair = 0;  // index into SelfCollision::pairs
    SelfPairLink a, b;
    std::optional<JointSpaceTable> table;
    double seconds = 0;
    std::exception_ptr error;
  };

  void checkOptions();
  void measureLinkGeometry();
  void boundReach();
  void fitUniverse();
  void voxelizeLinks();
  void buildEnvironmentTree();
  void setUpExactPrimitives();
  void buildObjectBoxes();
  void resolveEnvironmentPreTest();
  void buildSolidBoxes();
  void buildClearanceLevels();
  void keepLinksThatCanTouch();
  void foldStaticLinks();
  void orderEnvironmentLinks();
  std::vector<TableJob> collectSelfPairs();
  void classifyPairTables(std::vector<TableJob>& jobs) const;
  void keepPairTables(std::vector<TableJob>& jobs);
  void indexSelfBroadPhase();
  void resolveSelfBroadPhase();
  // Share of the pair's joint space (its variables `vars`, 256 samples) whose states reach the
  // tree test.
  double treeTestShare(const SelfPair& pair, const std::vector<int>& vars) const;
  // The self-pair tables' inside/outside oracle of a link, made on first use.
  const Octree* oracle(int link);

  const RobotModel& robot_;
  const EnvironmentGeometry& scene_;
  const CollisionModelOptions& options_;
  CollisionModelReport& report_;
  std::unique_ptr<CollisionModelParts> parts_ = std::make_unique<CollisionModelParts>();
  EnvironmentModel& environment_ = parts_->environment;
  LinkModels& links_ = parts_->links;
  SelfCollision& self_ = parts_->self;

  double link_res_ = 0, self_res_ = 0;
  CollisionMeshes meshes_;  // holds the meshes element_meshes_ points to
  // Per robot link: its geometry's extent in its frame, its elements' meshes (nullptr for a
  // primitive), the farthest point of its geometry from its frame origin (exact: the self-pair
  // tables' motion bound), and how far it reaches from the base region.
  std::vector<Eigen::AlignedBox3d> boxes_L_;
  std::vector<std::vector<const TriangleMesh*>> element_meshes_;
  std::vector<double> geometry_extent_;
  std::vector<double> link_reach_;
  std::vector<bool> in_pair_;        // the link is in some checked pair
  std::vector<LinkTree> trees_;      // per robot link, before the modelled ones are kept
  Eigen::AlignedBox3d base_region_;  // where the base's origin may be
  Eigen::AlignedBox3d region_;       // what the universe must cover
  WorldGrid grid_{Eigen::Vector3d::Zero(), 1.0, 1};
  bool exact_ = false;  // exact primitives in force
  std::map<int, Octree> oracles_;
  std::set<std::pair<int, int>> folded_pairs_;  // constant self pairs (robot link indices)
};

}  // namespace octomotion::detail
