#include "octomotion/planner/ompl/planning_scene.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/util/Exception.h>
#include <ompl/util/RandomNumbers.h>

#include "octomotion/octree/mesh.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/link_pose_goal.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/scene/planning_group.h"
#include "octomotion/planner/scene/scene_frames.h"

namespace octomotion {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

// How far (in environment voxels) any point of the robot may move between two checked states of
// a motion. Conservative voxels inflate each surface by up to a voxel diagonal, so a step of two
// voxels rarely lets a contact slip between checks (validation_planned_paths_test re-checks).
constexpr double kMaxStepVoxels = 2.0;

// Below this a motion across the space would need more than a billion checked states (and
// OMPL refuses fractions below machine epsilon with an exception that names nothing).
constexpr double kMinSegmentFraction = 1e-9;

// More states than this in an interpolated path is a spacing typo, not a request.
constexpr double kMaxPathStates = 1e6;

std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The OMPL part of loadPlanningScene and plan, whose ompl::Exceptions the callers translate.
void setUpOmpl(PlanningScene& scene, bool free_flying, double robot_diagonal, double resolution,
               bool bounds_given);
PlanResult planWithOmpl(PlanningScene& scene, double interpolation);

}  // namespace

Eigen::AlignedBox3d robotGeometryBox(const RobotModel& robot) {
  RobotData data = robot.makeData();
  const std::vector<double> q(static_cast<std::size_t>(robot.variableCount()), 0.0);
  robot.forwardKinematics(q.data(), q.size(), data);
  Eigen::AlignedBox3d box;
  // A size estimate: the files' meshes as stored (no root transform, not centred).
  CollisionMeshes meshes(false, false);
  for (int l = 0; l < robot.linkCount(); ++l) {
    for (const CollisionElement& e : robot.link(l).collision) {
      const Eigen::Isometry3d X = data.linkPose(l) * e.X_LE;
      if (const auto* p = std::get_if<Primitive>(&e.geometry)) {
        box.extend(boundingBox(*p, X));
      } else {
        for (const Eigen::Vector3d& v : meshes.get(std::get<MeshRef>(e.geometry)).vertices) {
          box.extend(X * v);
        }
      }
    }
  }
  return box;
}

double autoResolution(const RobotModel& robot, const Eigen::AlignedBox3d& scene_box,
                      double robot_diagonal) {
  if (!robot.isFreeFlying()) return 0.01;
  const double scene = scene_box.isEmpty() ? 0.0 : scene_box.diagonal().norm();
  return std::max(scene / 1024.0, robot_diagonal / 32.0);
}

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si) {
  using Factory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;
  static const std::map<std::string, Factory> factories = {
      {"RRTConnect", [](auto s) { return std::make_shared<og::RRTConnect>(s); }},
      {"RRT", [](auto s) { return std::make_shared<og::RRT>(s); }},
      {"RRTstar", [](auto s) { return std::make_shared<og::RRTstar>(s); }},
      {"InformedRRTstar", [](auto s) { return std::make_shared<og::InformedRRTstar>(s); }},
      {"BITstar", [](auto s) { return std::make_shared<og::BITstar>(s); }},
      {"PRM", [](auto s) { return std::make_shared<og::PRM>(s); }},
      {"PRMstar", [](auto s) { return std::make_shared<og::PRMstar>(s); }},
      {"LazyPRM", [](auto s) { return std::make_shared<og::LazyPRM>(s); }},
      {"FMT", [](auto s) { return std::make_shared<og::FMT>(s); }},
      {"KPIECE1", [](auto s) { return std::make_shared<og::KPIECE1>(s); }},
      {"BKPIECE1", [](auto s) { return std::make_shared<og::BKPIECE1>(s); }},
      {"LBKPIECE1", [](auto s) { return std::make_shared<og::LBKPIECE1>(s); }},
      {"EST", [](auto s) { return std::make_shared<og::EST>(s); }},
      {"SBL", [](auto s) { return std::make_shared<og::SBL>(s); }},
  };
  const auto it = factories.find(name);
  if (it == factories.end()) {
    std::string known;
    for (const auto& kv : factories) known += (known.empty() ? "" : ", ") + kv.first;
    throw InvalidArgument("planner: unknown OMPL planner '" + name + "' (known: " + known + ")");
  }
  return it->second(si);
}

