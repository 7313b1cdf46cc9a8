#include "internal/collision_model_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

#include "internal/environment_boxes.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion::detail {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool isPrimitive(const EnvironmentGeometry::Item& item) {
  return item.spec.kind == EnvironmentObject::Kind::kPrimitive;
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

// The same objects voxelized again (on a shifted grid, or apart from the primitives) warn of
// nothing new; an empty WarningSink would print to stderr.
const WarningSink kIgnoreWarnings = [](const std::string&) {};

}  // namespace

CollisionModelBuilder::CollisionModelBuilder(const RobotModel& robot,
                                             const EnvironmentGeometry& environment,
                                             const CollisionModelOptions& options,
                                             CollisionModelReport& report)
    : robot_(robot),
      scene_(environment),
      options_(options),
      report_(report),
      meshes_(options.keep_mesh_root_transform, options.center_mesh_vertices) {}

std::unique_ptr<CollisionModelParts> CollisionModelBuilder::build() {
  checkOptions();
  measureLinkGeometry();
  boundReach();
  fitUniverse();
  voxelizeLinks();
  buildEnvironmentTree();
  setUpExactPrimitives();
  buildObjectBoxes();
  resolveEnvironmentPreTest();
  buildSolidBoxes();
  buildClearanceLevels();
  keepLinksThatCanTouch();
  foldStaticLinks();
  orderEnvironmentLinks();
  std::vector<TableJob> jobs = collectSelfPairs();
  classifyPairTables(jobs);
  keepPairTables(jobs);
  indexSelfBroadPhase();
  resolveSelfBroadPhase();
  return std::move(parts_);
}

// Bad options fail before anything is built; the tree resolutions are resolved here.
void CollisionModelBuilder::checkOptions() {
  if (!(std::isfinite(options_.resolution) && options_.resolution > 0)) {
    throw InvalidArgument("resolution must be finite and > 0");
  }
  const LinkTreeResolutions tree_res = linkTreeResolutions(
      options_.resolution, options_.link_resolution, options_.self_link_resolution);
  link_res_ = tree_res.link;
  self_res_ = tree_res.self;
  if (!(std::isfinite(link_res_) && link_res_ > 0)) {
    throw InvalidArgument("link resolution must be finite and > 0");
  }
  if (!(std::isfinite(self_res_) && self_res_ > 0)) {
    throw InvalidArgument("self-collision link resolution must be finite and > 0");
  }
  if (!(std::isfinite(options_.self_pair_table_tolerance) &&
        options_.self_pair_table_tolerance > 0)) {
    throw InvalidArgument("self_pair_table_tolerance must be finite and > 0");
  }
  if (options_.self_broad_phase_leaf_capacity < 1) {
    throw InvalidArgument("self_broad_phase_leaf_capacity must be >= 1");
  }
  if (robot_.isFreeFlying() && !options_.base_position_bounds) {
    throw InvalidArgument("a free-flying robot needs base_position_bounds (the SE(3) bounds)");
  }
  report_.link_resolution = link_res_;
  report_.self_link_resolution = self_res_;
  environment_.rounding = options_.rounding;
  self_.rounding = options_.rounding;
  self_.leaf_capacity = options_.self_broad_phase_leaf_capacity;
}

