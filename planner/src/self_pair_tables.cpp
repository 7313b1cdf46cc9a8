#include "self_pair_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_robot.h"

namespace octomotion::detail {

namespace {

// Links from `link` up to the root, `link` first.
std::vector<int> ancestors(const RobotModel& robot, int link) {
  std::vector<int> chain;
  for (int l = link; l >= 0; l = robot.link(l).parent_link) chain.push_back(l);
  return chain;
}

// The joints whose values change the relative pose of a and b: those on the path between them
// (below their common ancestor), fixed ones included; a's branch first, each branch from the
// link upwards.
struct PathJoints {
  std::vector<int> a_branch, b_branch;
};
PathJoints pathJoints(const RobotModel& robot, int link_a, int link_b) {
  const std::vector<int> up_a = ancestors(robot, link_a);
  const std::vector<int> up_b = ancestors(robot, link_b);
  const std::set<int> in_a(up_a.begin(), up_a.end());
  const std::set<int> in_b(up_b.begin(), up_b.end());
  PathJoints path;
  for (int l : up_a) {
    if (in_b.count(l)) break;
    path.a_branch.push_back(robot.link(l).parent_joint);
  }
  for (int l : up_b) {
    if (in_a.count(l)) break;
    path.b_branch.push_back(robot.link(l).parent_joint);
  }
  return path;
}

int variableOf(const RobotModel& robot, const Joint& j) {
  if (!j.movable()) return -1;
  return j.isMimic() ? robot.joint(j.mimic_master).variable : j.variable;
}

double prismaticTravel(const RobotModel& robot, const Joint& j) {
  if (j.type != JointType::kPrismatic) return 0;
  if (j.isMimic()) {
    const Joint& m = robot.joint(j.mimic_master);
    return std::abs(j.mimic_multiplier) * std::max(std::abs(m.lower), std::abs(m.upper)) +
           std::abs(j.mimic_offset);
  }
  return std::max(std::abs(j.lower), std::abs(j.upper));
}

// Unsigned distance from p (element frame) to a primitive's surface.
double primitiveSurfaceDistance(const Primitive& shape, const Eigen::Vector3d& p) {
  if (const auto* b = std::get_if<Box>(&shape)) {
    const Eigen::Vector3d q = p.cwiseAbs() - b->half_extents;
    if ((q.array() <= 0).all()) return -q.maxCoeff();
    return q.cwiseMax(0.0).norm();
  }
  if (const auto* s = std::get_if<Sphere>(&shape)) return std::abs(p.norm() - s->radius);
  const auto& c = std::get<Cylinder>(shape);
  const double dr = std::hypot(p.x(), p.y()) - c.radius;
  const double dz = std::abs(p.z()) - c.length / 2;
  if (dr <= 0 && dz <= 0) return std::min(-dr, -dz);
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
}

// A link's exact geometry as FCL objects in its own frame, with points of its solid.
class LinkShapes {
 public:
  LinkShapes(const RobotModel& robot, const SelfPairLink& in) : in_(in) {
    const Link& link = robot.link(in.link);
    for (std::size_t k = 0; k < link.collision.size(); ++k) {
      const CollisionElement& e = link.collision[k];
      const TriangleMesh* mesh = in.element_mesh[k];
      fcl_internal::Geom g = mesh ? fcl_internal::meshOf(*mesh)
                                  : fcl_internal::shapeOf(std::get<Primitive>(e.geometry));
      elements_.push_back({e.X_LE, mesh ? nullptr : &std::get<Primitive>(e.geometry), g,
                           fcl::CollisionObjectd(g, e.X_LE.rotation(), e.X_LE.translation())});
      // Points of the solid: a spread of mesh vertices, or the primitive's centre and corners.
      if (mesh) {
        const std::size_t n = mesh->vertices.size();
        const std::size_t stride = std::max<std::size_t>(1, n / kPointsPerElement);
        for (std::size_t i = 0; i < n; i += stride) points_L_.push_back(e.X_LE * mesh->vertices[i]);
      } else {
        points_L_.push_back(e.X_LE.translation());
        const Primitive& shape = std::get<Primitive>(e.geometry);
        if (const auto* b = std::get_if<Box>(&shape)) {
          // Corners, edge midpoints and face centres: the 26 non-centre points of a 3x3x3 grid.
          for (int c = 0; c < 27; ++c) {
            const Eigen::Vector3d s(c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1);
            if (c != 13) points_L_.push_back(e.X_LE * s.cwiseProduct(b->half_extents));
          }
        } else if (const auto* sp = std::get_if<Sphere>(&shape)) {
          for (int axis = 0; axis < 3; ++axis) {
            for (const double sign : {-1.0, 1.0}) {
              points_L_.push_back(e.X_LE * (sign * sp->radius * Eigen::Vector3d::Unit(axis)));
            }
          }
        } else {
          // Cap centres and 12 points around each cap's rim and around the middle.
          const auto& cy = std::get<Cylinder>(shape);
          for (const double z : {-cy.length / 2, 0.0, cy.length / 2}) {
            if (z != 0.0) points_L_.push_back(e.X_LE * Eigen::Vector3d(0, 0, z));
            for (int step = 0; step < 12; ++step) {
              const double t = 2 * M_PI * step / 12;
              points_L_.push_back(
                  e.X_LE * Eigen::Vector3d(cy.radius * std::cos(t), cy.radius * std::sin(t), z));
            }
          }
        }
      }
    }
  }
  struct Element {
    Eigen::Isometry3d X_LE;
    const Primitive* primitive;  // nullptr: a mesh
    fcl_internal::Geom geometry;
    fcl::CollisionObjectd posed;  // in the link frame, made once (FCL computes its AABBs then)
  };
  const std::vector<Element>& elements() const { return elements_; }
  const std::vector<Eigen::Vector3d>& points_L() const { return points_L_; }
  const Octree& oracle() const { return *in_.oracle; }
  double oracleDiagonal() const { return std::sqrt(3.0) * in_.oracle->grid().voxelSize(); }

