#include "internal/link_models.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>

#include "internal/environment_model.h"
#include "internal/sampling.h"
#include "octomotion/octree/inner_boxes.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion::detail {

namespace {

// Clearance spheres circumscribe cubes of kSphereVoxels voxels a side that hold black voxels:
// coarse enough to be few, fine enough to keep the bound useful. The tree and point methods
// count the link's voxels; the grid counts the environment's, which are coarser when the link
// trees are finer: the grid is loose by a cell of four of them, so finer spheres would cost
// more lookups per state and prove no more.
constexpr double kSphereVoxels = 8;

}  // namespace

LinkVoxels voxelizeLink(const Link& link, const std::vector<const TriangleMesh*>& element_mesh,
                        Eigen::AlignedBox3d box_L, double resolution,
                        const CollisionModelOptions& options, bool for_self_pairs) {
  // One voxel of margin so conservative voxels on the boundary stay inside the universe.
  box_L.extend(box_L.min() - Eigen::Vector3d::Constant(resolution));
  box_L.extend(box_L.max() + Eigen::Vector3d::Constant(resolution));
  const WorldGrid grid = fitGrid(box_L, resolution);
  Octree source(grid);
  for (std::size_t k = 0; k < link.collision.size(); ++k) {
    const CollisionElement& e = link.collision[k];
    const Octree part =
        element_mesh[k]
            ? voxelizeMesh(grid, *element_mesh[k], e.X_LE, options.rounding, options.warnings)
            : voxelize(grid, std::get<Primitive>(e.geometry), e.X_LE, options.rounding);
    source = unite(source, part);
  }
  LinkVoxels v;
  v.source_diagonal = std::sqrt(3.0) * grid.voxelSize();
  // Bounding sphere of the black voxels (centre: middle of their box).
  Eigen::AlignedBox3d black_L;
  if (const auto b = source.bounds()) {
    black_L = Eigen::AlignedBox3d(grid.cubeMin(Cube{0, b->min}), grid.cubeMax(Cube{0, b->max}));
    v.center_L = black_L.center();
    v.half_L = black_L.sizes() / 2;
    v.radius = black_L.sizes().norm() / 2;
  }
  // The tree must hold the whole link: every mesh vertex within its black voxels' box (up to the
  // builders' tie). The grid was fitted to the link, so a failure here is a defect, reported
  // instead of a link that silently lost part of itself.
  if (options.rounding == Rounding::kConservative) {
    const double tie = 1e-5 * grid.voxelSize();
    for (std::size_t k = 0; k < link.collision.size(); ++k) {
      if (element_mesh[k] == nullptr) continue;
      for (const Eigen::Vector3d& p : element_mesh[k]->vertices) {
        const Eigen::Vector3d p_L = link.collision[k].X_LE * p;
        if (black_L.isEmpty() || (p_L.array() < black_L.min().array() - tie).any() ||
            (p_L.array() > black_L.max().array() + tie).any()) {
          throw Error("link '" + link.name + "': its source tree (" +
                      std::to_string(grid.voxelSize()) +
                      " m voxels) does not hold its collision "
                      "geometry (a vertex of element " +
                      std::to_string(k) + " lies outside)");
        }
      }
    }
  }
  if (!for_self_pairs && options.core_boxes && options.rounding == Rounding::kConservative) {
    const double shrink = kSolidShrink * std::max(resolution, options.resolution);
    // innerBoxes' three boxes, of cells of 1/64 of the link's universe: more boxes or finer
    // cells cost more to build than the certain contacts they add save.
    for (const Eigen::AlignedBox3d& box : innerBoxes(source)) {
      const Eigen::Vector3d half = box.sizes() / 2 - Eigen::Vector3d::Constant(shrink);
      if ((half.array() > 0).all()) v.core_boxes.push_back({box.center(), half});
    }
  }
  v.source = std::move(source);
  // Self trees are only ever tested against other self trees of the same resolution.
  const bool deep_pairs = for_self_pairs && grid.depth() >= MovableSource::kDeepPairLevels;
  v.movable = std::make_unique<const MovableSource>(
      v.source,
      deep_pairs ? MovableSource::kExpandFactorDeepPairs : MovableSource::kExpandFactorDefault);
  return v;
}

std::vector<Eigen::Vector4d> clearanceSpheres(const Octree& source, double voxel) {
  const WorldGrid& grid = source.grid();
  int level = 0;
  while (level < grid.depth() &&
         std::ldexp(grid.voxelSize(), level) < kSphereVoxels * voxel * (1 - 1e-9)) {
    ++level;
  }
  std::vector<Cube> cells;
  source.forEachBlackLeaf([&](const Cube& c) {
    if (c.level >= level) {
      cells.push_back(c);
    } else {
      const std::uint32_t mask = ~((std::uint32_t{1} << level) - 1);
      const Cube parent{level, {c.origin.x & mask, c.origin.y & mask, c.origin.z & mask}};
      if (cells.empty() || !(cells.back() == parent)) cells.push_back(parent);
    }
  });
  std::sort(cells.begin(), cells.end(), [](const Cube& a, const Cube& c) {
    return std::tie(a.level, a.origin.x, a.origin.y, a.origin.z) <
           std::tie(c.level, c.origin.x, c.origin.y, c.origin.z);
  });
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  std::vector<Eigen::Vector4d> spheres;
  spheres.reserve(cells.size());
  for (const Cube& c : cells) {
    const Eigen::Vector3d cmin = grid.cubeMin(c), cmax = grid.cubeMax(c);
    Eigen::Vector4d sphere;
    sphere.head<3>() = (cmin + cmax) / 2;
    sphere[3] = (cmax - cmin).norm() / 2;
    spheres.push_back(sphere);
  }
  return spheres;
}

