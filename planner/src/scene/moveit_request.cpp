// A MoveIt MotionPlanRequest as a problem's group, start, goal and time (moveit_scene.h).
#include <algorithm>
#include <set>

#include "internal/moveit_yaml.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/scene/moveit_scene.h"

namespace octomotion {

namespace {

using detail::MessageYaml;

// A moveit_msgs/Constraints that must be empty (path and trajectory constraints, which the
// planner cannot honour: ignoring them would plan paths that break them).
void requireNoConstraints(const MessageYaml& r, const YAML::Node& node, const std::string& field) {
  if (!node) return;
  r.allowOnly(node, field,
              {"name", "joint_constraints", "position_constraints", "orientation_constraints",
               "visibility_constraints"});
  for (const char* key : {"joint_constraints", "position_constraints", "orientation_constraints",
                          "visibility_constraints"}) {
    if (!r.list(r.child(node, field, key), field + "." + key).empty()) {
      r.fail(field + "." + key, node[key], "constraints are not supported here");
    }
  }
}

StateSpec startOf(const MessageYaml& r, const YAML::Node& node, const std::string& field) {
  r.allowOnly(node, field,
              {"joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"});
  if (!r.list(r.child(node, field, "attached_collision_objects"),
              field + ".attached_collision_objects")
           .empty()) {
    r.fail(field + ".attached_collision_objects", node["attached_collision_objects"],
           "attached objects are not supported");
  }
  // A virtual joint (MoveIt's robot-to-world joint) at the identity is the fixed mount; any other
  // pose must be given as robot.pose.
  if (const YAML::Node multi = r.child(node, field, "multi_dof_joint_state")) {
    const std::string mf = field + ".multi_dof_joint_state";
    r.allowOnly(multi, mf, {"header", "joint_names", "transforms", "twist", "wrench"});
    const std::vector<YAML::Node> transforms =
        r.list(r.child(multi, mf, "transforms"), mf + ".transforms");
    for (std::size_t i = 0; i < transforms.size(); ++i) {
      const std::string tf = MessageYaml::index(mf + ".transforms", i);
      const Eigen::Isometry3d X = r.transform(transforms[i], tf);
      if (!X.isApprox(Eigen::Isometry3d::Identity(), 1e-9)) {
        r.fail(tf, transforms[i],
               "a multi-DOF joint away from the identity is not supported; mount the robot "
               "with robot.pose instead");
      }
    }
  }
  const std::string jf = field + ".joint_state";
  const YAML::Node joints = r.required(node, field, "joint_state");
  r.allowOnly(joints, jf, {"header", "name", "position", "velocity", "effort"});
  const std::vector<YAML::Node> names = r.list(r.required(joints, jf, "name"), jf + ".name");
  const std::vector<double> positions =
      r.numbers(r.required(joints, jf, "position"), jf + ".position");
  if (names.empty()) r.fail(jf + ".name", joints["name"], "no joints");
  if (positions.size() != names.size()) {
    r.fail(jf + ".position", joints["position"],
           "expected one position per name (" + std::to_string(names.size()) + "), got " +
               std::to_string(positions.size()));
  }
  StateSpec start;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name = r.name(names[i], MessageYaml::index(jf + ".name", i));
    if (!seen.insert(name).second) {
      r.fail(MessageYaml::index(jf + ".name", i), names[i], "joint '" + name + "' given twice");
    }
    start.named.emplace_back(name, positions[i]);
  }
  return start;
}

// The frame of a constraint's header (empty: the robot's root link, MoveIt's model frame).
std::string frameOf(const MessageYaml& r, const YAML::Node& node, const std::string& field) {
  const YAML::Node header = r.child(node, field, "header");
  if (!header) return "";
  r.allowOnly(header, field + ".header", {"seq", "stamp", "frame_id"});
  return r.text(r.child(header, field + ".header", "frame_id"), field + ".header.frame_id");
}

// One link's position constraint (a sphere or box region about a point) and optionally its
// orientation constraint, as a link-pose goal; tolerances the largest ball and angle that fit.
LinkPoseGoalSpec linkPoseOf(const MessageYaml& r, const YAML::Node& position, const std::string& pf,
                            const YAML::Node* orientation, const std::string& of) {
  r.allowOnly(position, pf,
              {"header", "link_name", "target_point_offset", "constraint_region", "weight"});
  LinkPoseGoalSpec goal;
  goal.link = r.name(r.child(position, pf, "link_name"), pf + ".link_name");
  const std::string frame = frameOf(r, position, pf);
  goal.frame = frame;
  goal.robot_root_frame = frame.empty();
  if (const YAML::Node offset = r.child(position, pf, "target_point_offset")) {
    if (!r.vector3(offset, pf + ".target_point_offset").isZero()) {
      r.fail(pf + ".target_point_offset", offset, "an offset point is not supported");
    }
  }
  const std::string rf = pf + ".constraint_region";
  const YAML::Node region = r.required(position, pf, "constraint_region");
  r.allowOnly(region, rf, {"primitives", "primitive_poses", "meshes", "mesh_poses"});
  const std::vector<YAML::Node> shapes =
      r.list(r.child(region, rf, "primitives"), rf + ".primitives");
  const std::vector<YAML::Node> poses =
      r.list(r.child(region, rf, "primitive_poses"), rf + ".primitive_poses");
  if (shapes.size() != 1 || poses.size() != 1 ||
      !r.list(r.child(region, rf, "meshes"), rf + ".meshes").empty()) {
    r.fail(rf, region, "expected one primitive (a sphere or a box) and its pose");
  }
  const std::string sf = rf + ".primitives[0]";
  r.allowOnly(shapes[0], sf, {"type", "dimensions"});
  const int type =
      r.constant(r.child(shapes[0], sf, "type"), sf + ".type", {{"box", 1}, {"sphere", 2}});
  const std::vector<double> d =
      r.numbers(r.required(shapes[0], sf, "dimensions"), sf + ".dimensions");
  if (d.size() != (type == 1 ? 3u : 1u) ||
      !std::all_of(d.begin(), d.end(), [](double v) { return v > 0; })) {
    r.fail(sf + ".dimensions", shapes[0]["dimensions"],
           type == 1 ? "expected a box's 3 sizes > 0" : "expected a sphere's radius > 0");
  }
  goal.position_tolerance = type == 1 ? *std::min_element(d.begin(), d.end()) / 2 : d[0];
  goal.position = r.pose(poses[0], rf + ".primitive_poses[0]").translation();
  if (orientation) {
    const YAML::Node& o = *orientation;
    r.allowOnly(
        o, of,
        {"header", "orientation", "link_name", "absolute_x_axis_tolerance",
         "absolute_y_axis_tolerance", "absolute_z_axis_tolerance", "parameterization", "weight"});
    if (r.name(r.child(o, of, "link_name"), of + ".link_name") != goal.link) {
      r.fail(of + ".link_name", o["link_name"], "not the position constraint's link");
    }
    if (frameOf(r, o, of) != frame) {
      r.fail(of + ".header.frame_id", o, "not the position constraint's frame");
    }
    goal.orientation = r.quaternion(r.required(o, of, "orientation"), of + ".orientation");
    double tolerance = 0;
    bool first = true;
    for (const char* axis :
         {"absolute_x_axis_tolerance", "absolute_y_axis_tolerance", "absolute_z_axis_tolerance"}) {
      const double t = r.number(r.required(o, of, axis), of + "." + axis);
      if (!(t > 0)) r.fail(of + "." + axis, o[axis], "must be > 0");
      tolerance = first ? t : std::min(tolerance, t);
      first = false;
    }
    goal.orientation_tolerance = tolerance;
  }
  return goal;
}

StateSpec goalOf(const MessageYaml& r, const YAML::Node& node, const std::string& field) {
  r.allowOnly(node, field,
              {"name", "joint_constraints", "position_constraints", "orientation_constraints",
               "visibility_constraints"});
  if (!r.list(r.child(node, field, "visibility_constraints"), field + ".visibility_constraints")
           .empty()) {
    r.fail(field + ".visibility_constraints", node["visibility_constraints"],
           "visibility constraints are not supported");
  }
  const std::vector<YAML::Node> joints =
      r.list(r.child(node, field, "joint_constraints"), field + ".joint_constraints");
  const std::vector<YAML::Node> positions =
      r.list(r.child(node, field, "position_constraints"), field + ".position_constraints");
  const std::vector<YAML::Node> orientations =
      r.list(r.child(node, field, "orientation_constraints"), field + ".orientation_constraints");
  StateSpec goal;
  if (!joints.empty()) {
    if (!positions.empty() || !orientations.empty()) {
      r.fail(field, node, "joint constraints together with pose constraints are not supported");
    }
    std::set<std::string> seen;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const std::string jf = MessageYaml::index(field + ".joint_constraints", i);
      r.allowOnly(joints[i], jf,
                  {"joint_name", "position", "tolerance_above", "tolerance_below", "weight"});
      const std::string name = r.name(r.child(joints[i], jf, "joint_name"), jf + ".joint_name");
      if (!seen.insert(name).second) {
        r.fail(jf + ".joint_name", joints[i], "joint '" + name + "' constrained twice");
      }
      goal.named.emplace_back(name, r.number(r.child(joints[i], jf, "position"), jf + ".position"));
    }
    return goal;
  }
  if (positions.size() != 1 || orientations.size() > 1) {
    r.fail(field, node,
           positions.empty() ? "no joint or position constraints: nothing to plan to"
                             : "expected one link's position constraint (and at most one "
                               "orientation constraint)");
  }
  const std::string of = field + ".orientation_constraints[0]";
  goal.link_pose = linkPoseOf(r, positions[0], field + ".position_constraints[0]",
                              orientations.empty() ? nullptr : &orientations[0], of);
  return goal;
}

}  // namespace

