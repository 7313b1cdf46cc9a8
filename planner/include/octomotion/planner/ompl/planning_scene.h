// From a scene file to an OMPL problem: loads the robot (URDF + SRDF, or a rigid-body mesh),
// builds the collision model on a universe fitted to the scene, makes the state space and the
// validity checker, and solves with the scene's OMPL planner.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/reference/fcl_octomap_collision_model.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// What the command line may override in a scene.
struct SceneOverrides {
  std::optional<double> resolution;  // metres; NaN-free, > 0
  bool auto_resolution = false;      // --resolution auto
  std::optional<Rounding> rounding;
  std::optional<CheckerKind> checker;
  std::optional<std::string> planner;
  std::optional<MotionValidatorKind> motion_validator;  // problem.motion_validator
  std::optional<double> time;
  std::optional<std::uint64_t> seed;
  std::optional<double> range;  // > 0; problem.range
  std::vector<std::string> package_paths;
  std::optional<double> max_surface_voxels;    // > 0; the memory guard, see CollisionModelOptions
  std::optional<double> link_resolution;       // > 0; octree.link_resolution
  std::optional<double> self_link_resolution;  // > 0; octree.self_link_resolution
  std::optional<bool> self_pair_tables;        // octree.self_pair_tables
  std::optional<bool> exact_primitives;        // octree.exact_primitives
  std::optional<RefineMode> refine;            // octree.refine
  // loadPlanningScene refuses a start or goal in collision (requireFreeStartAndGoal); commands
  // that look at colliding states on purpose (check, view) turn it off.
  bool require_free_start_goal = true;
  // CollisionModelOptions::fit_universe_to_reach: for scenes whose world changes between plans
  // (PlanningScene::addObject and the others).
  bool fit_universe_to_reach = false;
};

// The resolution used when a scene says `auto` (or a .cfg says nothing): fixed-base arms 1 cm;
// free-flying bodies max(scene diagonal / 1024, robot diagonal / 32), so the body spans about 32
// voxels and the universe needs at most 10 levels.
double autoResolution(const RobotModel& robot, const Eigen::AlignedBox3d& scene_box,
                      double robot_diagonal);

// A model built on first use, once, whichever thread asks first (the reference checkers cost
// time and memory that a scene planned with the octree checker should not pay). Reads like the
// shared_ptr it holds: `lazy->f()`, `*lazy`, and converts to std::shared_ptr<const Model>.
template <class Model>
class LazyModel {
 public:
  LazyModel() = default;
  explicit LazyModel(std::function<std::shared_ptr<const Model>()> build)
      : state_(std::make_shared<State>()) {
    state_->build = std::move(build);
  }
  // Builds the model the first time (a build that throws is retried by the next call).
  const std::shared_ptr<const Model>& get() const {
    if (!state_) throw Error("LazyModel: no model to build");
    std::call_once(state_->once, [this] { state_->model = state_->build(); });
    return state_->model;
  }
  bool built() const { return state_ && state_->model; }
  const Model* operator->() const { return get().get(); }
  const Model& operator*() const { return *get(); }
  operator std::shared_ptr<const Model>() const { return get(); }  // NOLINT: reads as a pointer

 private:
  struct State {
    std::once_flag once;
    std::function<std::shared_ptr<const Model>()> build;
    std::shared_ptr<const Model> model;
  };
  std::shared_ptr<State> state_;
};

// The box of every link's collision geometry at the zero configuration, in the root frame (reads
// the mesh files). Free-flying bodies use its diagonal for autoResolution and the SE(3) bounds.
Eigen::AlignedBox3d robotGeometryBox(const RobotModel& robot);

struct PlanningScene {
  SceneSpec spec;  // with the overrides applied
  // Not const: the world updates below change it in place (between plans).
  std::shared_ptr<OctreeCollisionModel> model;
  // The references on the same robot and environment, built on first use (already built when
  // the scene's checker is one of them): exact FCL, and FCL on an OctoMap of the environment at
  // the scene's resolution.
  LazyModel<FclCollisionModel> fcl_model;
  LazyModel<FclOctomapCollisionModel> fcl_octomap_model;
  std::shared_ptr<const FclCollisionModel> fclModel() const { return fcl_model.get(); }
  std::shared_ptr<const FclOctomapCollisionModel> fclOctomapModel() const {
    return fcl_octomap_model.get();
  }
  std::shared_ptr<const EnvironmentGeometry> environment;  // the loaded objects
  ompl::geometric::SimpleSetupPtr setup;  // checker installed, start/goal set if the scene has them
  CheckerKind checker = CheckerKind::kOctreeFused;  // the checker in use

  // ---- A world that changes between plans (docs/robots.md; planning_scene_world.cpp): one
  // call updates the octree model in place (OctreeCollisionModel::addObject and the others),
  // `environment`, the references (rebuilt on next use, with the attached objects) and the
  // checker, and clears the planner's data (setup->clear()). Not while a plan runs.
  void addObject(const EnvironmentObject& object, const WarningSink& warnings = {});
  void removeObject(const std::string& name);
  void moveObject(const std::string& name, const Eigen::Isometry3d& X_WO);
  void attachObject(const AttachedObject& object, const WarningSink& warnings = {});
  // With `leave_at_q` (a configuration, RobotModel::variables() order) the object stays in the
  // world where its link holds it there.
  void detachObject(const std::string& name, const std::vector<double>* leave_at_q = nullptr);
  std::vector<AttachedObject> attached;  // what is attached now, in order
};

// The octree model's query for an octree checker kind (kOctree: moveTree, kOctreeFused: the
// fused query); InvalidArgument for the FCL kinds.
CheckerPath octreeCheckerPath(CheckerKind kind);

