// OctreeCollisionModel, the facade: it owns the model's parts (internal/collision_model_parts.h),
// built once by CollisionModelBuilder, and runs the queries on them.
#include "octomotion/planner/model/collision_model.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "internal/collision_model_builder.h"
#include "internal/collision_model_parts.h"
#include "internal/explain_data.h"
#include "internal/refine.h"

namespace octomotion {

std::uint64_t nextModelId() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1);
}

OctreeCollisionModel::OctreeCollisionModel(RobotModel robot, const EnvironmentGeometry& environment,
                                           const CollisionModelOptions& options)
    : OctreeCollisionModel(std::move(robot),
                           std::make_shared<const EnvironmentGeometry>(environment), options) {}

OctreeCollisionModel::OctreeCollisionModel(RobotModel robot,
                                           std::shared_ptr<const EnvironmentGeometry> environment,
                                           const CollisionModelOptions& options)
    : id_(nextModelId()), robot_(std::move(robot)), options_(options) {
  if (!environment) throw InvalidArgument("OctreeCollisionModel: no environment");
  options_.refine =
      resolveRefineMode(options_.refine, options_.rounding, options_.fit_universe_to_reach);
  if (options_.refine == RefineMode::kExact) {
    // Centre rounding's "no shared voxel" does not prove freedom, so nothing could be certified.
    if (options_.rounding != Rounding::kConservative) {
      throw InvalidArgument(
          "refine exact needs conservative rounding (the octree certifies "
          "freedom only when its voxels contain the geometry)");
    }
    // Both prove a shared voxel, not a contact of the exact shapes.
    options_.core_boxes = false;
    options_.fold_static = false;
  }
  const auto start = std::chrono::steady_clock::now();
  parts_ = detail::CollisionModelBuilder(robot_, *environment, options_, report_).build();
  parts_->world.objects = *environment;  // for world updates (world_updates.cpp)
  report_.refine = options_.refine;
  if (options_.refine == RefineMode::kExact) {
    const auto refine_start = std::chrono::steady_clock::now();
    refine_ = std::make_unique<const detail::RefineData>(robot_, *environment, grid(), options_);
    report_.refine_build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - refine_start).count();
  }
  report_.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  resetExplainData();
}

OctreeCollisionModel::OctreeCollisionModel(OctreeCollisionModel&&) noexcept = default;
OctreeCollisionModel& OctreeCollisionModel::operator=(OctreeCollisionModel&&) noexcept = default;
OctreeCollisionModel::~OctreeCollisionModel() = default;

const Octree& OctreeCollisionModel::environment() const {
  return parts_->environment.tree;
}

const WorldGrid& OctreeCollisionModel::grid() const {
  return parts_->environment.tree.grid();
}

std::vector<OctreeCollisionModel::LinkSourceTree> OctreeCollisionModel::linkSourceTrees() const {
  std::vector<LinkSourceTree> trees;
  trees.reserve(parts_->links.links.size());
  for (const detail::LinkTree& lt : parts_->links.links) {
    trees.push_back(
        {lt.link, &lt.voxels.source, lt.self_voxels ? &lt.self_voxels->source : nullptr});
  }
  return trees;
}

CheckScratch OctreeCollisionModel::makeScratch() const {
  CheckScratch s;
  s.robot = robot_.makeData();
  if (report_.self_broad_phase == SelfBroadPhase::kNObjectsOctree) {
    s.self_broad_phase.reset(parts_->self.makeBroadPhase());
  }
  s.owner = id_;
  return s;
}

bool OctreeCollisionModel::environmentInCollision(CheckerPath path, CheckScratch& scratch) const {
  if (refine_) return refinedEnvironmentInCollision(path, scratch);
  return parts_->environment.inCollision(parts_->links, path, scratch.robot, scratch.fused);
}

bool OctreeCollisionModel::selfInCollision(CheckerPath path, CheckScratch& scratch) const {
  if (refine_) return refinedSelfInCollision(path, scratch);
  return parts_->self.inCollision(parts_->links, path, scratch);
}

