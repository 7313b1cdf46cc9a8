// An object attached to a robot link (a grasped part, a tool), as MoveIt's AttachedCollisionObject
// describes it: it moves with the link, is checked against the environment and against the
// robot's other links, except the links it may touch (touch_links) and the link itself.
#pragma once

#include <string>
#include <vector>

#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

struct AttachedObject {
  // Its name and geometry (a primitive or a mesh); object.X_WO is read as X_LO, its pose in the
  // link's frame.
  EnvironmentObject object;
  std::string link;                      // the robot link that carries it
  std::vector<std::string> touch_links;  // links allowed to touch it (besides `link`)
};

// The checks every checker makes before attaching: the object is a primitive or a mesh, its link
// and touch links exist (InvalidArgument naming them). Returns the carrying link's index and sets
// `allowed` (one flag per link) on the links the object may touch: that link and touch_links.
int attachmentLinks(const RobotModel& robot, const AttachedObject& object,
                    std::vector<bool>& allowed);

}  // namespace octomotion
