// A scene's frames resolved once the robot is loaded: environment objects given in a robot link's
// frame (EnvironmentObject::frame, a MoveIt frame_id) or in the robot's root frame (MoveIt's empty
// frame_id) are placed in the world at the start configuration, mount (robot.pose) included, and
// so are link-pose goals given in such a frame (docs/robots.md, "MoveIt planning scenes").
#pragma once

#include <vector>

#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

// The configuration frames are resolved at: problem.start's full joint vector, or its joints by
// name (problem.fixed by name fills the joints it does not name, and every other joint is 0
// clamped into its limits). Throws FileError naming the scene and the field for an unknown joint
// or a start vector that is not the full configuration.
std::vector<double> frameConfiguration(const SceneSpec& spec, const RobotModel& robot);

// Replaces every frame-relative pose of the scene by its world pose (clearing the frames), and
// drops mimic joints from problem.start's named values once they are found to agree with their
// masters (multiplier * master + offset, within 1e-9; a MoveIt start state lists them). Throws
// FileError naming the object or goal and the frame when the frame is no link of the robot, or
// the joint when a mimic value disagrees. The parent frame of the SRDF's virtual joint (MoveIt's
// model frame, often "world") is the root link's frame, at the mount.
void resolveSceneFrames(SceneSpec& spec, const RobotModel& robot);

}  // namespace octomotion
