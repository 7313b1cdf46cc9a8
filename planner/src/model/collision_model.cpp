#include "octomotion/planner/model/collision_model.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <system_error>
#include <thread>

#include "internal/self_pair_tables.h"
#include "octomotion/motion/box_overlap.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/distance.h"
#include "octomotion/octree/inner_boxes.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"
#include "octomotion/planner/robot/collision_meshes.h"

namespace octomotion {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Clearance spheres circumscribe the level-kSphereLevel cubes that hold black voxels: coarse
// enough to be few, fine enough (8 voxels) to keep the bound useful.
constexpr int kSphereLevel = 3;

// Self-pair table oracles have at least the tolerance's double and at most this many voxels
// across the link's longest side (time and memory stay those of a 256^3 surface).
constexpr double kOracleVoxelsAcross = 256;

// A value uniform in the variable's range from the top 53 bits of one draw: the same sequence on
// every standard library (unlike std::uniform_real_distribution), so build-time samples are.
double uniformIn(const Variable& var, std::mt19937_64& rng) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return var.lower + u * (var.upper - var.lower);
}

double squaredDistanceToBox(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  return (p - p.cwiseMax(box.min()).cwiseMin(box.max())).squaredNorm();
}

// Every entry 0 or ±1: the rotation only permutes and flips the axes, so boxes along them are
// exactly axis-aligned in the world.
bool isAxisPermutation(const Eigen::Matrix3d& R) {
  return (R.array() == 0 || R.array().abs() == 1).all();
}

// Surface voxels of a box at a resolution: what a tree of a solid that fills it has to store.
double surfaceVoxels(const Eigen::AlignedBox3d& box, double resolution) {
  if (box.isEmpty()) return 0;
  const Eigen::Vector3d s = box.sizes() / resolution + Eigen::Vector3d::Ones();
  return 2 * (s.x() * s.y() + s.y() * s.z() + s.z() * s.x());
}

void guardTreeSizes(const RobotModel& robot, const std::vector<Eigen::AlignedBox3d>& boxes_L,
                    double link_res, const EnvironmentGeometry& environment,
                    const Eigen::AlignedBox3d& region, const CollisionModelOptions& options) {
  auto check = [&](const std::string& what, double voxels, double resolution) {
    if (voxels > options.max_surface_voxels) {
      std::ostringstream msg;
      msg << what << " at resolution " << resolution << " m would need about "
          << std::llround(voxels) << " surface voxels (limit "
          << std::llround(options.max_surface_voxels) << "); use a coarser resolution";
      throw InvalidArgument(msg.str());
    }
  };
  for (std::size_t i = 0; i < boxes_L.size(); ++i) {
    check("link " + robot.link(static_cast<int>(i)).name, surfaceVoxels(boxes_L[i], link_res),
          link_res);
  }
  for (const EnvironmentGeometry::Item& item : environment.items()) {
    double voxels = surfaceVoxels(item.bounds_W.intersection(region), options.resolution);
    // A point cloud marks at most one voxel per point, however large its box (a sparse scan).
    if (item.spec.kind == EnvironmentObject::Kind::kPointCloud) {
      voxels = std::min(voxels, static_cast<double>(item.points_W.size()));
    }
    check(item.spec.name, voxels, options.resolution);
  }
}

// Clearance spheres of a link: they circumscribe the level-kSphereLevel ancestors of its black
// leaves.
std::vector<Eigen::Vector4d> clearanceSpheres(const Octree& source) {
  const WorldGrid& grid = source.grid();
  const int level = std::min(kSphereLevel, grid.depth());
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

// The same objects voxelized again (on a shifted grid, or apart from the primitives) warn of
// nothing new; an empty WarningSink would print to stderr.
const WarningSink kIgnoreWarnings = [](const std::string&) {};

}  // namespace

// A link's collision elements voxelized in its frame at `resolution` (box_L: their extent).
OctreeCollisionModel::LinkVoxels OctreeCollisionModel::voxelizeLink(
    const Link& link, const std::vector<const TriangleMesh*>& element_mesh,
    Eigen::AlignedBox3d box_L, double resolution, const CollisionModelOptions& options,
    bool for_self_pairs) {
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
    // Three boxes of cells of 1/64 of the link's universe: more boxes found nothing more on
    // octo7 in the bookshelf (callgrind, 3,000 states: 6 or 10 boxes +0.0-0.2 % instructions),
    // 1/128 cells 2.7 % fewer instructions for 8x the cells to build them from.
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

const char* selfBroadPhaseName(SelfBroadPhase strategy) {
  switch (strategy) {
    case SelfBroadPhase::kAuto:
      return "auto";
    case SelfBroadPhase::kPairs:
      return "all checked pairs";
    case SelfBroadPhase::kNObjectsOctree:
      return "N-objects octree";
  }
  return "?";
}

std::uint64_t nextModelId() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1);
}

