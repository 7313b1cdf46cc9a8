// Inverse kinematics: joint values that put one link at a world position (and optionally a world
// orientation). Damped least squares (Levenberg-Marquardt) on the analytic Jacobian of the chain
// from the root to the link, over the model's variables only: a joint the model holds fixed
// (fixed in the URDF, or made fixed by a reduction) is not moved, a mimic joint moves with its
// master (its column, times its multiplier, adds to the master's). Bounded variables are clamped
// into their limits at every step; continuous ones are free and wrapped into [-pi, pi] (the range
// the planner's state space gives them). When a descent stalls (a local minimum, a limit), the
// solver restarts from a configuration drawn uniformly within the limits by the caller's RNG, so a
// seeded RNG gives the same answer every time.
//
// The model is only read; the solver keeps no state between calls, and every call works in the
// caller's IkScratch (one per thread), whose inner loop allocates nothing.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

// Where a link should be, in the world frame (the frame forwardKinematics gives poses in: the
// base pose X_WB passed to the solver is included).
struct LinkPoseTarget {
  int link = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<Eigen::Quaterniond> orientation;  // empty: any orientation (position only)
};

struct IkOptions {
  double position_tolerance = 1e-3;     // metres; > 0
  double orientation_tolerance = 1e-2;  // radians; > 0 (ignored without a target orientation)
  // Forward kinematics evaluations per attempt (one per accepted or rejected step), and attempts
  // (the first from the caller's seed, the others from random configurations): a solve costs at
  // most max_iterations * max_attempts evaluations, reachable target or not.
  int max_iterations = 150;
  int max_attempts = 20;
  // The largest change of one variable in one step (radians or metres): keeps the linearisation
  // honest far from the target.
  double max_step = 0.5;
};

struct IkResult {
  bool success = false;   // both errors within the tolerances
  std::vector<double> q;  // the solution, or the closest configuration found
  double position_error = std::numeric_limits<double>::infinity();     // metres
  double orientation_error = std::numeric_limits<double>::infinity();  // radians; 0 without one
  int iterations = 0;  // forward kinematics evaluations, over every attempt
  int attempts = 0;
};

// Per-thread scratch of one solver (InverseKinematics::makeScratch).
struct IkScratch {
  RobotData data;
  Eigen::Matrix<double, 6, Eigen::Dynamic> J;
  std::vector<double> q, trial, best;
  std::vector<int> chain;  // movable joints between the root and the target link
};

class InverseKinematics {
 public:
  // `robot` must outlive the solver. X_WB: the root link's pose in the world (a robot's mount).
  // Throws InvalidArgument for a free-flying robot (give its goal as a pose), a robot without
  // variables, non-finite X_WB, or options out of range.
  explicit InverseKinematics(const RobotModel& robot,
                             const Eigen::Isometry3d& X_WB = Eigen::Isometry3d::Identity(),
                             const IkOptions& options = {});

  const RobotModel& robot() const { return *robot_; }
  const IkOptions& options() const { return options_; }
  const Eigen::Isometry3d& basePose() const { return X_WB_; }
  IkScratch makeScratch() const;

  // A target for the link named `link` (InvalidArgument naming it when unknown, or for a
  // non-finite position, or a zero or non-finite orientation, which is normalised).
  LinkPoseTarget target(const std::string& link, const Eigen::Vector3d& position,
                        const std::optional<Eigen::Quaterniond>& orientation = {}) const;

  // Solves from `seed` (variableCount() values; clamped into the limits), then from random
  // configurations drawn with `rng`. Throws InvalidArgument for a bad target (see target()) or a
  // seed of the wrong size or with a non-finite value.
  IkResult solve(const LinkPoseTarget& target, const std::vector<double>& seed,
                 std::mt19937_64& rng, IkScratch& scratch) const;
  // The same with its own scratch and an RNG seeded with `rng_seed`.
  IkResult solve(const LinkPoseTarget& target, const std::vector<double>& seed,
                 std::uint64_t rng_seed = 0) const;

  // The link's position error (metres) and orientation error (radians, 0 without a target
  // orientation) at q, by forward kinematics.
  std::pair<double, double> errors(const LinkPoseTarget& target, const std::vector<double>& q,
                                   RobotData& data) const;

  // The link's geometric Jacobian at q: rows [linear velocity of the link origin; angular
  // velocity], world frame, one column per variable (what the solver descends along).
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian(int link, const std::vector<double>& q) const;

  // A configuration drawn uniformly within the limits (continuous joints in [-pi, pi]).
  void randomConfiguration(std::mt19937_64& rng, std::vector<double>& q) const;

 private:
  void checkTarget(const LinkPoseTarget& target) const;

  const RobotModel* robot_;
  Eigen::Isometry3d X_WB_;
  IkOptions options_;
};

}  // namespace octomotion
