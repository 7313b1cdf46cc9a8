#include "octomotion/planner/robot/motion_bound.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

#include "octomotion/motion/point_clusters.h"
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

// What bounds a 1-Lipschitz function of the link's points in the anchor's frame (a distance to a
// point or an axis) over every value of the joints in `chain` (from the anchor's frame down to the
// link, in order): its largest value at `points` (in the anchor's frame) plus `slack`. While the
// chain is rigid, the link's points themselves (slack 0); past the first movable joint, that
// joint's origin (rigid in the anchor's frame) and the triangle inequality through each later
// joint's origin.
struct ChainReach {
  Points points;
  double slack = 0.0;
};

ChainReach chainReach(const RobotModel& robot, const std::vector<int>& chain,
                      const Points& points) {
  Eigen::Isometry3d X_AF = Eigen::Isometry3d::Identity();  // current frame F in the anchor's A
  std::size_t k = 0;
  for (; k < chain.size() && !robot.joint(chain[k]).movable(); ++k) {
    X_AF = X_AF * robot.joint(chain[k]).X_PJ;
  }
  ChainReach reach;
  if (k == chain.size()) {
    for (const Eigen::Vector3d& p : points) reach.points.push_back(X_AF * p);
    return reach;
  }
  const Joint& first = robot.joint(chain[k]);
  reach.points.push_back((X_AF * first.X_PJ).translation());
  reach.slack = travel(robot, first);  // from that origin to the current frame's origin
  Eigen::Isometry3d X_CF = Eigen::Isometry3d::Identity();  // F in the last movable joint's child
  for (++k; k < chain.size(); ++k) {
    const Joint& joint = robot.joint(chain[k]);
    if (joint.movable()) {
      reach.slack += (X_CF * joint.X_PJ).translation().norm() + travel(robot, joint);
      X_CF = Eigen::Isometry3d::Identity();
    } else {
      X_CF = X_CF * joint.X_PJ;
    }
  }
  double tail = 0.0;
  for (const Eigen::Vector3d& p : points) tail = std::max(tail, (X_CF * p).norm());
  reach.slack += tail;
  return reach;
}

// An upper bound of `distance` (1-Lipschitz, in the anchor's frame) at the link's points over
// every value of the joints in `chain` (chainReach); exact while the chain is rigid.
double chainBound(const RobotModel& robot, const std::vector<int>& chain, const Points& points,
                  const DistanceTo& distance) {
  const ChainReach reach = chainReach(robot, chain, points);
  double bound = 0.0;
  for (const Eigen::Vector3d& p : reach.points) bound = std::max(bound, distance(p));
  return bound + reach.slack;
}

// The cells of axis directions (LinkMotionBound::axisCell): an axis u and -u are the same axis,
// so each is taken with its largest coordinate k positive, then projected on the face of the
// cube where that coordinate is 1, cut into kAxisCells x kAxisCells squares.
constexpr int kCells = LinkMotionBound::kAxisCells;

// The cell's corner (i, j) of face k (i, j from 0 to kCells), as a direction.
Eigen::Vector3d cellCorner(int k, double i, double j) {
  Eigen::Vector3d d;
  d[k] = 1.0;
  d[(k + 1) % 3] = -1.0 + 2.0 * i / kCells;
  d[(k + 2) % 3] = -1.0 + 2.0 * j / kCells;
  return d.normalized();
}

