// OctreeCollisionModel::explainContacts: which links, objects and pairs a colliding state
// involves (internal/explain_data.h says what is kept for it and why).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "internal/collision_model_parts.h"
#include "internal/explain_data.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

namespace {

bool boxesOverlap(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  return !a.isEmpty() && !b.isEmpty() && (a.min().array() <= b.max().array()).all() &&
         (b.min().array() <= a.max().array()).all();
}

// Object i's tree on `grid`, built on first use.
std::shared_ptr<const Octree> objectTree(detail::ExplainData& data, std::size_t i,
                                         const WorldGrid& grid, Rounding rounding) {
  std::lock_guard<std::mutex> lock(data.mutex);
  if (!data.object_trees[i]) {
    data.object_trees[i] =
        std::make_shared<const Octree>(data.objects->voxelizeObject(i, grid, rounding));
  }
  return data.object_trees[i];
}

// Object i as a posed FCL object (null without an exact shape), built on first use.
std::shared_ptr<const fcl::CollisionObjectd> objectShape(detail::ExplainData& data, std::size_t i) {
  std::lock_guard<std::mutex> lock(data.mutex);
  if (!data.shape_built[i]) {
    const EnvironmentGeometry::Item& item = data.objects->items()[i];
    fcl_internal::Geom g;
    if (item.spec.kind == EnvironmentObject::Kind::kPrimitive) {
      g = fcl_internal::shapeOf(item.spec.primitive);
    } else if (item.spec.kind == EnvironmentObject::Kind::kMesh) {
      g = fcl_internal::meshOf(item.mesh);
    }
    if (g) {
      auto object = std::make_shared<fcl::CollisionObjectd>(g, item.spec.X_WO.rotation(),
                                                            item.spec.X_WO.translation());
      fcl_internal::setTightAabb(*object);
      data.object_shapes[i] = std::move(object);
    }
    data.shape_built[i] = true;
  }
  return data.object_shapes[i];
}

}  // namespace

void OctreeCollisionModel::explainContacts(CheckerPath path, CheckScratch& scratch, bool all,
                                           StateExplanation& explanation) const {
  const detail::CollisionModelParts& parts = *parts_;
  const detail::EnvironmentModel& environment = parts.environment;
  const detail::LinkModels& links = parts.links;
  detail::ExplainData& data = *explain_;
  const WorldGrid& grid = environment.tree.grid();
  const bool exact_primitives = !environment.exact_primitives.empty();

  // The exact shapes, posed at the scratch's link poses once a contact needs them.
  fcl_internal::RobotScratch exact;
  bool exact_posed = false;
  auto exactShapes = [&]() -> fcl_internal::RobotScratch& {
    if (!exact_posed) {
      {
        std::lock_guard<std::mutex> lock(data.mutex);
        if (!data.robot) {
          data.robot = std::make_unique<const fcl_internal::RobotGeometry>(
              robot_, options_.keep_mesh_root_transform, options_.center_mesh_vertices);
        }
      }
      data.robot->initScratch(robot_, exact);
      data.robot->poseElements(scratch.robot, exact);
      exact_posed = true;
    }
    return exact;
  };
  auto add = [&](InvalidityReason::Kind kind, int link, const std::string& other, bool touching,
                 bool known, double margin) {
    InvalidityReason r;
    r.kind = kind;
    r.link = robot_.link(link).name;
    r.other = other;
    r.exact = !known ? ExactContact::kUnknown
                     : (touching ? ExactContact::kTouching : ExactContact::kApart);
    r.margin = margin;
    explanation.reasons.push_back(r);
  };

  // The environment: the links whose test hits, in model order.
  std::vector<const detail::EnvironmentLinkTest*> tests;
  for (const detail::EnvironmentLinkTest& t : links.environment_tests) tests.push_back(&t);
  std::sort(tests.begin(), tests.end(),
            [](const auto* a, const auto* b) { return a->link < b->link; });
  const std::vector<EnvironmentGeometry::Item>& items = data.objects->items();
  for (const detail::EnvironmentLinkTest* t : tests) {
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(t->link);
    const detail::LinkVoxels& v = links.links[t->slot].voxels;
    if (!(detail::sphereMeetsBox(*t, X_WL, environment.box_W) &&
          environment.linkHits(*t, v, X_WL, path, scratch.fused))) {
      continue;
    }
    // The objects whose voxels (or exact primitive) the link's voxels meet, among those whose
    // box meets the box of the link's black voxels grown by what both placements add: a voxel
    // of the environment's grid on each side, and a link voxel.
    const double reach = std::sqrt(3.0) * (2 * grid.voxelSize() + v.source.grid().voxelSize());
    const Eigen::Vector3d c_W = X_WL * v.center_L;
    const Eigen::Vector3d h_W = X_WL.linear().cwiseAbs() * v.half_L;
    const Eigen::AlignedBox3d link_box(c_W - h_W, c_W + h_W);
    std::optional<Octree> moved;
    std::vector<std::size_t> met;
    std::size_t nearest = items.size();
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < items.size(); ++i) {
      const Eigen::AlignedBox3d& box = items[i].bounds_W;
      if (box.isEmpty()) continue;
      const Eigen::AlignedBox3d grown(box.min() - Eigen::Vector3d::Constant(reach),
                                      box.max() + Eigen::Vector3d::Constant(reach));
      if (!boxesOverlap(grown, link_box)) continue;
      const double distance = box.exteriorDistance(link_box);
      if (distance < nearest_distance) {
        nearest_distance = distance;
        nearest = i;
      }
      bool hit = false;
      if (exact_primitives && items[i].spec.kind == EnvironmentObject::Kind::kPrimitive) {
        hit = blackLeafMeetsPrimitive(*v.movable, items[i].spec.X_WO.inverse() * X_WL,
                                      PrimitiveShape(items[i].spec.primitive));
      } else {
        if (!moved) moved = moveTree(v.source, X_WL, grid, environment.rounding);
        hit = intersects(*moved, *objectTree(data, i, grid, environment.rounding));
      }
      if (hit) met.push_back(i);
    }
    // Ties at voxel boundaries may leave the per-object test empty: name the nearest object.
    if (met.empty() && nearest < items.size()) met.push_back(nearest);
    if (met.empty()) {
      add(InvalidityReason::Kind::kEnvironment, t->link, "", false, false, grid.voxelSize());
      if (!all) return;
      continue;
    }
    for (std::size_t i : met) {
      const auto shape = objectShape(data, i);
      const bool touching = shape && [&] {
        fcl_internal::RobotScratch& posed = exactShapes();  // builds data.robot
        return data.robot->linkCollides(posed, t->link, *shape);
      }();
      // Refine exact: the answer is FCL's, so only objects FCL finds touching are reasons.
      if (refine_ && shape && !touching) continue;
      add(InvalidityReason::Kind::kEnvironment, t->link, items[i].spec.name, touching,
          shape != nullptr, grid.voxelSize());
      if (!all) return;
    }
  }

  // The self pairs.
  for (std::size_t pair : parts.self.hitPairs(links, path, scratch, all || refine_)) {
    const detail::SelfPair& p = parts.self.pairs[pair];
    const int a = links.links[p.a].link, b = links.links[p.b].link;
    fcl_internal::RobotScratch& posed = exactShapes();  // builds data.robot
    const bool touching = data.robot->linksCollide(posed, a, b);
    if (refine_ && !touching) continue;  // refine exact: FCL's answer
    add(InvalidityReason::Kind::kSelf, a, robot_.link(b).name, touching, true,
        report_.self_link_resolution);
    if (refine_ && !all) return;
  }
}

}  // namespace octomotion
