#include "octomotion/planner/ompl/link_pose_goal.h"

#include <cmath>
#include <limits>
#include <ostream>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalStates.h>

#include "octomotion/planner/ompl/state_space.h"

namespace octomotion {

namespace ob = ompl::base;

LinkPoseGoal::LinkPoseGoal(const ob::SpaceInformationPtr& si,
                           std::shared_ptr<const RobotModel> robot, const Eigen::Isometry3d& X_WB,
                           const LinkPoseTarget& target, const IkOptions& options,
                           std::uint64_t seed, double orientation_weight)
    : ob::GoalSampleableRegion(si),
      robot_(std::move(robot)),
      solver_(*robot_, X_WB, options),
      target_(target),
      orientation_weight_(orientation_weight),
      rng_(seed),
      scratch_(solver_.makeScratch()),
      seed_(static_cast<std::size_t>(robot_->variableCount())) {
  if (target_.link < 0 || target_.link >= robot_->linkCount()) {
    throw InvalidArgument("link pose goal: link index " + std::to_string(target_.link) +
                          " is not a link of robot '" + robot_->name() + "'");
  }
  target_ = solver_.target(robot_->link(target_.link).name, target_.position, target_.orientation);
  if (!(std::isfinite(orientation_weight) && orientation_weight >= 0)) {
    throw InvalidArgument("link pose goal: the orientation weight must be finite and >= 0");
  }
  // OMPL's own threshold test (GoalRegion) would accept what distanceGoal puts within it; ours
  // tests both tolerances, and the threshold is only what planners read as the goal's size.
  setThreshold(options.position_tolerance +
               (target_.orientation ? orientation_weight_ * options.orientation_tolerance : 0.0));
}

bool LinkPoseGoal::sampleValidGoal(ob::State* state, int solves) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  double best = std::numeric_limits<double>::infinity();
  bool written = false;
  for (int k = 0; k < solves; ++k) {
    solver_.randomConfiguration(rng_, seed_);
    const IkResult r = solver_.solve(target_, seed_, rng_, scratch_);
    const double cost = r.position_error + orientation_weight_ * r.orientation_error;
    if (r.success || cost < best || !written) {
      configurationToState(*robot_, r.q, Eigen::Isometry3d::Identity(), state);
      written = true;
      best = std::min(best, cost);
    }
    if (r.success && si_->isValid(state)) return true;
  }
  return false;
}

void LinkPoseGoal::sampleGoal(ob::State* state) const {
  sampleValidGoal(state, kSolvesPerSample);
}

unsigned int LinkPoseGoal::maxSampleCount() const {
  return std::numeric_limits<unsigned int>::max();
}

bool LinkPoseGoal::errors(const ob::State* state, double& position, double& orientation) const {
  std::vector<double> q(static_cast<std::size_t>(robot_->variableCount()));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (!stateToConfiguration(*robot_, state, q, X)) return false;
  RobotData data = robot_->makeData();
  const auto e = solver_.errors(target_, q, data);
  position = e.first;
  orientation = e.second;
  return true;
}

double LinkPoseGoal::distanceGoal(const ob::State* state) const {
  double position = 0, orientation = 0;
  if (!errors(state, position, orientation)) return std::numeric_limits<double>::infinity();
  return position + orientation_weight_ * orientation;
}

bool LinkPoseGoal::isSatisfied(const ob::State* state) const {
  return isSatisfied(state, nullptr);
}

bool LinkPoseGoal::isSatisfied(const ob::State* state, double* distance) const {
  double position = 0, orientation = 0;
  if (!errors(state, position, orientation)) {
    if (distance) *distance = std::numeric_limits<double>::infinity();
    return false;
  }
  if (distance) *distance = position + orientation_weight_ * orientation;
  const IkOptions& o = solver_.options();
  return position <= o.position_tolerance && orientation <= o.orientation_tolerance;
}

void LinkPoseGoal::print(std::ostream& out) const {
  out << "Link pose goal: link '" << robot_->link(target_.link).name << "' at ["
      << target_.position.transpose() << "]";
  if (target_.orientation)
    out << " orientation (xyzw) [" << target_.orientation->coeffs().transpose() << "]";
  out << ", tolerances " << solver_.options().position_tolerance << " m, "
      << solver_.options().orientation_tolerance << " rad\n";
}

bool plannerNeedsGoalStates(const std::string& planner) {
  // The informed samplers of InformedRRTstar and BITstar take their foci from goal states
  // (GOAL_STATE(S) only); FMT draws every goal sample before it starts (assureGoalIsSampled asks
  // for samples until maxSampleCount), which a region without end never finishes.
  return planner == "InformedRRTstar" || planner == "BITstar" || planner == "FMT";
}

ob::GoalPtr makeLinkPoseGoal(const ob::SpaceInformationPtr& si,
                             std::shared_ptr<const RobotModel> robot, const Eigen::Isometry3d& X_WB,
                             const LinkPoseGoalSpec& spec, const std::string& planner,
                             std::uint64_t seed) {
  if (robot->isFreeFlying()) {
    throw InvalidArgument("problem.goal.link: robot '" + robot->name() +
                          "' is a free-flying body; give its goal as a pose {xyz, rpy|quat}");
  }
  if (robot->findLink(spec.link) < 0) {
    throw InvalidArgument("problem.goal.link: robot '" + robot->name() + "' has no link '" +
                          spec.link + "'");
  }
  IkOptions options;
  options.position_tolerance = spec.position_tolerance;
  options.orientation_tolerance = spec.orientation_tolerance;
  LinkPoseTarget target;
  target.link = robot->findLink(spec.link);
  target.position = spec.position;
  target.orientation = spec.orientation;
  auto goal = std::make_shared<LinkPoseGoal>(si, robot, X_WB, target, options, seed);
  if (!plannerNeedsGoalStates(planner)) return goal;
  auto states = std::make_shared<ob::GoalStates>(si);
  ob::ScopedState<> state(si);
  for (int solves = 0; solves < kPresampleSolves && states->getStateCount() < kPresampledGoals;
       ++solves) {
    if (goal->sampleValidGoal(state.get(), 1)) states->addState(state);
  }
  if (states->getStateCount() == 0) {
    throw InvalidArgument("problem.goal: no valid configuration puts link '" + spec.link +
                          "' within the tolerances in " + std::to_string(kPresampleSolves) +
                          " inverse kinematics solves (planner " + planner +
                          " needs goal states); is the pose reachable and free?");
  }
  return states;
}

}  // namespace octomotion