void boundMotionStep(ompl::base::SpaceInformation& si, const RobotModel& robot, double reach,
                     double resolution) {
  // Motions are checked state by state, so a collision between two checked states goes unseen
  // unless the robot moves less than about one voxel between them. OMPL's default step (1% of
  // the space's extent) moves an arm's tool by centimetres; bound the step instead so that no
  // point of the robot moves more than kMaxStepVoxels voxels (docs/validation.md §4):
  // arms: |dp| <= sum_j R |dq_j| <= R sqrt(n) |dq| (R: the robot's reach from its base);
  // SE(3): |dp| <= |dt| + r theta = |dt| + 2 r d_SO3 <= max(1, 2 r) d (r: the body's size).
  const double speed = robot.isFreeFlying()
                           ? std::max(1.0, 2 * reach)
                           : std::max(1e-9, reach * std::sqrt(std::max(1, robot.variableCount())));
  const double extent = si.getStateSpace()->getMaximumExtent();
  const double fraction = kMaxStepVoxels * resolution / speed / extent;
  if (!(fraction >= kMinSegmentFraction)) {
    std::string culprit = "the state space";
    if (robot.isFreeFlying()) {
      culprit = "the position bounds";
    } else if (!robot.variables().empty()) {
      const Variable* widest = &robot.variables().front();
      for (const Variable& v : robot.variables()) {
        if (v.upper - v.lower > widest->upper - widest->lower) widest = &v;
      }
      culprit = "joint '" + widest->name + "' with limits [" + shortNumber(widest->lower) + ", " +
                shortNumber(widest->upper) + "]";
    }
    throw InvalidArgument(culprit + " make" + (robot.isFreeFlying() ? "" : "s") +
                          " motions too long to check at a resolution of " +
                          shortNumber(resolution) + " m (more than " +
                          shortNumber(1 / kMinSegmentFraction) +
                          " states per motion across the space); narrow them or use a coarser "
                          "resolution");
  }
  if (std::isfinite(fraction) && fraction > 0 &&
      fraction < si.getStateValidityCheckingResolution()) {
    si.setStateValidityCheckingResolution(fraction);
  }
}

CheckerPath octreeCheckerPath(CheckerKind kind) {
  switch (kind) {
    case CheckerKind::kOctree:
      return CheckerPath::kMoveTree;
    case CheckerKind::kOctreeFused:
      return CheckerPath::kFused;
    case CheckerKind::kFcl:
    case CheckerKind::kFclOctomap:
      break;
  }
  throw InvalidArgument(std::string("checker ") + checkerKindName(kind) +
                        ": not an octree checker (expected octree or octree-fused)");
}

