// The reference MoveIt users run with sensor data: the environment as an OctoMap (wrapped in
// fcl::OcTree), the robot as exact FCL meshes and primitives, the same self-collision pairs.
//
// The environment is voxelized conservatively (every voxel the geometry touches is occupied) at
// `resolution` on OctoMap's native key grid (octomapNativeGrid in octomotion/octree/octomap_io.h),
// and the occupied cubes are inserted as OctoMap nodes directly (no ray casting), so the map holds
// exactly the voxels our own conservative environment tree holds on that grid. Point clouds mark
// the voxel of each point; OctoMap files are resampled onto the grid.
#pragma once

#include <cstdint>
#include <memory>

#include <ompl/base/StateValidityChecker.h>

#include "octomotion/planner/ompl/octree_validity_checker.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {

class FclOctomapCollisionModel {
 public:
  // Mesh conventions as in CollisionModelOptions. Throws InvalidArgument for a bad resolution or
  // an environment outside OctoMap's key range (+-32768 voxels about the origin).
  FclOctomapCollisionModel(const RobotModel& robot, const EnvironmentGeometry& environment,
                           double resolution, bool keep_mesh_root_transform = false,
                           bool center_mesh_vertices = false);
  ~FclOctomapCollisionModel();
  FclOctomapCollisionModel(FclOctomapCollisionModel&&) noexcept;

  struct Scratch;  // per-thread: FK results and the robot's FCL objects (opaque)
  struct ScratchDeleter {
    void operator()(Scratch* s) const;
  };
  using ScratchPtr = std::unique_ptr<Scratch, ScratchDeleter>;
  ScratchPtr makeScratch() const;

  // Link poses from q (and X_WB for free-flying robots) into the scratch.
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

  const RobotModel& robot() const { return robot_; }
  std::uint64_t id() const { return id_; }  // see OctreeCollisionModel::id

 private:
  struct Geometry;
  std::uint64_t id_;
  RobotModel robot_;
  double resolution_;
  std::size_t octomap_bytes_ = 0;
  double build_seconds_ = 0;
  std::unique_ptr<Geometry> geometry_;
};

class FclOctomapValidityChecker : public ompl::base::StateValidityChecker {
 public:
  FclOctomapValidityChecker(const ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const FclOctomapCollisionModel> model);
  ~FclOctomapValidityChecker() override;
  // Invalid when outside the space's bounds, non-finite, or in collision. Never throws.
  bool isValid(const ompl::base::State* state) const override;

  const FclOctomapCollisionModel& model() const { return *model_; }

 private:
  std::shared_ptr<const FclOctomapCollisionModel> model_;
  BoundsCheck in_bounds_;
};

}  // namespace octomotion
