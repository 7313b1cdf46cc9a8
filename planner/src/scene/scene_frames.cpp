#include "octomotion/planner/scene/scene_frames.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include <tinyxml.h>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The parent frames of the SRDF's virtual joints: MoveIt's model frame when the robot has one
// ("world" in most MoveIt configurations), which a fixed-base robot's mount puts at its root.
std::vector<std::string> virtualJointParents(const std::string& srdf_path) {
  std::vector<std::string> frames;
  if (srdf_path.empty()) return frames;
  TiXmlDocument doc;
  doc.Parse(readWholeFile(srdf_path, "SRDF file", kMaxXmlFileBytes).c_str());
  const TiXmlElement* robot = doc.Error() ? nullptr : doc.RootElement();
  if (robot == nullptr) return frames;  // the SRDF loader has reported it already
  for (const TiXmlElement* e = robot->FirstChildElement("virtual_joint"); e != nullptr;
       e = e->NextSiblingElement("virtual_joint")) {
    if (const char* parent = e->Attribute("parent_frame")) frames.emplace_back(parent);
  }
  return frames;
}

bool needsLinkPoses(const SceneSpec& spec) {
  for (const EnvironmentObject& obj : spec.environment) {
    if (!obj.frame.empty()) return true;
  }
  const auto& goal = spec.problem.goal;
  return goal && goal->link_pose && !goal->link_pose->frame.empty();
}

// Checks the mimic joints among `named` against their masters and removes them.
void dropConsistentMimics(const SceneSpec& spec, const RobotModel& robot,
                          std::vector<std::pair<std::string, double>>& named) {
  auto valueOf = [&](int joint) -> std::optional<double> {
    for (const auto& [name, value] : named) {
      if (name == robot.joint(joint).name) return value;
    }
    return std::nullopt;
  };
  std::vector<std::pair<std::string, double>> kept;
  for (const auto& [name, value] : named) {
    const int j = robot.findJoint(name);
    if (j < 0 || !robot.joint(j).isMimic()) {
      kept.emplace_back(name, value);
      continue;
    }
    const Joint& joint = robot.joint(j);
    const Joint& master = robot.joint(joint.mimic_master);
    const std::optional<double> q_master = valueOf(joint.mimic_master);
    if (!q_master) {
      throw FileError(spec.path, "problem.start: joint '" + name + "' mimics '" + master.name +
                                     "', which the start does not give");
    }
    const double expected = joint.mimic_multiplier * *q_master + joint.mimic_offset;
    if (std::abs(value - expected) > 1e-9) {
      throw FileError(spec.path, "problem.start: joint '" + name + "' = " + number(value) +
                                     " disagrees with its master '" + master.name +
                                     "' = " + number(*q_master) + " (it mimics it: expected " +
                                     number(expected) + ")");
    }
  }
  named = std::move(kept);
}

}  // namespace

std::vector<double> frameConfiguration(const SceneSpec& spec, const RobotModel& robot) {
  std::vector<double> q;
  for (const Variable& v : robot.variables()) q.push_back(std::clamp(0.0, v.lower, v.upper));
  auto setByName = [&](const std::vector<std::pair<std::string, double>>& values,
                       const std::string& field) {
    for (const auto& [name, value] : values) {
      const int j = robot.findJoint(name);
      if (j < 0) {
        throw FileError(spec.path, field + ": '" + name + "' is not a joint of " + robot.name());
      }
      const Joint& joint = robot.joint(j);
      if (joint.variable >= 0) q[static_cast<std::size_t>(joint.variable)] = value;
    }
  };
  setByName(spec.problem.fixed, "problem.fixed");
  if (const auto& start = spec.problem.start) {
    if (!start->joints.empty()) {
      if (start->joints.size() != q.size()) {
        throw FileError(spec.path, "problem.start: " + std::to_string(start->joints.size()) +
                                       " values, but placing objects on links needs all " +
                                       std::to_string(q.size()) +
                                       " joints of the robot (or the start by name)");
      }
      q = start->joints;
    }
    setByName(start->named, "problem.start");
  }
  return q;
}

void resolveSceneFrames(SceneSpec& spec, const RobotModel& robot) {
  if (spec.problem.start) dropConsistentMimics(spec, robot, spec.problem.start->named);
  const Eigen::Isometry3d X_WB = robot.isFreeFlying()
                                     ? Eigen::Isometry3d::Identity()
                                     : spec.robot.pose.value_or(Eigen::Isometry3d::Identity());
  RobotData data = robot.makeData();
  if (needsLinkPoses(spec)) {
    if (robot.isFreeFlying()) {
      throw FileError(spec.path, "a free-flying robot has no link frames to place objects in");
    }
    const std::vector<double> q = frameConfiguration(spec, robot);
    robot.forwardKinematics(q.data(), q.size(), data, X_WB);
  }
  std::optional<std::vector<std::string>> model_frames;  // read on first need
  // The world pose of a frame; `what` names its user in errors.
  auto frameToWorld = [&](const std::string& frame, bool root,
                          const std::string& what) -> Eigen::Isometry3d {
    if (frame.empty()) return root ? X_WB : Eigen::Isometry3d::Identity();
    const int link = robot.findLink(frame);
    if (link < 0) {
      if (!model_frames) model_frames = virtualJointParents(spec.robot.srdf);
      if (std::find(model_frames->begin(), model_frames->end(), frame) != model_frames->end()) {
        return X_WB;
      }
      throw FileError(spec.path, what + ": frame '" + frame + "' is not a link of " + robot.name() +
                                     " (a frame is one of the robot's links, or the parent "
                                     "frame of the SRDF's virtual joint)");
    }
    return data.linkPose(link);
  };
  for (EnvironmentObject& obj : spec.environment) {
    obj.X_WO =
        frameToWorld(obj.frame, obj.robot_root_frame, "environment object '" + obj.name + "'") *
        obj.X_WO;
    obj.frame.clear();
    obj.robot_root_frame = false;
  }
  if (spec.problem.goal && spec.problem.goal->link_pose) {
    LinkPoseGoalSpec& goal = *spec.problem.goal->link_pose;
    const Eigen::Isometry3d X_WF =
        frameToWorld(goal.frame, goal.robot_root_frame, "problem.goal (link " + goal.link + ")");
    goal.position = X_WF * goal.position;
    if (goal.orientation) goal.orientation = Eigen::Quaterniond(X_WF.linear()) * *goal.orientation;
    goal.frame.clear();
    goal.robot_root_frame = false;
  }
}

}  // namespace octomotion
