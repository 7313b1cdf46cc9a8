// What every comparison with FCL needs, without a test framework (the validation tests and the
// differential validation program share it): uniform random states of a scene's robot with a
// fixed seed, the exact reference of a scene, and the voxel sizes the margins follow from.
#pragma once

#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace octomotion::validation {

// One configuration: joint values (arms) or a base pose (free-flying bodies).
struct Sample {
  std::vector<double> q;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

// Uniform in the joint limits (continuous joints over [-pi, pi]); free-flying bodies uniform in
// the scene's position bounds with a uniformly random orientation (Shoemake's method).
inline std::vector<Sample> uniformSamples(const PlanningScene& scene, std::size_t count,
                                          std::uint64_t seed) {
  const RobotModel& robot = scene.model->robot();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Sample> samples(count);
  for (Sample& s : samples) {
    s.q.resize(static_cast<std::size_t>(robot.variableCount()));
    for (std::size_t k = 0; k < s.q.size(); ++k) {
      const Variable& v = robot.variables()[k];
      s.q[k] = v.lower + (v.upper - v.lower) * unit(rng);
    }
    if (robot.isFreeFlying()) {
      const Eigen::AlignedBox3d& bounds = *scene.spec.problem.bounds;
      const Eigen::Vector3d u(unit(rng), unit(rng), unit(rng));
      s.X_WB.translation() = bounds.min() + bounds.sizes().cwiseProduct(u);
      const double a = unit(rng), b = 2 * M_PI * unit(rng), c = 2 * M_PI * unit(rng);
      const Eigen::Quaterniond r(std::sqrt(a) * std::cos(c), std::sqrt(1 - a) * std::sin(b),
                                 std::sqrt(1 - a) * std::cos(b), std::sqrt(a) * std::sin(c));
      s.X_WB.linear() = r.normalized().toRotationMatrix();
    } else {
      s.X_WB = scene.model->baseMount();
    }
  }
  return samples;
}

// A sample as one line, for failure messages: joint values, base position and orientation.
inline std::string describe(const Sample& s) {
  std::ostringstream out;
  out.precision(17);
  out << "q = [";
  for (std::size_t k = 0; k < s.q.size(); ++k) out << (k ? ", " : "") << s.q[k];
  out << "], X_WB.t = [" << s.X_WB.translation().transpose() << "], X_WB.R = ["
      << Eigen::Quaterniond(s.X_WB.linear()).coeffs().transpose() << "] (xyzw)";
  return out.str();
}

// The reference's (FCL) and the checked backend's (octree) answers at one sample: environment
// and self pairs. Each backend's link poses stay in its scratch for further queries.
struct Answers {
  bool fcl_env, fcl_self, octree_env, octree_self;
};
inline Answers answersAt(const Sample& s, const CollisionBackend& reference, BackendScratch& exact,
                         const CollisionBackend& checked, BackendScratch& scratch) {
  const double* q = s.q.data();
  const std::size_t n = s.q.size();
  Answers a;
  a.fcl_env = reference.environmentInCollision(q, n, s.X_WB, exact);
  a.fcl_self = reference.selfInCollision(q, n, s.X_WB, exact);
  a.octree_env = checked.environmentInCollision(q, n, s.X_WB, scratch);
  a.octree_self = checked.selfInCollision(q, n, s.X_WB, scratch);
  return a;
}

// The exact reference of a scene: FCL on its primitives and meshes. Point clouds and OctoMaps
// are voxels by definition ("every voxel holding a point is an obstacle"), so their exact
// geometry is their own voxels on the octree model's grid, given to FCL as boxes.
inline std::shared_ptr<const FclCollisionModel> exactReference(const PlanningScene& scene) {
  bool voxel_objects = false;
  for (const auto& item : scene.environment->items()) {
    voxel_objects |= item.spec.kind == EnvironmentObject::Kind::kPointCloud ||
                     item.spec.kind == EnvironmentObject::Kind::kOctomap;
  }
  if (!voxel_objects) return scene.fcl_model;
  std::vector<EnvironmentObject> objects;
  const WorldGrid& grid = scene.model->grid();
  for (const auto& item : scene.environment->items()) {
    if (item.spec.kind != EnvironmentObject::Kind::kPointCloud &&
        item.spec.kind != EnvironmentObject::Kind::kOctomap) {
      objects.push_back(item.spec);
      continue;
    }
    const Octree voxels =
        EnvironmentGeometry::load({item.spec}).voxelize(grid, scene.spec.octree.rounding);
    voxels.forEachBlackLeaf([&](const Cube& c) {
      EnvironmentObject box;
      box.name = item.spec.name + " voxel";
      const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
      box.primitive = Box{(hi - lo) / 2};
      box.X_WO = Eigen::Translation3d((lo + hi) / 2) * Eigen::Isometry3d::Identity();
      objects.push_back(box);
    });
  }
  return std::make_shared<const FclCollisionModel>(
      scene.model->robot(), EnvironmentGeometry::load(objects),
      scene.spec.robot.keep_mesh_root_transform, scene.spec.robot.center_mesh_vertices,
      scene.model->baseMount());
}

// The octree model's voxel sizes, from which the margins of docs/validation.md follow.
struct Resolutions {
  double environment;  // r_e
  double link;         // r_l
  double self_link;    // r_s: the trees of the self pairs (r_l unless self_link_resolution)
};
inline Resolutions resolutionsOf(const OctreeCollisionModel& model) {
  return {model.grid().voxelSize(), model.report().link_resolution,
          model.report().self_link_resolution};
}

// Slack for floating-point ties in the voxelizers and FCL's distance (1 um, far below a voxel).
inline constexpr double kTieSlack = 1e-6;

}  // namespace octomotion::validation
