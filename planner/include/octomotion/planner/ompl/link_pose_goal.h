// A goal given as the pose of one robot link, for OMPL: a GoalSampleableRegion whose samples are
// inverse-kinematics solutions (robot/inverse_kinematics.h) that the space's validity checker
// accepts. Goal-sampling planners (RRTConnect, RRT, RRT*, PRM, KPIECE, EST, SBL, ...) use it
// as it is; planners that need goal *states* (the informed samplers of InformedRRTstar and
// BITstar) or draw every goal sample up front (FMT) get a few valid solutions sampled before
// planning (makeLinkPoseGoal).
//
// OMPL calls sampleGoal from one planning thread at a time (PlannerInputStates), but PRM's roadmap
// thread and its goal checks run side by side: sampling holds a lock around the goal's RNG and
// scratch, and distanceGoal / isSatisfied use scratch of their own, so every member is safe to call
// from any thread.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/goals/GoalSampleableRegion.h>

#include "octomotion/planner/robot/inverse_kinematics.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

class LinkPoseGoal : public ompl::base::GoalSampleableRegion {
 public:
  // Metres per radian in distanceGoal: an orientation error of 1 rad counts like a position error
  // of 0.1 m, what it moves a point a hand's length from the link's origin.
  static constexpr double kDefaultOrientationWeight = 0.1;

  // `si`: a space made by makeStateSpace(*robot) (a fixed-base robot) with its validity checker.
  // X_WB: the robot's mount (the target is in the world). `seed` seeds the goal's own RNG.
  // Throws InvalidArgument for a bad target or options (see InverseKinematics).
  LinkPoseGoal(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const RobotModel> robot,
               const Eigen::Isometry3d& X_WB, const LinkPoseTarget& target,
               const IkOptions& options = {}, std::uint64_t seed = 0,
               double orientation_weight = kDefaultOrientationWeight);

  // An IK solution from random seeds that the validity checker accepts; after kSolvesPerSample
  // solves without one, the closest configuration found (which the planner then rejects).
  void sampleGoal(ompl::base::State* state) const override;
  // Up to `solves` IK solves from random seeds; true with a valid solution in `state`.
  bool sampleValidGoal(ompl::base::State* state, int solves) const;
  // A region has no end of samples: different seeds give different solutions.
  unsigned int maxSampleCount() const override;

  // Position error + weight * orientation error of the link at the state (infinite for a state
  // that is not finite).
  double distanceGoal(const ompl::base::State* state) const override;
  // Within both tolerances (the IK solver's); `distance`, when given, gets distanceGoal.
  bool isSatisfied(const ompl::base::State* state) const override;
  bool isSatisfied(const ompl::base::State* state, double* distance) const override;

  const LinkPoseTarget& target() const { return target_; }
  const InverseKinematics& solver() const { return solver_; }
  void print(std::ostream& out) const override;

  static constexpr int kSolvesPerSample = 5;

 private:
  // The errors of the state; false when it is not finite.
  bool errors(const ompl::base::State* state, double& position, double& orientation) const;

  std::shared_ptr<const RobotModel> robot_;
  InverseKinematics solver_;
  LinkPoseTarget target_;
  double orientation_weight_;
  mutable std::mutex mutex_;  // guards rng_, scratch_ and seed_
  mutable std::mt19937_64 rng_;
  mutable IkScratch scratch_;
  mutable std::vector<double> seed_;
};

// The goal a scene's `problem.goal: {link: ...}` asks for, on `si` (a fixed-base robot's space
// with its validity checker): a LinkPoseGoal, or, for a planner whose informed sampler needs goal
// states (plannerNeedsGoalStates), an ompl::base::GoalStates of up to kPresampledGoals valid IK
// solutions found within kPresampleSolves solves. InvalidArgument naming the field
// ("problem.goal.link: ...") for an unknown link or a robot IK cannot drive, and, when goal
// states are needed, for a pose no valid solution was found for.
inline constexpr int kPresampledGoals = 8;
inline constexpr int kPresampleSolves = 200;
bool plannerNeedsGoalStates(const std::string& planner);
ompl::base::GoalPtr makeLinkPoseGoal(const ompl::base::SpaceInformationPtr& si,
                                     std::shared_ptr<const RobotModel> robot,
                                     const Eigen::Isometry3d& X_WB, const LinkPoseGoalSpec& spec,
                                     const std::string& planner, std::uint64_t seed);

}  // namespace octomotion
