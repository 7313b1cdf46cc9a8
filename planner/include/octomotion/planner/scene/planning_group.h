// The joints a scene plans: problem.group (an SRDF group; omitted, every movable joint not in
// problem.fixed), the values the other joints are held at, and starts and goals given by joint
// name or as SRDF group states, resolved against the robot (docs/scenes.md, "problem").
#pragma once

#include <string>

#include "octomotion/error.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// Returns the robot the scene plans with: `robot` (the whole robot, its SRDF loaded) with every
// joint outside the planned set held (holdJoints). Held values: problem.fixed, else the start's
// value for that joint (given by name, else by the start's group_state), else 0 clamped into the
// joint's limits. Fills spec.problem.start/goal->joints with the planned joints' values, in the
// reduced robot's variable order, for starts and goals given by name or group state; a joint
// vector must already hold one value per planned joint.
// Throws FileError naming the scene and the field: an unknown group, group state or joint, a
// joint of the group in problem.fixed, a planned joint without a value, a named goal value for a
// held joint, a mimic joint's value that disagrees with its master, a group or named joints for
// a rigid body. A held value outside the joint's limits is only a warning.
RobotModel resolvePlanningGroup(const RobotModel& robot, SceneSpec& spec,
                                const WarningSink& warnings = {});

}  // namespace octomotion