SceneInputs loadSceneInputs(const std::string& scene_path, const SceneOverrides& overrides,
                            const WarningSink& warnings) {
  SceneInputs inputs;
  SceneSpec& spec = inputs.spec;
  spec = loadScene(scene_path);
  if (overrides.auto_resolution) spec.octree.resolution.reset();
  if (overrides.resolution) spec.octree.resolution = *overrides.resolution;
  if (overrides.rounding) spec.octree.rounding = *overrides.rounding;
  if (overrides.checker) spec.octree.checker = *overrides.checker;
  if (overrides.planner) spec.problem.planner = *overrides.planner;
  if (overrides.motion_validator) spec.problem.motion_validator = *overrides.motion_validator;
  if (overrides.time) spec.problem.time = *overrides.time;
  if (overrides.seed) spec.problem.seed = *overrides.seed;
  if (overrides.range) spec.problem.range = *overrides.range;
  if (overrides.max_surface_voxels) spec.octree.max_surface_voxels = *overrides.max_surface_voxels;
  if (overrides.link_resolution) spec.octree.link_resolution = *overrides.link_resolution;
  if (overrides.self_link_resolution) {
    spec.octree.self_link_resolution = *overrides.self_link_resolution;
  }
  if (overrides.self_pair_tables) spec.octree.self_pair_tables = *overrides.self_pair_tables;
  if (overrides.exact_primitives) spec.octree.exact_primitives = *overrides.exact_primitives;
  if (overrides.refine) spec.octree.refine = *overrides.refine;
  if (spec.octree.refine == RefineMode::kExact && spec.octree.rounding != Rounding::kConservative) {
    throw InvalidArgument(spec.path +
                          ": octree.refine exact needs conservative rounding (the octree "
                          "certifies freedom only when its voxels contain the geometry)");
  }

  // The robot.
  std::optional<RobotModel>& robot = inputs.robot;
  double& robot_diagonal = inputs.robot_diagonal;
  if (!spec.robot.urdf.empty()) {
    RobotModelOptions options;
    options.package_paths = spec.robot.package_paths;
    options.package_paths.insert(options.package_paths.end(), overrides.package_paths.begin(),
                                 overrides.package_paths.end());
    options.warnings = warnings;
    robot = RobotModel::fromUrdfFile(spec.robot.urdf, options);
    if (robot->variableCount() == 0) {
      // A URDF without movable joints is a rigid body: it flies free in SE(3).
      options.base = BaseMotion::kFreeFlying;
      robot = RobotModel::fromUrdfFile(spec.robot.urdf, options);
      robot_diagonal = robotGeometryBox(*robot).diagonal().norm();
    }
    if (!spec.robot.srdf.empty()) robot->loadSrdfFile(spec.robot.srdf);
  } else {
    // Errors in the robot's mesh also name the scene (a .cfg names its robot by file).
    try {
      robot = RobotModel::fromMesh(spec.robot.mesh);
      MeshLoadOptions mo;
      mo.keep_root_transform = spec.robot.keep_mesh_root_transform;
      const TriangleMesh mesh = loadMesh(spec.robot.mesh, mo);
      Eigen::AlignedBox3d box;
      for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
      robot_diagonal = box.diagonal().norm();
    } catch (const Error& e) {
      throw FileError(spec.path, std::string("robot: ") + e.what());
    }
  }
  // The planned joints (problem.group, problem.fixed): every model is built on this robot.
  robot = resolvePlanningGroup(*robot, spec, warnings);

  // Objects and goals given in the robot's frames, placed at the start (mount included).
  resolveSceneFrames(spec, *robot);

  // The environment, and the region the problem lives in.
  // Errors in the files a scene names also name the scene.
  inputs.environment = [&] {
    try {
      return std::make_shared<const EnvironmentGeometry>(
          EnvironmentGeometry::load(spec.environment, warnings));
    } catch (const Error& e) {
      throw FileError(spec.path, e.what());
    }
  }();
  const EnvironmentGeometry& environment = *inputs.environment;
  Eigen::AlignedBox3d scene_box;
  if (const auto b = environment.bounds()) scene_box = *b;
  inputs.bounds_given = spec.problem.bounds.has_value();
  if (robot->isFreeFlying() && !spec.problem.bounds) {
    // OMPL.app infers the bounds from the environment when a problem gives none.
    if (scene_box.isEmpty()) {
      throw FileError(spec.path,
                      "problem.bounds: missing, and there is no environment to infer "
                      "them from");
    }
    spec.problem.bounds = scene_box;
  }
  if (spec.problem.bounds) scene_box.extend(*spec.problem.bounds);
  // How errors name the resolution's origin.
  std::string& resolution_field = inputs.resolution_field;
  resolution_field = overrides.resolution ? "--resolution" : "octree.resolution";
  if (!spec.octree.resolution) {
    spec.octree.resolution = autoResolution(*robot, scene_box, robot_diagonal);
    resolution_field += " auto";
    if (!(std::isfinite(*spec.octree.resolution) && *spec.octree.resolution > 0)) {
      throw FileError(spec.path,
                      resolution_field + ": the scene's extent (diagonal " +
                          shortNumber(scene_box.isEmpty() ? 0.0 : scene_box.diagonal().norm()) +
                          " m) and the robot's (diagonal " + shortNumber(robot_diagonal) +
                          " m) give " + shortNumber(*spec.octree.resolution) +
                          " m, not a voxel size; give the resolution in metres");
    }
  }
  return inputs;
}