// Each link's geometry in its own frame (meshes loaded once), its extent, and how far it
// reaches from its frame origin.
void CollisionModelBuilder::measureLinkGeometry() {
  const auto n = static_cast<std::size_t>(robot_.linkCount());
  boxes_L_.assign(n, Eigen::AlignedBox3d());
  element_meshes_.assign(n, {});
  geometry_extent_.assign(n, 0.0);
  report_.links.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const Link& link = robot_.link(static_cast<int>(s));
    report_.links[s].name = link.name;
    Eigen::AlignedBox3d& box_L = boxes_L_[s];
    for (const CollisionElement& e : link.collision) {
      if (const auto* prim = std::get_if<Primitive>(&e.geometry)) {
        box_L.extend(boundingBox(*prim, e.X_LE));
        element_meshes_[s].push_back(nullptr);
      } else {
        const TriangleMesh& mesh = meshes_.get(std::get<MeshRef>(e.geometry));
        for (const Eigen::Vector3d& v : mesh.vertices) box_L.extend(e.X_LE * v);
        element_meshes_[s].push_back(&mesh);
      }
    }
    if (box_L.isEmpty()) continue;
    for (int c = 0; c < 8; ++c) {
      geometry_extent_[s] =
          std::max(geometry_extent_[s],
                   box_L.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).norm());
    }
  }
}

// What the robot can reach: each link's distance from the base origin bounded along its chain
// (joint offsets, prismatic travel), plus its voxels' extent from its own origin.
void CollisionModelBuilder::boundReach() {
  const int n_links = robot_.linkCount();
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
  if (robot_.isFreeFlying()) {
    base_region_ = *options_.base_position_bounds;
  } else {
    base_region_.extend(options_.X_WB.translation());
  }
  // A link's voxels reach one voxel diagonal beyond its geometry.
  const double voxel_diagonal = std::sqrt(3.0) * std::max(link_res_, self_res_);
  link_reach_.assign(static_cast<std::size_t>(n_links), 0.0);
  double reach = 0;
  for (int i = 0; i < n_links; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const double geometry_reach =
        boxes_L_[s].isEmpty() ? 0.0 : geometry_extent_[s] + voxel_diagonal;
    link_reach_[s] = origin_reach[s] + geometry_reach;
    if (robot_.link(i).hasCollision()) reach = std::max(reach, link_reach_[s]);
  }
  report_.reach_W =
      Eigen::AlignedBox3d(base_region_.min().array() - reach, base_region_.max().array() + reach);
}

// The universe: the environment where the robot can reach it. Fitted before anything is
// voxelized, so an impossible resolution fails at once.
void CollisionModelBuilder::fitUniverse() {
  region_ = report_.reach_W;
  std::optional<Eigen::AlignedBox3d> env_box;
  if (!options_.fit_universe_to_reach) env_box = scene_.bounds();
  if (env_box) {
    const Eigen::AlignedBox3d overlap = env_box->intersection(report_.reach_W);
    if (!overlap.isEmpty()) {
      // No margin around it: the universe's minimum corner is then the lowest face of the
      // environment the robot can reach (or a few voxels below it, buildEnvironmentTree), so
      // faces at round distances from it (shelves, walls, a table top) fall on voxel
      // boundaries, where conservative voxels of primitives add no layer (voxelize: a voxel is
      // black when the solid meets its interior), and on the boundaries of larger cells. A
      // contact lies in both the reach and the environment, so in the universe; a voxel that
      // sticks out of it could only add a false positive.
      region_ = overlap;
    }
  }
  grid_ = fitGrid(region_, options_.resolution);  // its origin may move down later
  guardTreeSizes(robot_, boxes_L_, std::min(link_res_, self_res_), scene_, region_, options_);
}

