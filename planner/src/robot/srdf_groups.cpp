// SRDF groups the way MoveIt resolves them (moveit_core RobotModel::addJointModelGroup): every
// element adds joints, and the group's links are the child links of its joints.
#include "internal/srdf_groups.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>

#include <tinyxml.h>

namespace octomotion::detail {
namespace {

class GroupReader {
 public:
  GroupReader(const RobotModel& robot, std::string source)
      : robot_(robot), source_(std::move(source)) {}

  [[noreturn]] void fail(const TiXmlElement& e, const std::string& what) const {
    throw FileError(source_, "<" + std::string(e.Value()) + "> (line " + std::to_string(e.Row()) +
                                 "): " + what);
  }
  std::string attribute(const TiXmlElement& e, const char* name) const {
    const char* value = e.Attribute(name);
    if (value == nullptr || *value == '\0') fail(e, std::string("has no ") + name);
    return value;
  }
  int joint(const TiXmlElement& e, const std::string& group) const {
    const std::string name = attribute(e, "name");
    const int j = robot_.findJoint(name);
    if (j < 0) fail(e, "joint '" + name + "' of " + group + " is not a joint of " + robotName());
    return j;
  }
  int link(const TiXmlElement& e, const char* attribute_name, const std::string& group) const {
    const std::string name = attribute(e, attribute_name);
    const int l = robot_.findLink(name);
    if (l < 0) {
      fail(e, std::string(attribute_name) + " '" + name + "' of " + group + " is not a link of " +
                  robotName());
    }
    return l;
  }
  std::string robotName() const { return "robot '" + robot_.name() + "'"; }

  // The joints on the tree path between two links (MoveIt: tip up to base, or both up to their
  // common ancestor).
  std::vector<int> chain(int base, int tip) const {
    std::vector<int> tip_ancestors;  // tip, its parent, ..., the root
    for (int l = tip; l >= 0; l = robot_.link(l).parent_link) tip_ancestors.push_back(l);
    std::vector<int> joints;
    int common = base;
    while (std::find(tip_ancestors.begin(), tip_ancestors.end(), common) == tip_ancestors.end()) {
      joints.push_back(robot_.link(common).parent_joint);
      common = robot_.link(common).parent_link;
    }
    for (int l : tip_ancestors) {
      if (l == common) break;
      joints.push_back(robot_.link(l).parent_joint);
    }
    return joints;
  }

  const RobotModel& robot_;
  std::string source_;
};

}  // namespace

SrdfGroups parseSrdfGroups(const RobotModel& robot, const TiXmlElement& robot_element,
                           const std::string& source_name, const std::vector<JointGroup>& known) {
  const GroupReader r(robot, source_name);
  std::vector<const TiXmlElement*> elements;
  std::map<std::string, std::size_t> index;  // this file's groups by name
  for (const TiXmlElement* e = robot_element.FirstChildElement("group"); e != nullptr;
       e = e->NextSiblingElement("group")) {
    const std::string name = r.attribute(*e, "name");
    if (!index.emplace(name, elements.size()).second) {
      r.fail(*e, "group '" + name + "' is defined twice");
    }
    elements.push_back(e);
  }
  SrdfGroups out;
  out.groups.resize(elements.size());
  // 0: not resolved, 1: being resolved (a subgroup naming it is a cycle), 2: resolved.
  std::vector<int> state(elements.size(), 0);
  auto findKnown = [&](const std::string& name) -> const JointGroup* {
    for (const JointGroup& g : known) {
      if (g.name == name) return &g;
    }
    return nullptr;
  };
  std::function<void(std::size_t)> resolve = [&](std::size_t i) {
    const TiXmlElement& group = *elements[i];
    const std::string name = r.attribute(group, "name");
    const std::string what = "group '" + name + "'";
    state[i] = 1;
    std::vector<int> joints;
    for (const TiXmlElement* e = group.FirstChildElement(); e != nullptr;
         e = e->NextSiblingElement()) {
      const std::string tag = e->Value();
      if (tag == "joint") {
        joints.push_back(r.joint(*e, what));
      } else if (tag == "link") {
        const int parent = robot.link(r.link(*e, "name", what)).parent_joint;
        if (parent >= 0) joints.push_back(parent);
      } else if (tag == "chain") {
        const int base = r.link(*e, "base_link", what);
        const int tip = r.link(*e, "tip_link", what);
        for (int j : r.chain(base, tip)) joints.push_back(j);
      } else if (tag == "group") {
        const std::string sub = r.attribute(*e, "name");
        const auto it = index.find(sub);
        const JointGroup* other = nullptr;
        if (it != index.end()) {
          if (state[it->second] == 1)
            r.fail(*e, "subgroup '" + sub + "' of " + what + " is a cycle");
          if (state[it->second] == 0) resolve(it->second);
          other = &out.groups[it->second];
        } else {
          other = findKnown(sub);
        }
        if (other == nullptr) r.fail(*e, "subgroup '" + sub + "' of " + what + " is not a group");
        joints.insert(joints.end(), other->joints.begin(), other->joints.end());
      }
      // MoveIt ignores other elements (<passive_joint> inside a group, for instance).
    }
    std::sort(joints.begin(), joints.end());
    joints.erase(std::unique(joints.begin(), joints.end()), joints.end());
    JointGroup& g = out.groups[i];
    g.name = name;
    g.joints = joints;
    g.links.clear();
    for (int j : joints) g.links.push_back(robot.joint(j).child_link);
    std::sort(g.links.begin(), g.links.end());
    state[i] = 2;
  };
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (state[i] == 0) resolve(i);
  }
  for (const TiXmlElement* e = robot_element.FirstChildElement("group_state"); e != nullptr;
       e = e->NextSiblingElement("group_state")) {
    GroupState s;
    s.name = r.attribute(*e, "name");
    s.group = r.attribute(*e, "group");
    const std::string what = "group_state '" + s.name + "'";
    if (index.count(s.group) == 0 && findKnown(s.group) == nullptr) {
      r.fail(*e, "group '" + s.group + "' of " + what + " is not a group");
    }
    for (const TiXmlElement* j = e->FirstChildElement("joint"); j != nullptr;
         j = j->NextSiblingElement("joint")) {
      const int joint = r.joint(*j, what);
      const std::string text = r.attribute(*j, "value");
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      while (std::isspace(static_cast<unsigned char>(*end))) ++end;
      if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
        r.fail(*j, "value '" + text + "' of joint '" + robot.joint(joint).name + "' in " + what +
                       " is not a finite number (one value per joint)");
      }
      s.values.emplace_back(joint, value);
    }
    out.states.push_back(std::move(s));
  }
  return out;
}

}  // namespace octomotion::detail