OctreeCollisionModel::OctreeCollisionModel(RobotModel robot, const EnvironmentGeometry& environment,
                                           const CollisionModelOptions& options)
    : id_(nextModelId()),
      robot_(std::move(robot)),
      options_(options),
      environment_(WorldGrid({0, 0, 0}, 1, 1)) {
  const auto start = Clock::now();
  if (!(std::isfinite(options.resolution) && options.resolution > 0)) {
    throw InvalidArgument("resolution must be finite and > 0");
  }
  const LinkTreeResolutions tree_res = linkTreeResolutions(
      options.resolution, options.link_resolution, options.self_link_resolution);
  const double link_res = tree_res.link, self_res = tree_res.self;
  if (!(std::isfinite(link_res) && link_res > 0)) {
    throw InvalidArgument("link resolution must be finite and > 0");
  }
  if (!(std::isfinite(self_res) && self_res > 0)) {
    throw InvalidArgument("self-collision link resolution must be finite and > 0");
  }
  if (!(std::isfinite(options.self_pair_table_tolerance) &&
        options.self_pair_table_tolerance > 0)) {
    throw InvalidArgument("self_pair_table_tolerance must be finite and > 0");
  }
  if (options.self_broad_phase_leaf_capacity < 1) {
    throw InvalidArgument("self_broad_phase_leaf_capacity must be >= 1");
  }
  if (robot_.isFreeFlying() && !options.base_position_bounds) {
    throw InvalidArgument("a free-flying robot needs base_position_bounds (the SE(3) bounds)");
  }
  report_.link_resolution = link_res;
  report_.self_link_resolution = self_res;

  // 1. Each link's geometry in its own frame (meshes loaded once), and its extent.
  CollisionMeshes meshes(options.keep_mesh_root_transform, options.center_mesh_vertices);
  const int n_links = robot_.linkCount();
  const auto n = static_cast<std::size_t>(n_links);
  std::vector<Eigen::AlignedBox3d> boxes_L(n);
  std::vector<std::vector<const TriangleMesh*>> element_meshes(n);
  // Farthest point of a link's geometry from its frame origin (exact: the self-pair tables' motion
  // bound), and of its voxels (plus one voxel diagonal).
  std::vector<double> geometry_extent(n, 0.0), geometry_reach(n, 0.0);
  report_.links.resize(n);
  for (int i = 0; i < n_links; ++i) {
    const Link& link = robot_.link(i);
    report_.links[static_cast<std::size_t>(i)].name = link.name;
    Eigen::AlignedBox3d& box_L = boxes_L[static_cast<std::size_t>(i)];
    for (const CollisionElement& e : link.collision) {
      if (const auto* prim = std::get_if<Primitive>(&e.geometry)) {
        box_L.extend(boundingBox(*prim, e.X_LE));
        element_meshes[static_cast<std::size_t>(i)].push_back(nullptr);
      } else {
        const TriangleMesh& mesh = meshes.get(std::get<MeshRef>(e.geometry));
        for (const Eigen::Vector3d& v : mesh.vertices) box_L.extend(e.X_LE * v);
        element_meshes[static_cast<std::size_t>(i)].push_back(&mesh);
      }
    }
    if (box_L.isEmpty()) continue;
    double& extent = geometry_extent[static_cast<std::size_t>(i)];
    for (int c = 0; c < 8; ++c) {
      extent =
          std::max(extent, box_L.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).norm());
    }
    geometry_reach[static_cast<std::size_t>(i)] =
        extent + std::sqrt(3.0) * std::max(link_res, self_res);
  }

  // 2. What the robot can reach: bound each link's distance from the base origin along its
  // chain (joint offsets, prismatic travel), plus its geometry's extent from its own origin.
  std::vector<double> origin_reach(static_cast<std::size_t>(n_links), 0.0);
  for (const Joint& j : robot_.joints()) {
    double travel = 0;
    if (j.type == JointType::kPrismatic) {
      if (j.isMimic()) {
        const Joint& m = robot_.joint(j.mimic_master);
        travel = std::abs(j.mimic_multiplier) * std::max(std::abs(m.lower), std::abs(m.upper)) +
                 std::abs(j.mimic_offset);
      } else {
        travel = std::max(std::abs(j.lower), std::abs(j.upper));
      }
    }
    origin_reach[static_cast<std::size_t>(j.child_link)] =
        origin_reach[static_cast<std::size_t>(j.parent_link)] + j.X_PJ.translation().norm() +
        travel;
  }
  Eigen::AlignedBox3d base_region;
  if (robot_.isFreeFlying()) {
    base_region = *options.base_position_bounds;
  } else {
    base_region.extend(options.X_WB.translation());
  }
  std::vector<double> link_reach(static_cast<std::size_t>(n_links), 0.0);
  double reach = 0;
  for (int i = 0; i < n_links; ++i) {
    const auto s = static_cast<std::size_t>(i);
    link_reach[s] = origin_reach[s] + geometry_reach[s];
    if (robot_.link(i).hasCollision()) reach = std::max(reach, link_reach[s]);
  }
  report_.reach_W =
      Eigen::AlignedBox3d(base_region.min().array() - reach, base_region.max().array() + reach);

  // 3. The universe: the environment where the robot can reach it. Fitted before anything is
  // voxelized, so an impossible resolution fails at once.
  Eigen::AlignedBox3d region = report_.reach_W;
  if (const auto env_box = environment.bounds()) {
    const Eigen::AlignedBox3d overlap = env_box->intersection(report_.reach_W);
    if (!overlap.isEmpty()) {
      // No margin around it: the universe's minimum corner is then the lowest face of the
      // environment the robot can reach (or 1-3 voxels below it, step 5), so faces at round
      // distances from it (shelves, walls, a table top) fall on voxel boundaries, where
      // conservative voxels of primitives add no layer (voxelize: a voxel is black when the solid
      // meets its interior), and on the boundaries of larger cells. A contact lies in both the
      // reach and the environment, so in the universe; a voxel that sticks out of it could only add
      // a false positive.
      region = overlap;
    }
  }
  WorldGrid grid = fitGrid(region, options.resolution);  // its origin may move down in step 5
  guardTreeSizes(robot_, boxes_L, std::min(link_res, self_res), environment, region, options);

  // 4. Each link's source tree, in its own frame, at the link resolution (and a second one at
  // the self-collision resolution when that differs).
  std::vector<bool> in_pair(n, false);
  for (const auto& [a, b] : robot_.checkedPairs()) {
    in_pair[static_cast<std::size_t>(a)] = in_pair[static_cast<std::size_t>(b)] = true;
  }
  std::vector<LinkTree> trees(n);
  for (int i = 0; i < n_links; ++i) {
    const Link& link = robot_.link(i);
    LinkReport& lr = report_.links[static_cast<std::size_t>(i)];
    if (!link.hasCollision()) continue;
    const auto t0 = Clock::now();
    const auto s = static_cast<std::size_t>(i);
    LinkTree& lt = trees[s];
    lt.link = i;
    lt.voxels = voxelizeLink(link, element_meshes[s], boxes_L[s], link_res, options, false);
    if (self_res != link_res && in_pair[s]) {
      lt.self_voxels = std::make_unique<const LinkVoxels>(
          voxelizeLink(link, element_meshes[s], boxes_L[s], self_res, options, true));
      lr.self_source_bytes = lt.self_voxels->source.bytes();
    }
    const Octree& source = lt.voxels.source;
    lt.spheres_L = clearanceSpheres(source);
    lr.source_internal_nodes = source.internalNodeCount();
    lr.source_black_leaves = source.blackLeafCount();
    lr.source_bytes = source.bytes();
    lr.source_depth = source.grid().depth();
    lr.radius = lt.voxels.radius;
    lr.core_boxes = static_cast<int>(lt.voxels.core_boxes.size());
    lr.build_seconds = secondsSince(t0);
  }

  // 5. The environment tree, on the universe whose origin is the region's lowest corner or up
  // to kOriginShifts - 1 voxels below it on every axis (while the same depth covers the region):
  // the faces at round distances from the corner lie on voxel boundaries at every shift, but
  // which of them also lie on the boundaries of larger cells — so how many nodes the tree needs
  // along them, and how deep a query near them descends — depends on the shift (environment
  // nodes at shifts 0-3: rooms 5 mm 109k, 1,102k, 202k, 1,102k; rooms 2 cm 46k, 29k, 48k, 31k;
  // bookshelf 1 cm 10.7k, 9.4k, 10.2k, 9.7k). The tree with the fewest nodes is kept; the
  // others cost a build each (build_seconds counts them all).
  {
    const auto t0 = Clock::now();
    environment_ =
        environment.voxelize(grid, options.rounding, &report_.environment, options.warnings);
    for (int shift = 1; shift < kOriginShifts; ++shift) {
      const Eigen::Vector3d origin =
          region.min() - Eigen::Vector3d::Constant(shift * options.resolution);
      if (!((region.max() - origin).maxCoeff() <= grid.sideMetres())) break;
      const WorldGrid shifted(origin, options.resolution, grid.depth());
      EnvironmentReport candidate_report;
      Octree candidate =
          environment.voxelize(shifted, options.rounding, &candidate_report, kIgnoreWarnings);
      if (candidate.internalNodeCount() < environment_.internalNodeCount()) {
        environment_ = std::move(candidate);
        report_.environment = std::move(candidate_report);
        grid = shifted;
      }
    }
    report_.environment.build_seconds = secondsSince(t0);
    report_.grid = grid;
  }
  environment_cells_ = std::make_unique<const BlackCellGrid>(environment_);
  report_.environment_cell_grid_level = environment_cells_->level();
  report_.environment_cell_grid_bytes = environment_cells_->bytes();
  environment_clearance_ = std::make_unique<const ClearanceGrid>(environment_);
  report_.environment_clearance_grid_level = environment_clearance_->level();
  report_.environment_clearance_grid_bytes = environment_clearance_->bytes();
  // 5'. Exact primitives: the environment half tests the links' black source voxels against the
  // primitives themselves (linkHitsEnvironment) instead of the environment tree; the other
  // objects, which have no such shape, get a tree of their own on the same grid.
  auto isPrimitive = [](const EnvironmentGeometry::Item& item) {
    return item.spec.kind == EnvironmentObject::Kind::kPrimitive;
  };
  const bool any_primitive =
      std::any_of(environment.items().begin(), environment.items().end(), isPrimitive);
  if (options.exact_primitives && !environment.items().empty() &&
      (options.rounding != Rounding::kConservative || !any_primitive)) {
    warn(options.warnings,
         options.rounding != Rounding::kConservative
             ? "octree.exact_primitives: not applied under centre rounding"
             : "octree.exact_primitives: not applied, the environment has no primitives (boxes, "
               "balls, cylinders); the voxel answers stand");
  }
  const bool exact =
      options.exact_primitives && options.rounding == Rounding::kConservative && any_primitive;
  auto blackBox = [&grid](const Octree& tree) {
    const auto b = tree.bounds();
    return b ? Eigen::AlignedBox3d(grid.cubeMin(Cube{0, b->min}), grid.cubeMax(Cube{0, b->max}))
             : Eigen::AlignedBox3d();
  };
  if (exact) {
    for (const EnvironmentGeometry::Item& item : environment.items()) {
      if (!isPrimitive(item)) continue;
      exact_primitives_.push_back({PrimitiveShape(item.spec.primitive), item.spec.X_WO.inverse(),
                                   item.bounds_W.center(), item.bounds_W.sizes() / 2});
      environment_box_W_.extend(item.bounds_W);
    }
    const EnvironmentGeometry others = environment.withoutPrimitives();
    if (others.size() > 0) {
      auto v = std::make_unique<VoxelObjects>(
          VoxelObjects{others.voxelize(grid, Rounding::kConservative, nullptr, kIgnoreWarnings),
                       nullptr, nullptr});
      v->cells = std::make_unique<const BlackCellGrid>(v->tree);
      v->clearance = std::make_unique<const ClearanceGrid>(v->tree);
      environment_box_W_.extend(blackBox(v->tree));
      report_.exact_primitives_other_objects = others.size();
      other_objects_ = std::move(v);
    }
  } else {
    environment_box_W_ = blackBox(environment_);
  }
  report_.exact_primitives = exact_primitives_.size();

  // 5a. Object boxes for the environment pre-test: every voxel an object marks (any rounding,
  // any kind) overlaps the object's box, so it lies within one voxel of it. With exact
  // primitives a link leaf's bounding sphere that meets the object reaches past the link's box
  // by less than a link voxel: the boxes grow by the larger of the two voxels and keep the
  // parts outside the universe.
  const double growth = exact ? std::max(grid.voxelSize(), link_res) : grid.voxelSize();
  const Eigen::Vector3d one_voxel = Eigen::Vector3d::Constant(growth * (1 + 1e-9));
  const Eigen::AlignedBox3d universe_W(grid.origin(), grid.origin().array() + grid.sideMetres());
  for (const EnvironmentGeometry::Item& item : environment.items()) {
    if (item.bounds_W.isEmpty()) continue;
    const Eigen::AlignedBox3d box(item.bounds_W.min() - one_voxel, item.bounds_W.max() + one_voxel);
    if (!exact && box.intersection(universe_W).isEmpty()) continue;
    object_boxes_W_.push_back(box);
    ObjectFrameBox frame_box;
    const Eigen::Matrix3d& R_WO = item.spec.X_WO.linear();
    if (item.spec.kind == EnvironmentObject::Kind::kPrimitive &&
        !std::holds_alternative<Sphere>(item.spec.primitive) && !isAxisPermutation(R_WO)) {
      frame_box.tilted = true;
      frame_box.centre_W = item.spec.X_WO.translation();
      frame_box.R_OW = R_WO.transpose();
      frame_box.half =
          boxHalfSides(item.spec.primitive) + Eigen::Vector3d::Constant(std::sqrt(3.0) * growth);
    }
    object_frame_boxes_.push_back(frame_box);
  }
  switch (options.environment_pre_test) {
    case EnvironmentPreTest::kAuto:
      report_.environment_pre_test =
          object_boxes_W_.size() >= 2 && object_boxes_W_.size() <= kObjectBoxesMaxObjects
              ? EnvironmentPreTest::kObjectBoxes
              : EnvironmentPreTest::kEnvironmentBox;
      break;
    default:
      report_.environment_pre_test = options.environment_pre_test;
  }
  if (report_.environment_pre_test != EnvironmentPreTest::kObjectBoxes) {
    object_boxes_W_.clear();
    object_frame_boxes_.clear();
  }
  report_.environment_object_boxes = object_boxes_W_.size();
  // 5a'. Solid boxes for the links' core boxes (conservative rounding): each primitive's
  // inscribed box, its part inside the universe (a moved link voxel outside it is dropped),
  // shrunk like the cores.
  if (options.core_boxes && options.rounding == Rounding::kConservative) {
    const double shrink = kSolidShrink * std::max(options.resolution, link_res);
    const Eigen::AlignedBox3d inner_universe_W(universe_W.min().array() + shrink,
                                               universe_W.max().array() - shrink);
    for (const EnvironmentGeometry::Item& item : environment.items()) {
      if (item.spec.kind != EnvironmentObject::Kind::kPrimitive) continue;
      const Eigen::Vector3d half_O = inscribedBoxHalfSides(item.spec.primitive);
      const Eigen::Matrix3d& R_WO = item.spec.X_WO.linear();
      const Eigen::Vector3d extent_W = R_WO.cwiseAbs() * half_O;
      const Eigen::AlignedBox3d aabb_W(item.spec.X_WO.translation() - extent_W,
                                       item.spec.X_WO.translation() + extent_W);
      SolidBox solid;
      if (inner_universe_W.contains(aabb_W)) {
        solid.centre_W = item.spec.X_WO.translation();
        solid.R_OW = R_WO.transpose();
        solid.half = half_O - Eigen::Vector3d::Constant(shrink);
        solid.extent_W = extent_W;
      } else if (isAxisPermutation(R_WO)) {
        // Exactly axis-aligned (a box crossing the universe's side, e.g. a floor beyond the
        // robot's reach): the part inside the universe, which is its own world box.
        const Eigen::AlignedBox3d inside = aabb_W.intersection(inner_universe_W);
        if (inside.isEmpty()) continue;
        solid.centre_W = inside.center();
        solid.R_OW = Eigen::Matrix3d::Identity();
        solid.half = inside.sizes() / 2 - Eigen::Vector3d::Constant(shrink);
        solid.extent_W = inside.sizes() / 2;
      } else {
        continue;  // rotated and leaving the universe
      }
      if (!(solid.half.array() > 0).all()) continue;
      solid_boxes_W_.push_back(solid);
    }
  }
  report_.environment_solid_boxes = solid_boxes_W_.size();
  const double tie_margin = kMotionTieTolerance * grid.voxelSize();
  for (const Eigen::AlignedBox3d& box : object_boxes_W_) {
    for (int a = 0; a < 3; ++a) {
      object_centre_W_[static_cast<std::size_t>(a)].push_back(0.5 * (box.min()[a] + box.max()[a]));
      object_reach_W_[static_cast<std::size_t>(a)].push_back(0.5 * (box.max()[a] - box.min()[a]) +
                                                             tie_margin);
    }
  }

  // 5b. Clearance point trees: the black leaves' centres, one PointOctree per leaf level, so a
  // nearest centre at distance d bounds the distance to its cube by d - half diagonal.
  if (options.clearance == ClearanceMethod::kPointOctree && !environment_.empty()) {
    std::vector<std::vector<Eigen::Vector3f>> centres(static_cast<std::size_t>(grid.depth()) + 1);
    environment_.forEachBlackLeaf([&](const Cube& c) {
      centres[static_cast<std::size_t>(c.level)].push_back(
          ((grid.cubeMin(c) + grid.cubeMax(c)) / 2).cast<float>());
    });
    for (std::size_t level = 0; level < centres.size(); ++level) {
      if (centres[level].empty()) continue;
      const double side = grid.voxelSize() * static_cast<double>(std::uint64_t{1} << level);
      clearance_levels_.push_back(
          {side * std::sqrt(3.0) / 2, pointcloud::PointOctree::build(centres[level])});
    }
    // Centres rounded to float move by at most |coordinate| * 2^-24 per axis, and float
    // distances carry a few ulps of relative error: 1e-6 of the largest coordinate (plus 1 um)
    // covers both with a wide margin.
    const double extent = std::max(grid.origin().cwiseAbs().maxCoeff(),
                                   (grid.origin().array() + grid.sideMetres()).abs().maxCoeff());
    clearance_float_slack_ = 1e-6 * (1 + 4 * extent);
  }

  // 6. Keep the links that can touch something: the environment, or another link.
  link_slot_.assign(static_cast<std::size_t>(n_links), -1);
  for (int i = 0; i < n_links; ++i) {
    const auto s = static_cast<std::size_t>(i);
    LinkTree& lt = trees[s];
    if (lt.link < 0 || (lt.voxels.source.empty() && lt.forSelf().source.empty())) continue;
    const Eigen::AlignedBox3d link_box(base_region.min().array() - link_reach[s],
                                       base_region.max().array() + link_reach[s]);
    lt.touches_environment = !environment_.empty() && !lt.voxels.source.empty() &&
                             !link_box.intersection(environment_box_W_).isEmpty();
    if (!lt.touches_environment && !in_pair[s]) continue;
    link_slot_[s] = static_cast<int>(links_.size());
    report_.links[s].modelled = true;
    links_.push_back(std::move(lt));
  }
  // links_ is final: the self trees' addresses stay valid (moving the model moves the buffer).
  for (const LinkTree& lt : links_) self_voxels_.push_back(&lt.forSelf());
  orderEnvironmentLinks();
  const bool tables = options.self_pair_tables && options.rounding == Rounding::kConservative;
  detail::SelfPairTableOptions table_options;
  table_options.tolerance = options.self_pair_table_tolerance;
  table_options.max_cells = options.self_pair_table_max_cells;
  // The tables' inside/outside oracles: conservative trees fine enough that "black and more than
  // a voxel diagonal from the surface" certifies shallow contacts too (one per link, on demand).
  std::map<int, Octree> oracles;
  auto oracle = [&](int link) -> const Octree* {
    auto it = oracles.find(link);
    if (it == oracles.end()) {
      const auto s = static_cast<std::size_t>(link);
      const double extent = boxes_L[s].sizes().maxCoeff();
      const double res = std::min(
          link_res, std::max(2 * options.self_pair_table_tolerance, extent / kOracleVoxelsAcross));
      CollisionModelOptions conservative = options;
      conservative.rounding = Rounding::kConservative;
      it = oracles
               .emplace(link, voxelizeLink(robot_.link(link), element_meshes[s], boxes_L[s], res,
                                           conservative, false)
                                  .source)
               .first;
    }
    return &it->second;
  };
  // The pairs that get a table; their classifications run in parallel below (each job owns its
  // FCL objects and robot data; the oracles are made first, so the jobs only read shared state).
  struct TableJob {
    std::size_t pair = 0;  // index into pairs_
    detail::SelfPairLink a, b;
    std::optional<JointSpaceTable> table;
    double seconds = 0;
    std::exception_ptr error;
  };
  std::vector<TableJob> jobs;
  for (const auto& [a, b] : robot_.checkedPairs()) {
    const int sa = link_slot_[static_cast<std::size_t>(a)];
    const int sb = link_slot_[static_cast<std::size_t>(b)];
    if (sa < 0 || sb < 0) continue;
    const double pair_reach = spheresReach(*self_voxels_[static_cast<std::size_t>(sa)],
                                           *self_voxels_[static_cast<std::size_t>(sb)]);
    SelfPair pair{static_cast<std::size_t>(sa), static_cast<std::size_t>(sb),
                  pair_reach * pair_reach, nullptr};
    // 6a. The pair's joint-space table, classified on the exact geometry, when its pose depends
    // on few variables and its tree test runs often enough to be worth the build.
    const std::vector<int> vars = tables ? detail::pairVariables(robot_, a, b) : std::vector<int>{};
    if (tables && vars.size() <= options.self_pair_table_max_variables &&
        treeTestShare(pair, vars) >= kSelfPairTableMinShare) {
      auto side = [&](int link) {
        const auto s = static_cast<std::size_t>(link);
        return detail::SelfPairLink{link, element_meshes[s], oracle(link), geometry_extent[s]};
      };
      jobs.push_back({pairs_.size(), side(a), side(b), std::nullopt, 0, nullptr});
    }
    pairs_.push_back(pair);
  }
  std::atomic<std::size_t> next_job{0};
  auto work = [&] {
    for (std::size_t j; (j = next_job++) < jobs.size();) {
      TableJob& job = jobs[j];
      try {
        const auto t0 = Clock::now();
        job.table = detail::buildSelfPairTable(robot_, job.a, job.b, table_options);
        job.seconds = secondsSince(t0);
      } catch (...) {
        job.error = std::current_exception();
      }
    }
  };
  {
    const std::size_t threads_wanted =
        std::min<std::size_t>(jobs.size(), std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < threads_wanted; ++t) {
      try {
        helpers.emplace_back(work);
      } catch (const std::system_error&) {
        break;  // no more threads to be had: fewer workers, the same tables
      }
    }
    work();
    for (std::thread& t : helpers) t.join();
  }
  for (TableJob& job : jobs) {
    if (job.error) std::rethrow_exception(job.error);
    if (!job.table) continue;
    const JointSpaceTable& table = *job.table;
    SelfPairTableReport r;
    r.link_a = robot_.link(job.a.link).name;
    r.link_b = robot_.link(job.b.link).name;
    r.variables = table.dims();
    r.depth = table.depth();
    r.nodes = table.nodeCount();
    r.bytes = table.bytes();
    r.classified = table.classified();
    r.free_fraction = table.volumeFractions()[JointSpaceTable::kFree];
    r.colliding_fraction = table.volumeFractions()[JointSpaceTable::kColliding];
    r.build_seconds = job.seconds;
    pair_tables_.push_back(std::make_unique<const JointSpaceTable>(std::move(*job.table)));
    pairs_[job.pair].table = pair_tables_.back().get();
    report_.self_pair_tables.push_back(std::move(r));
  }
  report_.self_pairs = pairs_.size();

  // 7. The self-collision broad phase: the links in some pair, and which of their pairs count.
  std::vector<int> id_of_slot(links_.size(), -1);
  for (const SelfPair& p : pairs_) id_of_slot[p.a] = id_of_slot[p.b] = 0;
  for (std::size_t slot = 0; slot < links_.size(); ++slot) {
    if (id_of_slot[slot] < 0) continue;
    id_of_slot[slot] = static_cast<int>(self_links_.size());
    self_links_.push_back(static_cast<int>(slot));
  }
  const std::size_t m = self_links_.size();
  self_pair_of_.assign(m * m, -1);
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const auto a = static_cast<std::size_t>(id_of_slot[pairs_[i].a]);
    const auto b = static_cast<std::size_t>(id_of_slot[pairs_[i].b]);
    self_pair_of_[a * m + b] = static_cast<std::int32_t>(i);
  }
  // Root of the broad phase: the reach box grown by the largest link sphere, so link boxes stay
  // inside it (a box leaving it would only cost a re-root, never a wrong answer).
  double max_radius = 0;
  for (const int slot : self_links_) {
    max_radius = std::max(max_radius, self_voxels_[static_cast<std::size_t>(slot)]->radius);
  }
  self_root_box_W_ = Eigen::AlignedBox3d(report_.reach_W.min().array() - max_radius,
                                         report_.reach_W.max().array() + max_radius);
  report_.self_links = m;
  switch (options.self_broad_phase) {
    case SelfBroadPhase::kAuto:
      report_.self_broad_phase = static_cast<int>(m) >= kSelfBroadPhaseAutoLinks
                                     ? SelfBroadPhase::kNObjectsOctree
                                     : SelfBroadPhase::kPairs;
      break;
    default:
      report_.self_broad_phase = options.self_broad_phase;
  }
  report_.build_seconds = secondsSince(start);
}