// Per cell of axis directions, the largest distance of `points` from an axis of the cell, plus
// `slack`, rounded up to float. A cell's axes lie within a cap about its centre's c (its
// corners do, and a cap is convex on the sphere), of angular radius rho; a point x at angle
// alpha from c is at angle alpha +- rho at most from any of them, so its distance from one is at
// most |x| max sin over [alpha - rho, alpha + rho]: |x| when that holds pi / 2, else
// |x x c| cos(rho) + |x . c| sin(rho). The points are in clusters (clusterPoints), each with a
// ball about its centre: the ball's bound (the centre's plus its radius, the bound being
// 1-Lipschitz) skips the clusters that cannot hold the largest.
constexpr std::size_t kAxisClusterPoints = 8;
std::vector<float> axisRadiusTable(Points points, double slack) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::vector<std::uint32_t> order;
  const std::vector<PointCluster> clusters = clusterPoints(points, kAxisClusterPoints, order);
  std::vector<float> table;
  table.reserve(3 * kCells * kCells);
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < kCells; ++i) {
      for (int j = 0; j < kCells; ++j) {
        const Eigen::Vector3d c = cellCorner(k, i + 0.5, j + 0.5);
        double rho = 0.0;
        for (int corner = 0; corner < 4; ++corner) {
          const double cos = c.dot(cellCorner(k, i + (corner & 1), j + (corner >> 1)));
          rho = std::max(rho, std::acos(std::clamp(cos, -1.0, 1.0)));
        }
        rho += 1e-9;  // rounding in the corners and in the axis looked up
        const double sin_rho = std::sin(rho), cos_rho = std::cos(rho);
        auto distance = [&](const Eigen::Vector3d& x) {
          const double along = std::abs(x.dot(c));
          const double norm = x.norm();
          return along <= norm * sin_rho ? norm : x.cross(c).norm() * cos_rho + along * sin_rho;
        };
        double best = 0.0;
        for (const PointCluster& g : clusters) {
          best = std::max(best, distance(points[order[g.begin]]));
        }
        for (const PointCluster& g : clusters) {
          if (distance(g.centre) + g.radius <= best) continue;
          for (std::uint32_t m = g.begin; m < g.end; ++m) {
            best = std::max(best, distance(points[order[m]]));
          }
        }
        const double value = (best + slack) * (1 + 1e-12);
        table.push_back(
            std::nextafter(static_cast<float>(value), std::numeric_limits<float>::infinity()));
      }
    }
  }
  return table;
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
  axis_radius_.resize(static_cast<std::size_t>(link_count_));
  for (int l = 0; l < link_count_; ++l) {
    path_begin_.push_back(path_joints_.size());
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
    if (robot.isFreeFlying()) {
      const ChainReach reach = chainReach(robot, path, points);
      axis_radius_[static_cast<std::size_t>(l)] = axisRadiusTable(reach.points, reach.slack);
    }
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
      const double sign = joint.isMimic() && joint.mimic_multiplier < 0 ? -1.0 : 1.0;
      levers_[static_cast<std::size_t>(l * variable_count_ + variable)] += multiplier * arm;
      path_joints_.push_back({path[i], variable, joint.child_link, multiplier, arm, sign,
                              joint.type != JointType::kPrismatic, joint.axis.normalized()});
      arm_link_.push_back(l);
    }
  }
  path_begin_.push_back(path_joints_.size());
  // A pair's relative motion: the joints on one link's path and not on the other's (the common
  // ones, above the two links' common ancestor, move both rigidly). By joint, not by variable:
  // a mimic joint moves one finger while its master moves the other.
  pairs_ = robot.checkedPairs();
  pair_levers_.assign(pairs_.size() * static_cast<std::size_t>(variable_count_), 0.0);
  auto onPath = [&](int link, int joint) {
    const auto begin = path_joints_.begin() + static_cast<std::ptrdiff_t>(path_begin_[link]);
    const auto end = path_joints_.begin() + static_cast<std::ptrdiff_t>(path_begin_[link + 1]);
    return std::any_of(begin, end, [joint](const PathJoint& j) { return j.joint == joint; });
  };
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    pair_begin_.push_back(pair_arms_.size());
    double* lever = pair_levers_.data() + p * static_cast<std::size_t>(variable_count_);
    // Each movable joint on one link's path (its arms) and not on the other's.
    for (const auto& [link, other] :
         {pairs_[p], std::make_pair(pairs_[p].second, pairs_[p].first)}) {
      std::size_t first = path_begin_[link + 1];
      for (std::size_t k = path_begin_[link]; k < path_begin_[link + 1]; ++k) {
        const PathJoint& j = path_joints_[k];
        if (onPath(other, j.joint)) {
          // The shared joints come first on both paths (speedFrom reads the rest as one sum).
          if (first != path_begin_[link + 1]) {
            throw std::logic_error("LinkMotionBound: a pair's joints are not the end of a path");
          }
          continue;
        }
        first = std::min(first, k);
        lever[j.variable] += j.multiplier * j.lever;
        pair_arms_.push_back(k);
      }
      pair_suffix_.push_back(first);
    }
  }
  pair_begin_.push_back(pair_arms_.size());
}

