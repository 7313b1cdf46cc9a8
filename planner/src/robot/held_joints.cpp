#include "octomotion/planner/robot/held_joints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "internal/robot_model_builder.h"

namespace octomotion {
namespace {

// The motion of a movable joint at `value`, in its frame J.
Eigen::Isometry3d jointMotion(const Joint& joint, double value) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::kPrismatic) {
    X.translation() = joint.axis * value;
  } else {
    X.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  }
  return X;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

RobotModel holdJoints(const RobotModel& robot, const std::vector<int>& planned_variables,
                      const std::vector<double>& values, const WarningSink& warnings) {
  const std::size_t n = static_cast<std::size_t>(robot.variableCount());
  if (values.size() != n) {
    throw InvalidArgument("holdJoints: " + std::to_string(values.size()) + " values for robot '" +
                          robot.name() + "' with " + std::to_string(n) + " variables");
  }
  std::vector<bool> planned(n, false);
  for (int v : planned_variables) {
    if (v < 0 || static_cast<std::size_t>(v) >= n) {
      throw InvalidArgument("holdJoints: variable " + std::to_string(v) + " of robot '" +
                            robot.name() + "' does not exist (it has " + std::to_string(n) + ")");
    }
    if (planned[static_cast<std::size_t>(v)]) {
      throw InvalidArgument("holdJoints: variable " + std::to_string(v) + " (" +
                            robot.variables()[static_cast<std::size_t>(v)].name +
                            ") is planned twice");
    }
    planned[static_cast<std::size_t>(v)] = true;
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (!planned[v] && !std::isfinite(values[v])) {
      throw InvalidArgument("holdJoints: the value of joint '" + robot.variables()[v].name +
                            "' is not finite");
    }
  }
  std::vector<Link> links = robot.links();
  std::vector<Joint> joints = robot.joints();
  std::vector<HeldJoint> held = robot.heldJoints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    Joint& joint = joints[j];
    if (!joint.movable()) continue;
    const bool mimic = joint.isMimic();
    const int variable = mimic ? robot.joint(joint.mimic_master).variable : joint.variable;
    if (planned[static_cast<std::size_t>(variable)]) continue;
    const double master_value = values[static_cast<std::size_t>(variable)];
    const double value =
        mimic ? joint.mimic_multiplier * master_value + joint.mimic_offset : master_value;
    if (!mimic && joint.type != JointType::kContinuous &&
        (value < joint.lower || value > joint.upper)) {
      warn(warnings, "joint '" + joint.name + "' of robot '" + robot.name() + "' is held at " +
                         number(value) + ", outside its limits [" + number(joint.lower) + ", " +
                         number(joint.upper) + "]");
    }
    HeldJoint h;
    h.joint = static_cast<int>(j);
    h.value = value;
    h.type = joint.type;
    h.mimic = mimic;
    held.push_back(h);
    joint.X_PJ = joint.X_PJ * jointMotion(joint, value);
    joint.type = JointType::kFixed;
    joint.mimic_master = -1;
    joint.mimic_multiplier = 1.0;
    joint.mimic_offset = 0.0;
  }
  std::sort(held.begin(), held.end(),
            [](const HeldJoint& a, const HeldJoint& b) { return a.joint < b.joint; });
  RobotModel reduced = RobotModelBuilder::build(
      robot.name(), robot.sourcePath(), robot.baseMotion(), std::move(links), std::move(joints));
  RobotModelBuilder::keepSemantics(robot, reduced, std::move(held));
  return reduced;
}

std::vector<double> expandConfiguration(const RobotModel& full, const RobotModel& reduced,
                                        const std::vector<double>& q) {
  if (full.jointCount() != reduced.jointCount() || full.linkCount() != reduced.linkCount()) {
    throw InvalidArgument("expandConfiguration: robot '" + reduced.name() +
                          "' is not a reduction of robot '" + full.name() + "'");
  }
  if (q.size() != static_cast<std::size_t>(reduced.variableCount())) {
    throw InvalidArgument("expandConfiguration: q has " + std::to_string(q.size()) +
                          " values but the reduced robot has " +
                          std::to_string(reduced.variableCount()) + " variables");
  }
  std::vector<double> out(static_cast<std::size_t>(full.variableCount()),
                          std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> set(out.size(), false);
  auto assign = [&](int joint, double value) {
    const int v = full.joint(joint).variable;
    if (v < 0) {
      throw InvalidArgument("expandConfiguration: joint '" + full.joint(joint).name +
                            "' has no variable in robot '" + full.name() + "'");
    }
    out[static_cast<std::size_t>(v)] = value;
    set[static_cast<std::size_t>(v)] = true;
  };
  for (std::size_t i = 0; i < q.size(); ++i) assign(reduced.variables()[i].joint, q[i]);
  for (const HeldJoint& h : reduced.heldJoints()) {
    if (!h.mimic && full.joint(h.joint).variable >= 0) assign(h.joint, h.value);
  }
  for (std::size_t v = 0; v < out.size(); ++v) {
    if (!set[v]) {
      throw InvalidArgument("expandConfiguration: joint '" + full.variables()[v].name +
                            "' is neither planned nor held in robot '" + reduced.name() + "'");
    }
  }
  return out;
}

}  // namespace octomotion
