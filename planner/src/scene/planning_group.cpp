#include "octomotion/planner/scene/planning_group.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "octomotion/planner/robot/held_joints.h"

namespace octomotion {
namespace {

// A mimic joint's value in a named state must agree with its master to this (YAML round trips).
constexpr double kMimicTolerance = 1e-6;

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The joint values a start or goal gives by name or group state.
struct NamedState {
  std::map<int, double> values;               // joint index -> value (non-mimic joints)
  std::set<int> named;                        // the joints given by name (not the state's)
  std::vector<std::pair<int, double>> mimic;  // mimic joints given by name
};

class Resolver {
 public:
  Resolver(const RobotModel& robot, SceneSpec& spec) : robot_(robot), spec_(spec) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw FileError(spec_.path, field + ": " + what);
  }
  std::string robotName() const { return "robot '" + robot_.name() + "'"; }

  // A group state by name: the problem's group's if it has one of that name, else the only one.
  const GroupState& groupState(const std::string& name, const std::string& field) const {
    std::vector<const GroupState*> candidates;
    for (const GroupState& s : robot_.groupStates()) {
      if (s.name != name) continue;
      if (s.group == spec_.problem.group) return s;
      candidates.push_back(&s);
    }
    if (candidates.size() == 1) return *candidates.front();
    if (candidates.empty()) {
      std::string known;
      for (const GroupState& s : robot_.groupStates()) {
        known += (known.empty() ? "" : ", ") + s.name + " (" + s.group + ")";
      }
      fail(field,
           robotName() + " has no SRDF group_state '" + name + "'" +
               (known.empty() ? std::string(" (its SRDF has none)") : " (known: " + known + ")"));
    }
    std::string groups;
    for (const GroupState* s : candidates) groups += (groups.empty() ? "" : ", ") + s->group;
    fail(field, "group_state '" + name + "' is defined for several groups (" + groups +
                    "); give problem.group");
  }

  NamedState collect(const StateSpec& state, const std::string& field) const {
    NamedState out;
    if (!state.group_state.empty()) {
      const std::string state_field = state.named.empty() ? field : field + ".group_state";
      for (const auto& [joint, value] : groupState(state.group_state, state_field).values) {
        const Joint& j = robot_.joint(joint);
        // Fixed and mimic joints have no value of their own to take.
        if (j.movable() && !j.isMimic()) out.values[joint] = value;
      }
    }
    for (const auto& [name, value] : state.named) {
      const std::string joint_field = field + "." + name;
      const int joint = robot_.findJoint(name);
      if (joint < 0) fail(joint_field, robotName() + " has no joint '" + name + "'");
      const Joint& j = robot_.joint(joint);
      if (!j.movable()) fail(joint_field, "joint '" + name + "' is fixed in the URDF");
      if (j.isMimic()) {
        out.mimic.emplace_back(joint, value);
      } else {
        out.values[joint] = value;
        out.named.insert(joint);
      }
    }
    return out;
  }

  // A named mimic joint's value must be what its master gives: the state's value for a planned
  // master, the held value for a held one.
  void checkMimics(const NamedState& state, const std::vector<double>& values,
                   const std::vector<bool>& planned, const std::string& field) const {
    for (const auto& [joint, value] : state.mimic) {
      const Joint& j = robot_.joint(joint);
      const Joint& master = robot_.joint(j.mimic_master);
      const auto v = static_cast<std::size_t>(master.variable);
      const double master_value = planned[v] ? state.values.at(j.mimic_master) : values[v];
      const double expected = j.mimic_multiplier * master_value + j.mimic_offset;
      if (std::abs(value - expected) > kMimicTolerance) {
        fail(field + "." + j.name,
             "mimic joint '" + j.name + "' = " + number(value) + ", but its master '" +
                 master.name + "' = " + number(master_value) + " gives " + number(expected));
      }
    }
  }

  const RobotModel& robot_;
  SceneSpec& spec_;
};

bool byName(const std::optional<StateSpec>& s) {
  return s && (!s->named.empty() || !s->group_state.empty());
}

}  // namespace