void LinkMotionBound::posedArms(const RobotData& data, int link, double* arms) const {
  const std::size_t begin = path_begin_[static_cast<std::size_t>(link)];
  const std::size_t end = path_begin_[static_cast<std::size_t>(link) + 1];
  if (begin == end) return;
  const Spheres& sphere = spheres_[static_cast<std::size_t>(link)];
  const Eigen::Vector3d centre_W = data.linkPose(link) * sphere.center;
  for (std::size_t k = begin; k < end; ++k) {
    const PathJoint& j = path_joints_[k];
    double* arm = arms + k * kArmValues;
    Eigen::Map<Eigen::Vector3d> velocity(arm + 1), turn(arm + 4);
    // The axis passes through the joint's child frame's origin, along its axis there.
    const Eigen::Isometry3d& X_WC = data.linkPose(j.axis_link);
    const Eigen::Vector3d u_W = X_WC.linear() * j.axis;
    if (!j.revolute) {
      arm[0] = 1.0;
      velocity = u_W;
      turn.setZero();
      continue;
    }
    velocity = u_W.cross(centre_W - X_WC.translation());
    turn = u_W;
    // A micrometre covers rounding in the poses.
    arm[0] = std::min(j.lever, velocity.norm() + sphere.radius + 1e-6);
  }
}

void LinkMotionBound::edgeTerms(const double* dq, EdgeTerms& terms) const {
  const std::size_t arm_count = path_joints_.size();
  terms.weight.resize(arm_count);
  terms.signed_weight.resize(arm_count);
  terms.link_growth.assign(static_cast<std::size_t>(link_count_), 0.0);
  terms.link_speed_growth.assign(static_cast<std::size_t>(link_count_), 0.0);
  terms.pair_growth.assign(pairs_.size(), 0.0);
  terms.pair_speed_growth.assign(pairs_.size(), 0.0);
  // Per arm, its weight times S_j (the levers below j on the link's path times their weights).
  std::vector<double>& below = terms.arm_growth;
  below.assign(arm_count, 0.0);
  // Per arm, T_j: its own and the levers below it times their weights (the speed growth's).
  std::vector<double>& from = terms.arm_reach;
  from.assign(arm_count, 0.0);
  for (int l : geometry_links_) {
    const std::size_t begin = path_begin_[static_cast<std::size_t>(l)];
    const std::size_t end = path_begin_[static_cast<std::size_t>(l) + 1];
    double speed_below = 0.0;  // of the link's points relative to the current joint's child
    double growth = 0.0;
    for (std::size_t k = end; k-- > begin;) {
      const PathJoint& j = path_joints_[k];
      const double w = std::abs(dq[j.variable]) * j.multiplier;
      terms.weight[k] = w;
      terms.signed_weight[k] = dq[j.variable] * j.multiplier * j.sign;
      below[k] = j.revolute ? w * speed_below : 0.0;
      growth += below[k];
      speed_below += w * j.lever;
      from[k] = speed_below;
    }
    terms.link_growth[static_cast<std::size_t>(l)] = growth;
    terms.link_speed_growth[static_cast<std::size_t>(l)] = speedGrowth(terms, begin, end, nullptr);
  }
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    double growth = 0.0;
    for (std::size_t i = pair_begin_[p]; i < pair_begin_[p + 1]; ++i) {
      growth += below[pair_arms_[i]];
    }
    terms.pair_growth[p] = growth;
    terms.pair_speed_growth[p] =
        speedGrowth(terms, pair_begin_[p], pair_begin_[p + 1], pair_arms_.data());
  }
}

double LinkMotionBound::speedGrowth(const EdgeTerms& terms, std::size_t begin, std::size_t end,
                                    const std::size_t* indices) const {
  // Arms of one link's path in order, root first (a pair's: each link's in turn, a suffix of
  // its path); Omega restarts at each link's first.
  double growth = 0.0, omega = 0.0;
  int link_path = -1;
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t k = indices ? indices[i] : i;
    const int path = pathOf(k);
    if (path != link_path) omega = 0.0;
    link_path = path;
    const PathJoint& j = path_joints_[k];
    const double w = terms.weight[k];
    growth += w * (omega * j.lever + (j.revolute ? terms.arm_reach[k] : 0.0));
    if (j.revolute) omega += w;
  }
  return growth;
}

double LinkMotionBound::linkRate(int link, const EdgeTerms& terms, const double* arms) const {
  double rate = 0.0;
  const std::size_t end = path_begin_[static_cast<std::size_t>(link) + 1];
  for (std::size_t k = path_begin_[static_cast<std::size_t>(link)]; k < end; ++k) {
    rate += terms.weight[k] * arms[k * kArmValues];
  }
  return rate;
}