CheckScratch OctreeCollisionModel::makeScratch() const {
  CheckScratch s;
  s.robot = robot_.makeData();
  if (report_.self_broad_phase == SelfBroadPhase::kNObjectsOctree) {
    s.self_broad_phase.emplace(makeSelfBroadPhase());
  }
  s.owner = id_;
  return s;
}

broadphase::NObjectsOctree OctreeCollisionModel::makeSelfBroadPhase() const {
  broadphase::NObjectsOctree::Options o;
  o.leaf_capacity = options_.self_broad_phase_leaf_capacity;
  // Links are centimetres to metres across in a universe of a few metres: 8 levels (cells of
  // 1/256 of the reach) are already finer than any link.
  o.max_depth = 8;
  broadphase::Aabb root{self_root_box_W_.min(), self_root_box_W_.max()};
  if (self_root_box_W_.isEmpty()) root = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  broadphase::NObjectsOctree tree(root, o);
  // Every link starts as a point at the root's centre; the first check moves them all.
  const Eigen::Vector3d c = (root.min + root.max) / 2;
  for (std::size_t i = 0; i < self_links_.size(); ++i) tree.add({c, c});
  tree.rebalance();
  return tree;
}

OctreeCollisionModel::EnvironmentLinkTest OctreeCollisionModel::environmentTest(
    std::size_t slot) const {
  const LinkVoxels& v = links_[slot].voxels;
  EnvironmentLinkTest t;
  t.center_L = v.center_L;
  t.half_L = v.half_L;
  // Placed on the environment grid, the link's voxels reach up to one voxel diagonal beyond its
  // bounding sphere (a target voxel is black when it overlaps a moved source voxel); with exact
  // primitives a leaf's bounding sphere reaches less than a link voxel diagonal beyond it.
  const double voxel = exact_primitives_.empty()
                           ? environment_.grid().voxelSize()
                           : std::max(environment_.grid().voxelSize(), v.source.grid().voxelSize());
  const double reach = v.radius + std::sqrt(3.0) * voxel;
  t.reach_squared = reach * reach;
  const double origin_reach = (reach + v.center_L.norm()) * (1 + 1e-12);
  t.origin_reach_squared = origin_reach * origin_reach;
  t.link = links_[slot].link;
  t.slot = slot;
  return t;
}