PlanningScene loadPlanningScene(const std::string& scene_path, const SceneOverrides& overrides,
                                const WarningSink& warnings) {
  SceneInputs inputs = loadSceneInputs(scene_path, overrides, warnings);
  PlanningScene scene;
  scene.spec = std::move(inputs.spec);
  scene.environment = std::move(inputs.environment);
  const SceneSpec& spec = scene.spec;
  std::optional<RobotModel>& robot = inputs.robot;
  // Seed before OMPL creates any random number generator.
  if (spec.problem.seed) ompl::RNG::setSeed(*spec.problem.seed);

  CollisionModelOptions options;
  options.resolution = *spec.octree.resolution;
  options.link_resolution = spec.octree.link_resolution;
  // The moveTree path materialises every source leaf of every link per query, so link trees
  // 4x finer (the library's default, made for the fused query, which descends only near
  // contacts) cost it several times over; it keeps the link trees at the voxel unless the scene
  // says.
  if (!options.link_resolution && spec.octree.checker == CheckerKind::kOctree) {
    options.link_resolution = options.resolution;
  }
  options.self_link_resolution = spec.octree.self_link_resolution;
  options.self_pair_tables = spec.octree.self_pair_tables;
  options.exact_primitives = spec.octree.exact_primitives;
  options.refine = spec.octree.refine;
  options.fit_universe_to_reach = overrides.fit_universe_to_reach;
  options.rounding = spec.octree.rounding;
  if (spec.octree.max_surface_voxels) options.max_surface_voxels = *spec.octree.max_surface_voxels;
  options.base_position_bounds = spec.problem.bounds;
  if (spec.robot.pose) options.X_WB = *spec.robot.pose;
  options.keep_mesh_root_transform = spec.robot.keep_mesh_root_transform;
  options.center_mesh_vertices = spec.robot.center_mesh_vertices;
  options.warnings = warnings;
  const bool free_flying = robot->isFreeFlying();
  try {
    scene.model =
        std::make_shared<OctreeCollisionModel>(std::move(*robot), scene.environment, options);
  } catch (const InvalidArgument& e) {
    // Most model errors depend on the resolution (depth, memory guard): say where it came from.
    throw InvalidArgument(spec.path + ": at " + inputs.resolution_field + " " +
                          shortNumber(options.resolution) + " m: " + e.what());
  }
  // The references, lazily: they keep the octree model (for its robot) and the objects alive.
  {
    const std::shared_ptr<const OctreeCollisionModel> octree_model = scene.model;
    const std::shared_ptr<const EnvironmentGeometry> objects = scene.environment;
    const bool keep = options.keep_mesh_root_transform;
    const bool center = options.center_mesh_vertices;
    const double resolution = options.resolution;
    scene.fcl_model = LazyModel<FclCollisionModel>([octree_model, objects, keep, center] {
      return std::make_shared<const FclCollisionModel>(octree_model->robot(), *objects, keep,
                                                       center, octree_model->baseMount());
    });
    scene.fcl_octomap_model =
        LazyModel<FclOctomapCollisionModel>([octree_model, objects, keep, center, resolution] {
          return std::make_shared<const FclOctomapCollisionModel>(
              octree_model->robot(), *objects, resolution, keep, center, octree_model->baseMount());
        });
  }

  // OMPL. Its exceptions name no file: ours do.
  try {
    setUpOmpl(scene, free_flying, inputs.robot_diagonal, options.resolution, inputs.bounds_given);
  } catch (const ompl::Exception& e) {
    throw InvalidArgument(spec.path + ": OMPL refused the problem: " + e.what());
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(spec.path + ": " + e.what());
  }
  // Next to requireWithinBounds (setUpOmpl), once the checker is in place.
  if (overrides.require_free_start_goal) requireFreeStartAndGoal(scene);
  return scene;
}

