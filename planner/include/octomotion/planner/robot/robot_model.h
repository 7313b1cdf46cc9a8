// The kinematic and collision model of a robot, split Pinocchio-style into a constant
// RobotModel (links, joints, limits, collision geometry, which link pairs to check) and a
// RobotData scratch object per thread. Queries are const on the model, so one model can be
// shared by every planning thread while each thread owns its RobotData.
//
// Conventions:
// - Links are stored in depth-first order from the root (link 0); the children of a link are
//   visited in the order their joints appear in the URDF file. Joint j is the parent joint of
//   link j + 1, so iterating joints in index order visits every parent before its child.
// - The configuration vector q has one entry per movable joint (revolute, continuous,
//   prismatic) that is not a mimic joint, in the same depth-first joint order (`variables()`).
//   Mimic joints follow their master: value = multiplier * q_master + offset.
// - Floating and planar URDF joints are rejected (octomotion::Error naming the joint): model a
//   free-flying robot with BaseMotion::kFreeFlying instead, whose base pose X_WB is passed to
//   forwardKinematics next to q (the planner samples it from SE(3)).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/StdVector>

#include "octomotion/error.h"
#include "octomotion/planner/robot/collision_geometry.h"

namespace octomotion {

enum class JointType { kRevolute, kContinuous, kPrismatic, kFixed };
const char* toString(JointType type);

// Whether the root link is bolted to the world at a given pose or moves freely in SE(3).
enum class BaseMotion { kFixed, kFreeFlying };

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  // Joint frame J in the parent link frame P (URDF <origin>). At value v the child link frame is
  // X_PJ * Rot(axis, v) (revolute/continuous) or X_PJ * Trans(axis * v) (prismatic).
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit vector in J
  // Position limits (rad or m) from <limit>; for continuous joints the wrap interval [-pi, pi].
  double lower = 0.0;
  double upper = 0.0;
  double max_velocity = 0.0;
  double max_effort = 0.0;
  int variable = -1;  // index in q; -1 for fixed and mimic joints
  // Mimic joints: the (ultimate, non-mimic) master joint and the composed affine map.
  int mimic_master = -1;
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;

  bool movable() const { return type != JointType::kFixed; }
  bool isMimic() const { return mimic_master >= 0; }
};

struct Link {
  std::string name;
  int parent_joint = -1;  // -1 for the root
  int parent_link = -1;
  std::vector<int> child_joints;
  std::vector<CollisionElement> collision;

  bool hasCollision() const { return !collision.empty(); }
};

// One entry of the configuration vector q.
struct Variable {
  std::string name;  // the joint's name
  int joint = -1;
  double lower = 0.0;
  double upper = 0.0;
  bool continuous = false;  // unbounded angle: wraps around, [lower, upper] = [-pi, pi]
};

// An SRDF <group> (MoveIt's JointModelGroup), resolved to this robot's joints: a <joint> adds
// itself, a <link> its parent joint, a <chain base_link tip_link> the joints on the path between
// the two links (through their common ancestor when neither is above the other), a <group> the
// joints of that group. Its planned joints are those of its joints that have a variable.
struct JointGroup {
  std::string name;
  std::vector<int> joints;  // joint indices, ascending (fixed and mimic joints included)
  std::vector<int> links;   // the child links of `joints`, ascending
};

// An SRDF <group_state>: named joint values for a group ("ready", "open").
struct GroupState {
  std::string name;
  std::string group;
  std::vector<std::pair<int, double>> values;  // joint index and value, in file order
};

// A joint that was movable in the robot's description and is fixed at `value` in this model
// (see holdJoints in held_joints.h): its motion is part of its X_PJ.
struct HeldJoint {
  int joint = -1;
  double value = 0.0;
  JointType type = JointType::kFixed;  // its type in the description
  bool mimic = false;                  // it mimicked a joint that is held too
};

struct RobotModelOptions {
  // Directories searched for package:// URIs before the environment's (see PackageLocator).
  std::vector<std::string> package_paths;
  bool use_environment_package_paths = true;  // OCTOMOTION_PACKAGE_PATH, ROS_PACKAGE_PATH
  BaseMotion base = BaseMotion::kFixed;
  WarningSink warnings;  // urdfdom's warnings are forwarded here
};

