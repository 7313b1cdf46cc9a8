// OctreeCollisionModel's world updates between plans: objects added, removed and moved (the
// environment tree rebuilt only where they were and are), objects attached to links and detached
// (only their own trees built). Everything the environment feeds follows: its grids and boxes,
// the pre-test, the clearance levels and which links are tested against it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "internal/collision_model_parts.h"
#include "internal/environment_boxes.h"
#include "internal/region_splice.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/octree/voxelize.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/pointcloud/environment.h"

namespace octomotion {

namespace {

const WarningSink kIgnoreWarnings = [](const std::string&) {};

// Updates between two exact rebuilds of the environment's ClearanceGrid (the others lower it
// near the change only).
constexpr int kClearanceGridRefreshUpdates = 16;

// One object's voxels, as EnvironmentGeometry::voxelize makes them.
Octree voxelizeItem(const EnvironmentGeometry::Item& item, const WorldGrid& grid,
                    Rounding rounding) {
  switch (item.spec.kind) {
    case EnvironmentObject::Kind::kPrimitive:
      return voxelize(grid, item.spec.primitive, item.spec.X_WO, rounding);
    case EnvironmentObject::Kind::kMesh:
      return voxelizeMesh(grid, item.mesh, item.spec.X_WO, rounding, kIgnoreWarnings);
    case EnvironmentObject::Kind::kOctomap:
      return importOctoMap(item.spec.file, grid, rounding, kIgnoreWarnings);
    case EnvironmentObject::Kind::kPointCloud:
      return pointcloud::environmentFromPoints(grid, item.points_W);
  }
  return Octree(grid);
}

// A link's (or an attached object's) trees, as the builder makes them: one element mesh per
// collision element (nullptr for a primitive), the box of its geometry in the link frame.
detail::LinkTree makeLinkTree(int robot_link, const Link& geometry,
                              const std::vector<const TriangleMesh*>& element_mesh,
                              const CollisionModelOptions& options,
                              const CollisionModelReport& report, bool in_pairs) {
  Eigen::AlignedBox3d box_L;
  for (std::size_t k = 0; k < geometry.collision.size(); ++k) {
    const CollisionElement& e = geometry.collision[k];
    if (element_mesh[k] == nullptr) {
      box_L.extend(boundingBox(std::get<Primitive>(e.geometry), e.X_LE));
    } else {
      for (const Eigen::Vector3d& v : element_mesh[k]->vertices) box_L.extend(e.X_LE * v);
    }
  }
  detail::LinkTree lt;
  lt.link = robot_link;
  lt.voxels =
      detail::voxelizeLink(geometry, element_mesh, box_L, report.link_resolution, options, false);
  if (in_pairs && report.self_link_resolution != report.link_resolution) {
    lt.self_voxels = std::make_unique<const detail::LinkVoxels>(detail::voxelizeLink(
        geometry, element_mesh, box_L, report.self_link_resolution, options, true));
  }
  detail::setClearanceSpheres(lt, options.resolution);
  return lt;
}

// The self broad phase's index after the pairs changed (CollisionModelBuilder::
// indexSelfBroadPhase over the current pairs; the strategy stays the one the build chose).
void indexSelfBroadPhase(detail::SelfCollision& self, const detail::LinkModels& links,
                         CollisionModelReport& report) {
  std::vector<int> id_of_slot(links.links.size(), -1);
  for (const detail::SelfPair& p : self.pairs) id_of_slot[p.a] = id_of_slot[p.b] = 0;
  self.self_links.clear();
  for (std::size_t slot = 0; slot < links.links.size(); ++slot) {
    if (id_of_slot[slot] < 0) continue;
    id_of_slot[slot] = static_cast<int>(self.self_links.size());
    self.self_links.push_back(static_cast<int>(slot));
  }
  const std::size_t m = self.self_links.size();
  self.pair_of.assign(m * m, -1);
  for (std::size_t i = 0; i < self.pairs.size(); ++i) {
    auto a = static_cast<std::size_t>(id_of_slot[self.pairs[i].a]);
    auto b = static_cast<std::size_t>(id_of_slot[self.pairs[i].b]);
    if (a > b) std::swap(a, b);
    self.pair_of[a * m + b] = static_cast<std::int32_t>(i);
  }
  double max_radius = 0;
  for (const int slot : self.self_links) {
    max_radius = std::max(max_radius, links.self_voxels[static_cast<std::size_t>(slot)]->radius);
  }
  self.root_box_W = Eigen::AlignedBox3d(report.reach_W.min().array() - max_radius,
                                        report.reach_W.max().array() + max_radius);
  report.self_pairs = self.pairs.size();
  report.self_links = m;
}

// How far a link's origin can be from the base origin (CollisionModelBuilder::boundReach's
// chain: joint offsets and prismatic travel).
double originReach(const RobotModel& robot, int link) {
  std::vector<double> reach(static_cast<std::size_t>(robot.linkCount()), 0.0);
  for (const Joint& j : robot.joints()) {
    double travel = 0;
    if (j.type == JointType::kPrismatic) {
      if (j.isMimic()) {
        const Joint& m = robot.joint(j.mimic_master);
        travel = std::abs(j.mimic_multiplier) * std::max(std::abs(m.lower), std::abs(m.upper)) +
                 std::abs(j.mimic_offset);
      } else {
        travel = std::max(std::abs(j.lower), std::abs(j.upper));
      }
    }
    reach[static_cast<std::size_t>(j.child_link)] =
        reach[static_cast<std::size_t>(j.parent_link)] + j.X_PJ.translation().norm() + travel;
  }
  return reach[static_cast<std::size_t>(link)];
}

void refreshSelfVoxels(detail::LinkModels& links) {
  links.self_voxels.clear();
  for (const detail::LinkTree& lt : links.links) links.self_voxels.push_back(&lt.forSelf());
}

// Gives every robot link with geometry a slot (once): an update may bring the environment into
// the reach of a link the build left out.
void modelEveryLink(const RobotModel& robot, const CollisionModelOptions& options,
                    CollisionModelReport& report, detail::CollisionModelParts& parts) {
  if (parts.world.all_links_modelled) return;
  CollisionMeshes meshes(options.keep_mesh_root_transform, options.center_mesh_vertices);
  detail::LinkModels& links = parts.links;
  for (int l = 0; l < robot.linkCount(); ++l) {
    const Link& link = robot.link(l);
    if (!link.hasCollision() || links.link_slot[static_cast<std::size_t>(l)] >= 0) continue;
    std::vector<const TriangleMesh*> element_mesh;
    for (const CollisionElement& e : link.collision) {
      const auto* mesh = std::get_if<MeshRef>(&e.geometry);
      element_mesh.push_back(mesh ? &meshes.get(*mesh) : nullptr);
    }
    detail::LinkTree lt = makeLinkTree(l, link, element_mesh, options, report, false);
    if (lt.voxels.source.empty()) continue;
    lt.touches_environment = false;  // set by the update
    links.link_slot[static_cast<std::size_t>(l)] = static_cast<int>(links.links.size());
    links.links.push_back(std::move(lt));
    report.links[static_cast<std::size_t>(l)].modelled = true;
  }
  refreshSelfVoxels(links);
  parts.world.all_links_modelled = true;
}

// The links tested against the environment: every modelled link with voxels while the
// environment has any (those a first build found out of reach stay correct: they never meet
// its box). Tests already in the list keep their order; new ones follow.
void updateEnvironmentTests(detail::CollisionModelParts& parts) {
  detail::LinkModels& links = parts.links;
  const detail::EnvironmentModel& environment = parts.environment;
  const bool any = !environment.tree.empty();
  for (detail::LinkTree& lt : links.links) {
    lt.touches_environment = any && !lt.voxels.source.empty();
  }
  links.unreachable_clearance = std::numeric_limits<double>::infinity();  // every link is queried
  std::vector<detail::EnvironmentLinkTest> tests;
  std::vector<bool> listed(links.links.size(), false);
  for (const detail::EnvironmentLinkTest& t : links.environment_tests) {
    if (!links.links[t.slot].touches_environment) continue;
    tests.push_back(t);
    listed[t.slot] = true;
  }
  const double voxel = environment.tree.grid().voxelSize();
  for (std::size_t slot = 0; slot < links.links.size(); ++slot) {
    if (links.links[slot].touches_environment && !listed[slot]) {
      tests.push_back(links.environmentTest(slot, voxel, false));
    }
  }
  links.environment_tests = std::move(tests);
}

}  // namespace

const EnvironmentGeometry& OctreeCollisionModel::objects() const {
  return parts_->world.objects;
}

std::vector<std::string> OctreeCollisionModel::attachedObjects() const {
  std::vector<std::string> names;
  for (const detail::AttachedEntry& a : parts_->world.attached) names.push_back(a.spec.object.name);
  return names;
}

void OctreeCollisionModel::requireUpdatable() const {
  if (options_.refine == RefineMode::kExact) {
    throw InvalidArgument(
        "world updates: not available for a model built with refine exact "
        "(CollisionModelOptions::refine; the default, auto, is exact unless "
        "fit_universe_to_reach is set); build it with refine none or fit_universe_to_reach, or "
        "build a new model instead");
  }
  if (options_.exact_primitives) {
    throw InvalidArgument(
        "world updates: not available for a model built with exact primitives "
        "(CollisionModelOptions::exact_primitives); build a new model instead");
  }
}

void OctreeCollisionModel::requireInUniverse(const EnvironmentGeometry::Item& item) const {
  Eigen::AlignedBox3d reach_W = report_.reach_W;
  if (!parts_->world.attached_reach_W.isEmpty()) reach_W.extend(parts_->world.attached_reach_W);
  const Eigen::AlignedBox3d reachable = item.bounds_W.intersection(reach_W);
  if (reachable.isEmpty()) return;  // the robot never reaches it: nothing to model
  const WorldGrid& grid = parts_->environment.tree.grid();
  const Eigen::AlignedBox3d universe(grid.origin(), grid.origin().array() + grid.sideMetres());
  // The builder's memory guard (CollisionModelOptions::max_surface_voxels), per object.
  const Eigen::Vector3d cells =
      item.bounds_W.intersection(universe).sizes() / grid.voxelSize() + Eigen::Vector3d::Ones();
  const double surface =
      2 * (cells.x() * cells.y() + cells.y() * cells.z() + cells.z() * cells.x());
  if (item.spec.kind != EnvironmentObject::Kind::kPointCloud &&
      !item.bounds_W.intersection(universe).isEmpty() && surface > options_.max_surface_voxels) {
    throw InvalidArgument(item.spec.name + ": would need about " +
                          std::to_string(std::llround(surface)) + " surface voxels (limit " +
                          std::to_string(std::llround(options_.max_surface_voxels)) + ")");
  }
  if (!universe.contains(reachable)) {
    throw InvalidArgument(item.spec.name +
                          ": the part of it the robot can reach lies outside the model's universe "
                          "(fitted to the environment it was built with); build the model with "
                          "CollisionModelOptions::fit_universe_to_reach for a changing world");
  }
}

void OctreeCollisionModel::updateEnvironment(const std::vector<Eigen::AlignedBox3d>& changed_W) {
  detail::CollisionModelParts& parts = *parts_;
  detail::EnvironmentModel& environment = parts.environment;
  const EnvironmentGeometry& objects = parts.world.objects;
  const WorldGrid grid = environment.tree.grid();
  std::optional<VoxelBounds> region;
  for (const Eigen::AlignedBox3d& box : changed_W) {
    if (const auto r = detail::touchedVoxels(grid, box)) {
      region = region ? detail::merge(*region, *r) : *r;
    }
  }
  if (region) {
    // Every object whose voxels can lie in the region, voxelized whole (primitives cost their
    // surface); only its part inside the region is kept.
    Octree inside(grid);
    for (const EnvironmentGeometry::Item& item : objects.items()) {
      const auto r = detail::touchedVoxels(grid, item.bounds_W);
      if (r && detail::overlap(*r, *region)) {
        inside = unite(inside, voxelizeItem(item, grid, options_.rounding));
      }
    }
    environment.tree = detail::spliceRegion(environment.tree, inside, *region);
  }
  // What the tree and the objects feed, as the builder makes it.
  environment.cells = std::make_unique<const BlackCellGrid>(environment.tree);
  // The clearance grid only needs lowering where voxels may have been added (a distance
  // transform costs more than the rest of an update); a full one every
  // kClearanceGridRefreshUpdates updates keeps it from loosening for good.
  if (region && ++parts.world.clearance_grid_lowerings < kClearanceGridRefreshUpdates) {
    auto lowered = std::make_unique<ClearanceGrid>(*environment.clearance);
    lowered->addBlack(*region);
    environment.clearance = std::move(lowered);
  } else if (region) {
    environment.clearance = std::make_unique<const ClearanceGrid>(environment.tree);
    parts.world.clearance_grid_lowerings = 0;
  }
  environment.box_W = detail::blackBox(environment.tree);
  environment.object_boxes_W.clear();
  environment.object_frame_boxes.clear();
  for (std::size_t a = 0; a < 3; ++a) {
    environment.object_centre_W[a].clear();
    environment.object_reach_W[a].clear();
  }
  environment.solid_boxes_W.clear();
  detail::buildObjectBoxes(environment, objects, grid, report_.link_resolution, false);
  report_.environment_pre_test =
      detail::resolveEnvironmentPreTest(environment, options_.environment_pre_test, grid);
  report_.environment_object_boxes = environment.object_boxes_W.size();
  detail::buildSolidBoxes(environment, objects, grid, options_, report_.link_resolution);
  report_.environment_solid_boxes = environment.solid_boxes_W.size();
  if (options_.clearance == ClearanceMethod::kPointOctree) {
    // Built by the first clearance query after the update (OctreeCollisionModel::
    // clearanceLowerBoundPoints): planning without clearance never pays for it.
    parts.clearance = detail::ClearanceLevels();
    parts.world.clearance_levels_once = std::make_unique<std::once_flag>();
  }
  modelEveryLink(robot_, options_, report_, parts);
  updateEnvironmentTests(parts);
  indexSelfBroadPhase(parts.self, parts.links, report_);
  // The report's environment: the objects by name (their figures are the first build's).
  EnvironmentReport& er = report_.environment;
  er.objects.erase(std::remove_if(er.objects.begin(), er.objects.end(),
                                  [&](const EnvironmentObjectReport& o) {
                                    return objects.find(o.name) == nullptr;
                                  }),
                   er.objects.end());
  for (const EnvironmentGeometry::Item& item : objects.items()) {
    if (std::none_of(er.objects.begin(), er.objects.end(),
                     [&](const EnvironmentObjectReport& o) { return o.name == item.spec.name; })) {
      er.objects.push_back({item.spec.name, 0, 0, 0});
    }
  }
  er.internal_nodes = environment.tree.internalNodeCount();
  er.bytes = environment.tree.bytes();
  report_.environment_cell_grid_bytes = environment.cells->bytes();
  report_.environment_clearance_grid_bytes = environment.clearance->bytes();
  id_ = nextModelId();
  resetExplainData();
}

void OctreeCollisionModel::addObject(const EnvironmentObject& object, const WarningSink& warnings) {
  addObject(EnvironmentGeometry::loadItem(object, warnings));
}

void OctreeCollisionModel::addObject(EnvironmentGeometry::Item item) {
  requireUpdatable();
  for (const detail::AttachedEntry& a : parts_->world.attached) {
    if (a.spec.object.name == item.spec.name) {
      throw InvalidArgument("environment: '" + item.spec.name + "' names an attached object");
    }
  }
  requireInUniverse(item);
  const Eigen::AlignedBox3d box = item.bounds_W;
  parts_->world.objects.add(std::move(item));
  updateEnvironment({box});
}

void OctreeCollisionModel::removeObject(const std::string& name) {
  requireUpdatable();
  const Eigen::AlignedBox3d box = parts_->world.objects.remove(name).bounds_W;
  updateEnvironment({box});
}

void OctreeCollisionModel::moveObject(const std::string& name, const Eigen::Isometry3d& X_WO) {
  requireUpdatable();
  EnvironmentGeometry& objects = parts_->world.objects;
  const EnvironmentGeometry::Item* item = objects.find(name);
  if (item == nullptr) throw InvalidArgument("environment: no object named '" + name + "'");
  const Eigen::AlignedBox3d old_box = item->bounds_W;
  const Eigen::Isometry3d old_pose = item->spec.X_WO;
  objects.setPose(name, X_WO);
  try {
    requireInUniverse(*objects.find(name));
  } catch (...) {
    objects.setPose(name, old_pose);
    throw;
  }
  updateEnvironment({old_box, objects.find(name)->bounds_W});
}

void OctreeCollisionModel::attachObject(const AttachedObject& object, const WarningSink& warnings) {
  requireUpdatable();
  detail::WorldState& world = parts_->world;
  const std::string& name = object.object.name;
  if (world.objects.find(name) != nullptr) {
    throw InvalidArgument("attach: '" + name + "' names an object of the world");
  }
  for (const detail::AttachedEntry& a : world.attached) {
    if (a.spec.object.name == name) {
      throw InvalidArgument("attach: an object named '" + name + "' is attached already");
    }
  }
  std::vector<bool> allowed;
  const int link = attachmentLinks(robot_, object, allowed);
  detail::AttachedEntry entry{object, EnvironmentGeometry::loadItem(object.object, warnings), link,
                              0, Eigen::AlignedBox3d()};
  // Its geometry as a link's: one element at X_LO.
  Link geometry;
  geometry.name = name;
  CollisionElement element;
  element.X_LE = object.object.X_WO;
  element.name = name;
  const TriangleMesh* mesh = nullptr;
  if (object.object.kind == EnvironmentObject::Kind::kPrimitive) {
    element.geometry = object.object.primitive;
  } else {
    element.geometry = MeshRef{object.object.file, object.object.scale};
    mesh = &entry.item.mesh;
  }
  geometry.collision.push_back(element);
  detail::LinkTree lt = makeLinkTree(link, geometry, {mesh}, options_, report_, true);
  if (lt.voxels.source.empty()) {
    throw InvalidArgument("attach: '" + name + "' has no voxels at the link resolution");
  }
  // Where the carried object can go: it may reach objects beyond the robot's own reach, whose
  // parts there must then lie in the universe (the rest of them was never modelled).
  double extent = 0;
  const Eigen::AlignedBox3d box_L(lt.voxels.center_L - lt.voxels.half_L,
                                  lt.voxels.center_L + lt.voxels.half_L);
  for (int c = 0; c < 8; ++c) {
    extent = std::max(extent, box_L.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).norm());
  }
  const double carried = originReach(robot_, link) + extent;
  Eigen::AlignedBox3d base =
      options_.base_position_bounds && robot_.isFreeFlying()
          ? *options_.base_position_bounds
          : Eigen::AlignedBox3d(options_.X_WB.translation(), options_.X_WB.translation());
  const Eigen::AlignedBox3d carried_W(base.min().array() - carried, base.max().array() + carried);
  {
    const WorldGrid& grid = parts_->environment.tree.grid();
    const Eigen::AlignedBox3d universe(grid.origin(), grid.origin().array() + grid.sideMetres());
    for (const EnvironmentGeometry::Item& item : world.objects.items()) {
      if (!universe.contains(item.bounds_W.intersection(carried_W)) &&
          !item.bounds_W.intersection(carried_W).isEmpty()) {
        throw InvalidArgument("attach: '" + name + "' carried by " + object.link +
                              " can reach the part of '" + item.spec.name +
                              "' outside the model's universe; build the model with "
                              "CollisionModelOptions::fit_universe_to_reach or attach a smaller "
                              "object");
      }
    }
  }
  modelEveryLink(robot_, options_, report_, *parts_);
  world.attached_reach_W.extend(carried_W);
  detail::LinkModels& links = parts_->links;
  const std::size_t slot = links.links.size();
  links.links.push_back(std::move(lt));
  refreshSelfVoxels(links);
  // Pairs with every other entry but the carrying link, its touch links and the objects on the
  // same link.
  detail::SelfCollision& self = parts_->self;
  for (std::size_t s = 0; s < slot; ++s) {
    if (allowed[static_cast<std::size_t>(links.links[s].link)]) continue;
    const double reach =
        detail::SelfCollision::spheresReach(*links.self_voxels[s], *links.self_voxels[slot]);
    self.pairs.push_back({s, slot, reach * reach, nullptr});
  }
  entry.slot = slot;
  entry.carried_W = carried_W;
  world.attached.push_back(std::move(entry));
  updateEnvironment({});
}