MoveItRequest parseMoveItRequest(const std::string& text, const std::string& path) {
  const MessageYaml r(path);
  const YAML::Node root = r.parse(text);
  r.allowOnly(root, "",
              {"workspace_parameters", "start_state", "goal_constraints", "path_constraints",
               "trajectory_constraints", "reference_trajectories", "pipeline_id", "planner_id",
               "group_name", "num_planning_attempts", "allowed_planning_time",
               "max_velocity_scaling_factor", "max_acceleration_scaling_factor",
               "cartesian_speed_end_effector_link", "max_cartesian_speed"});
  try {
    MoveItRequest request;
    request.group = r.name(r.child(root, "", "group_name"), "group_name");
    request.start = startOf(r, r.required(root, "", "start_state"), "start_state");
    const YAML::Node goals_node = r.required(root, "", "goal_constraints");
    const std::vector<YAML::Node> goals = r.list(goals_node, "goal_constraints");
    if (goals.size() != 1) {
      r.fail("goal_constraints", goals_node,
             "expected one goal, got " + std::to_string(goals.size()) +
                 " (alternative goals are not supported)");
    }
    request.goal = goalOf(r, goals[0], "goal_constraints[0]");
    requireNoConstraints(r, r.child(root, "", "path_constraints"), "path_constraints");
    if (const YAML::Node t = r.child(root, "", "trajectory_constraints")) {
      r.allowOnly(t, "trajectory_constraints", {"constraints"});
      if (!r.list(r.child(t, "trajectory_constraints", "constraints"),
                  "trajectory_constraints.constraints")
               .empty()) {
        r.fail("trajectory_constraints", t, "trajectory constraints are not supported");
      }
    }
    if (const YAML::Node t = r.child(root, "", "allowed_planning_time")) {
      const double seconds = r.number(t, "allowed_planning_time");
      if (seconds > kMaxPlanningSeconds) {
        r.fail("allowed_planning_time", t, planningTimeTooLong(seconds));
      }
      if (seconds > 0) request.time = seconds;  // MoveIt: 0 means its default
    }
    return request;
  } catch (const YAML::Exception& e) {
    throw FileError(path,
                    "invalid value at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

MoveItRequest loadMoveItRequest(const std::string& path) {
  return parseMoveItRequest(readWholeFile(path, "MoveIt motion plan request", kMaxSceneFileBytes),
                            path);
}

}  // namespace octomotion
