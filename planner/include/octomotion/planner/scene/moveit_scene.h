// MoveIt's YAML messages as scene parts: a PlanningScene's collision objects as environment
// objects (the `moveit_scene` environment item) and a MotionPlanRequest as a problem's group,
// start, goal and time (`problem.moveit_request`). docs/robots.md says what is read and what is
// refused. Every error is a FileError naming the file and the field path
// (world.collision_objects[3].primitives[0].dimensions).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// world.collision_objects[] of a moveit_msgs/PlanningScene, applied in order as MoveIt does
// (ADD, or an absent operation, adds or replaces the object of that id; APPEND adds shapes to it;
// REMOVE removes it, or every object when the id is empty; MOVE is refused). One object per
// shape (box, cylinder, sphere, inline mesh), named by the object's id, or id/k for its k-th
// shape when it has several. Poses: the shape's pose, relative to the object's `pose` when one is
// given (MoveIt Noetic and later), in header.frame_id (EnvironmentObject::frame; empty: the
// robot's root link, EnvironmentObject::robot_root_frame). Refused: cones, planes, attached
// objects in robot_state, a world octomap.
std::vector<EnvironmentObject> parseMoveItScene(const std::string& text, const std::string& path);
std::vector<EnvironmentObject> loadMoveItScene(const std::string& path);

// What a moveit_msgs/MotionPlanRequest gives a problem.
struct MoveItRequest {
  std::string group;           // group_name
  StateSpec start;             // start_state.joint_state as `named` (mimic joints included)
  StateSpec goal;              // goal_constraints[0]: joints as `named`, or one link's pose
  std::optional<double> time;  // allowed_planning_time, when > 0
};
MoveItRequest parseMoveItRequest(const std::string& text, const std::string& path);
MoveItRequest loadMoveItRequest(const std::string& path);

}  // namespace octomotion