namespace {

// "[problem] start.x" for an OMPL.app .cfg, "problem.start: x" for a YAML scene.
bool isCfg(const SceneSpec& spec) {
  return std::filesystem::path(spec.path).extension() == ".cfg";
}

// A start or goal outside the joint limits or the position bounds: OMPL would only warn and find
// no solution, so the scene is refused with the value and the bound.
void requireWithinBounds(const SceneSpec& spec, const RobotModel& robot, const StateSpec& state,
                         const char* which, bool bounds_given) {
  constexpr double eps = std::numeric_limits<double>::epsilon();  // OMPL's tolerance
  auto outside = [&](double v, double lo, double hi) { return v + eps < lo || v - eps > hi; };
  const bool cfg = isCfg(spec);
  if (robot.isFreeFlying()) {
    const Eigen::AlignedBox3d& box = *spec.problem.bounds;
    const Eigen::Vector3d p = state.pose->translation();
    for (int a = 0; a < 3; ++a) {
      if (!outside(p[a], box.min()[a], box.max()[a])) continue;
      const std::string axis(1, "xyz"[a]);
      std::string bound;
      if (!bounds_given) {
        bound = "the environment's bounds";
      } else if (cfg) {
        bound = "[volume.min." + axis + ", volume.max." + axis + "]";
      } else {
        bound = "problem.bounds";
      }
      const std::string field = cfg ? "[problem] " + std::string(which) + "." + axis
                                    : "problem." + std::string(which) + ": " + axis;
      throw FileError(spec.path, field + " = " + shortNumber(p[a]) + " is outside " + bound + " [" +
                                     shortNumber(box.min()[a]) + ", " + shortNumber(box.max()[a]) +
                                     "]");
    }
    return;
  }
  for (std::size_t i = 0; i < state.joints.size(); ++i) {
    const Variable& v = robot.variables()[i];
    if (!outside(state.joints[i], v.lower, v.upper)) continue;
    throw FileError(spec.path, "problem." + std::string(which) + "[" + std::to_string(i) +
                                   "]: joint '" + v.name + "' = " + shortNumber(state.joints[i]) +
                                   " is outside its " + (v.continuous ? "range" : "limits") + " [" +
                                   shortNumber(v.lower) + ", " + shortNumber(v.upper) + "]");
  }
}

// problem.goal: {link: ...}: the start, and a goal whose samples are IK solutions (the pose is
// in the world, so the robot's mount is part of the kinematics).
void setLinkPoseGoal(PlanningScene& scene, const ob::ScopedState<>& start) {
  const SceneSpec& spec = scene.spec;
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  ompl::RNG rng;  // seeded by problem.seed, like the planner's
  const auto seed = static_cast<std::uint64_t>(rng.uniformInt(0, std::numeric_limits<int>::max()));
  const std::shared_ptr<const RobotModel> robot(scene.model, &scene.model->robot());
  scene.setup->setStartState(start);
  scene.setup->setGoal(makeLinkPoseGoal(si, robot,
                                        spec.robot.pose.value_or(Eigen::Isometry3d::Identity()),
                                        *spec.problem.goal->link_pose, spec.problem.planner, seed));
}

void setUpOmpl(PlanningScene& scene, bool free_flying, double robot_diagonal, double resolution,
               bool bounds_given) {
  const SceneSpec& spec = scene.spec;
  const RobotModel& model_robot = scene.model->robot();
  const Eigen::AlignedBox3d* bounds = free_flying ? &*spec.problem.bounds : nullptr;
  scene.setup = std::make_shared<og::SimpleSetup>(makeStateSpace(model_robot, bounds));
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  // ompl-default keeps OMPL's own step, the baseline it stands for.
  if (spec.problem.motion_validator != MotionValidatorKind::kOmplDefault) {
    boundMotionStep(
        *si, model_robot,
        free_flying ? robot_diagonal : scene.model->report().reach_W.sizes().maxCoeff() / 2,
        resolution);
  }
  scene.checker = spec.octree.checker;
  const std::shared_ptr<const CollisionBackend> backend = checkerBackend(scene);
  scene.setup->setStateValidityChecker(makeValidityChecker(si, backend));
  installMotionValidator(scene, backend);
  auto toState = [&](const StateSpec& s, const char* field) {
    ob::ScopedState<> state(si);
    if (free_flying) {
      if (!s.pose) throw FileError(spec.path, std::string(field) + ": a rigid body needs a pose");
      configurationToState(model_robot, {}, *s.pose, state.get());
    } else {
      if (s.joints.size() != static_cast<std::size_t>(model_robot.variableCount())) {
        throw FileError(spec.path, std::string(field) + ": expected " +
                                       std::to_string(model_robot.variableCount()) +
                                       " joint values for " + model_robot.name() + ", got " +
                                       std::to_string(s.joints.size()));
      }
      configurationToState(model_robot, s.joints, Eigen::Isometry3d::Identity(), state.get());
    }
    return state;
  };
  if (spec.problem.start && spec.problem.goal && spec.problem.goal->link_pose) {
    setLinkPoseGoal(scene, toState(*spec.problem.start, "problem.start"));
    requireWithinBounds(spec, model_robot, *spec.problem.start, "start", bounds_given);
  } else if (spec.problem.start && spec.problem.goal) {
    const auto start = toState(*spec.problem.start, "problem.start");
    const auto goal = toState(*spec.problem.goal, "problem.goal");
    requireWithinBounds(spec, model_robot, *spec.problem.start, "start", bounds_given);
    requireWithinBounds(spec, model_robot, *spec.problem.goal, "goal", bounds_given);
    scene.setup->setStartAndGoalStates(start, goal);
  }
  scene.setup->setPlanner(makePlanner(spec.problem.planner, si));
  std::optional<double> range = spec.problem.range;
  // ompl-default keeps OMPL's range too.
  if (!range && !free_flying &&
      spec.problem.motion_validator != MotionValidatorKind::kOmplDefault &&
      scene.setup->getPlanner()->params().hasParam("range")) {
    range = kArmRangeShare * si->getStateSpace()->getMaximumExtent();
  }
  try {
    setPlannerRange(*scene.setup->getPlanner(), range);
  } catch (const InvalidArgument& e) {
    throw FileError(spec.path, std::string("problem.range: ") + e.what());
  }
}

}  // namespace