// The pre-test's first stage, the link's bounding sphere against the environment's box: it
// rejects most links of most states (bookshelf: 96 % of them), so it runs inline in the loops
// over links, on the link frame's origin alone (a sphere about it, of radius |center_L| plus
// the bounding sphere's reach, holds that sphere: no transform of the centre), then on the
// sphere itself.
inline bool OctreeCollisionModel::sphereMeetsBox(const EnvironmentLinkTest& t,
                                                 const Eigen::Isometry3d& X_WL,
                                                 const Eigen::AlignedBox3d& box) {
  return squaredDistanceToBox(X_WL.translation(), box) <= t.origin_reach_squared &&
         squaredDistanceToBox(X_WL * t.center_L, box) <= t.reach_squared;
}

bool OctreeCollisionModel::linkNearEnvironment(const EnvironmentLinkTest& t,
                                               const Eigen::Isometry3d& X_WL) const {
  // The box of the link's black voxels, oriented with the link: a link voxel can only meet an
  // environment voxel inside the environment's (or an object's) box. The margin, a millionth of
  // a voxel, is the overlap the colour rule itself demands (kMotionTieTolerance).
  const Eigen::Vector3d c_W = X_WL * t.center_L;
  const double margin = kMotionTieTolerance * environment_.grid().voxelSize();
  const Eigen::Matrix3d& R_WL = X_WL.linear();
  if (object_boxes_W_.empty()) {
    return boxesOverlap(environment_box_W_.center(), environment_box_W_.sizes() / 2, R_WL, c_W,
                        t.half_L, margin);
  }
  // The link box's half extents along the world axes (with boxesOverlap's 1e-12 padding): its
  // first three axes, tested on their own first, reject most object boxes without the other
  // twelve or the sphere's distance.
  const Eigen::Vector3d h_W = (R_WL.cwiseAbs().array() + 1e-12).matrix() * t.half_L;
  const double* centre[3] = {object_centre_W_[0].data(), object_centre_W_[1].data(),
                             object_centre_W_[2].data()};
  const double* reach[3] = {object_reach_W_[0].data(), object_reach_W_[1].data(),
                            object_reach_W_[2].data()};
  const std::size_t n = object_boxes_W_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (std::fabs(c_W[0] - centre[0][i]) > reach[0][i] + h_W[0] ||
        std::fabs(c_W[1] - centre[1][i]) > reach[1][i] + h_W[1] ||
        std::fabs(c_W[2] - centre[2][i]) > reach[2][i] + h_W[2]) {
      continue;
    }
    const Eigen::AlignedBox3d& box = object_boxes_W_[i];
    if (squaredDistanceToBox(c_W, box) <= t.reach_squared &&
        boxesOverlap(box.center(), box.sizes() / 2, R_WL, c_W, t.half_L, margin)) {
      const ObjectFrameBox& o = object_frame_boxes_[i];
      if (!o.tilted) return true;
      if (boxesOverlap(Eigen::Vector3d::Zero(), o.half, o.R_OW * R_WL, o.R_OW * (c_W - o.centre_W),
                       t.half_L, margin)) {
        return true;
      }
    }
  }
  return false;
}