double LinkMotionBound::pairRate(std::size_t p, const EdgeTerms& terms, const double* arms) const {
  double rate = 0.0;
  for (std::size_t i = pair_begin_[p]; i < pair_begin_[p + 1]; ++i) {
    rate += terms.weight[pair_arms_[i]] * arms[pair_arms_[i] * kArmValues];
  }
  return rate;
}

double LinkMotionBound::speedOver(const EdgeTerms& terms, const double* arms, std::size_t begin,
                                  std::size_t end, const std::size_t* indices) const {
  // Per link among the arms (one, or a pair's two in turn): |V| + |W| r.
  double speed = 0.0;
  Eigen::Vector3d V = Eigen::Vector3d::Zero(), W = Eigen::Vector3d::Zero();
  int link_path = -1;
  auto close = [&] {
    if (link_path < 0) return;
    speed += speedOf(link_path, V, W);
    V.setZero();
    W.setZero();
  };
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t k = indices ? indices[i] : i;
    const int path = pathOf(k);
    if (path != link_path) {
      close();
      link_path = path;
    }
    const double* arm = arms + k * kArmValues;
    V += terms.signed_weight[k] * Eigen::Map<const Eigen::Vector3d>(arm + 1);
    W += terms.signed_weight[k] * Eigen::Map<const Eigen::Vector3d>(arm + 4);
  }
  close();
  return speed;
}

void LinkMotionBound::speedSums(int link, const EdgeTerms& terms, const double* arms,
                                double* sums) const {
  Eigen::Vector3d V = Eigen::Vector3d::Zero(), W = Eigen::Vector3d::Zero();
  const std::size_t begin = path_begin_[static_cast<std::size_t>(link)];
  for (std::size_t k = path_begin_[static_cast<std::size_t>(link) + 1]; k-- > begin;) {
    const double* arm = arms + k * kArmValues;
    V += terms.signed_weight[k] * Eigen::Map<const Eigen::Vector3d>(arm + 1);
    W += terms.signed_weight[k] * Eigen::Map<const Eigen::Vector3d>(arm + 4);
    Eigen::Map<Eigen::Vector3d>(sums + k * kSumValues) = V;
    Eigen::Map<Eigen::Vector3d>(sums + k * kSumValues + 3) = W;
  }
}

double LinkMotionBound::linkSpeed(int link, const EdgeTerms& terms, const double* arms) const {
  return speedOver(terms, arms, path_begin_[static_cast<std::size_t>(link)],
                   path_begin_[static_cast<std::size_t>(link) + 1], nullptr);
}

double LinkMotionBound::pairSpeed(std::size_t p, const EdgeTerms& terms, const double* arms) const {
  return speedOver(terms, arms, pair_begin_[p], pair_begin_[p + 1], pair_arms_.data());
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

LinkMotionBound::RootMotion::RootMotion(const Eigen::Isometry3d& X_WB1,
                                        const Eigen::Isometry3d& X_WB2) {
  const Eigen::AngleAxisd turn(Eigen::Matrix3d(X_WB1.linear().transpose() * X_WB2.linear()));
  axis = turn.axis();
  angle = turn.angle();
  const Eigen::Vector3d dt =
      X_WB1.linear().transpose() * (X_WB2.translation() - X_WB1.translation());
  const double on_axis = dt.dot(axis);
  along = std::abs(on_axis);
  across = (dt - on_axis * axis).norm();
}

int LinkMotionBound::axisCell(const Eigen::Vector3d& axis) {
  int k = 0;
  axis.cwiseAbs().maxCoeff(&k);
  int cell = k;
  for (int a : {(k + 1) % 3, (k + 2) % 3}) {
    // The coordinate on the face, from -1 to 1 (NaN for a zero axis: cell 0).
    double at = (axis[a] / axis[k] + 1.0) * (0.5 * kCells);
    if (!(at >= 0.0)) at = 0.0;
    cell = cell * kCells + std::min(static_cast<int>(at), kCells - 1);
  }
  return cell;
}

double LinkMotionBound::axisRadius(int link, const Eigen::Vector3d& axis) const {
  const std::vector<float>& table = axis_radius_[static_cast<std::size_t>(link)];
  return table.empty() ? 0.0 : table[static_cast<std::size_t>(axisCell(axis))];
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
