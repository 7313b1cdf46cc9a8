// How far any point of each link can travel along a motion (Schwarzer, Saha & Latombe, "Adaptive
// dynamic collision checking for single and multiple articulated robots", IEEE T-RO 2005): the
// certified motion validator (ompl/certified_motion_validator.h) compares it with the clearance.
//
// Fixed-base robots, straight-line motions in q: the path of any point of link l is at most
// sum_v lever(l, v) |dq_v|, where lever(l, v) bounds, over every configuration, the distance from
// the axis of joint v (and of the mimic joints that follow it, times their multiplier) to the
// points of link l; 1 for prismatic joints. Free-flying bodies (OMPL's SE(3) interpolation: the
// root's origin moves along the segment dt while the root turns at a constant rate by angle
// theta about an axis u fixed in the root frame, through its origin): a point x of the root
// frame moves at a speed whose part along u is that of dt (the rotation's is across u), so its
// path is at most sqrt(along^2 + (across + theta * |u x x|)^2), along and across the parts of
// |dt| along and across u; |u x x| (the distance from the axis) is bounded per link by a table
// over cells of axis directions (axisRadius), loose by at most twice a cell's angular radius
// (under 0.05 rad) times |x|.
//
// Self pairs (RobotModel::checkedPairs): the distance between two links changes only through
// the joints that move one of them and not the other (those above their common ancestor move
// both rigidly); in that ancestor's frame each such joint moves the link below it by at most its
// lever, so the distance changes by at most sum_v pairLever(p, v) |dq_v| over those joints
// alone (pairBound); and a lower bound on the distance between the two links' geometry at a pose
// comes from spheres that hold each link's points (pairDistance).
//
// The geometry is read once (meshes through CollisionMeshes with the conventions given, so the
// points are those the collision models use); primitives by their bounding box's corners.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

class LinkMotionBound {
 public:
  // Points carried by a link besides its own geometry (in its frame): attached objects' hulls.
  struct CarriedPoints {
    int link = -1;
    std::vector<Eigen::Vector3d> points;
  };
  // Throws what loading the meshes throws, and InvalidArgument for a carried link out of range.
  LinkMotionBound(const RobotModel& robot, bool keep_mesh_root_transform = false,
                  bool center_mesh_vertices = false,
                  const std::vector<CarriedPoints>& carried = {});

  int linkCount() const { return link_count_; }
  int variableCount() const { return variable_count_; }
  // lever(l, v): metres per radian (revolute) or per metre (prismatic); 0 when joint v does not
  // move link l or the link has no geometry.
  double lever(int link, int variable) const {
    return levers_[static_cast<std::size_t>(link * variable_count_ + variable)];
  }
  // The path-length bound of link l for a joint displacement dq (variableCount() values).
  double linkBound(int link, const double* dq) const;
  // The largest over the links with geometry.
  double maxBound(const double* dq) const;
  const std::vector<int>& geometryLinks() const { return geometry_links_; }
  // Free-flying bodies: the largest distance of a point from the root frame's origin, over every
  // configuration of the robot's own joints (held joints included in their transforms).
  double radius() const { return radius_; }
  // A motion of the root frame as OMPL's SE(3) interpolation makes it from X_WB1 to X_WB2: the
  // origin along the segment between theirs, the rotation by `angle` (0 to pi) at a constant rate
  // about `axis` (a unit vector of the root frame; fixed in the world too, as X_WB1 * axis). Any
  // part [a, b] of it is the same motion scaled by b - a.
  struct RootMotion {
    RootMotion() = default;  // no motion
    RootMotion(const Eigen::Isometry3d& X_WB1, const Eigen::Isometry3d& X_WB2);
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    double angle = 0;
    double along = 0, across = 0;  // the origin's displacement along the axis and across it
  };
  // Free-flying bodies: the path-length bound of link l's points (over every configuration of
  // the robot's own joints) for the root's motion alone; a joint motion adds linkBound.
  double freeFlyingBound(int link, const RootMotion& motion) const {
    const double turn = motion.across + motion.angle * axisRadius(link, motion.axis);
    return std::sqrt(motion.along * motion.along + turn * turn);
  }
  // Free-flying bodies: at least the largest distance of link l's points (over every
  // configuration) from the axis through the root's origin along the unit vector `axis` (root
  // frame), at most their largest distance from the origin; 0 for a link without geometry.
  double axisRadius(int link, const Eigen::Vector3d& axis) const;
  // The axis tables' cells: kAxisCells x kAxisCells per half cube face (an axis and its opposite
  // share a cell).
  static constexpr int kAxisCells = 32;

