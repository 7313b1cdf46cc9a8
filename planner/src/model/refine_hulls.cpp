// RefineMode::kExact's hull filter (internal/refine.h): each link's elements as one convex
// point set, and the certified test that clears a self pair whose hulls are apart. FCL's
// triangle tests only report contacts between triangles, which lie inside their mesh's hull,
// so apart hulls prove what FCL would answer without running it.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <variant>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/math/bv/OBBRSS.h>

#include "internal/refine.h"
#include "octomotion/motion/box_overlap.h"

namespace octomotion::detail {

namespace {

// A link's points in L, each once (meshes repeat a vertex per triangle), and the triangles over
// them of its meshes.
struct HullPoints {
  std::vector<Eigen::Vector3d> points_L;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::map<std::array<double, 3>, std::uint32_t> index;

  std::uint32_t add(const Eigen::Vector3d& p_L) {
    const auto [it, added] = index.emplace(std::array<double, 3>{p_L.x(), p_L.y(), p_L.z()},
                                           static_cast<std::uint32_t>(points_L.size()));
    if (added) points_L.push_back(p_L);
    return it->second;
  }
};

// Adds the points whose hull holds the element (every triangle FCL tests, or the solid box);
// false for any other shape.
bool addElement(const fcl::CollisionGeometryd& geometry, const Eigen::Isometry3d& X_LE,
                HullPoints& hull) {
  if (geometry.getObjectType() == fcl::OT_BVH) {
    const auto* mesh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(&geometry);
    if (mesh == nullptr || mesh->vertices == nullptr || mesh->tri_indices == nullptr) return false;
    for (int t = 0; t < mesh->num_tris; ++t) {
      std::array<std::uint32_t, 3> triangle{};
      for (int k = 0; k < 3; ++k) {
        triangle[static_cast<std::size_t>(k)] =
            hull.add(X_LE * mesh->vertices[mesh->tri_indices[t][k]]);
      }
      hull.triangles.push_back(triangle);
    }
    return true;
  }
  if (geometry.getNodeType() == fcl::GEOM_BOX) {
    const Eigen::Vector3d half = static_cast<const fcl::Boxd&>(geometry).side / 2;
    for (const Eigen::Vector3d& corner : boxCorners(half)) hull.add(X_LE * corner);
    return true;
  }
  return false;
}

}  // namespace

std::vector<ConvexPoints> linkHulls(const fcl_internal::RobotGeometry& robot,
                                    const RobotModel& model,
                                    const std::vector<std::vector<std::size_t>>& link_elements) {
  fcl_internal::RobotScratch prototypes;
  robot.initScratch(model, prototypes);
  std::vector<ConvexPoints> hulls(link_elements.size());
  for (std::size_t l = 0; l < link_elements.size(); ++l) {
    const std::vector<CollisionElement>& collision = model.link(static_cast<int>(l)).collision;
    // RobotGeometry makes one element per collision element, in order.
    if (link_elements[l].empty() || link_elements[l].size() != collision.size()) continue;
    HullPoints hull;
    bool all = true;
    for (std::size_t k = 0; k < collision.size() && all; ++k) {
      const fcl::CollisionObjectd& element = prototypes.objects[link_elements[l][k]];
      all = addElement(*element.collisionGeometry(), collision[k].X_LE, hull);
    }
    if (!all || hull.points_L.empty()) continue;
    // The hull's own edges make the support search a climb (ConvexPoints::hullOf); without a
    // hull, a mesh's edges still guide it when they connect every point (one mesh).
    ConvexPoints exact = ConvexPoints::hullOf(hull.points_L);
    if (exact.hasEdges()) {  // a hull (without one, hullOf keeps the points alone)
      hulls[l] = std::move(exact);
    } else if (collision.size() == 1 && !hull.triangles.empty()) {
      hulls[l] = ConvexPoints(hull.points_L, hull.triangles);
    } else {
      hulls[l] = ConvexPoints(hull.points_L);
    }
  }
  return hulls;
}

ConvexPoints objectHull(const EnvironmentObject& spec, const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> points_W;
  double radius = 0;
  if (spec.kind == EnvironmentObject::Kind::kPrimitive) {
    if (const auto* box = std::get_if<Box>(&spec.primitive)) {
      for (const Eigen::Vector3d& corner : boxCorners(box->half_extents)) {
        points_W.push_back(spec.X_WO * corner);
      }
    } else if (const auto* ball = std::get_if<Sphere>(&spec.primitive)) {
      points_W.push_back(spec.X_WO.translation());
      radius = ball->radius;
    } else {
      const auto& c = std::get<Cylinder>(spec.primitive);
      points_W.push_back(spec.X_WO * Eigen::Vector3d(0, 0, c.length / 2));
      points_W.push_back(spec.X_WO * Eigen::Vector3d(0, 0, -c.length / 2));
      radius = c.radius;
    }
  } else if (spec.kind == EnvironmentObject::Kind::kMesh) {
    for (const Eigen::Vector3d& v : mesh.vertices) points_W.push_back(spec.X_WO * v);
  }
  if (points_W.empty() || !(radius >= 0) || !std::isfinite(radius)) return {};
  // A mesh's vertices: the hull's boundary makes the support search a climb.
  if (spec.kind == EnvironmentObject::Kind::kMesh) return ConvexPoints::hullOf(points_W, radius);
  return ConvexPoints(points_W, radius);
}

bool linkApartFromObjects(const RefineData& data, RefineScratch& r, const RobotData& robot,
                          int link) {
  const ConvexPoints& hull_L = data.link_hulls_L[static_cast<std::size_t>(link)];
  if (hull_L.empty()) return false;
  const Eigen::Isometry3d& X_WL = robot.linkPose(link);
  // The link's hull lies in this ball; an object's shapes lie in its box.
  const Eigen::Vector3d centre_W = X_WL * hull_L.centroid();
  const double reach = hull_L.reach() + hull_L.radius() + kHullGap;
  const std::size_t objects = data.objects.size();
  for (std::size_t i = 0; i < objects; ++i) {
    const RefineObject& object = data.objects[i];
    if (object.shapes.empty() || distanceToBox(object.box_W, centre_W) > reach) continue;
    // A primitive's hull in its own frame (a box's support in closed form), else in W.
    const bool own_frame = !object.hull_O.empty();
    const ConvexPoints& hull = own_frame ? object.hull_O : object.hull_W;
    if (hull.empty()) return false;
    Eigen::Vector3d& direction = r.link_object_apart[static_cast<std::size_t>(link) * objects + i];
    if (!convexApart(hull, hull_L, own_frame ? object.X_OW * X_WL : X_WL, kHullGap, &direction)) {
      return false;
    }
  }
  return true;
}

bool linkApartFromObject(const RefineData& data, const RobotData& robot, int link,
                         const RefineObject& object) {
  const ConvexPoints& hull_L = data.link_hulls_L[static_cast<std::size_t>(link)];
  if (hull_L.empty() || object.hull_W.empty()) return false;
  return convexApart(hull_L, object.hull_W, robot.linkPose(link).inverse(), kHullGap);
}

bool refineHullsApart(const RefineData& data, const RobotData& robot, int link_a, int link_b,
                      Eigen::Vector3d& direction) {
  const ConvexPoints& a = data.link_hulls_L[static_cast<std::size_t>(link_a)];
  const ConvexPoints& b = data.link_hulls_L[static_cast<std::size_t>(link_b)];
  if (a.empty() || b.empty()) return false;
  const Eigen::Isometry3d X_AB = robot.linkPose(link_a).inverse() * robot.linkPose(link_b);
  // The boxes hold the hulls' points (grown by their radii, zero for these hulls): boxes
  // more than kHullGap apart leave the hulls so.
  const auto& [ca_L, ha_L] = data.link_hull_boxes_L[static_cast<std::size_t>(link_a)];
  const auto& [cb_L, hb_L] = data.link_hull_boxes_L[static_cast<std::size_t>(link_b)];
  if (!boxesOverlap(ca_L, ha_L, X_AB.linear(), X_AB * cb_L, hb_L,
                    kHullGap + a.radius() + b.radius())) {
    return true;
  }
  return convexApart(a, b, X_AB, kHullGap, &direction);
}

}  // namespace octomotion::detail