bool OctreeCollisionModel::certainContact(const LinkVoxels& v,
                                          const Eigen::Isometry3d& X_WL) const {
  if (v.core_boxes.empty()) return false;
  const Eigen::Matrix3d& R_WL = X_WL.linear();
  // The link box's extent along the world axes, to skip far obstacles with three comparisons.
  const Eigen::Vector3d c_W = X_WL * v.center_L;
  const Eigen::Vector3d h_W = R_WL.cwiseAbs() * v.half_L;
  for (const SolidBox& solid : solid_boxes_W_) {
    if (((c_W - solid.centre_W).cwiseAbs() - solid.extent_W - h_W).maxCoeff() > 0) continue;
    const Eigen::Matrix3d R_OL = solid.R_OW * R_WL;
    for (const LinkVoxels::CoreBox& core : v.core_boxes) {
      const Eigen::Vector3d t_O = solid.R_OW * (X_WL * core.centre_L - solid.centre_W);
      if (boxesOverlap(Eigen::Vector3d::Zero(), solid.half, R_OL, t_O, core.half_L)) return true;
    }
  }
  return false;
}

bool OctreeCollisionModel::leavesMeetPrimitives(const LinkVoxels& v,
                                                const Eigen::Isometry3d& X_WL) const {
  const Eigen::Vector3d c_W = X_WL * v.center_L;
  const Eigen::Vector3d h_W =
      X_WL.linear().cwiseAbs() * v.half_L +
      Eigen::Vector3d::Constant(kExactReachVoxels * v.source.grid().voxelSize());
  for (const ExactPrimitive& p : exact_primitives_) {
    if (((c_W - p.centre_W).cwiseAbs() - p.extent_W - h_W).maxCoeff() > 0) continue;
    if (blackLeafMeetsPrimitive(*v.movable, p.X_PW * X_WL, p.shape)) return true;
  }
  return false;
}