  // Lower bound on the distance from p (link frame) to the boundary of the link's solid: the
  // boundary of a union lies on its elements' surfaces.
  double surfaceDistance(const Eigen::Vector3d& p_L) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Element& e : elements_) {
      if (e.primitive) {
        best = std::min(best, primitiveSurfaceDistance(*e.primitive, e.X_LE.inverse() * p_L));
        continue;
      }
      fcl::CollisionObjectd point(probe_, Eigen::Matrix3d::Identity(), p_L);
      fcl::DistanceRequestd request;
      fcl::DistanceResultd result;
      fcl::distance(&point, &e.posed, request, result);
      best = std::min(best, std::max(0.0, result.min_distance));
    }
    return best;
  }

 private:
  static constexpr std::size_t kPointsPerElement = 48;
  const SelfPairLink& in_;
  std::vector<Element> elements_;
  std::vector<Eigen::Vector3d> points_L_;
  std::shared_ptr<fcl::Sphered> probe_ = std::make_shared<fcl::Sphered>(1e-9);
};

// FCL's distances are exact up to rounding; certificates keep this much in hand.
constexpr double kCertificateSlack = 1e-6;
// Point-depth queries tried per colliding cell before it is left to be split.
constexpr int kDeepPointTries = 32;

}  // namespace

std::vector<int> pairVariables(const RobotModel& robot, int link_a, int link_b) {
  std::set<int> vars;
  const PathJoints path = pathJoints(robot, link_a, link_b);
  for (const std::vector<int>* branch : {&path.a_branch, &path.b_branch}) {
    for (int j : *branch) {
      const int v = variableOf(robot, robot.joint(j));
      if (v >= 0) vars.insert(v);
    }
  }
  return {vars.begin(), vars.end()};
}

std::vector<double> middleConfiguration(const RobotModel& robot) {
  std::vector<double> q;
  for (const Variable& var : robot.variables()) {
    q.push_back(var.continuous ? 0.0 : (var.lower + var.upper) / 2);
  }
  return q;
}