void OctreeCollisionModel::detachObject(const std::string& name,
                                        const std::optional<Eigen::Isometry3d>& leave_at_W) {
  requireUpdatable();
  detail::WorldState& world = parts_->world;
  const auto it =
      std::find_if(world.attached.begin(), world.attached.end(),
                   [&](const detail::AttachedEntry& a) { return a.spec.object.name == name; });
  if (it == world.attached.end())
    throw InvalidArgument("detach: no attached object '" + name + "'");
  std::optional<EnvironmentGeometry::Item> left;
  if (leave_at_W) {
    left = it->item;
    EnvironmentGeometry one;
    one.add(std::move(*left));
    one.setPose(name, *leave_at_W);
    left = one.remove(name);
    requireInUniverse(*left);
  }
  const std::size_t slot = it->slot;
  world.attached.erase(it);
  // Drop its slot; the later slots move down by one.
  detail::LinkModels& links = parts_->links;
  auto shifted = [slot](std::size_t s) { return s > slot ? s - 1 : s; };
  links.links.erase(links.links.begin() + static_cast<std::ptrdiff_t>(slot));
  refreshSelfVoxels(links);
  for (int& s : links.link_slot) {
    if (s > static_cast<int>(slot)) --s;
  }
  std::vector<detail::EnvironmentLinkTest> tests;
  for (detail::EnvironmentLinkTest t : links.environment_tests) {
    if (t.slot == slot) continue;
    t.slot = shifted(t.slot);
    tests.push_back(t);
  }
  links.environment_tests = std::move(tests);
  std::vector<detail::SelfPair> pairs;
  for (detail::SelfPair p : parts_->self.pairs) {
    if (p.a == slot || p.b == slot) continue;
    p.a = shifted(p.a);
    p.b = shifted(p.b);
    pairs.push_back(p);
  }
  parts_->self.pairs = std::move(pairs);
  world.attached_reach_W.setEmpty();
  for (detail::AttachedEntry& a : world.attached) {
    a.slot = shifted(a.slot);
    world.attached_reach_W.extend(a.carried_W);
  }
  if (left) {
    const Eigen::AlignedBox3d box = left->bounds_W;
    world.objects.add(std::move(*left));
    updateEnvironment({box});
  } else {
    updateEnvironment({});
  }
}

Eigen::Isometry3d OctreeCollisionModel::attachedObjectPose(const std::string& name, const double* q,
                                                           std::size_t q_size,
                                                           const Eigen::Isometry3d& X_WB) const {
  for (const detail::AttachedEntry& a : parts_->world.attached) {
    if (a.spec.object.name != name) continue;
    RobotData data = robot_.makeData();
    robot_.forwardKinematics(q, q_size, data, robot_.isFreeFlying() ? X_WB : options_.X_WB);
    return data.linkPose(a.link) * a.spec.object.X_WO;
  }
  throw InvalidArgument("no attached object '" + name + "'");
}

}  // namespace octomotion