bool OctreeCollisionModel::linkHitsEnvironment(const EnvironmentLinkTest& t,
                                               const Eigen::Isometry3d& X_WL, CheckerPath path,
                                               CollisionScratch& fused) const {
  if (!linkNearEnvironment(t, X_WL)) return false;
  const LinkVoxels& v = links_[t.slot].voxels;
  // A certain contact has a point inside a primitive and inside a black link leaf: the exact
  // primitives' answer too.
  if (certainContact(v, X_WL)) return true;
  // The voxels left to query: the environment tree, or with exact primitives the tree of the
  // other objects, if any.
  auto voxelsHit = [&](const Octree& tree, const BlackCellGrid* cells,
                       const ClearanceGrid* clearance) {
    if (path == CheckerPath::kFused) {
      return collides(*v.movable, X_WL, tree, options_.rounding, fused, nullptr, cells, clearance);
    }
    return intersects(moveTree(v.source, X_WL, tree.grid(), options_.rounding), tree);
  };
  if (exact_primitives_.empty()) {
    return voxelsHit(environment_, environment_cells_.get(), environment_clearance_.get());
  }
  if (leavesMeetPrimitives(v, X_WL)) return true;
  return other_objects_ && voxelsHit(other_objects_->tree, other_objects_->cells.get(),
                                     other_objects_->clearance.get());
}