std::optional<JointSpaceTable> buildSelfPairTable(const RobotModel& robot, const SelfPairLink& a,
                                                  const SelfPairLink& b,
                                                  const SelfPairTableOptions& options) {
  const std::vector<int> vars = pairVariables(robot, a.link, b.link);
  if (vars.empty() || vars.size() > static_cast<std::size_t>(JointSpaceTable::kMaxDims)) {
    return std::nullopt;
  }
  // Motion bound, in the frame of the links' common ancestor C. Changing a joint on a's branch
  // by h moves a's points along arcs about its axis (segments, prismatic) of length at most h
  // times their distance from the joint's origin, which the offsets and travel of the joints
  // below it on that branch plus a's reach bound, whatever the other joints are (likewise for
  // b's branch and b). Cells change their joints one after the other, and the distance between
  // a and b changes by at most the sum of both links' motions: the bounds add.
  const PathJoints path = pathJoints(robot, a.link, b.link);
  std::vector<double> weight(vars.size(), 0.0);
  auto addBranch = [&](const std::vector<int>& branch, double reach) {
    double arm = reach;  // from the origin of the child link of branch[i] to the link's points
    for (int j : branch) {
      const Joint& joint = robot.joint(j);
      const int v = variableOf(robot, joint);
      if (v >= 0) {
        const auto d =
            static_cast<std::size_t>(std::lower_bound(vars.begin(), vars.end(), v) - vars.begin());
        const double multiplier = joint.isMimic() ? std::abs(joint.mimic_multiplier) : 1.0;
        weight[d] += multiplier * (joint.type == JointType::kPrismatic ? 1.0 : arm);
      }
      arm += joint.X_PJ.translation().norm() + prismaticTravel(robot, joint);
    }
  };
  addBranch(path.a_branch, a.reach);
  addBranch(path.b_branch, b.reach);
  std::vector<JointSpaceTable::Dim> dims;
  for (const int v : vars) {
    const Variable& var = robot.variables()[static_cast<std::size_t>(v)];
    dims.push_back({var.joint, var.lower, var.upper});
  }
  // Finest cells: their bound, sum over d of (range_d / 2^depth / 2) * weight_d, is within
  // the tolerance.
  double total = 0;
  for (std::size_t d = 0; d < dims.size(); ++d)
    total += (dims[d].upper - dims[d].lower) * weight[d];
  JointSpaceTable::BuildLimits limits;
  limits.max_cells = options.max_cells;
  limits.max_depth = std::clamp(
      static_cast<int>(std::ceil(std::log2(std::max(total / options.tolerance, 2.0)))) - 1, 1,
      JointSpaceTable::kMaxDepth);

  const LinkShapes shapes_a(robot, a), shapes_b(robot, b);
  RobotData data = robot.makeData();
  std::vector<double> q = middleConfiguration(robot);
  fcl::CollisionRequestd collide_request;
  fcl::CollisionResultd collide_result;
  fcl::DistanceRequestd distance_request;
  fcl::DistanceResultd distance_result;
  std::vector<fcl::CollisionObjectd> objects_b;
  for (const auto& e : shapes_b.elements()) objects_b.emplace_back(e.geometry);

  // Some point of `from` (its frame) is outside `to`'s solid (a white voxel of its oracle).
  auto someOutside = [](const LinkShapes& from, const Eigen::Isometry3d& X_to_from,
                        const LinkShapes& to) {
    for (const Eigen::Vector3d& p : from.points_L()) {
      if (!to.oracle().occupiedAt(X_to_from * p)) return true;
    }
    return false;
  };
  // Some point of `from` lies inside `to`'s solid, deeper than `depth`: a black voxel of the
  // oracle more than a voxel diagonal from the boundary is inside.
  int tries = 0;
  auto deepInside = [&](const LinkShapes& from, const Eigen::Isometry3d& X_to_from,
                        const LinkShapes& to, double depth) {
    const double need = std::max(depth, to.oracleDiagonal()) + kCertificateSlack;
    for (const Eigen::Vector3d& p : from.points_L()) {
      const Eigen::Vector3d p_to = X_to_from * p;
      if (!to.oracle().occupiedAt(p_to)) continue;
      if (++tries > kDeepPointTries) return false;
      if (to.surfaceDistance(p_to) > need) return true;
    }
    return false;
  };

  auto classify = [&](const double* centre, const double* half) -> JointSpaceTable::Verdict {
    double bound = 0;
    for (std::size_t d = 0; d < vars.size(); ++d) {
      q[static_cast<std::size_t>(vars[d])] = centre[d];
      bound += half[d] * weight[d];
    }
    robot.forwardKinematics(q.data(), q.size(), data);
    const Eigen::Isometry3d X_AB = data.linkPose(a.link).inverse() * data.linkPose(b.link);
    for (std::size_t k = 0; k < objects_b.size(); ++k) {
      const Eigen::Isometry3d X_AE = X_AB * shapes_b.elements()[k].X_LE;
      objects_b[k].setTransform(X_AE.rotation(), X_AE.translation());
      objects_b[k].computeAABB();
    }
    bool touching = false;
    double distance = std::numeric_limits<double>::infinity();
    for (const auto& ea : shapes_a.elements()) {  // a does not move: posed once
      const fcl::CollisionObjectd& oa = ea.posed;
      for (const auto& ob : objects_b) {
        collide_result.clear();
        if (fcl::collide(&oa, &ob, collide_request, collide_result) > 0) {
          touching = true;
          break;
        }
        distance_result.clear();
        fcl::distance(&oa, &ob, distance_request, distance_result);
        distance = std::min(distance, distance_result.min_distance);
      }
      if (touching) break;
    }
    if (touching || distance <= 0) {
      tries = 0;
      if (deepInside(shapes_b, X_AB, shapes_a, bound) ||
          deepInside(shapes_a, X_AB.inverse(), shapes_b, bound)) {
        return {JointSpaceTable::kColliding, false};
      }
      return {JointSpaceTable::kUnknown, true};
    }
    // Surfaces apart by more than any motion in the cell, and neither solid inside the other
    // (one inside the other with surfaces apart: colliding, when deep enough).
    if (distance > bound + kCertificateSlack) {
      if (someOutside(shapes_b, X_AB, shapes_a) &&
          someOutside(shapes_a, X_AB.inverse(), shapes_b)) {
        return {JointSpaceTable::kFree, false};
      }
      tries = 0;
      if (deepInside(shapes_b, X_AB, shapes_a, bound) ||
          deepInside(shapes_a, X_AB.inverse(), shapes_b, bound)) {
        return {JointSpaceTable::kColliding, false};
      }
    }
    return {JointSpaceTable::kUnknown, true};
  };
  return JointSpaceTable::build(dims, classify, limits);
}

}  // namespace octomotion::detail
