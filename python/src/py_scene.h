// The Python module's Scene: a PlanningScene with its OMPL space, checked from NumPy arrays of
// states. Only the planner library's public API is used.
#pragma once

#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/tools/problem_set.h"

namespace octomotion::python {

// One reason a state is invalid (InvalidityReason, plus "bounds" for a state outside the space's
// bounds only), with its line of text (describe()).
struct Reason {
  std::string kind;  // "non-finite", "outside-limits", "environment", "self", "bounds"
  std::string link, other;
  std::string exact;  // "touching", "apart", "unknown"
  double margin = 0, value = 0, lower = 0, upper = 0;
  std::string text;
};

// A shape given by the scene file's keys: exactly one of box (full sizes), sphere (radius),
// cylinder (radius, length), mesh (a file, with scale).
struct ShapeArgs {
  std::optional<std::vector<double>> box;
  std::optional<double> sphere;
  std::optional<std::vector<double>> cylinder;
  std::optional<std::string> mesh;
  std::optional<std::vector<double>> scale;
};

// Queries share the scene; plan and the world updates take it alone (a shared_mutex), so calls
// from several Python threads wait for each other instead of racing.
class Scene {
 public:
  // `flags`: command-line scene options (tools::sceneOptions()) as (flag, value) pairs.
  Scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags,
        bool require_free_start_goal, bool fit_universe_to_reach);

  int dof() const { return dof_; }
  const std::vector<std::string>& jointNames() const { return names_; }
  bool freeFlying() const;
  std::string checkerName() const { return checkerKindName(scene_->checker); }
  double resolution() const { return scene_->spec.octree.resolution.value_or(0.0); }
  const std::string& path() const { return scene_->spec.path; }
  // The state space's bounds per column (joint limits; free-flying: the position bounds and
  // [-1, 1] for the quaternion), for sampling states.
  std::pair<std::vector<double>, std::vector<double>> bounds() const;

  // The OMPL checker's answer (as `octomotion check`): in bounds, finite and collision-free.
  bool check(const double* q) const;
  // rows × dof states, row-major; `valid` gets one 0/1 per row. Threads share the checker, each
  // with its own scratch (the checker keeps one per thread). Call without the GIL.
  void checkMany(const double* Q, std::size_t rows, std::uint8_t* valid, unsigned threads) const;
  double clearance(const double* q) const;
  std::vector<Reason> explain(const double* q) const;
  // World pose of every link (the robot's mount or, free-flying, the state's pose applied).
  std::vector<std::pair<std::string, Eigen::Matrix4d>> forwardKinematics(const double* q) const;

  // Plans from start to goal (the scene's when not given); an empty path when none was found.
  std::vector<double> plan(const std::string& planner, std::optional<double> time,
                           std::optional<std::uint64_t> seed, const std::vector<double>* start,
                           const std::vector<double>* goal, double interpolation,
                           std::size_t& states);

  // World updates (PlanningScene::addObject and the others). Poses are 4×4 homogeneous matrices.
  void addObject(const std::string& name, const ShapeArgs& shape, const Eigen::Matrix4d& X_WO);
  void removeObject(const std::string& name);
  void moveObject(const std::string& name, const Eigen::Matrix4d& X_WO);
  void attachObject(const std::string& name, const std::string& link, const ShapeArgs& shape,
                    const Eigen::Matrix4d& X_LO, const std::vector<std::string>& touch_links);
  void detachObject(const std::string& name, const std::vector<double>* leave_at);
  std::vector<std::string> objectNames() const;
  std::vector<std::string> attachedNames() const;

 private:
  bool checkUnlocked(const double* q) const;
  std::vector<Reason> explainUnlocked(const double* q) const;
  void setState(const double* q, ompl::base::State* state) const;
  std::vector<double> configuration(const double* q, Eigen::Isometry3d& X_WB, bool& finite) const;

  mutable std::shared_mutex mutex_;
  std::shared_ptr<PlanningScene> scene_;
  ompl::base::SpaceInformationPtr si_;
  // The scene's own start (empty when none) and goal, restored when plan() is not given them.
  std::vector<double> scene_start_;
  ompl::base::GoalPtr scene_goal_;
  int dof_ = 0;
  std::vector<std::string> names_;
};

// The trade study (tools::runTradeStudy) with `octomotion bench`'s flags; returns the check and
// planning CSV text.
std::pair<std::string, std::string> tradeStudy(
    const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags);

// The planning benchmark over a folder of problems (tools::runProblemSet, `octomotion bench-set`)
// with the command's scene options as `flags`. MoveIt pairs' scene files go to a temporary folder
// removed afterwards; OMPL logs are written to `log_dir` when it is not empty.
struct BenchSetResult {
  std::string runs_csv;  // tools::writeProblemCsv
  std::vector<tools::SetSummary> summary;
  std::vector<std::string> logs;
  double seconds = 0;
};
BenchSetResult benchSet(tools::ProblemSetOptions options,
                        const std::vector<std::pair<std::string, std::string>>& flags,
                        const std::string& log_dir);

}  // namespace octomotion::python