PlanResult plan(PlanningScene& scene, double interpolation) {
  try {
    return planWithOmpl(scene, interpolation);
  } catch (const ompl::Exception& e) {
    throw InvalidArgument(scene.spec.path + ": OMPL failed: " + e.what());
  }
}

namespace {

PlanResult planWithOmpl(PlanningScene& scene, double interpolation) {
  PlanResult result;
  og::SimpleSetup& ss = *scene.setup;
  ss.setup();
  // The time limit checked in this thread: SimpleSetup::solve(t) with t >= 1 s checks it from a
  // helper thread that wakes every millisecond and returns only at its next wake-up.
  const ob::PlannerStatus status =
      ss.solve(ob::timedPlannerTerminationCondition(scene.spec.problem.time));
  result.seconds = ss.getLastPlanComputationTime();
  result.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  if (!result.solved) return result;
  ss.simplifySolution();
  result.path = std::make_shared<og::PathGeometric>(ss.getSolutionPath());
  result.waypoints = std::make_shared<og::PathGeometric>(*result.path);
  if (interpolation > 0) {
    const double length = result.path->length();
    const double states = std::ceil(length / interpolation) + 1;
    if (!(states <= kMaxPathStates)) {
      throw InvalidArgument(scene.spec.path + ": interpolation (--interpolation): a spacing of " +
                            shortNumber(interpolation) + " along a path of length " +
                            shortNumber(length) + " needs " + shortNumber(states) +
                            " states, more than the limit of " + shortNumber(kMaxPathStates) +
                            "; give a larger spacing");
    }
    result.path->interpolate(static_cast<unsigned>(states));
  } else {
    result.path->interpolate();
  }
  return result;
}

}  // namespace

void writePath(const PlanningScene& scene, const og::PathGeometric& path, std::ostream& out) {
  const RobotModel& robot = scene.model->robot();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  out.precision(17);
  if (!robot.isFreeFlying()) {
    // Which joints the columns are (a group plans fewer than the robot has); readers of OMPL's
    // format skip '#' lines.
    out << "# joints:";
    for (const Variable& v : robot.variables()) out << ' ' << v.name;
    out << '\n';
  }
  for (unsigned i = 0; i < path.getStateCount(); ++i) {
    if (!stateToConfiguration(robot, path.getState(i), q, X)) {
      throw Error("writePath: state " + std::to_string(i) + " is not finite");
    }
    if (robot.isFreeFlying()) {
      const Eigen::Quaterniond r(X.linear());
      out << X.translation().x() << ' ' << X.translation().y() << ' ' << X.translation().z() << ' '
          << r.x() << ' ' << r.y() << ' ' << r.z() << ' ' << r.w() << '\n';
    } else {
      for (std::size_t k = 0; k < q.size(); ++k) out << (k ? " " : "") << q[k];
      out << '\n';
    }
  }
}

}  // namespace octomotion
