// The reference MoveIt users run with sensor data: the environment as an OctoMap (wrapped in
// fcl::OcTree), the robot as exact FCL meshes and primitives, the same self-collision pairs.
//
// The environment is voxelized conservatively (every voxel the geometry touches is occupied) at
// `resolution` on OctoMap's native key grid (octomapNativeGrid in octomotion/octree/octomap_io.h),
// and the occupied cubes are inserted as OctoMap nodes directly (no ray casting), so the map holds
// exactly the voxels our own conservative environment tree holds on that grid. Point clouds mark
// the voxel of each point; OctoMap files are resampled onto the grid.
//
// A CollisionBackend without clearance; its OMPL checker is FclOctomapValidityChecker
// (ompl/validity_checker.h).
#pragma once

#include <cstdint>
#include <memory>

#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

class FclOctomapCollisionModel final : public CollisionBackend {
 public:
  // Mesh conventions as in CollisionModelOptions; `mount` as in FclCollisionModel. Throws
  // InvalidArgument for a bad resolution or an environment outside OctoMap's key range (+-32768
  // voxels about the origin).
  FclOctomapCollisionModel(const RobotModel& robot, const EnvironmentGeometry& environment,
                           double resolution, bool keep_mesh_root_transform = false,
                           bool center_mesh_vertices = false,
                           const Eigen::Isometry3d& mount = Eigen::Isometry3d::Identity());
  ~FclOctomapCollisionModel() override;
  FclOctomapCollisionModel(FclOctomapCollisionModel&&) noexcept;

  struct Scratch;  // per-thread: FK results and the robot's FCL objects (opaque BackendScratch)
  struct ScratchDeleter {
    void operator()(Scratch* s) const;
  };
  using ScratchPtr = std::unique_ptr<Scratch, ScratchDeleter>;
  ScratchPtr makeScratch() const;

  // Link poses from q (and X_WB for free-flying robots; fixed-base robots use baseMount()) into
  // the scratch.
  void setConfiguration(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                        Scratch& scratch) const;
  // The OctoMap environment and the checked self pairs.
  bool inCollision(Scratch& scratch) const;
  bool environmentInCollision(Scratch& scratch) const;  // the OctoMap only
  bool selfInCollision(Scratch& scratch) const;         // the checked self pairs only

  double resolution() const { return resolution_; }
  // liboctomap's OcTree::memoryUsage() for the map.
  std::size_t octomapBytes() const { return octomap_bytes_; }
  // Voxelizing the environment and building the OctoMap (not the robot's geometry).
  double buildSeconds() const { return build_seconds_; }

  // CollisionBackend: setConfiguration, then the query above; no clearance (always 0).
  std::unique_ptr<BackendScratch> makeBackendScratch() const override;
  bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                   BackendScratch& scratch) const override;
  bool environmentInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                              BackendScratch& scratch) const override;
  bool selfInCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch) const override;
  double clearance(BackendScratch&) const override { return 0.0; }
  ClearanceBound clearanceBound() const override { return ClearanceBound::kNone; }

  // The scratch behind one made by makeBackendScratch, for the queries above (InvalidArgument for
  // another backend's).
  Scratch& scratchOf(BackendScratch& scratch) const;

  const RobotModel& robot() const override { return robot_; }
  std::uint64_t id() const override { return id_; }  // see OctreeCollisionModel::id
  CheckerKind kind() const override { return CheckerKind::kFclOctomap; }
  const Eigen::Isometry3d& baseMount() const { return mount_; }

 private:
  void explainContacts(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                       BackendScratch& scratch, bool all,
                       StateExplanation& explanation) const override;

  struct Geometry;
  std::uint64_t id_;
  RobotModel robot_;
  Eigen::Isometry3d mount_;
  double resolution_;
  std::size_t octomap_bytes_ = 0;
  double build_seconds_ = 0;
  std::unique_ptr<Geometry> geometry_;
};

}  // namespace octomotion
