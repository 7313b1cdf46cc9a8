#include "octomotion/planner/robot/motion_bound.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <variant>

#include "octomotion/octree/shapes.h"
#include "octomotion/planner/robot/collision_meshes.h"

namespace octomotion {
namespace {

using Points = std::vector<Eigen::Vector3d>;
using DistanceTo = std::function<double(const Eigen::Vector3d&)>;

// The points whose hull holds the link's geometry, in the link frame: mesh vertices, and the
// corners of each primitive's bounding box (a distance to a point or an axis is convex, so its
// largest value over a hull is at one of these points).
Points linkPoints(const Link& link, CollisionMeshes& meshes) {
  Points points;
  for (const CollisionElement& e : link.collision) {
    if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
      const Eigen::AlignedBox3d box = boundingBox(*p, e.X_LE);
      for (int c = 0; c < 8; ++c) {
        points.push_back(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
      }
    } else {
      for (const Eigen::Vector3d& v : meshes.get(std::get<MeshRef>(e.geometry)).vertices) {
        points.push_back(e.X_LE * v);
      }
    }
  }
  return points;
}

// The largest value a prismatic joint can take (what its child's origin can slide).
double travel(const RobotModel& robot, const Joint& joint) {
  if (joint.type != JointType::kPrismatic) return 0.0;
  if (!joint.isMimic()) return std::max(std::abs(joint.lower), std::abs(joint.upper));
  const Joint& master = robot.joint(joint.mimic_master);
  return std::abs(joint.mimic_multiplier) *
             std::max(std::abs(master.lower), std::abs(master.upper)) +
         std::abs(joint.mimic_offset);
}

// An upper bound, over every value of the joints in `chain` (from the anchor's frame down to
// the link, in order), of `distance` (1-Lipschitz, in the anchor's frame) at the link's points.
// Exact while the chain is rigid; past the first movable joint, the triangle inequality from
// that joint's origin (rigid in the anchor's frame) through each later joint's origin.
double chainBound(const RobotModel& robot, const std::vector<int>& chain, const Points& points,
                  const DistanceTo& distance) {
  Eigen::Isometry3d X_AF = Eigen::Isometry3d::Identity();  // current frame F in the anchor's A
  std::size_t k = 0;
  for (; k < chain.size() && !robot.joint(chain[k]).movable(); ++k) {
    X_AF = X_AF * robot.joint(chain[k]).X_PJ;
  }
  double bound = 0.0;
  if (k == chain.size()) {
    for (const Eigen::Vector3d& p : points) bound = std::max(bound, distance(X_AF * p));
    return bound;
  }
  const Joint& first = robot.joint(chain[k]);
  const Eigen::Vector3d origin_A = (X_AF * first.X_PJ).translation();
  double reach = travel(robot, first);  // from `origin_A` to the current frame's origin
  Eigen::Isometry3d X_CF = Eigen::Isometry3d::Identity();  // F in the last movable joint's child
  for (++k; k < chain.size(); ++k) {
    const Joint& joint = robot.joint(chain[k]);
    if (joint.movable()) {
      reach += (X_CF * joint.X_PJ).translation().norm() + travel(robot, joint);
      X_CF = Eigen::Isometry3d::Identity();
    } else {
      X_CF = X_CF * joint.X_PJ;
    }
  }
  double tail = 0.0;
  for (const Eigen::Vector3d& p : points) tail = std::max(tail, (X_CF * p).norm());
  return distance(origin_A) + reach + tail;
}

}  // namespace

LinkMotionBound::LinkMotionBound(const RobotModel& robot, bool keep_mesh_root_transform,
                                 bool center_mesh_vertices,
                                 const std::vector<CarriedPoints>& carried)
    : link_count_(robot.linkCount()), variable_count_(robot.variableCount()) {
  for (const CarriedPoints& c : carried) {
    if (c.link < 0 || c.link >= link_count_) {
      throw InvalidArgument("LinkMotionBound: carried points on link " + std::to_string(c.link) +
                            " of " + robot.name() + ", which has " + std::to_string(link_count_) +
                            " links");
    }
  }
  levers_.assign(static_cast<std::size_t>(link_count_) * static_cast<std::size_t>(variable_count_),
                 0.0);
  CollisionMeshes meshes(keep_mesh_root_transform, center_mesh_vertices);
  spheres_.resize(static_cast<std::size_t>(link_count_));
  // Per link, each movable joint on its path from the root with its lever (times the mimic
  // multiplier) and variable: the self pairs' levers are sums of these.
  struct JointLever {
    int joint, variable;
    double lever;
  };
  std::vector<std::vector<JointLever>> joint_levers(static_cast<std::size_t>(link_count_));
  for (int l = 0; l < link_count_; ++l) {
    Points points = linkPoints(robot.link(l), meshes);
    for (const CarriedPoints& c : carried) {
      if (c.link == l) points.insert(points.end(), c.points.begin(), c.points.end());
    }
    if (points.empty()) continue;
    geometry_links_.push_back(l);
    spheres_[static_cast<std::size_t>(l)] = makeSpheres(points);
    // The joints from the root down to the link.
    std::vector<int> path;
    for (int j = robot.link(l).parent_joint; j >= 0;
         j = robot.link(robot.joint(j).parent_link).parent_joint) {
      path.push_back(j);
    }
    std::reverse(path.begin(), path.end());
    radius_ = std::max(radius_, chainBound(robot, path, points,
                                           [](const Eigen::Vector3d& x) { return x.norm(); }));
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Joint& joint = robot.joint(path[i]);
      if (!joint.movable()) continue;
      const int variable =
          joint.isMimic() ? robot.joint(joint.mimic_master).variable : joint.variable;
      if (variable < 0) continue;
      double arm = 1.0;  // prismatic: every point slides with the joint
      if (joint.type != JointType::kPrismatic) {
        // The child's frame at value 0 is the joint frame; turning about the axis through its
        // origin keeps every distance to that axis.
        const std::vector<int> below(path.begin() + static_cast<std::ptrdiff_t>(i) + 1, path.end());
        const Eigen::Vector3d axis = joint.axis.normalized();
        arm = chainBound(robot, below, points, [&axis](const Eigen::Vector3d& x) {
          return (x - x.dot(axis) * axis).norm();
        });
      }
      const double multiplier = joint.isMimic() ? std::abs(joint.mimic_multiplier) : 1.0;
      levers_[static_cast<std::size_t>(l * variable_count_ + variable)] += multiplier * arm;
      joint_levers[static_cast<std::size_t>(l)].push_back({path[i], variable, multiplier * arm});
    }
  }
  // A pair's relative motion: the joints on one link's path and not on the other's (the common
  // ones, above the two links' common ancestor, move both rigidly). By joint, not by variable:
  // a mimic joint moves one finger while its master moves the other.
  pairs_ = robot.checkedPairs();
  pair_levers_.assign(pairs_.size() * static_cast<std::size_t>(variable_count_), 0.0);
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const auto& a = joint_levers[static_cast<std::size_t>(pairs_[p].first)];
    const auto& b = joint_levers[static_cast<std::size_t>(pairs_[p].second)];
    double* lever = pair_levers_.data() + p * static_cast<std::size_t>(variable_count_);
    auto onPath = [](const std::vector<JointLever>& path, int joint) {
      return std::any_of(path.begin(), path.end(),
                         [joint](const JointLever& j) { return j.joint == joint; });
    };
    for (const JointLever& j : a) {
      if (!onPath(b, j.joint)) lever[j.variable] += j.lever;
    }
    for (const JointLever& j : b) {
      if (!onPath(a, j.joint)) lever[j.variable] += j.lever;
    }
  }
}