// How loadSrdf combines the file's pairs with the current disabled set.
enum class SrdfMode {
  kReplace,  // the SRDF is the whole list (MoveIt semantics; adjacent defaults are dropped)
  kMerge,    // the SRDF's pairs are added to (or, for <enable_collisions>, removed from) it
};

// Per-thread scratch: the world pose of every link after forwardKinematics.
class RobotData {
 public:
  RobotData() = default;
  const Eigen::Isometry3d& linkPose(int link) const { return X_WL[static_cast<std::size_t>(link)]; }

  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> X_WL;
  std::vector<double> joint_values;  // every joint's value (mimic joints included, 0 for fixed)
};

class RobotModel {
 public:
  // Parses a URDF with urdfdom. Throws FileError (message starts with the path) for an
  // unreadable file, text that is not UTF-8 (or holds a NUL byte), an XML syntax error, urdfdom's
  // complaints, an unknown, floating or planar joint type, a cycle, several root links, a
  // non-finite number, a non-positive size, a bad mimic reference or a collision mesh that cannot
  // be resolved (naming link and URI).
  static RobotModel fromUrdfFile(const std::string& path, const RobotModelOptions& options = {});
  // The same for URDF text; `source_name` stands in for the path in messages and relative mesh
  // paths are resolved against `base_dir`.
  static RobotModel fromUrdfString(const std::string& urdf_xml, const std::string& source_name,
                                   const std::string& base_dir,
                                   const RobotModelOptions& options = {});
  // A free-flying rigid body: one link (named `name`, or the file's stem when empty) whose
  // collision geometry is the mesh. Throws FileError when the file does not exist and
  // InvalidArgument for a zero or non-finite scale. The mesh is not loaded here.
  static RobotModel fromMesh(const std::string& mesh_path,
                             const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                             const std::string& name = "");
  // A free-flying rigid body made of the given elements (primitives are validated).
  static RobotModel rigidBody(const std::string& name, std::vector<CollisionElement> elements);

  const std::string& name() const { return name_; }
  const std::string& sourcePath() const { return source_; }
  BaseMotion baseMotion() const { return base_; }
  bool isFreeFlying() const { return base_ == BaseMotion::kFreeFlying; }

  int linkCount() const { return static_cast<int>(links_.size()); }
  int jointCount() const { return static_cast<int>(joints_.size()); }
  int variableCount() const { return static_cast<int>(variables_.size()); }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Variable>& variables() const { return variables_; }
  const Link& link(int i) const { return links_.at(static_cast<std::size_t>(i)); }
  const Joint& joint(int i) const { return joints_.at(static_cast<std::size_t>(i)); }
  // -1 when absent; the *Index forms throw InvalidArgument naming the missing name.
  int findLink(const std::string& link_name) const;
  int findJoint(const std::string& joint_name) const;
  int linkIndex(const std::string& link_name) const;
  int jointIndex(const std::string& joint_name) const;
  // Index in q of a joint by name; throws InvalidArgument for unknown, fixed or mimic joints.
  int variableIndex(const std::string& joint_name) const;

  // --- Self-collision filtering (MoveIt's "allowed collision matrix") ---
  // Without an SRDF, adjacent links are not checked: each link against its parent and, when the
  // parent has no geometry, further up to the first ancestor that has some (links without
  // geometry are transparent, as in MoveIt Setup Assistant). The SRDF and the edits below change
  // the model: make them before sharing it between threads. SRDF errors (FileError naming the
  // file, line and attribute) leave the filter unchanged.
  void loadSrdfFile(const std::string& path, SrdfMode mode = SrdfMode::kReplace);
  void loadSrdfString(const std::string& srdf_xml, const std::string& source_name,
                      SrdfMode mode = SrdfMode::kReplace);
  void disableCollision(int link_a, int link_b);
  void enableCollision(int link_a, int link_b);
  void disableCollision(const std::string& link_a, const std::string& link_b);
  void enableCollision(const std::string& link_a, const std::string& link_b);
  void resetCollisionFilterToAdjacent();
  void clearDisabledCollisions();
  // True when the pair is not checked: the same link, or a disabled pair.
  bool collisionAllowed(int link_a, int link_b) const;
  // Pairs (a < b) of links that both have geometry and are not allowed to touch, i.e. the pairs
  // a self-collision check must test. Recomputed whenever the filter changes.
  const std::vector<std::pair<int, int>>& checkedPairs() const { return checked_pairs_; }
  std::vector<std::pair<int, int>> disabledPairs() const;