void OctreeCollisionModel::orderEnvironmentLinks() {
  // One test record per link that can touch the environment, in model order, reordered below.
  for (std::size_t slot = 0; slot < links_.size(); ++slot) {
    if (links_[slot].touches_environment) environment_tests_.push_back(environmentTest(slot));
  }
  // Free-flying robots have no joint limits to sample their poses from (the scene's bounds are
  // the planner's): model order.
  if (!robot_.isFreeFlying() && environment_tests_.size() > 1 && !robot_.variables().empty()) {
    std::vector<int> hits(links_.size(), 0);  // per slot
    std::vector<double> q(robot_.variables().size());
    RobotData data = robot_.makeData();
    CollisionScratch fused;
    std::mt19937_64 rng(2);
    for (int i = 0; i < kEnvironmentOrderSamples; ++i) {
      for (std::size_t v = 0; v < q.size(); ++v) q[v] = uniformIn(robot_.variables()[v], rng);
      robot_.forwardKinematics(q.data(), q.size(), data, options_.X_WB);
      for (const EnvironmentLinkTest& t : environment_tests_) {
        const Eigen::Isometry3d& X_WL = data.linkPose(t.link);
        if (sphereMeetsBox(t, X_WL, environment_box_W_) &&
            linkHitsEnvironment(t, X_WL, CheckerPath::kFused, fused)) {
          ++hits[t.slot];
        }
      }
    }
    std::stable_sort(environment_tests_.begin(), environment_tests_.end(),
                     [&](const EnvironmentLinkTest& a, const EnvironmentLinkTest& b) {
                       return hits[a.slot] > hits[b.slot];
                     });
    for (const EnvironmentLinkTest& t : environment_tests_) {
      report_.links[static_cast<std::size_t>(t.link)].environment_hit_share =
          static_cast<double>(hits[t.slot]) / kEnvironmentOrderSamples;
    }
  }
  for (const EnvironmentLinkTest& t : environment_tests_) {
    report_.environment_order.push_back(robot_.link(t.link).name);
  }
}

double OctreeCollisionModel::treeTestShare(const SelfPair& pair,
                                           const std::vector<int>& vars) const {
  std::vector<double> q = detail::middleConfiguration(robot_);
  RobotData data = robot_.makeData();
  std::mt19937_64 rng(1);
  int reached = 0;
  constexpr int kSamples = 256;
  const LinkVoxels& a = *self_voxels_[pair.a];
  const LinkVoxels& b = *self_voxels_[pair.b];
  for (int i = 0; i < kSamples; ++i) {
    for (int v : vars) {
      const auto var = static_cast<std::size_t>(v);
      q[var] = uniformIn(robot_.variables()[var], rng);
    }
    robot_.forwardKinematics(q.data(), q.size(), data);
    const Eigen::Isometry3d& X_WA = data.linkPose(links_[pair.a].link);
    const Eigen::Isometry3d& X_WB = data.linkPose(links_[pair.b].link);
    const Eigen::Vector3d ca_W = X_WA * a.center_L, cb_W = X_WB * b.center_L;
    const Eigen::Matrix3d R_AB = X_WA.linear().transpose() * X_WB.linear();
    if (spheresMeet(pair, ca_W, cb_W) && boxesMeet(a, X_WA, R_AB, b, cb_W)) {
      ++reached;
    }
  }
  return static_cast<double>(reached) / kSamples;
}

bool OctreeCollisionModel::linksHit(const LinkVoxels& a, const Eigen::Isometry3d& X_WA,
                                    const LinkVoxels& b, const Eigen::Isometry3d& X_WB,
                                    const Eigen::Vector3d& cb_W, CheckerPath path,
                                    CollisionScratch& fused) const {
  // B's source tree placed in A's frame, tested against A's source tree. A voxel of A that a
  // moved voxel of B overlaps lies in A's box, so the boxes of their black voxels must overlap
  // (much tighter than the spheres for long links). Only the rotation is formed for the test.
  const Eigen::Matrix3d R_AW = X_WA.linear().transpose();
  const Eigen::Matrix3d R_AB = R_AW * X_WB.linear();
  if (!boxesMeet(a, X_WA, R_AB, b, cb_W)) return false;
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  X_AB.linear() = R_AB;
  X_AB.translation() = R_AW * (X_WB.translation() - X_WA.translation());
  if (path == CheckerPath::kFused) {
    return collides(*b.movable, X_AB, a.source, options_.rounding, fused);
  }
  return intersects(moveTree(b.source, X_AB, a.source.grid(), options_.rounding), a.source);
}

void OctreeCollisionModel::placeCentres(CheckScratch& scratch) const {
  scratch.centres_W.resize(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    scratch.centres_W[i] = scratch.robot.linkPose(links_[i].link) * self_voxels_[i]->center_L;
  }
}

bool OctreeCollisionModel::environmentInCollision(CheckerPath path, CheckScratch& scratch) const {
  for (const EnvironmentLinkTest& t : environment_tests_) {
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(t.link);
    if (sphereMeetsBox(t, X_WL, environment_box_W_) &&
        linkHitsEnvironment(t, X_WL, path, scratch.fused)) {
      return true;
    }
  }
  return false;
}

bool OctreeCollisionModel::selfInCollision(CheckerPath path, CheckScratch& scratch) const {
  if (pairs_.empty()) return false;
  if (report_.self_broad_phase == SelfBroadPhase::kNObjectsOctree) {
    return selfBroadPhaseInCollision(path, scratch);
  }
  return selfPairsInCollision(path, scratch);
}

bool OctreeCollisionModel::selfBroadPhaseInCollision(CheckerPath path,
                                                     CheckScratch& scratch) const {
  // Created lazily for scratch made by hand (or for another model): once per thread, not per
  // query.
  if (!scratch.self_broad_phase || scratch.self_broad_phase->objectCount() != self_links_.size()) {
    scratch.self_broad_phase.emplace(makeSelfBroadPhase());
  }
  broadphase::NObjectsOctree& tree = *scratch.self_broad_phase;
  // Each link's box bounds its bounding sphere grown by its voxel diagonal, slightly padded: two
  // links that pass linksHit's pre-test (centre distance <= r_a + r_b + diagonal) then always have
  // overlapping boxes even after rounding, so every pair the all-pairs loop would test in depth is
  // a candidate here.
  placeCentres(scratch);
  for (std::size_t i = 0; i < self_links_.size(); ++i) {
    const auto slot = static_cast<std::size_t>(self_links_[i]);
    const LinkVoxels& v = *self_voxels_[slot];
    const Eigen::Vector3d& c = scratch.centres_W[slot];
    const double r = (v.radius + v.source_diagonal) * (1 + 1e-9) + 1e-9;
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(r);
    tree.move(static_cast<std::uint32_t>(i), {c - half, c + half});
  }
  const std::size_t m = self_links_.size();
  bool hit = false;
  tree.forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) {
    if (hit) return;
    const std::int32_t pair = self_pair_of_[a * m + b];
    if (pair >= 0) hit = pairHits(static_cast<std::size_t>(pair), path, scratch);
  });
  return hit;
}

bool OctreeCollisionModel::pairStagesHit(const SelfPair& p, CheckerPath path,
                                         CheckScratch& scratch) const {
  if (p.table) {
    const JointSpaceTable::Cell cell = p.table->lookup(scratch.robot.joint_values.data());
    if (cell != JointSpaceTable::kUnknown) return cell == JointSpaceTable::kColliding;
  }
  return linksHit(*self_voxels_[p.a], scratch.robot.linkPose(links_[p.a].link), *self_voxels_[p.b],
                  scratch.robot.linkPose(links_[p.b].link), scratch.centres_W[p.b], path,
                  scratch.fused);
}

