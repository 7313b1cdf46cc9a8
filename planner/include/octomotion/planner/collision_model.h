// The octree collision model of one scene, Pinocchio-style: a constant OctreeCollisionModel
// (robot, environment tree, one source tree per link) shared by every thread, and a
// CheckScratch per thread. Each link is voxelized once, in its own frame, into a source tree;
// every query derives the link's placement from that source tree and the link's pose (never from
// a previous placement), then tests it against the environment tree and against the other
// links' source trees (self-collision, in the other link's frame).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/motion/collides.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/environment.h"
#include "octomotion/planner/robot_model.h"

namespace octomotion {

// (a) the mission's path: moveTree from the source tree, then the parallel traversal;
// (b) the fused query: both at once, without materialising the moved tree.
enum class CheckerPath { kMoveTree, kFused };
CheckerPath checkerPathFromName(const std::string& name);  // "octree" | "octree-fused"

// A fresh process-unique id for a model (see OctreeCollisionModel::id).
std::uint64_t nextModelId();

struct CollisionModelOptions {
  double resolution = 0.01;               // environment voxel size (metres)
  std::optional<double> link_resolution;  // source-tree voxel size; default: resolution
  Rounding rounding = Rounding::kConservative;
  // Fixed-base robots: the root link's pose. Free-flying robots: ignored.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  // Free-flying robots: where the body's origin may go (SE(3) position bounds). Required.
  std::optional<Eigen::AlignedBox3d> base_position_bounds;
  // Robot mesh conventions: URDF robots reset the mesh file's root transform (ROS/MoveIt);
  // OMPL.app rigid bodies keep it and are shifted so the mean of their vertices is the origin.
  bool keep_mesh_root_transform = false;
  bool center_mesh_vertices = false;
  // Building fails early (InvalidArgument naming the object and the resolution) when a tree's
  // surface, estimated from its bounding box, would exceed this many voxels: a typo such as a
  // micrometre resolution must not exhaust the machine. 2e8 surface voxels is about 0.5 GB.
  double max_surface_voxels = 2e8;
  WarningSink warnings;
};

struct LinkReport {
  std::string name;
  bool modelled = false;  // false: no geometry, or it can neither touch the scene nor a link
  std::size_t source_internal_nodes = 0;
  std::size_t source_black_leaves = 0;
  std::size_t source_bytes = 0;
  int source_depth = 0;
  double radius = 0;  // bounding sphere of the source tree's black voxels (metres)
  double build_seconds = 0;
};

struct CollisionModelReport {
  WorldGrid grid{Eigen::Vector3d::Zero(), 1.0, 1};
  double link_resolution = 0;
  Eigen::AlignedBox3d reach_W;  // what the robot can reach
  EnvironmentReport environment;
  std::vector<LinkReport> links;
  std::size_t self_pairs = 0;
  double build_seconds = 0;
  std::string toString() const;  // the human-readable "what was modelled" summary
};

// Per-thread scratch for queries: FK results and the fused query's buffers. One per thread.
struct CheckScratch {
  RobotData robot;
  CollisionScratch fused;
  std::uint64_t owner = 0;  // id() of the model it was made for
};

class OctreeCollisionModel {
 public:
  // Builds the environment tree on a universe fitted to what the robot can reach (parts of the
  // environment it can never reach are not modelled) and one source tree per link.
  OctreeCollisionModel(RobotModel robot, const EnvironmentGeometry& environment,
                       const CollisionModelOptions& options);

  const RobotModel& robot() const { return robot_; }
  const Octree& environment() const { return environment_; }
  const WorldGrid& grid() const { return environment_.grid(); }
  Rounding rounding() const { return options_.rounding; }
  const CollisionModelReport& report() const { return report_; }
  const Eigen::Isometry3d& baseMount() const { return options_.X_WB; }

  CheckScratch makeScratch() const;
  // Unique for the process's lifetime (addresses may be reused; ids are not), so per-thread
  // scratch can tell which model it belongs to.
  std::uint64_t id() const { return id_; }

  // Runs FK for q (and base pose X_WB for free-flying robots) into the scratch, then tests every
  // modelled link against the environment and every checked pair against each other, cheapest
  // tests first, stopping at the first contact. Throws InvalidArgument for a non-finite input.
  bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                   CheckerPath path, CheckScratch& scratch) const;
  // The same tests on link poses already in the scratch (after forwardKinematics).
  bool linksInCollision(CheckerPath path, CheckScratch& scratch) const;

  // A lower bound on the distance between the robot (at the poses in the scratch) and the
  // environment's black voxels; 0 when in contact. See docs: it is loose by up to the link's
  // source-voxel diagonal plus the spread of the link's bounding spheres.
  double clearanceLowerBound(const CheckScratch& scratch) const;

 private:
  struct LinkTree {
    int link = -1;
    Octree source{WorldGrid(Eigen::Vector3d::Zero(), 1.0, 1)};  // in the link frame L
    std::unique_ptr<const MovableSource> movable;  // the source prepared for the fused query
    Eigen::Vector3d center_L;                      // bounding sphere of the black voxels
    double radius = 0;
    bool touches_environment = true;         // false: cannot reach the modelled environment
    std::vector<Eigen::Vector4d> spheres_L;  // coarse cover of the black voxels (clearance)
  };

  bool linkHitsEnvironment(const LinkTree& lt, const Eigen::Isometry3d& X_WL, CheckerPath path,
                           CollisionScratch& fused) const;
  bool linksHit(const LinkTree& a, const Eigen::Isometry3d& X_WA, const LinkTree& b,
                const Eigen::Isometry3d& X_WB, CheckerPath path, CollisionScratch& fused) const;

  std::uint64_t id_;
  RobotModel robot_;
  CollisionModelOptions options_;
  Octree environment_;
  Eigen::AlignedBox3d environment_box_W_;   // world box of the environment's black voxels
  std::vector<LinkTree> links_;             // modelled links only
  std::vector<int> link_slot_;              // robot link index -> index in links_, or -1
  std::vector<std::pair<int, int>> pairs_;  // self pairs, as indices into links_
  CollisionModelReport report_;
};

}  // namespace octomotion
