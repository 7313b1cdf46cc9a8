// Internal: the <group> and <group_state> elements of an SRDF, resolved against a robot.
#pragma once

#include <string>
#include <vector>

#include "octomotion/planner/robot/robot_model.h"

class TiXmlElement;

namespace octomotion::detail {

struct SrdfGroups {
  std::vector<JointGroup> groups;
  std::vector<GroupState> states;
};

// Reads the groups and group states under `robot_element` (the SRDF's <robot>). A <group> may
// name a group of this file (in any order) or of `known` (the groups already on the robot).
// Throws FileError naming `source_name`, the line and the unknown name.
SrdfGroups parseSrdfGroups(const RobotModel& robot, const TiXmlElement& robot_element,
                           const std::string& source_name, const std::vector<JointGroup>& known);

}  // namespace octomotion::detail
