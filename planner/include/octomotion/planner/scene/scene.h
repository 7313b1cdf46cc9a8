// Scene files: what a planning problem is made of, read from a YAML scene (docs/scenes.md) or an
// OMPL.app rigid-body `.cfg` problem. This layer only parses and validates; building the robot
// model and the environment octree from a SceneSpec happens elsewhere. Every path in a SceneSpec
// is absolute (resolved against the scene file's directory).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/octree/mesh.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/octree/shapes.h"

namespace octomotion {

struct RobotSpec {
  std::string urdf;                        // a URDF, or
  std::string mesh;                        // a single mesh: a free-flying rigid body in SE(3)
  std::string srdf;                        // optional
  std::vector<std::string> package_paths;  // extra package:// search paths
  // Mesh conventions: URDF robots reset the mesh root transform (ROS/MoveIt); OMPL.app keeps it
  // and shifts the robot so that the mean of its vertices is at its origin.
  bool keep_mesh_root_transform = false;
  bool center_mesh_vertices = false;
  // robot.pose: where a fixed-base robot's root link is mounted in the world (X_WB); every
  // checker honours it. Empty: the identity.
  std::optional<Eigen::Isometry3d> pose;
};

struct EnvironmentObject {
  enum class Kind { kPrimitive, kMesh, kPointCloud, kOctomap };
  std::string name;  // given in the file, or "environment[i]"
  Kind kind = Kind::kPrimitive;
  Primitive primitive = Sphere{1.0};                // kPrimitive
  std::string file;                                 // kMesh, kPointCloud, kOctomap
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // kMesh
  bool keep_mesh_root_transform = true;             // kMesh
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  // The frame X_WO is given in: empty = the world; otherwise a robot link's name (MoveIt's
  // frame_id), resolved once the robot is loaded (at its start configuration).
  std::string frame;
  // MoveIt's empty frame_id: X_WO is in the robot's model frame, its root link (which sits at
  // robot.pose); `frame` is then empty. Resolved with `frame`.
  bool robot_root_frame = false;
  // kMesh given inline (a MoveIt shape_msgs/Mesh) in the object's frame instead of a file (then
  // empty); `scale` and `keep_mesh_root_transform` do not apply.
  std::shared_ptr<const TriangleMesh> mesh;
};

// The validity checker a scene plans with: the octree model's moveTree path or fused query, exact
// FCL, or FCL on an OctoMap of the environment. Names ("octree", "octree-fused", "fcl",
// "fcl-octomap") appear only where scenes and command lines are read and results are written.
enum class CheckerKind { kOctree, kOctreeFused, kFcl, kFclOctomap };
inline constexpr CheckerKind kCheckerKinds[] = {CheckerKind::kOctree, CheckerKind::kOctreeFused,
                                                CheckerKind::kFcl, CheckerKind::kFclOctomap};
const char* checkerKindName(CheckerKind kind);
// The kind a name stands for, or InvalidArgument naming the known ones.
CheckerKind parseCheckerKind(const std::string& name);
inline bool isOctreeChecker(CheckerKind kind) {
  return kind == CheckerKind::kOctree || kind == CheckerKind::kOctreeFused;
}

// What decides the pairs the octree cannot certify (docs/planner.md, "Exact refine mode"):
// kNone: the octree's voxels (conservative rounding: never misses, rejects some free states
//   within the voxels' margin of contact);
// kExact: the octree certifies freedom (no shared voxel under conservative rounding); each
//   link-object or link-link pair whose voxels meet is decided by FCL on the original geometry
//   (the link's meshes and primitives against that object; the two links), so the answer is
//   FCL's. Conservative rounding only (centre rounding is refused: its "free" is not a proof).
// kAuto (the default): kExact wherever it applies, else kNone (resolveRefineMode): a default
//   model accepts what FCL accepts (a grasp a few millimetres from an object), and centre
//   rounding or a world that changes between plans still work without naming a mode.
// In files and on command lines: "none", "exact", "auto".
enum class RefineMode { kNone, kExact, kAuto };
const char* refineModeName(RefineMode mode);
// The mode a name stands for, or InvalidArgument naming the known ones.
RefineMode parseRefineMode(const std::string& name);
// The mode a model is built with: kAuto becomes kExact under conservative rounding, and kNone
// under centre rounding (nothing to certify) or for a model meant for world updates
// (`world_updates`: CollisionModelOptions::fit_universe_to_reach; kExact refuses updates). An
// explicit kNone or kExact is kept as given.
RefineMode resolveRefineMode(RefineMode mode, Rounding rounding, bool world_updates);

// Which OMPL MotionValidator a scene plans with (problem.motion_validator, --motion-validator).
enum class MotionValidatorKind {
  kCertified,  // CertifiedMotionValidator (ompl/certified_motion_validator.h), the default
  kDiscrete,   // OMPL's DiscreteMotionValidator at the step boundMotionStep sets
  // OMPL's DiscreteMotionValidator at OMPL's own default step (1 % of the state space's extent),
  // as OMPL.app plans: a baseline for comparisons, neither a proof nor bounded by the voxels.
  kOmplDefault,
};
// "certified", "discrete", "ompl-default"
const char* motionValidatorKindName(MotionValidatorKind kind);
// The kind a name stands for, or InvalidArgument naming the known ones.
MotionValidatorKind parseMotionValidatorKind(const std::string& name);

struct OctreeSettings {
  std::optional<double> resolution;       // metres; empty = auto (derived from the scene)
  std::optional<double> link_resolution;  // coarser per-link source trees; empty = resolution
  // Finer trees for the self-collision pairs only; empty = link_resolution.
  std::optional<double> self_link_resolution;
  // Joint-space tables for self pairs of few joints (CollisionModelOptions::self_pair_tables).
  bool self_pair_tables = false;
  // Contacts confirmed against primitives' exact shapes (CollisionModelOptions::exact_primitives).
  bool exact_primitives = false;
  // What decides the pairs the voxels cannot certify (CollisionModelOptions::refine).
  RefineMode refine = RefineMode::kAuto;
  Rounding rounding = Rounding::kConservative;
  CheckerKind checker = CheckerKind::kOctreeFused;
  // Memory guard (CollisionModelOptions::max_surface_voxels); empty = the library default.
  std::optional<double> max_surface_voxels;
};

// A goal given as the pose of one robot link, reached through inverse kinematics.
struct LinkPoseGoalSpec {
  std::string link;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<Eigen::Quaterniond> orientation;  // empty: any orientation
  double position_tolerance = 1e-3;               // metres
  double orientation_tolerance = 1e-2;            // radians
  // The frame position and orientation are given in, as EnvironmentObject::frame and
  // ::robot_root_frame (a MoveIt request's header.frame_id); resolved to the world with them.
  std::string frame;
  bool robot_root_frame = false;
};

// A start or goal: a joint vector (arms), joint values by name, an SRDF group state, a link pose
// (goals only) or a pose (rigid bodies).
struct StateSpec {
  std::vector<double> joints;  // the planned variables in order (the group's, or every one)
  std::vector<std::pair<std::string, double>> named;  // {joint: value}, in file order
  std::string group_state;                            // an SRDF <group_state> name
  std::optional<LinkPoseGoalSpec> link_pose;          // goals only
  std::optional<Eigen::Isometry3d> pose;
};

struct ProblemSpec {
  // An SRDF group: its joints are planned, every other joint is held (problem.fixed, the start,
  // else 0 clamped into its limits). Empty: every movable joint is planned.
  std::string group;
  std::vector<std::pair<std::string, double>> fixed;  // problem.fixed: {joint: value}
  std::string moveit_request;  // the MotionPlanRequest YAML the problem came from, if any
  std::optional<StateSpec> start, goal;
  std::optional<Eigen::AlignedBox3d> bounds;  // SE(3) position bounds; empty = inferred
  std::string planner = "RRTConnect";         // an OMPL geometric planner
  double time = 5.0;                          // seconds
  std::optional<std::uint64_t> seed;
  MotionValidatorKind motion_validator = MotionValidatorKind::kCertified;
  // problem.range: how far one step of the planner reaches (OMPL's "range" parameter, in the
  // state space's distance: radians over the joints for an arm). Empty: the planner's own.
  std::optional<double> range;
};

struct SceneSpec {
  std::string path;  // the scene file
  std::string name;
  RobotSpec robot;
  std::vector<EnvironmentObject> environment;
  OctreeSettings octree;
  ProblemSpec problem;
};

// Dispatches on the extension: .yaml/.yml or .cfg. Throws FileError naming the file and the field.
SceneSpec loadScene(const std::string& path);
// `path` names the file in errors and anchors relative paths; the file is not read.
SceneSpec parseSceneYaml(const std::string& text, const std::string& path);
SceneSpec parseOmplAppCfg(const std::string& text, const std::string& path);

// Shared by scene parsing and the command line.
// The longest planning time accepted: OMPL's deadline is the system clock plus the time in
// nanoseconds, which overflows (and ends the search at once) from about 7e9 s.
inline constexpr double kMaxPlanningSeconds = 1e6;
std::string planningTimeTooLong(double seconds);  // "... s is more than the limit of ..."
// The largest seed accepted: every integer up to it is exact in a double.
inline constexpr double kMaxSeed = 9.0e15;
// URDF convention: fixed axes, roll about x, then pitch about y, then yaw about z.
Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw);

}  // namespace octomotion
