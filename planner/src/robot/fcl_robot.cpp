#include "internal/fcl_robot.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <string>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "octomotion/planner/robot/collision_meshes.h"

namespace octomotion::fcl_internal {

Geom shapeOf(const Primitive& p) {
  Geom g;
  if (const auto* b = std::get_if<Box>(&p)) {
    const Eigen::Vector3d size = 2 * b->half_extents;
    g = std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z());
  } else if (const auto* s = std::get_if<Sphere>(&p)) {
    g = std::make_shared<fcl::Sphered>(s->radius);
  } else {
    const auto& c = std::get<Cylinder>(p);
    g = std::make_shared<fcl::Cylinderd>(c.radius, c.length);
  }
  g->computeLocalAABB();
  return g;
}

Geom meshOf(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices.size()));
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

void setTightAabb(fcl::CollisionObjectd& object) {
  const fcl::Transform3d& X = object.getTransform();
  const fcl::AABBd& local = object.collisionGeometry()->aabb_local;
  const Eigen::Vector3d center = X * (0.5 * (local.min_ + local.max_));
  const Eigen::Vector3d half = X.linear().cwiseAbs() * (0.5 * (local.max_ - local.min_));
  // The AABB is a cache FCL declares mutable; CollisionObject has no setter for it.
  fcl::AABBd& aabb = const_cast<fcl::AABBd&>(object.getAABB());
  aabb.min_ = center - half;
  aabb.max_ = center + half;
}

bool collidePair(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                 const fcl::CollisionRequestd& request, fcl::CollisionResultd& result) {
  if (!a.getAABB().overlap(b.getAABB())) return false;
  result.clear();
  return fcl::collide(&a, &b, request, result) > 0;
}

RobotGeometry::RobotGeometry(const RobotModel& robot, bool keep_mesh_root_transform,
                             bool center_mesh_vertices) {
  CollisionMeshes meshes(keep_mesh_root_transform, center_mesh_vertices);
  std::map<const TriangleMesh*, Geom> geoms;  // one FCL model per loaded mesh
  std::vector<std::vector<int>> link_elements(static_cast<std::size_t>(robot.linkCount()));
  for (int l = 0; l < robot.linkCount(); ++l) {
    for (const CollisionElement& e : robot.link(l).collision) {
      Geom g;
      if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
        g = shapeOf(*p);
      } else {
        const TriangleMesh& mesh = meshes.get(std::get<MeshRef>(e.geometry));
        auto it = geoms.find(&mesh);
        if (it == geoms.end()) it = geoms.emplace(&mesh, meshOf(mesh)).first;
        g = it->second;
      }
      link_elements[static_cast<std::size_t>(l)].push_back(static_cast<int>(elements_.size()));
      elements_.push_back({l, e.X_LE});
      prototypes_.emplace_back(g);
    }
  }
  for (const auto& [a, b] : robot.checkedPairs()) {
    for (int ea : link_elements[static_cast<std::size_t>(a)]) {
      for (int eb : link_elements[static_cast<std::size_t>(b)]) element_pairs_.emplace_back(ea, eb);
    }
  }
}

std::size_t RobotGeometry::addElement(int link, const Eigen::Isometry3d& X_LE, Geom geometry,
                                      const std::vector<bool>& allowed_links) {
  const std::size_t index = elements_.size();
  for (std::size_t e = 0; e < index; ++e) {
    if (!allowed_links[static_cast<std::size_t>(elements_[e].link)]) {
      element_pairs_.emplace_back(static_cast<int>(e), static_cast<int>(index));
    }
  }
  elements_.push_back({link, X_LE});
  prototypes_.emplace_back(std::move(geometry));
  return index;
}

void RobotGeometry::removeElement(std::size_t element) {
  const int gone = static_cast<int>(element);
  elements_.erase(elements_.begin() + gone);
  prototypes_.erase(prototypes_.begin() + gone);
  std::vector<std::pair<int, int>> pairs;
  for (auto [a, b] : element_pairs_) {
    if (a == gone || b == gone) continue;
    pairs.emplace_back(a > gone ? a - 1 : a, b > gone ? b - 1 : b);
  }
  element_pairs_ = std::move(pairs);
}