// Sets the space's state-validity checking resolution (if OMPL's is coarser) so that no point of
// the robot moves more than two voxels of `resolution` between the checked states of a motion.
// `reach`: for arms, half the largest side of the region the robot can reach
// (CollisionModelReport::reach_W); for free-flying bodies, the robot's diagonal. loadPlanningScene
// uses it; so should any caller that plans on its own SpaceInformation.
void boundMotionStep(ompl::base::SpaceInformation& si, const RobotModel& robot, double reach,
                     double resolution);

// The scene's motion validator (problem.motion_validator) on its setup's SpaceInformation, over
// `backend` (the scene's checker) at the scene's resolution, with the attached objects in the
// links' motion bound (ompl/certified_motion_validator.h). loadPlanningScene and the world
// updates call it.
void installMotionValidator(PlanningScene& scene,
                            const std::shared_ptr<const CollisionBackend>& backend);

// A SimpleSetup for a scene file in one call: loadPlanningScene's setup — the scene's robot,
// environment, resolution, checker, planner, start and goal, and motion validator (certified by
// default). The setup keeps the models it needs alive.
ompl::geometric::SimpleSetupPtr makeSimpleSetup(const std::string& scene_path,
                                                const SceneOverrides& overrides = {},
                                                const WarningSink& warnings = {});

// What loadPlanningScene reads before it builds any model: the scene with the overrides applied
// (octree.resolution resolved, auto included; problem.bounds set for free-flying bodies), the
// robot and the environment. Callers that build their own models (several settings of one
// scene, for instance) start here; it leaves OMPL (and its seed) alone.
struct SceneInputs {
  SceneSpec spec;
  std::optional<RobotModel> robot;
  std::shared_ptr<const EnvironmentGeometry> environment;
  double robot_diagonal = 0;     // free-flying bodies: their geometry's diagonal; arms: 0
  bool bounds_given = false;     // the scene gave problem.bounds (else the environment's box)
  std::string resolution_field;  // how errors name the resolution's origin
};
SceneInputs loadSceneInputs(const std::string& scene_path, const SceneOverrides& overrides = {},
                            const WarningSink& warnings = {});

// Throws octomotion::Error (naming the file and field) for anything wrong with the scene: a start
// or goal outside the joint limits or bounds, or (unless overrides.require_free_start_goal is
// off) in collision for the scene's checker (requireFreeStartAndGoal).
PlanningScene loadPlanningScene(const std::string& scene_path, const SceneOverrides& overrides = {},
                                const WarningSink& warnings = {});

// The scene's checker as a CollisionBackend (building the reference model it needs).
std::shared_ptr<const CollisionBackend> checkerBackend(const PlanningScene& scene);
// Throws FileError when the scene's start or goal is in collision for its checker, naming the
// contacts (CollisionBackend::explain), e.g. "problem.goal is in collision for the octree-fused
// checker: link panda_hand with object shelf_top", and when only the voxels' margin collides (the
// exact shapes do not touch) "...; the exact shapes do not touch: within the voxel margin of
// resolution R m, try a finer --resolution".
void requireFreeStartAndGoal(const PlanningScene& scene);
// The contacts of a colliding state as that message words them (at most three named).
std::string describeCollision(const StateExplanation& explanation);

// Makes an OMPL geometric planner by name (RRTConnect, RRT, RRTstar, PRM, KPIECE1, BKPIECE1,
// LBKPIECE1, EST, SBL, BITstar, InformedRRTstar, PRMstar, LazyPRM, FMT, ...); InvalidArgument
// otherwise.
ompl::base::PlannerPtr makePlanner(const std::string& name,
                                   const ompl::base::SpaceInformationPtr& si);

// Sets the planner's "range" parameter (how far one extension reaches, in the state space's
// distance) to `range` when given; else leaves the planner's own default (OMPL: a fifth of the
// space's extent). InvalidArgument when `range` is not positive and finite, or when the planner
// has no range parameter (PRM, FMT, ... build their graphs otherwise). loadPlanningScene applies
// problem.range with it.
void setPlannerRange(ompl::base::Planner& planner, std::optional<double> range);

// The range loadPlanningScene gives a planner with one when the scene sets none, for a
// fixed-base robot: this share of the joint space's extent (OMPL's own default is a fifth).
// An edge's certified check costs more the farther its links travel, and long edges rarely
// survive clutter (docs/planner.md, "The planner's range"). Free-flying bodies, and scenes
// with the ompl-default motion validator, keep OMPL's.
inline constexpr double kArmRangeShare = 0.075;

struct PlanResult {
  bool solved = false;  // an exact solution was found
  double seconds = 0;   // planning time
  std::size_t checks = 0;
  std::shared_ptr<ompl::geometric::PathGeometric> path;  // simplified and interpolated
  // The simplified path's own states, before interpolation (what OMPL.app writes).
  std::shared_ptr<ompl::geometric::PathGeometric> waypoints;
};

// Solves the scene's problem (its planner, time limit and seed), simplifies the path and
// interpolates it so consecutive states are at most `resolution` apart in the space's distance
// (0: OMPL's default interpolation).
PlanResult plan(PlanningScene& scene, double interpolation = 0.0);

// OMPL's path format: one state per line, SE(3) as "x y z qx qy qz qw", joints in q order (the
// planned joints only, named on a first "# joints: ..." line; rigid bodies have no such line).
void writePath(const PlanningScene& scene, const ompl::geometric::PathGeometric& path,
               std::ostream& out);

}  // namespace octomotion