// Each link's source tree, in its own frame, at the link resolution (and a second one at the
// self-collision resolution when that differs, for links in a checked pair).
void CollisionModelBuilder::voxelizeLinks() {
  const auto n = static_cast<std::size_t>(robot_.linkCount());
  in_pair_.assign(n, false);
  for (const auto& [a, b] : robot_.checkedPairs()) {
    in_pair_[static_cast<std::size_t>(a)] = in_pair_[static_cast<std::size_t>(b)] = true;
  }
  trees_ = std::vector<LinkTree>(n);
  for (std::size_t s = 0; s < n; ++s) {
    const Link& link = robot_.link(static_cast<int>(s));
    if (!link.hasCollision()) continue;
    LinkReport& lr = report_.links[s];
    const auto t0 = Clock::now();
    LinkTree& lt = trees_[s];
    lt.link = static_cast<int>(s);
    lt.voxels = voxelizeLink(link, element_meshes_[s], boxes_L_[s], link_res_, options_, false);
    if (self_res_ != link_res_ && in_pair_[s]) {
      lt.self_voxels = std::make_unique<const LinkVoxels>(
          voxelizeLink(link, element_meshes_[s], boxes_L_[s], self_res_, options_, true));
      lr.self_source_bytes = lt.self_voxels->source.bytes();
    }
    const Octree& source = lt.voxels.source;
    setClearanceSpheres(lt, options_.resolution);
    lr.source_internal_nodes = source.internalNodeCount();
    lr.source_black_leaves = source.blackLeafCount();
    lr.source_bytes = source.bytes();
    lr.source_depth = source.grid().depth();
    lr.radius = lt.voxels.radius;
    lr.core_boxes = static_cast<int>(lt.voxels.core_boxes.size());
    lr.build_seconds = secondsSince(t0);
  }
}

// The environment tree, on the universe whose origin is the region's lowest corner or up to
// kOriginShifts - 1 voxels below it on every axis (while the same depth covers the region):
// the faces at round distances from the corner lie on voxel boundaries at every shift, but
// which of them also lie on the boundaries of larger cells (so how many nodes the tree needs
// along them, and how deep a query near them descends) depends on the shift. The tree with the
// fewest nodes is kept; the others cost a build each (build_seconds counts them all). Then the
// tree's BlackCellGrid and ClearanceGrid.
void CollisionModelBuilder::buildEnvironmentTree() {
  const auto t0 = Clock::now();
  Octree& tree = environment_.tree;
  tree = scene_.voxelize(grid_, options_.rounding, &report_.environment, options_.warnings);
  // A universe fitted to the reach keeps its origin: the objects it will hold are not known.
  const int shifts = options_.fit_universe_to_reach ? 1 : kOriginShifts;
  for (int shift = 1; shift < shifts; ++shift) {
    const Eigen::Vector3d origin =
        region_.min() - Eigen::Vector3d::Constant(shift * options_.resolution);
    if (!((region_.max() - origin).maxCoeff() <= grid_.sideMetres())) break;
    const WorldGrid shifted(origin, options_.resolution, grid_.depth());
    EnvironmentReport candidate_report;
    Octree candidate =
        scene_.voxelize(shifted, options_.rounding, &candidate_report, kIgnoreWarnings);
    if (candidate.internalNodeCount() < tree.internalNodeCount()) {
      tree = std::move(candidate);
      report_.environment = std::move(candidate_report);
      grid_ = shifted;
    }
  }
  report_.environment.build_seconds = secondsSince(t0);
  report_.grid = grid_;
  environment_.cells = std::make_unique<const BlackCellGrid>(tree);
  report_.environment_cell_grid_level = environment_.cells->level();
  report_.environment_cell_grid_bytes = environment_.cells->bytes();
  environment_.clearance = std::make_unique<const ClearanceGrid>(tree);
  report_.environment_clearance_grid_level = environment_.clearance->level();
  report_.environment_clearance_grid_bytes = environment_.clearance->bytes();
}

