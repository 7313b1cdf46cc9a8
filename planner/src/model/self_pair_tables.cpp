#include "internal/self_pair_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "../robot/internal/fcl_robot.h"

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

bool isRevolute(const Joint& j) {
  return j.type == JointType::kRevolute || j.type == JointType::kContinuous;
}

// The link's solid is a solid of revolution about its parent joint's axis (spheres centred on
// the axis, cylinders along it: octo6's flange and tool ball): turning that joint leaves the
// solid where it was, so a pair's table need not span its variable. Meshes never qualify.
bool turnsOntoItself(const RobotModel& robot, int link) {
  const Link& l = robot.link(link);
  if (l.parent_joint < 0 || l.collision.empty()) return false;
  const Joint& j = robot.joint(l.parent_joint);
  if (!isRevolute(j) || j.isMimic()) return false;
  // The child frame turns about `axis` through its own origin (X_PJ * Rot(axis, v)).
  const Eigen::Vector3d axis = j.axis.normalized();
  constexpr double kOnAxis = 1e-9;  // metres, and radians for the cylinders' direction
  for (const CollisionElement& e : l.collision) {
    const auto* shape = std::get_if<Primitive>(&e.geometry);
    if (!shape) return false;
    const Eigen::Vector3d c = e.X_LE.translation();
    if ((c - c.dot(axis) * axis).norm() > kOnAxis) return false;
    if (std::holds_alternative<Sphere>(*shape)) continue;
    if (!std::holds_alternative<Cylinder>(*shape)) return false;
    if (e.X_LE.rotation().col(2).cross(axis).norm() > kOnAxis) return false;
  }
  return true;
}

// The variables a pair's table spans, each with whether it wraps by whole turns.
struct TableVariable {
  int variable = -1;
  bool periodic = false;
};
std::vector<TableVariable> tableVariables(const RobotModel& robot, int link_a, int link_b) {
  const PathJoints path = pathJoints(robot, link_a, link_b);
  std::map<int, std::vector<const Joint*>> joints_of;  // variable -> the path joints it drives
  for (const std::vector<int>* branch : {&path.a_branch, &path.b_branch}) {
    for (int j : *branch) {
      const Joint& joint = robot.joint(j);
      const int v = variableOf(robot, joint);
      if (v >= 0) joints_of[v].push_back(&joint);
    }
  }
  std::vector<TableVariable> out;
  for (const auto& [v, joints] : joints_of) {
    // Dropped: the variable turns only the end link of a branch, which turns onto itself.
    if (joints.size() == 1) {
      const int child = joints.front()->child_link;
      if ((child == link_a || child == link_b) && turnsOntoItself(robot, child)) continue;
    }
    // Periodic: every joint it drives turns by it one for one, and its range covers a turn.
    const Variable& var = robot.variables()[static_cast<std::size_t>(v)];
    bool periodic = var.continuous || var.upper - var.lower >= 2 * M_PI;
    for (const Joint* joint : joints)
      periodic = periodic && isRevolute(*joint) && !joint->isMimic();
    out.push_back({v, periodic});
  }
  return out;
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

// The largest distance from the line through o along u (link frame) to the link's solid: the
// distance to a line is convex, so a convex hull's extreme points bound it (mesh vertices, box
// corners; a sphere's centre plus its radius, a cylinder's cap centres plus its radius).
double farthestFromLine(const RobotModel& robot, const SelfPairLink& link, const Eigen::Vector3d& o,
                        const Eigen::Vector3d& u) {
  const Eigen::Vector3d axis = u.normalized();
  auto from = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d r = p - o;
    return (r - r.dot(axis) * axis).norm();
  };
  const Link& l = robot.link(link.link);
  double farthest = 0;
  for (std::size_t k = 0; k < l.collision.size(); ++k) {
    const CollisionElement& e = l.collision[k];
    if (const TriangleMesh* mesh = link.element_mesh[k]) {
      for (const Eigen::Vector3d& v : mesh->vertices)
        farthest = std::max(farthest, from(e.X_LE * v));
      continue;
    }
    const Primitive& shape = std::get<Primitive>(e.geometry);
    if (const auto* b = std::get_if<Box>(&shape)) {
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d s(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
        farthest = std::max(farthest, from(e.X_LE * s.cwiseProduct(b->half_extents)));
      }
    } else if (const auto* sp = std::get_if<Sphere>(&shape)) {
      farthest = std::max(farthest, from(e.X_LE.translation()) + sp->radius);
    } else {
      const auto& cy = std::get<Cylinder>(shape);
      for (const double z : {-cy.length / 2, cy.length / 2}) {
        farthest = std::max(farthest, from(e.X_LE * Eigen::Vector3d(0, 0, z)) + cy.radius);
      }
    }
  }
  return farthest;
}

// FCL's distances are exact up to rounding; certificates keep this much in hand.
constexpr double kCertificateSlack = 1e-6;
// Point-depth queries tried per colliding cell before it is left to be split.
constexpr int kDeepPointTries = 32;

}  // namespace

