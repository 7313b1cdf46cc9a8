// The collision-filter part of MoveIt's SRDF: <disable_collisions link1 link2/>, plus
// <disable_default_collisions link/> (the link against every other) and
// <enable_collisions link1 link2/> (an exception to the former), applied in that order.
// Groups and group states are read by srdf_groups.cpp; other elements (end effectors, virtual
// joints...) are ignored.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <tinyxml.h>

#include "internal/srdf_groups.h"
#include "internal/xml_text.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

void RobotModel::loadSrdfFile(const std::string& path, SrdfMode mode) {
  loadSrdfString(readWholeFile(path, "SRDF file", kMaxXmlFileBytes), path, mode);
}

void RobotModel::loadSrdfString(const std::string& srdf_xml, const std::string& source_name,
                                SrdfMode mode) {
  detail::requireXmlText(srdf_xml, source_name);
  TiXmlDocument doc;
  doc.Parse(srdf_xml.c_str());
  if (doc.Error()) {
    throw FileError(source_name, "XML syntax error at line " + std::to_string(doc.ErrorRow()) +
                                     ", column " + std::to_string(doc.ErrorCol()) + ": " +
                                     doc.ErrorDesc());
  }
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Value()) != "robot") {
    throw FileError(source_name, "root element must be <robot>");
  }
  auto linkAttribute = [&](const TiXmlElement* e, const char* attribute) {
    const char* value = e->Attribute(attribute);
    const std::string where =
        "<" + std::string(e->Value()) + "> (line " + std::to_string(e->Row()) + ")";
    if (value == nullptr) throw FileError(source_name, where + " has no " + attribute);
    const int link = findLink(value);
    if (link < 0) {
      throw FileError(source_name, where + ": " + attribute + " '" + value +
                                       "' is not a link of robot '" + name_ + "'");
    }
    return link;
  };
  // Validate everything before changing the filter, so a bad file leaves it untouched.
  std::vector<std::pair<int, int>> disable;
  std::vector<int> disable_all;
  std::vector<std::pair<int, int>> enable;
  for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    if (tag == "disable_collisions") {
      disable.emplace_back(linkAttribute(e, "link1"), linkAttribute(e, "link2"));
    } else if (tag == "enable_collisions") {
      enable.emplace_back(linkAttribute(e, "link1"), linkAttribute(e, "link2"));
    } else if (tag == "disable_default_collisions") {
      disable_all.push_back(linkAttribute(e, "link"));
    }
  }
  detail::SrdfGroups groups = detail::parseSrdfGroups(
      *this, *robot, source_name, mode == SrdfMode::kMerge ? groups_ : std::vector<JointGroup>{});
  if (mode == SrdfMode::kReplace) {
    groups_.clear();
    group_states_.clear();
  }
  for (JointGroup& g : groups.groups) {
    const auto same = std::find_if(groups_.begin(), groups_.end(),
                                   [&](const JointGroup& old) { return old.name == g.name; });
    if (same != groups_.end()) {
      *same = std::move(g);
    } else {
      groups_.push_back(std::move(g));
    }
  }
  for (GroupState& s : groups.states) {
    const auto same = std::find_if(
        group_states_.begin(), group_states_.end(),
        [&](const GroupState& old) { return old.name == s.name && old.group == s.group; });
    if (same != group_states_.end()) {
      *same = std::move(s);
    } else {
      group_states_.push_back(std::move(s));
    }
  }
  if (mode == SrdfMode::kReplace) disabled_.assign(links_.size() * links_.size(), 0);
  auto set = [&](int a, int b, unsigned char value) {
    disabled_[pairSlot(a, b)] = value;
    disabled_[pairSlot(b, a)] = value;
  };
  for (const auto& [a, b] : disable) set(a, b, 1);
  for (int a : disable_all) {
    for (int b = 0; b < linkCount(); ++b) set(a, b, 1);
  }
  for (const auto& [a, b] : enable) set(a, b, 0);
  rebuildCheckedPairs();
}

const JointGroup* RobotModel::findGroup(const std::string& group_name) const {
  for (const JointGroup& g : groups_) {
    if (g.name == group_name) return &g;
  }
  return nullptr;
}

std::vector<int> RobotModel::groupVariables(const JointGroup& group) const {
  std::vector<int> variables;
  for (int j : group.joints) {
    const int v = joint(j).variable;
    if (v >= 0) variables.push_back(v);
  }
  std::sort(variables.begin(), variables.end());
  return variables;
}

}  // namespace octomotion