// Exact primitives: the environment half tests the links' black source voxels against the
// primitives themselves instead of the environment tree; the other objects, which have no such
// shape, get a tree of their own on the same grid. Also the box of what the links are tested
// against.
void CollisionModelBuilder::setUpExactPrimitives() {
  const bool any_primitive = std::any_of(scene_.items().begin(), scene_.items().end(), isPrimitive);
  if (options_.exact_primitives && !scene_.items().empty() &&
      (options_.rounding != Rounding::kConservative || !any_primitive)) {
    warn(options_.warnings,
         options_.rounding != Rounding::kConservative
             ? "octree.exact_primitives: not applied under centre rounding"
             : "octree.exact_primitives: not applied, the environment has no primitives (boxes, "
               "balls, cylinders); the voxel answers stand");
  }
  exact_ =
      options_.exact_primitives && options_.rounding == Rounding::kConservative && any_primitive;
  if (!exact_) {
    environment_.box_W = blackBox(environment_.tree);
    return;
  }
  for (const EnvironmentGeometry::Item& item : scene_.items()) {
    if (!isPrimitive(item)) continue;
    environment_.exact_primitives.push_back({PrimitiveShape(item.spec.primitive),
                                             item.spec.X_WO.inverse(), item.bounds_W.center(),
                                             item.bounds_W.sizes() / 2});
    environment_.box_W.extend(item.bounds_W);
  }
  report_.exact_primitives = environment_.exact_primitives.size();
  const EnvironmentGeometry others = scene_.withoutPrimitives();
  if (others.size() == 0) return;
  auto v = std::make_unique<VoxelObjects>(VoxelObjects{
      others.voxelize(grid_, Rounding::kConservative, nullptr, kIgnoreWarnings), nullptr, nullptr});
  v->cells = std::make_unique<const BlackCellGrid>(v->tree);
  v->clearance = std::make_unique<const ClearanceGrid>(v->tree);
  environment_.box_W.extend(blackBox(v->tree));
  report_.exact_primitives_other_objects = others.size();
  environment_.other_objects = std::move(v);
}

// Object boxes for the environment pre-test (environment_boxes.cpp).
void CollisionModelBuilder::buildObjectBoxes() {
  detail::buildObjectBoxes(environment_, scene_, grid_, link_res_, exact_);
}

void CollisionModelBuilder::resolveEnvironmentPreTest() {
  report_.environment_pre_test =
      detail::resolveEnvironmentPreTest(environment_, options_.environment_pre_test, grid_);
  report_.environment_object_boxes = environment_.object_boxes_W.size();
}

void CollisionModelBuilder::buildSolidBoxes() {
  detail::buildSolidBoxes(environment_, scene_, grid_, options_, link_res_);
  report_.environment_solid_boxes = environment_.solid_boxes_W.size();
}

void CollisionModelBuilder::buildClearanceLevels() {
  if (options_.clearance == ClearanceMethod::kPointOctree) {
    parts_->clearance = ClearanceLevels::build(environment_.tree);
  }
}

// Keeps the links that can touch something: the environment, or another link.
void CollisionModelBuilder::keepLinksThatCanTouch() {
  links_.link_slot.assign(trees_.size(), -1);
  for (std::size_t s = 0; s < trees_.size(); ++s) {
    LinkTree& lt = trees_[s];
    if (lt.link < 0 || (lt.voxels.source.empty() && lt.forSelf().source.empty())) continue;
    const Eigen::AlignedBox3d link_box(base_region_.min().array() - link_reach_[s],
                                       base_region_.max().array() + link_reach_[s]);
    lt.touches_environment = !environment_.tree.empty() && !lt.voxels.source.empty() &&
                             !link_box.intersection(environment_.box_W).isEmpty();
    if (!lt.touches_environment && !environment_.tree.empty() && !lt.voxels.source.empty()) {
      links_.unreachable_clearance =
          std::min(links_.unreachable_clearance, link_box.exteriorDistance(environment_.box_W));
    }
    if (!lt.touches_environment && !in_pair_[s]) continue;
    links_.link_slot[s] = static_cast<int>(links_.links.size());
    report_.links[s].modelled = true;
    links_.links.push_back(std::move(lt));
  }
  trees_.clear();
  // links_.links is final: the self trees' addresses stay valid.
  for (const LinkTree& lt : links_.links) links_.self_voxels.push_back(&lt.forSelf());
}

void CollisionModelBuilder::orderEnvironmentLinks() {
  links_.orderEnvironmentTests(environment_, robot_, options_.X_WB, report_);
}

}  // namespace octomotion::detail