std::vector<int> pairVariables(const RobotModel& robot, int link_a, int link_b) {
  std::vector<int> vars;
  for (const TableVariable& t : tableVariables(robot, link_a, link_b)) vars.push_back(t.variable);
  return vars;
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
  const std::vector<TableVariable> table_vars = tableVariables(robot, a.link, b.link);
  if (table_vars.empty() ||
      table_vars.size() > static_cast<std::size_t>(JointSpaceTable::kMaxDims)) {
    return std::nullopt;
  }
  std::vector<int> vars;
  for (const TableVariable& t : table_vars) vars.push_back(t.variable);
  // Motion bound, in the frame of the links' common ancestor C. Changing a joint on a's branch
  // by h turns a's points about its axis (shifts them, prismatic) by at most h times their
  // distance from the joint's origin, which the offsets and travel of the joints below it on
  // that branch plus a's reach bound, whatever the other joints are (likewise for b's branch
  // and b). The pair's distance is the same if b turns the other way instead, so the smaller
  // of the two arms serves: b's distance from the axis is bounded by the offsets up to C and
  // down b's branch plus b's reach — exactly, from b's geometry, when no joint between b and
  // the axis moves (a base about its pan axis: its radius, not the arm's length). Cells change
  // their joints one after the other, and the distance changes by at most the sum over them.
  const PathJoints path = pathJoints(robot, a.link, b.link);
  RobotData middle = robot.makeData();
  {
    const std::vector<double> q_mid = middleConfiguration(robot);
    robot.forwardKinematics(q_mid.data(), q_mid.size(), middle);
  }
  auto offset = [&](int j) {
    const Joint& joint = robot.joint(j);
    return joint.X_PJ.translation().norm() + prismaticTravel(robot, joint);
  };
  std::vector<double> weight(vars.size(), 0.0);
  auto addBranch = [&](const std::vector<int>& branch, const SelfPairLink& own,
                       const std::vector<int>& other_branch, const SelfPairLink& other) {
    double other_to_c = other.reach;  // from C's origin to the other link's points
    bool other_rigid = true;          // the other link is fixed in C
    for (int j : other_branch) {
      other_to_c += offset(j);
      other_rigid = other_rigid && !robot.joint(j).movable();
    }
    double arm = own.reach;  // from the origin of the child link of branch[k] to own's points
    bool own_rigid = true;   // no joint below branch[k] moves own
    for (std::size_t k = 0; k < branch.size(); ++k) {
      const Joint& joint = robot.joint(branch[k]);
      double above = 0;  // from the parent link of branch[k] up to C
      bool rigid = other_rigid;
      for (std::size_t i = k + 1; i < branch.size(); ++i) {
        above += offset(branch[i]);
        rigid = rigid && !robot.joint(branch[i]).movable();
      }
      const int v = variableOf(robot, joint);
      const auto it = std::lower_bound(vars.begin(), vars.end(), v);
      if (it != vars.end() && *it == v) {  // not a dropped variable (it moves no point)
        const auto d = static_cast<std::size_t>(it - vars.begin());
        const double multiplier = joint.isMimic() ? std::abs(joint.mimic_multiplier) : 1.0;
        double lever = 1.0;  // prismatic: every point moves by the change
        if (joint.type != JointType::kPrismatic) {
          // The axis in the frame of link `from`, fixed there when no joint between them moves.
          auto fromAxis = [&](const SelfPairLink& from) {
            const Eigen::Isometry3d X_FJ = middle.linkPose(from.link).inverse() *
                                           middle.linkPose(joint.parent_link) * joint.X_PJ;
            return farthestFromLine(robot, from, X_FJ.translation(), X_FJ.linear() * joint.axis);
          };
          const double own_arm = own_rigid ? std::min(arm, fromAxis(own)) : arm;
          double other_arm = offset(branch[k]) + above + other_to_c;
          if (rigid) other_arm = std::min(other_arm, fromAxis(other));
          lever = std::min(own_arm, other_arm);
        }
        weight[d] += multiplier * lever;
      }
      arm += offset(branch[k]);
      own_rigid = own_rigid && !joint.movable();
    }
  };
  addBranch(path.a_branch, a, path.b_branch, b);
  addBranch(path.b_branch, b, path.a_branch, a);
  // Each variable's share of a cell's bound is range_d * weight_d / 2^(depth + 1); a variable
  // that moves the pair less than the others gets a stretched side (JointSpaceTable::Dim), so
  // that the shares are within a factor 2 of each other and no budget goes to splitting along
  // it before it matters.
  std::vector<JointSpaceTable::Dim> dims;
  std::vector<double> share(vars.size());
  for (std::size_t d = 0; d < vars.size(); ++d) {
    const Variable& var = robot.variables()[static_cast<std::size_t>(vars[d])];
    const bool periodic = table_vars[d].periodic;
    dims.push_back({var.joint, var.lower, periodic ? var.lower + 2 * M_PI : var.upper, periodic});
    share[d] = (dims[d].upper - dims[d].lower) * weight[d];
  }
  const double widest = *std::max_element(share.begin(), share.end());
  // Finest cells: their bound, sum over d of the stretched shares / 2^(depth + 1), is within
  // the tolerance.
  double total = 0;
  for (std::size_t d = 0; d < dims.size(); ++d) {
    if (share[d] > 0) {
      dims[d].stretch = std::clamp(static_cast<int>(std::floor(std::log2(widest / share[d]))), 0,
                                   JointSpaceTable::kMaxDepth / 2);
    }
    total += std::ldexp(share[d], dims[d].stretch);
  }
  JointSpaceTable::BuildLimits limits;
  limits.max_cells = options.max_cells;
  limits.max_depth = std::clamp(
      static_cast<int>(std::ceil(std::log2(std::max(total / options.tolerance, 2.0)))) - 1, 1,
      JointSpaceTable::kMaxDepth);
  for (JointSpaceTable::Dim& dim : dims) dim.stretch = std::min(dim.stretch, limits.max_depth - 1);

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
      return {JointSpaceTable::kUnknown, true, true};
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