  // The robot's checked self pairs (RobotModel::checkedPairs at construction), in its order.
  const std::vector<std::pair<int, int>>& pairs() const { return pairs_; }
  // How much the distance between the two links of pair p can change along the straight-line
  // motion dq (variableCount() values): the sum of the two links' path-length bounds in their
  // common ancestor's frame; 0 when no joint moves them apart.
  double pairBound(std::size_t p, const double* dq) const;
  // Pair p's lever for variable v (pairBound is sum_v pairLever(p, v) |dq_v|): 0 when no joint
  // of that variable moves one link of the pair and not the other.
  double pairLever(std::size_t p, int variable) const {
    return pair_levers_[p * static_cast<std::size_t>(variable_count_) +
                        static_cast<std::size_t>(variable)];
  }
  // A lower bound (>= 0) on the distance between the two links' geometry of pair p at the link
  // poses in `data`, or `cap` when that bound is at least `cap`: spheres about the links'
  // points (a whole-link sphere, then kPairSlabs spheres each along the link's longest side).
  double pairDistance(std::size_t p, const RobotData& data, double cap) const;
  static constexpr int kPairSlabs = 4;

  // Posed bounds (fixed-base robots). The levers above hold over every configuration (the arm
  // stretched); at a given pose the joints' axes are mostly nearer. Along a straight-line
  // motion q(t) = q0 + t dq, a point x of link l moves at a speed of at most
  // sum_j |dq_v(j)| m_j d_j(t), d_j(t) its distance from joint j's axis (m_j the mimic
  // multiplier; a prismatic joint's d_j is 1). d_j changes only through the joints below j
  // (turning about j's own axis keeps it), so d_j(t) <= d_j(0) + |t| S_j with S_j the levers
  // below j times their |dq|; over a part of length s from a posed end the path is at most
  // rate * s + growth * s^2 / 2, rate = sum_j |dq_v(j)| m_j d_j(0) (linkRate, pairRate) and
  // growth = sum_j |dq_v(j)| m_j S_j (EdgeTerms). d_j(0) is bounded by the distance from the
  // axis to the link's sphere (its centre's plus its radius) and by j's lever (posedArms).
  //
  // A second posed bound keeps the joints' directions (linkSpeed, pairSpeed): the velocity of a
  // point x is sum_j dq_v(j) m_j u_j(x) (m_j with its sign here), u_j(x) = cross(w_j, x - p_j)
  // for a revolute joint (axis w_j through p_j) and w_j for a prismatic one, so over the link's
  // sphere (centre c, radius r) the speed is at most |V| + |W| r, V = sum_j dq_j m_j u_j(c),
  // W = sum_j dq_j m_j w_j over its revolute joints. Where the joints' motions partly cancel (an
  // elbow bending back while the shoulder lifts) it is well below the sum of the arms. Along the
  // motion, u_j turns with the frame of j's parent (at most Omega_j = sum of |dq| m over the
  // revolute joints above j) and changes with the motion of x relative to that frame (at most T_j =
  // sum over j and the joints below it of |dq| m times their lever), so the speed grows at most at
  // sum_j |dq_j| m_j (Omega_j lever_j + T_j) (speed growth; a prismatic joint's term has no T_j).
  // A pair's distance changes at most at the sum of its two links' speeds relative to their
  // common ancestor: the same sums over the pair's arms alone.
  //
  // Per link and each movable joint on its path ("arms"): armCount() arms of kArmValues values
  // each (the distance to the axis, V's and W's terms), posedArms writes those of one link (or
  // of every link).
  static constexpr std::size_t kArmValues = 7;
  std::size_t armCount() const { return path_joints_.size(); }
  void posedArms(const RobotData& data, int link, double* arms) const;
  void posedArms(const RobotData& data, double* arms) const {
    for (int l : geometry_links_) posedArms(data, l, arms);
  }
  // A straight-line motion's weights (|dq_v(j)| m_j per arm, and signed) and the growths of the
  // rates and of the speeds, per link and per pair.
  struct EdgeTerms {
    std::vector<double> weight, signed_weight, link_growth, pair_growth;
    std::vector<double> arm_growth;  // per arm, its part of the growth
    std::vector<double> arm_reach;   // per arm, T_j
    std::vector<double> link_speed_growth, pair_speed_growth;
  };
  void edgeTerms(const double* dq, EdgeTerms& terms) const;
  // The rate of link l (pair p) at a pose whose arms are given, for the motion of `terms`.
  double linkRate(int link, const EdgeTerms& terms, const double* arms) const;
  double pairRate(std::size_t p, const EdgeTerms& terms, const double* arms) const;
  // The speed bound of link l (pair p) at a pose whose arms are given (with the speed growth).
  double linkSpeed(int link, const EdgeTerms& terms, const double* arms) const;
  double pairSpeed(std::size_t p, const EdgeTerms& terms, const double* arms) const;
  // The same speeds from sums made once per pose: speedSums writes, for each arm k on link l's
  // path, V's and W's sums over k and the arms after it (kSumValues values at sums +
  // k * kSumValues). A pair's arms on a link are the end of that link's path (the joints above
  // the two links' common ancestor move both), so its speed is read from two such sums.
  static constexpr std::size_t kSumValues = 6;
  void speedSums(int link, const EdgeTerms& terms, const double* arms, double* sums) const;
  double linkSpeedFromSums(int link, const double* sums) const {
    return speedFrom(link, path_begin_[static_cast<std::size_t>(link)], sums);
  }
  // Needs the sums of both links.
  double pairSpeedFromSums(std::size_t p, const double* sums) const {
    return speedFrom(pairs_[p].first, pair_suffix_[2 * p], sums) +
           speedFrom(pairs_[p].second, pair_suffix_[2 * p + 1], sums);
  }
  // How fast link l's points move along the unit direction u (world frame) at a pose whose
  // speed sums are given: at most u . V + |u x W| r over the link's sphere (centre velocity V,
  // angular velocity W, radius r), and along -u at most -u . V + |u x W| r (`away`, the rate at
  // which the points move along u as the motion runs backwards). Along the motion the rate
  // changes at most at the speed growth (the bound on how fast a point's velocity vector turns
  // or grows), so over a part of length s the points advance along u by at most
  // rate * s + speed_growth * s^2 / 2. A micrometre covers rounding, as in the speed.
  void linkApproach(int link, const double* sums, const Eigen::Vector3d& u, double& toward,
                    double& away) const {
    const std::size_t first = path_begin_[static_cast<std::size_t>(link)];
    if (first >= path_begin_[static_cast<std::size_t>(link) + 1]) {
      toward = away = 0.0;
      return;
    }
    const Eigen::Map<const Eigen::Vector3d> V(sums + first * kSumValues);
    const Eigen::Map<const Eigen::Vector3d> W(sums + first * kSumValues + 3);
    const double along = u.dot(V);
    const double turn = u.cross(W).norm() * spheres_[static_cast<std::size_t>(link)].radius + 1e-6;
    toward = along + turn;
    away = turn - along;
  }