// Spheres that hold the hull of a link's points (its geometry): one about their box's centre
// (radius: the farthest point; a ball is convex), and kPairSlabs about equal slices of that box
// along its longest side (each circumscribes its slice, which holds the hull's part there).
LinkMotionBound::Spheres LinkMotionBound::makeSpheres(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  Spheres s;
  s.center = box.center();
  for (const Eigen::Vector3d& p : points) s.radius = std::max(s.radius, (p - s.center).norm());
  Eigen::Index axis = 0;
  box.sizes().maxCoeff(&axis);
  const double step = box.sizes()[axis] / LinkMotionBound::kPairSlabs;
  for (int k = 0; k < LinkMotionBound::kPairSlabs; ++k) {
    Eigen::AlignedBox3d slice = box;
    slice.min()[axis] = box.min()[axis] + step * k;
    slice.max()[axis] =
        k + 1 == LinkMotionBound::kPairSlabs ? box.max()[axis] : box.min()[axis] + step * (k + 1);
    Eigen::Vector4d sphere;
    sphere.head<3>() = slice.center();
    sphere[3] = 0.5 * slice.sizes().norm();
    s.slabs.push_back(sphere);
  }
  return s;
}

double LinkMotionBound::pairBound(std::size_t p, const double* dq) const {
  const double* lever = pair_levers_.data() + p * static_cast<std::size_t>(variable_count_);
  double bound = 0.0;
  for (int v = 0; v < variable_count_; ++v) bound += lever[v] * std::abs(dq[v]);
  return bound;
}

double LinkMotionBound::pairDistance(std::size_t p, const RobotData& data, double cap) const {
  const auto [a, b] = pairs_[p];
  const Spheres& sa = spheres_[static_cast<std::size_t>(a)];
  const Spheres& sb = spheres_[static_cast<std::size_t>(b)];
  if (sa.slabs.empty() || sb.slabs.empty()) return cap;  // a link without geometry
  const Eigen::Isometry3d& X_WA = data.linkPose(a);
  const Eigen::Isometry3d& X_WB = data.linkPose(b);
  const double whole = (X_WA * sa.center - X_WB * sb.center).norm() - sa.radius - sb.radius;
  if (whole >= cap) return cap;
  Eigen::Vector3d centres_b[kPairSlabs];
  for (std::size_t j = 0; j < sb.slabs.size(); ++j) {
    centres_b[j] = X_WB * Eigen::Vector3d(sb.slabs[j].head<3>());
  }
  double slabs = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector4d& s : sa.slabs) {
    const Eigen::Vector3d c = X_WA * Eigen::Vector3d(s.head<3>());
    for (std::size_t j = 0; j < sb.slabs.size(); ++j) {
      slabs = std::min(slabs, (c - centres_b[j]).norm() - s[3] - sb.slabs[j][3]);
    }
    if (slabs <= 0) return 0.0;
  }
  // Both are lower bounds; a micrometre covers rounding in the transforms.
  return std::clamp(std::max(whole, slabs) - 1e-6, 0.0, cap);
}

double LinkMotionBound::linkBound(int link, const double* dq) const {
  const double* lever = levers_.data() + static_cast<std::ptrdiff_t>(link) * variable_count_;
  double bound = 0.0;
  for (int v = 0; v < variable_count_; ++v) bound += lever[v] * std::abs(dq[v]);
  return bound;
}

double LinkMotionBound::maxBound(const double* dq) const {
  double bound = 0.0;
  for (int l : geometry_links_) bound = std::max(bound, linkBound(l, dq));
  return bound;
}

}  // namespace octomotion
