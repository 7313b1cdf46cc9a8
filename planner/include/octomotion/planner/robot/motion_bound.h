// How far any point of each link can travel along a motion (Schwarzer, Saha & Latombe, "Adaptive
// dynamic collision checking for single and multiple articulated robots", IEEE T-RO 2005): the
// certified motion validator (ompl/certified_motion_validator.h) compares it with the clearance.
//
// Fixed-base robots, straight-line motions in q: the path of any point of link l is at most
// sum_v lever(l, v) |dq_v|, where lever(l, v) bounds, over every configuration, the distance from
// the axis of joint v (and of the mimic joints that follow it, times their multiplier) to the
// points of link l; 1 for prismatic joints. Free-flying bodies, a translation dt with a rotation
// by angle theta (OMPL's SE(3) interpolation): at most |dt| + radius * theta, radius bounding the
// distance of every point from the root frame's origin.
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

#include <utility>
#include <vector>

#include <Eigen/Core>

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
  double freeFlyingBound(double translation, double angle) const {
    return translation + radius_ * angle;
  }

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

 private:
  struct Spheres {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  // in the link frame
    double radius = 0;
    std::vector<Eigen::Vector4d> slabs;  // centre (link frame), radius
  };
  static Spheres makeSpheres(const std::vector<Eigen::Vector3d>& points);
  std::vector<std::pair<int, int>> pairs_;
  std::vector<double> pair_levers_;  // pair-major, per variable
  std::vector<Spheres> spheres_;     // per link (empty slabs: no geometry)

  int link_count_ = 0;
  int variable_count_ = 0;
  std::vector<double> levers_;       // link-major
  std::vector<int> geometry_links_;  // links with geometry
  double radius_ = 0.0;
};

}  // namespace octomotion