  // --- SRDF groups ---
  // The SRDF's <group> and <group_state> elements (loadSrdf*; kReplace replaces them, kMerge adds
  // to them, a group of the same name replacing the old one). Errors name the file, the line and
  // the unknown joint, link or group.
  const std::vector<JointGroup>& groups() const { return groups_; }
  const std::vector<GroupState>& groupStates() const { return group_states_; }
  const JointGroup* findGroup(const std::string& group_name) const;  // nullptr when absent
  // The indices in q of the group's joints that have one (its planned joints), ascending.
  std::vector<int> groupVariables(const JointGroup& group) const;
  // Joints held at a value by holdJoints (empty for a model loaded from a description).
  const std::vector<HeldJoint>& heldJoints() const { return held_; }

  // --- Forward kinematics ---
  RobotData makeData() const;
  // World pose of every link, for configuration q (variableCount() values) and base pose X_WB
  // (the root link's pose; fixed-base robots usually pass their mounting pose). Allocation-free.
  // Throws InvalidArgument for a wrong q size, a non-finite q, a RobotData of another model or a
  // link pose that comes out non-finite (the checkers then call the state invalid).
  void forwardKinematics(const double* q, std::size_t q_size, RobotData& data,
                         const Eigen::Isometry3d& X_WB = Eigen::Isometry3d::Identity()) const;
  void forwardKinematics(const Eigen::VectorXd& q, RobotData& data,
                         const Eigen::Isometry3d& X_WB = Eigen::Isometry3d::Identity()) const {
    forwardKinematics(q.data(), static_cast<std::size_t>(q.size()), data, X_WB);
  }
  // True when every bounded variable is within [lower, upper] (continuous ones always are).
  bool withinLimits(const Eigen::VectorXd& q) const;

 private:
  friend class RobotModelBuilder;
  RobotModel() = default;

  // Hot-path copy of each joint: value = multiplier * q[source] + offset (source -1: fixed).
  // Axes along +-x, +-y or +-z (most robots) take a shortcut: axis_index k with the sign in
  // axis_sign, so a revolute joint only mixes two columns of the rotation.
  struct KinematicStep {
    Eigen::Isometry3d X_PJ;
    Eigen::Vector3d axis;
    double multiplier;
    double offset;
    double axis_sign;
    int axis_index;            // 0, 1, 2 for a coordinate axis, -1 for a general one
    bool X_PJ_is_translation;  // identity rotation (rpy="0 0 0", the usual case): skip a product
    int source;
    int parent_link;
    int child_link;
    JointType type;
  };

  // Derives variables, the kinematic steps and the default filter from links_ and joints_.
  void finalize();
  void rebuildCheckedPairs();
  std::size_t pairSlot(int a, int b) const {
    return static_cast<std::size_t>(a) * links_.size() + static_cast<std::size_t>(b);
  }
  void checkLinkIndex(int link, const char* what) const;

  std::string name_;
  std::string source_;
  BaseMotion base_ = BaseMotion::kFixed;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<Variable> variables_;
  std::vector<KinematicStep, Eigen::aligned_allocator<KinematicStep>> steps_;
  std::vector<unsigned char> disabled_;  // links x links, symmetric
  std::vector<std::pair<int, int>> checked_pairs_;
  std::vector<JointGroup> groups_;
  std::vector<GroupState> group_states_;
  std::vector<HeldJoint> held_;
};

}  // namespace octomotion