 private:
  // A movable joint on a link's path from the root (root first), with its fixed lever.
  struct PathJoint {
    int joint, variable, axis_link;  // axis_link: the joint's child, whose frame holds the axis
    double multiplier, lever;        // multiplier: the mimic multiplier's magnitude
    double sign;                     // the mimic multiplier's sign
    bool revolute;
    Eigen::Vector3d axis;  // unit, in axis_link's frame
  };
  std::vector<PathJoint> path_joints_;  // per link, in order (path_begin_ per link)
  std::vector<int> arm_link_;           // per arm, the link whose path holds it
  int pathOf(std::size_t arm) const { return arm_link_[arm]; }
  // The speed growth and the speed over arms [begin, end) (of `indices` when given): one link's
  // path, or a pair's arms (each link's in turn).
  double speedGrowth(const EdgeTerms& terms, std::size_t begin, std::size_t end,
                     const std::size_t* indices) const;
  double speedOver(const EdgeTerms& terms, const double* arms, std::size_t begin, std::size_t end,
                   const std::size_t* indices) const;
  std::vector<std::size_t> path_begin_;              // linkCount() + 1 offsets
  std::vector<std::size_t> pair_arms_, pair_begin_;  // per pair: its arms (pairBound's joints)
  // Per pair, the first of its arms on each link's path (the path's end when it has none).
  std::vector<std::size_t> pair_suffix_;
  // Link l's speed bound |V| + |W| r for the sums V and W over some of its arms; a micrometre
  // covers rounding.
  double speedOf(int link, const Eigen::Vector3d& V, const Eigen::Vector3d& W) const {
    return V.norm() + W.norm() * spheres_[static_cast<std::size_t>(link)].radius + 1e-6;
  }
  // speedOf from the sums at arm `first` of link l's path (0 past its end).
  double speedFrom(int link, std::size_t first, const double* sums) const {
    if (first >= path_begin_[static_cast<std::size_t>(link) + 1]) return 0.0;
    const double* s = sums + first * kSumValues;
    return speedOf(link, Eigen::Map<const Eigen::Vector3d>(s),
                   Eigen::Map<const Eigen::Vector3d>(s + 3));
  }
  struct Spheres {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  // in the link frame
    double radius = 0;
    std::vector<Eigen::Vector4d> slabs;  // centre (link frame), radius
  };
  static Spheres makeSpheres(const std::vector<Eigen::Vector3d>& points);
  std::vector<std::pair<int, int>> pairs_;
  std::vector<double> pair_levers_;  // pair-major, per variable
  std::vector<Spheres> spheres_;     // per link (empty slabs: no geometry)

  // Free-flying robots: per link, the bound of the distance from an axis in each cell of axis
  // directions (rounded up to float; empty for fixed-base robots and links without geometry).
  std::vector<std::vector<float>> axis_radius_;
  static int axisCell(const Eigen::Vector3d& axis);

  int link_count_ = 0;
  int variable_count_ = 0;
  std::vector<double> levers_;       // link-major
  std::vector<int> geometry_links_;  // links with geometry
  double radius_ = 0.0;
};

}  // namespace octomotion