RobotModel resolvePlanningGroup(const RobotModel& robot, SceneSpec& spec,
                                const WarningSink& warnings) {
  const Resolver r(robot, spec);
  ProblemSpec& problem = spec.problem;
  if (robot.isFreeFlying()) {
    if (!problem.group.empty()) r.fail("problem.group", "a rigid body has no joints to group");
    if (!problem.fixed.empty()) r.fail("problem.fixed", "a rigid body has no joints to hold");
    for (const auto& [state, field] :
         {std::pair{&problem.start, "problem.start"}, std::pair{&problem.goal, "problem.goal"}}) {
      if (byName(*state)) r.fail(field, "a rigid body needs a pose {xyz, rpy|quat|axis+theta}");
    }
    return robot;
  }
  const std::size_t n = static_cast<std::size_t>(robot.variableCount());
  std::vector<bool> planned(n, true);
  if (!problem.group.empty()) {
    const JointGroup* group = robot.findGroup(problem.group);
    if (group == nullptr) {
      std::string known;
      for (const JointGroup& g : robot.groups()) known += (known.empty() ? "" : ", ") + g.name;
      r.fail("problem.group",
             r.robotName() + " has no group '" + problem.group + "'" +
                 (known.empty() ? std::string(" (give robot.srdf with its <group>)")
                                : " (its SRDF's groups: " + known + ")"));
    }
    planned.assign(n, false);
    for (int v : robot.groupVariables(*group)) planned[static_cast<std::size_t>(v)] = true;
  }
  // Held values, in the priority order of the header.
  std::vector<double> values(n, 0.0);
  std::vector<bool> given(n, false);
  for (const auto& [name, value] : problem.fixed) {
    const std::string field = "problem.fixed." + name;
    const int joint = robot.findJoint(name);
    if (joint < 0) r.fail(field, r.robotName() + " has no joint '" + name + "'");
    const Joint& j = robot.joint(joint);
    if (!j.movable()) r.fail(field, "joint '" + name + "' is fixed in the URDF");
    if (j.isMimic()) {
      r.fail(field, "joint '" + name + "' mimics '" + robot.joint(j.mimic_master).name +
                        "': hold that one instead");
    }
    const auto v = static_cast<std::size_t>(j.variable);
    if (!problem.group.empty() && planned[v]) {
      r.fail(field, "joint '" + name + "' is in group '" + problem.group +
                        "', which is planned; a held joint must be outside the group");
    }
    planned[v] = false;
    values[v] = value;
    given[v] = true;
  }
  const bool start_by_name = byName(problem.start);
  const NamedState start =
      start_by_name ? r.collect(*problem.start, "problem.start") : NamedState{};
  for (std::size_t v = 0; v < n; ++v) {
    if (planned[v] || given[v]) continue;
    const Variable& var = robot.variables()[v];
    const auto it = start.values.find(var.joint);
    values[v] = it != start.values.end() ? it->second : std::clamp(0.0, var.lower, var.upper);
  }
  std::vector<int> planned_variables;
  std::string planned_names;
  for (std::size_t v = 0; v < n; ++v) {
    if (!planned[v]) continue;
    planned_variables.push_back(static_cast<int>(v));
    planned_names += (planned_names.empty() ? "" : ", ") + robot.variables()[v].name;
  }
  if (planned_variables.empty()) {
    r.fail(problem.group.empty() ? "problem.fixed" : "problem.group",
           "no joint is left to plan (" +
               (problem.group.empty() ? std::string("every movable joint is held")
                                      : "group '" + problem.group + "' has no movable joint") +
               ")");
  }
  // Starts and goals: by name or group state -> the planned joints' vector.
  auto resolveState = [&](std::optional<StateSpec>& state, const char* which) {
    if (!state) return;
    const std::string field = std::string("problem.") + which;
    if (!byName(state)) {
      if (!state->joints.empty() && state->joints.size() != planned_variables.size()) {
        r.fail(field, "expected " + std::to_string(planned_variables.size()) + " joint values (" +
                          planned_names + "), got " + std::to_string(state->joints.size()));
      }
      return;
    }
    const NamedState named = which == std::string("start") ? start : r.collect(*state, field);
    if (which == std::string("goal")) {
      for (int joint : named.named) {
        const int v = robot.joint(joint).variable;
        if (planned[static_cast<std::size_t>(v)]) continue;
        r.fail(field + "." + robot.joint(joint).name,
               "joint '" + robot.joint(joint).name + "' is not planned (held at " +
                   number(values[static_cast<std::size_t>(v)]) +
                   "); a goal gives only planned joints");
      }
    }
    state->joints.clear();
    for (int v : planned_variables) {
      const Variable& var = robot.variables()[static_cast<std::size_t>(v)];
      const auto it = named.values.find(var.joint);
      if (it == named.values.end()) {
        r.fail(field, "planned joint '" + var.name +
                          "' has no value (give it by name, or a group_state that has it)");
      }
      state->joints.push_back(it->second);
    }
    r.checkMimics(named, values, planned, field);
  };
  resolveState(problem.start, "start");
  resolveState(problem.goal, "goal");
  if (planned_variables.size() == n) return robot;
  const std::string& path = spec.path;
  return holdJoints(robot, planned_variables, values,
                    [&](const std::string& message) { warn(warnings, path + ": " + message); });
}

}  // namespace octomotion