bool OctreeCollisionModel::selfPairsInCollision(CheckerPath path, CheckScratch& scratch) const {
  placeCentres(scratch);
  // The sphere test inline, with the centres' address held across the loop: most pairs stop
  // there, so the loop is a few instructions per pair.
  const Eigen::Vector3d* centres = scratch.centres_W.data();
  for (const SelfPair& p : pairs_) {
    if (spheresMeet(p, centres[p.a], centres[p.b]) && pairStagesHit(p, path, scratch)) return true;
  }
  return false;
}

bool OctreeCollisionModel::linksInCollision(CheckerPath path, CheckScratch& scratch) const {
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
  return options_.clearance == ClearanceMethod::kPointOctree ? clearanceLowerBoundPoints(scratch)
                                                             : clearanceLowerBoundTree(scratch);
}

double OctreeCollisionModel::clearanceLowerBoundPoints(const CheckScratch& scratch) const {
  if (clearance_levels_.empty()) return clearanceLowerBoundTree(scratch);
  // For a clearance sphere (centre c, radius r) and a black cube of half diagonal h whose centre
  // is at distance d from c, every point of the cube is at least d - h from c, so at least
  // d - h - r from the sphere, which covers the link's black voxels. The minimum over levels and
  // spheres, less the float slack, is therefore a lower bound on the distance between the links'
  // voxels and the environment's; it is below kEnvironmentTree's by at most the nearest cube's h.
  double best = std::numeric_limits<double>::infinity();
  for (const LinkTree& lt : links_) {
    if (!lt.touches_environment) continue;
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(lt.link);
    for (const Eigen::Vector4d& s : lt.spheres_L) {
      const Eigen::Vector3f c_W = (X_WL * Eigen::Vector3d(s.head<3>())).cast<float>();
      for (const ClearanceLevel& level : clearance_levels_) {
        // Only centres nearer than `beat` can lower the bound: the search prunes the rest.
        const double margin = level.half_diagonal + s[3] + clearance_float_slack_;
        const double d = level.centres.nearestDistance(c_W, best + margin) - margin;
        best = std::min(best, d);
      }
      if (best <= 0) return 0;
    }
  }
  return best;
}

double OctreeCollisionModel::clearanceLowerBoundTree(const CheckScratch& scratch) const {
  double best = std::numeric_limits<double>::infinity();
  for (const LinkTree& lt : links_) {
    if (!lt.touches_environment) continue;
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(lt.link);
    for (const Eigen::Vector4d& s : lt.spheres_L) {
      // Distance to beat is best + r: a sphere can only lower the bound below `best` if its
      // centre is nearer than that.
      const double d =
          distanceToBlack(environment_, X_WL * Eigen::Vector3d(s.head<3>()), best + s[3]);
      best = std::min(best, d - s[3]);
      if (best <= 0) return 0;
    }
  }
  return best;
}

std::string CollisionModelReport::toString() const {
  std::ostringstream out;
  out << "universe: depth " << grid.depth() << ", " << grid.voxelSize() << " m voxels, side "
      << grid.sideMetres() << " m, origin [" << grid.origin().transpose() << "]\n";
  out << "environment: " << environment.internal_nodes << " internal nodes, " << environment.bytes
      << " bytes, built in " << environment.build_seconds << " s\n";
  if (environment_cell_grid_level >= 0) {
    out << "environment black-cell grid: level " << environment_cell_grid_level << " ("
        << (1u << environment_cell_grid_level) << "-voxel cells), " << environment_cell_grid_bytes
        << " bytes\n";
  }
  if (environment_clearance_grid_level >= 0) {
    out << "environment clearance grid: level " << environment_clearance_grid_level << " ("
        << (1u << environment_clearance_grid_level) << "-voxel cells), "
        << environment_clearance_grid_bytes << " bytes\n";
  }
  for (const auto& o : environment.objects) {
    out << "  " << o.name << ": " << o.black_leaves << " black leaves, " << o.internal_nodes
        << " internal nodes, " << o.build_seconds << " s\n";
  }
  out << "links (source voxels " << link_resolution << " m";
  if (self_link_resolution != link_resolution) {
    out << "; self-collision trees " << self_link_resolution << " m";
  }
  out << "):\n";
  for (const LinkReport& l : links) {
    out << "  " << l.name << ": ";
    if (!l.modelled) {
      out << "not modelled\n";
      continue;
    }
    out << l.source_internal_nodes << " internal nodes, " << l.source_black_leaves
        << " black leaves, " << l.source_bytes << " bytes, depth " << l.source_depth << ", radius "
        << l.radius << " m, " << l.core_boxes << " core boxes, " << l.build_seconds << " s";
    if (l.self_source_bytes > 0) out << "; self-collision tree " << l.self_source_bytes << " bytes";
    out << "\n";
  }
  out << "environment pre-test: "
      << (environment_pre_test == EnvironmentPreTest::kObjectBoxes
              ? "object boxes (" + std::to_string(environment_object_boxes) + ")"
              : std::string("environment box"))
      << "; certain contacts: links' core boxes against " << environment_solid_boxes
      << " primitives' inscribed boxes\n";
  if (exact_primitives > 0) {
    out << "exact primitives: the links' source voxels tested against " << exact_primitives
        << " primitives' exact shapes (not the environment tree)";
    if (exact_primitives_other_objects > 0) {
      out << "; the " << exact_primitives_other_objects << " other objects in a tree of their own";
    }
    out << "\n";
  }
  out << "environment tested in the order (share of sampled states hitting):";
  for (const std::string& name : environment_order) {
    out << " " << name;
    for (const LinkReport& l : links) {
      if (l.name == name && l.environment_hit_share >= 0) {
        out << " (" << std::round(1000 * l.environment_hit_share) / 10 << " %)";
      }
    }
  }
  out << "\n";
  out << "self-collision pairs checked: " << self_pairs << " among " << self_links
      << " links; broad phase: " << selfBroadPhaseName(self_broad_phase);
  if (self_links >= 2) {
    out << " (auto picks the N-objects octree from " << kSelfBroadPhaseAutoLinks << " links)";
  }
  if (!self_pair_tables.empty()) {
    out << "\nself-pair tables (joint space, FCL-certified cells): " << self_pair_tables.size();
  }
  for (const SelfPairTableReport& t : self_pair_tables) {
    out << "\n  " << t.link_a << "-" << t.link_b << ": " << t.variables << " variable"
        << (t.variables == 1 ? "" : "s") << ", depth " << t.depth << ", " << t.nodes << " nodes, "
        << t.bytes << " bytes, certified free " << 100 * t.free_fraction << " %, colliding "
        << 100 * t.colliding_fraction << " % (" << t.classified << " FCL cells, " << t.build_seconds
        << " s)";
  }
  out << "\nmodel built in " << build_seconds << " s\n";
  return out.str();
}

}  // namespace octomotion