bool OctreeCollisionModel::linksInCollision(CheckerPath path, CheckScratch& scratch) const {
  if (refine_) return refinedLinksInCollision(path, scratch);
  return environmentInCollision(path, scratch) || selfInCollision(path, scratch);
}

bool OctreeCollisionModel::inCollision(const double* q, std::size_t q_size,
                                       const Eigen::Isometry3d& X_WB, CheckerPath path,
                                       CheckScratch& scratch) const {
  if (scratch.owner != id_) scratch = makeScratch();
  robot_.forwardKinematics(q, q_size, scratch.robot, robot_.isFreeFlying() ? X_WB : options_.X_WB);
  return linksInCollision(path, scratch);
}

double OctreeCollisionModel::clearanceLowerBound(const CheckScratch& scratch) const {
  if (refine_) return refinedClearance(scratch, options_.refine_clearance_margin);
  return options_.clearance == ClearanceMethod::kPointOctree ? clearanceLowerBoundPoints(scratch)
                                                             : clearanceLowerBoundTree(scratch);
}

double OctreeCollisionModel::clearanceLowerBoundPoints(const CheckScratch& scratch) const {
  if (parts_->world.clearance_levels_once) {  // after a world update (world_updates.cpp)
    std::call_once(*parts_->world.clearance_levels_once, [this] {
      parts_->clearance = detail::ClearanceLevels::build(parts_->environment.tree);
    });
  }
  if (parts_->clearance.empty()) return clearanceLowerBoundTree(scratch);
  return std::min(parts_->clearance.lowerBound(parts_->links, scratch.robot),
                  parts_->links.unreachable_clearance);
}

double OctreeCollisionModel::clearanceLowerBoundGrid(const CheckScratch& scratch) const {
  const ClearanceGrid* grid = parts_->environment.clearance.get();
  if (!grid) return 0.0;
  const WorldGrid& world = parts_->environment.tree.grid();
  const double voxel = world.voxelSize();
  double best = std::numeric_limits<double>::infinity();
  for (const detail::LinkTree& lt : parts_->links.links) {
    if (!lt.touches_environment) continue;
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(lt.link);
    // The grid bounds the distance from the sphere's centre to every black voxel; the sphere
    // covers the link's voxels it stands for. A micrometre covers rounding in the transform.
    auto sphereClearance = [&](const Eigen::Vector4d& s) {
      const Eigen::Vector3d g = world.toGrid(X_WL * Eigen::Vector3d(s.head<3>()));
      // Outside the universe (which holds every black voxel) from the nearest point p inside:
      // |g - b|^2 >= |g - p|^2 + |p - b|^2 for every b in the box.
      const double side = grid->sideVoxels();
      const Eigen::Vector3d p = g.cwiseMax(0.0).cwiseMin(side * (1 - 1e-12));
      const double c[3] = {p.x(), p.y(), p.z()};
      const double inside = grid->clearance(c);
      const double voxels = std::sqrt((g - p).squaredNorm() + inside * inside);
      return voxels * voxel - s[3] - 1e-6;
    };
    for (const detail::SphereGroup& group : lt.grid_sphere_groups_L) {
      // The group's sphere holds its members: its bound is theirs too, and when it is no
      // lower than the best so far, they cannot lower it.
      const double outer = sphereClearance(group.sphere_L);
      if (outer >= best) continue;
      double members = std::numeric_limits<double>::infinity();
      for (std::size_t i = group.begin; i < group.end && members > outer; ++i) {
        members = std::min(members, sphereClearance(lt.grid_spheres_L[i]));
      }
      best = std::min(best, std::max(outer, members));
      if (best <= 0) return 0.0;
    }
  }
  return best;  // infinite when no link can reach the environment
}

