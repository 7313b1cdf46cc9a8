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
// The geometry is read once (meshes through CollisionMeshes with the conventions given, so the
// points are those the collision models use); primitives by their bounding box's corners.
#pragma once

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
  // Free-flying bodies: the largest distance of a point from the root frame's origin, over every
  // configuration of the robot's own joints (held joints included in their transforms).
  double radius() const { return radius_; }
  double freeFlyingBound(double translation, double angle) const {
    return translation + radius_ * angle;
  }

 private:
  int link_count_ = 0;
  int variable_count_ = 0;
  std::vector<double> levers_;       // link-major
  std::vector<int> geometry_links_;  // links with geometry
  double radius_ = 0.0;
};

}  // namespace octomotion