void RobotGeometry::initScratch(const RobotModel& robot, RobotScratch& s) const {
  s.robot = robot.makeData();
  s.objects = prototypes_;
  s.request = fcl::CollisionRequestd();
  s.request.num_max_contacts = 1;
  s.request.enable_contact = false;
  s.result.clear();
}

void RobotGeometry::pose(const RobotModel& robot, const double* q, std::size_t q_size,
                         const Eigen::Isometry3d& X_WB, RobotScratch& s) const {
  robot.forwardKinematics(q, q_size, s.robot, X_WB);
  poseElements(s.robot, s);
}

void RobotGeometry::poseElements(const RobotData& data, RobotScratch& s) const {
  for (std::size_t i = 0; i < elements_.size(); ++i) poseElement(data, i, s);
}

void RobotGeometry::poseElement(const RobotData& data, std::size_t element, RobotScratch& s) const {
  const Element& e = elements_[element];
  const Eigen::Isometry3d X_WE = data.linkPose(e.link) * e.X_LE;
  s.objects[element].setTransform(X_WE.rotation(), X_WE.translation());
  setTightAabb(s.objects[element]);
}

std::vector<std::pair<int, int>> RobotGeometry::collidingPairs(RobotScratch& s, bool all) const {
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [a, b] : element_pairs_) {
    const std::pair<int, int> links(elements_[static_cast<std::size_t>(a)].link,
                                    elements_[static_cast<std::size_t>(b)].link);
    // Element pairs of one link pair are contiguous.
    if (!pairs.empty() && pairs.back() == links) continue;
    if (collidePair(s.objects[static_cast<std::size_t>(a)], s.objects[static_cast<std::size_t>(b)],
                    s.request, s.result)) {
      pairs.push_back(links);
      if (!all) break;
    }
  }
  return pairs;
}

bool RobotGeometry::linksCollide(RobotScratch& s, int link_a, int link_b) const {
  for (std::size_t a = 0; a < elements_.size(); ++a) {
    if (elements_[a].link != link_a) continue;
    for (std::size_t b = 0; b < elements_.size(); ++b) {
      if (elements_[b].link == link_b &&
          collidePair(s.objects[a], s.objects[b], s.request, s.result)) {
        return true;
      }
    }
  }
  return false;
}

bool RobotGeometry::linkCollides(RobotScratch& s, int link,
                                 const fcl::CollisionObjectd& object) const {
  for (std::size_t a = 0; a < elements_.size(); ++a) {
    if (elements_[a].link == link && collidePair(s.objects[a], object, s.request, s.result)) {
      return true;
    }
  }
  return false;
}

bool RobotGeometry::selfInCollision(RobotScratch& s) const {
  for (const auto& [a, b] : element_pairs_) {
    if (collidePair(s.objects[static_cast<std::size_t>(a)], s.objects[static_cast<std::size_t>(b)],
                    s.request, s.result)) {
      return true;
    }
  }
  return false;
}

double RobotGeometry::selfDistance(RobotScratch& s, double cap) const {
  double best = element_pairs_.empty() ? std::numeric_limits<double>::infinity() : cap;
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  for (const auto& [a, b] : element_pairs_) {
    const fcl::CollisionObjectd& oa = s.objects[static_cast<std::size_t>(a)];
    const fcl::CollisionObjectd& ob = s.objects[static_cast<std::size_t>(b)];
    if (oa.getAABB().distance(ob.getAABB()) >= best) continue;
    result.clear();
    fcl::distance(&oa, &ob, request, result);
    best = std::min(best, std::max(0.0, result.min_distance));
    if (best <= 0) return 0;
  }
  return best;
}

double distanceBelow(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b, double best) {
  if (a.getAABB().distance(b.getAABB()) >= best) return best;
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(&a, &b, request, result);
  return std::min(best, std::max(0.0, result.min_distance));
}

double RobotGeometry::linksDistance(RobotScratch& s, int link_a, int link_b, double cap) const {
  double best = cap;
  for (std::size_t a = 0; a < elements_.size() && best > 0; ++a) {
    if (elements_[a].link != link_a) continue;
    for (std::size_t b = 0; b < elements_.size() && best > 0; ++b) {
      if (elements_[b].link == link_b) best = distanceBelow(s.objects[a], s.objects[b], best);
    }
  }
  return best;
}

}  // namespace octomotion::fcl_internal