void OctreeCollisionModel::clearanceLowerBoundGridPerLink(const CheckScratch& scratch,
                                                          const double* caps, double slack,
                                                          double* per_link) const {
  const ClearanceGrid* grid = parts_->environment.clearance.get();
  // Links left out of the queries (their reach misses the environment's box): the gap.
  for (int l = 0; l < robot_.linkCount(); ++l) per_link[l] = parts_->links.unreachable_clearance;
  const WorldGrid& world = parts_->environment.tree.grid();
  const double voxel = world.voxelSize();
  const double side = grid ? grid->sideVoxels() : 0.0;
  // As in clearanceLowerBoundGrid: the grid bounds the distance from a sphere's centre to every
  // black voxel, outside the universe from the nearest point inside it. The centre is mapped
  // from the link frame to grid coordinates in one affine step (X_GL, set per link).
  Eigen::Matrix3d R_GL;
  Eigen::Vector3d p_GL;
  auto sphereClearance = [&](const Eigen::Vector3d& centre_L, double radius) {
    const Eigen::Vector3d g = R_GL * centre_L + p_GL;
    const Eigen::Vector3d p = g.cwiseMax(0.0).cwiseMin(side * (1 - 1e-12));
    const double c[3] = {p.x(), p.y(), p.z()};
    const double inside = grid->clearance(c);
    const double outside = (g - p).squaredNorm();
    const double voxels = outside > 0 ? std::sqrt(outside + inside * inside) : inside;
    return voxels * voxel - radius - 1e-6 - slack;
  };
  // The groups a link still has to look at, by their own bound (this thread's, reused).
  thread_local std::vector<std::pair<double, std::size_t>> order;
  for (const detail::LinkTree& lt : parts_->links.links) {
    if (!lt.touches_environment) continue;
    if (!grid) {
      per_link[lt.link] = 0.0;
      continue;
    }
    const double cap = caps[lt.link];
    if (cap <= 0) continue;
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(lt.link);
    R_GL = X_WL.linear() / voxel;
    p_GL = world.toGrid(X_WL.translation());
    // The link's bounding sphere first: one lookup settles a link far from every obstacle.
    const double whole = sphereClearance(lt.voxels.center_L, lt.voxels.radius);
    if (whole >= cap) {
      per_link[lt.link] = whole;
      continue;
    }
    // Then branch and bound over the groups (SphereGroup): each group's own bound, lowest
    // first; a group's value is the larger of its bound and its members' least, so a group
    // whose bound is no lower than the best so far cannot lower it, nor can those after it.
    // Groups at or above the cap are not opened: the least of their bounds stays a lower
    // bound for them (the result is then at least the cap, which decides the same).
    order.clear();
    double skipped = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < lt.grid_sphere_groups_L.size(); ++k) {
      const Eigen::Vector4d& g = lt.grid_sphere_groups_L[k].sphere_L;
      const double outer = sphereClearance(g.head<3>(), g[3]);
      if (outer >= cap) {
        skipped = std::min(skipped, outer);
      } else {
        order.emplace_back(outer, k);
      }
    }
    std::sort(order.begin(), order.end());
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [outer, k] : order) {
      if (outer >= best || best <= whole) break;  // no better than the bounding sphere's
      const detail::SphereGroup& group = lt.grid_sphere_groups_L[k];
      double members = std::numeric_limits<double>::infinity();
      for (std::size_t i = group.begin; i < group.end && members > outer; ++i) {
        const Eigen::Vector4d& s = lt.grid_spheres_L[i];
        members = std::min(members, sphereClearance(s.head<3>(), s[3]));
      }
      best = std::min(best, std::max(outer, members));
    }
    per_link[lt.link] = std::max(0.0, std::max(whole, std::min(best, skipped)));
  }
}

double OctreeCollisionModel::clearanceLowerBoundTree(const CheckScratch& scratch) const {
  return std::min(
      detail::clearanceLowerBoundTree(parts_->links, parts_->environment.tree, scratch.robot),
      parts_->links.unreachable_clearance);
}

// Explanations name the objects of the current world (world updates call this again); the data
// points into parts_, which lives as long as the model.
void OctreeCollisionModel::resetExplainData() {
  explain_ = std::make_unique<detail::ExplainData>(std::shared_ptr<const EnvironmentGeometry>(
      std::shared_ptr<const EnvironmentGeometry>(), &parts_->world.objects));
}

}  // namespace octomotion