std::vector<SphereGroup> groupClearanceSpheres(std::vector<Eigen::Vector4d>& spheres) {
  std::vector<SphereGroup> groups;
  if (spheres.empty()) return groups;
  // Cells of four of the smallest spheres' cubes (side = diameter / sqrt 3) from the lowest corner.
  double smallest = spheres.front()[3];
  Eigen::Vector3d low = spheres.front().head<3>();
  for (const Eigen::Vector4d& s : spheres) {
    smallest = std::min(smallest, s[3]);
    low = low.cwiseMin(s.head<3>());
  }
  const double cell = 4 * 2 * smallest / std::sqrt(3.0);
  auto key = [&](const Eigen::Vector4d& s) {
    const Eigen::Vector3d k = ((s.head<3>() - low) / cell).array().floor();
    return std::make_tuple(k.z(), k.y(), k.x());
  };
  std::stable_sort(
      spheres.begin(), spheres.end(),
      [&](const Eigen::Vector4d& a, const Eigen::Vector4d& b) { return key(a) < key(b); });
  for (std::size_t begin = 0; begin < spheres.size();) {
    std::size_t end = begin + 1;
    while (end < spheres.size() && key(spheres[end]) == key(spheres[begin])) ++end;
    Eigen::AlignedBox3d box;
    for (std::size_t i = begin; i < end; ++i) box.extend(spheres[i].head<3>());
    SphereGroup g;
    g.sphere_L.head<3>() = box.center();
    g.sphere_L[3] = 0;
    for (std::size_t i = begin; i < end; ++i) {
      g.sphere_L[3] =
          std::max(g.sphere_L[3], (spheres[i].head<3>() - box.center()).norm() + spheres[i][3]);
    }
    g.begin = begin;
    g.end = end;
    groups.push_back(g);
    begin = end;
  }
  return groups;
}

void setClearanceSpheres(LinkTree& lt, double environment_voxel) {
  const Octree& source = lt.voxels.source;
  lt.spheres_L = clearanceSpheres(source, source.grid().voxelSize());
  lt.grid_spheres_L = clearanceSpheres(source, environment_voxel);
  lt.grid_sphere_groups_L = groupClearanceSpheres(lt.grid_spheres_L);
}

EnvironmentLinkTest LinkModels::environmentTest(std::size_t slot, double environment_voxel,
                                                bool exact_primitives) const {
  const LinkVoxels& v = links[slot].voxels;
  EnvironmentLinkTest t;
  t.center_L = v.center_L;
  t.half_L = v.half_L;
  // Placed on the environment grid, the link's voxels reach up to one voxel diagonal beyond its
  // bounding sphere (a target voxel is black when it overlaps a moved source voxel); with exact
  // primitives a leaf's bounding sphere reaches less than a link voxel diagonal beyond it.
  const double voxel = exact_primitives ? std::max(environment_voxel, v.source.grid().voxelSize())
                                        : environment_voxel;
  const double reach = v.radius + std::sqrt(3.0) * voxel;
  t.reach_squared = reach * reach;
  const double origin_reach = (reach + v.center_L.norm()) * (1 + 1e-12);
  t.origin_reach_squared = origin_reach * origin_reach;
  t.link = links[slot].link;
  t.slot = slot;
  return t;
}

void LinkModels::orderEnvironmentTests(const EnvironmentModel& environment, const RobotModel& robot,
                                       const Eigen::Isometry3d& X_WB,
                                       CollisionModelReport& report) {
  // One test record per link that can touch the environment, in model order, reordered below.
  const double voxel = environment.tree.grid().voxelSize();
  const bool exact = !environment.exact_primitives.empty();
  for (std::size_t slot = 0; slot < links.size(); ++slot) {
    if (links[slot].touches_environment && !links[slot].folded) {
      environment_tests.push_back(environmentTest(slot, voxel, exact));
    }
  }
  // Free-flying robots have no joint limits to sample their poses from (the scene's bounds are
  // the planner's): model order.
  if (!robot.isFreeFlying() && environment_tests.size() > 1 && !robot.variables().empty()) {
    std::vector<int> hits(links.size(), 0);  // per slot
    std::vector<double> q(robot.variables().size());
    RobotData data = robot.makeData();
    CollisionScratch fused;
    std::mt19937_64 rng(2);
    for (int i = 0; i < kEnvironmentOrderSamples; ++i) {
      for (std::size_t v = 0; v < q.size(); ++v) q[v] = uniformIn(robot.variables()[v], rng);
      robot.forwardKinematics(q.data(), q.size(), data, X_WB);
      for (const EnvironmentLinkTest& t : environment_tests) {
        const Eigen::Isometry3d& X_WL = data.linkPose(t.link);
        if (sphereMeetsBox(t, X_WL, environment.box_W) &&
            environment.linkHits(t, links[t.slot].voxels, X_WL, CheckerPath::kFused, fused)) {
          ++hits[t.slot];
        }
      }
    }
    std::stable_sort(environment_tests.begin(), environment_tests.end(),
                     [&](const EnvironmentLinkTest& a, const EnvironmentLinkTest& b) {
                       return hits[a.slot] > hits[b.slot];
                     });
    for (const EnvironmentLinkTest& t : environment_tests) {
      report.links[static_cast<std::size_t>(t.link)].environment_hit_share =
          static_cast<double>(hits[t.slot]) / kEnvironmentOrderSamples;
    }
  }
  for (const EnvironmentLinkTest& t : environment_tests) {
    report.environment_order.push_back(robot.link(t.link).name);
  }
}

}  // namespace octomotion::detail
