// OMPL state spaces for a robot, and the conversions between their states and configurations.
//
// State spaces (makeStateSpace):
// - fixed-base robots: a RealVectorStateSpace with one dimension per entry of q, in
//   RobotModel::variables() order (movable, non-mimic joints in depth-first URDF order), bounded
//   by the URDF limits; continuous joints get [-pi, pi] (the planner does not take the short way
//   across +-pi; any value is still valid for forward kinematics);
// - free-flying robots: an SE3StateSpace with the given position bounds; the quaternion is
//   normalised before use (OMPL keeps it unit; a zero or NaN quaternion is invalid).
#pragma once

#include <vector>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <Eigen/Geometry>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

ompl::base::StateSpacePtr makeStateSpace(const RobotModel& robot,
                                         const Eigen::AlignedBox3d* position_bounds = nullptr);

// Reads a state of a space made by makeStateSpace into q (fixed base) or X_WB (free-flying).
// Returns false when the state holds a NaN/Inf or an unusable quaternion.
bool stateToConfiguration(const RobotModel& robot, const ompl::base::State* state,
                          std::vector<double>& q, Eigen::Isometry3d& X_WB);

// The inverse, for starts and goals.
void configurationToState(const RobotModel& robot, const std::vector<double>& q,
                          const Eigen::Isometry3d& X_WB, ompl::base::State* state);

// SpaceInformation::satisfiesBounds, the test every checker's isValid starts with, without
// OMPL's virtual call per component: on the spaces makeStateSpace builds (exactly SE3StateSpace
// or RealVectorStateSpace) it applies OMPL's own rules inline to the space's current bounds —
// joints and positions within the bounds up to one machine epsilon, a quaternion's norm within
// 1e-9 of 1 — and gives OMPL's answer (tests compare the two); any other space is passed to OMPL.
class BoundsCheck {
 public:
  explicit BoundsCheck(const ompl::base::SpaceInformationPtr& si);
  bool operator()(const ompl::base::State* state) const;

 private:
  const ompl::base::SpaceInformation* si_;
  const ompl::base::RealVectorStateSpace* joints_ = nullptr;    // the space, or
  const ompl::base::RealVectorStateSpace* position_ = nullptr;  // SE(3)'s first component
};

}  // namespace octomotion
