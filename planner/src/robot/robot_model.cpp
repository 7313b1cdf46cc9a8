#include "octomotion/planner/robot/robot_model.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "internal/robot_model_builder.h"
#include "octomotion/motion/sin_cos.h"

namespace octomotion {

const char* toString(JointType type) {
  switch (type) {
    case JointType::kRevolute:
      return "revolute";
    case JointType::kContinuous:
      return "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kFixed:
      return "fixed";
  }
  return "unknown";
}

void RobotModel::finalize() {
  const std::size_t n = links_.size();
  if (n == 0) throw Error(source_ + ": the robot has no links");
  if (joints_.size() + 1 != n) {
    throw Error(source_ + ": internal: expected one joint per non-root link");
  }
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const Joint& joint = joints_[j];
    // The depth-first layout is what makes forwardKinematics a single forward sweep.
    if (joint.child_link != static_cast<int>(j) + 1 || joint.parent_link < 0 ||
        joint.parent_link >= joint.child_link) {
      throw Error(source_ + ": internal: joint '" + joint.name + "' is out of depth-first order");
    }
  }
  variables_.clear();
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = joints_[j];
    joint.variable = -1;
    if (!joint.movable() || joint.isMimic()) continue;
    joint.variable = static_cast<int>(variables_.size());
    Variable v;
    v.name = joint.name;
    v.joint = static_cast<int>(j);
    v.continuous = joint.type == JointType::kContinuous;
    if (v.continuous) {
      joint.lower = -M_PI;
      joint.upper = M_PI;
    }
    v.lower = joint.lower;
    v.upper = joint.upper;
    variables_.push_back(v);
  }
  steps_.clear();
  steps_.reserve(joints_.size());
  for (const Joint& joint : joints_) {
    KinematicStep step;
    step.X_PJ = joint.X_PJ;
    step.axis = joint.axis;
    step.multiplier = 1.0;
    step.offset = 0.0;
    step.source = -1;
    step.parent_link = joint.parent_link;
    step.child_link = joint.child_link;
    step.type = joint.type;
    step.X_PJ_is_translation = joint.X_PJ.linear() == Eigen::Matrix3d::Identity();
    step.axis_sign = 1.0;
    step.axis_index = -1;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
      if (joint.axis == e || joint.axis == -e) {
        step.axis_index = k;
        step.axis_sign = joint.axis[k];
      }
    }
    if (joint.movable()) {
      if (joint.isMimic()) {
        const Joint& master = joints_.at(static_cast<std::size_t>(joint.mimic_master));
        if (master.variable < 0) {
          throw Error(source_ + ": internal: mimic master of '" + joint.name + "' has no variable");
        }
        step.source = master.variable;
        step.multiplier = joint.mimic_multiplier;
        step.offset = joint.mimic_offset;
      } else {
        step.source = joint.variable;
      }
    }
    steps_.push_back(step);
  }
  resetCollisionFilterToAdjacent();
}

int RobotModel::findLink(const std::string& link_name) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == link_name) return static_cast<int>(i);
  }
  return -1;
}

int RobotModel::findJoint(const std::string& joint_name) const {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    if (joints_[i].name == joint_name) return static_cast<int>(i);
  }
  return -1;
}

int RobotModel::linkIndex(const std::string& link_name) const {
  const int i = findLink(link_name);
  if (i < 0) throw InvalidArgument("robot '" + name_ + "' has no link named '" + link_name + "'");
  return i;
}

int RobotModel::jointIndex(const std::string& joint_name) const {
  const int i = findJoint(joint_name);
  if (i < 0) {
    throw InvalidArgument("robot '" + name_ + "' has no joint named '" + joint_name + "'");
  }
  return i;
}

int RobotModel::variableIndex(const std::string& joint_name) const {
  const Joint& j = joint(jointIndex(joint_name));
  if (j.variable < 0) {
    throw InvalidArgument("joint '" + joint_name + "' of robot '" + name_ + "' is " +
                          (j.isMimic() ? "a mimic joint" : "fixed") +
                          ": it has no entry in the configuration vector");
  }
  return j.variable;
}

// --- Collision filter ---

void RobotModel::checkLinkIndex(int link, const char* what) const {
  if (link < 0 || link >= linkCount()) {
    throw InvalidArgument(std::string(what) + " = " + std::to_string(link) +
                          " is not a link index of robot '" + name_ + "' (it has " +
                          std::to_string(linkCount()) + " links)");
  }
}

void RobotModel::disableCollision(int link_a, int link_b) {
  checkLinkIndex(link_a, "link_a");
  checkLinkIndex(link_b, "link_b");
  disabled_[pairSlot(link_a, link_b)] = 1;
  disabled_[pairSlot(link_b, link_a)] = 1;
  rebuildCheckedPairs();
}

void RobotModel::enableCollision(int link_a, int link_b) {
  checkLinkIndex(link_a, "link_a");
  checkLinkIndex(link_b, "link_b");
  disabled_[pairSlot(link_a, link_b)] = 0;
  disabled_[pairSlot(link_b, link_a)] = 0;
  rebuildCheckedPairs();
}

void RobotModel::disableCollision(const std::string& link_a, const std::string& link_b) {
  disableCollision(linkIndex(link_a), linkIndex(link_b));
}

void RobotModel::enableCollision(const std::string& link_a, const std::string& link_b) {
  enableCollision(linkIndex(link_a), linkIndex(link_b));
}

void RobotModel::clearDisabledCollisions() {
  disabled_.assign(links_.size() * links_.size(), 0);
  rebuildCheckedPairs();
}

void RobotModel::resetCollisionFilterToAdjacent() {
  disabled_.assign(links_.size() * links_.size(), 0);
  for (std::size_t i = 1; i < links_.size(); ++i) {
    const int child = static_cast<int>(i);
    int ancestor = links_[i].parent_link;
    // The parent always; further up only while the links in between have no geometry.
    while (ancestor >= 0) {
      disabled_[pairSlot(child, ancestor)] = 1;
      disabled_[pairSlot(ancestor, child)] = 1;
      if (links_[static_cast<std::size_t>(ancestor)].hasCollision()) break;
      ancestor = links_[static_cast<std::size_t>(ancestor)].parent_link;
    }
  }
  rebuildCheckedPairs();
}

bool RobotModel::collisionAllowed(int link_a, int link_b) const {
  checkLinkIndex(link_a, "link_a");
  checkLinkIndex(link_b, "link_b");
  return link_a == link_b || disabled_[pairSlot(link_a, link_b)] != 0;
}

std::vector<std::pair<int, int>> RobotModel::disabledPairs() const {
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < linkCount(); ++a) {
    for (int b = a + 1; b < linkCount(); ++b) {
      if (disabled_[pairSlot(a, b)] != 0) pairs.emplace_back(a, b);
    }
  }
  return pairs;
}

void RobotModel::rebuildCheckedPairs() {
  checked_pairs_.clear();
  for (int a = 0; a < linkCount(); ++a) {
    if (!links_[static_cast<std::size_t>(a)].hasCollision()) continue;
    for (int b = a + 1; b < linkCount(); ++b) {
      if (!links_[static_cast<std::size_t>(b)].hasCollision()) continue;
      if (disabled_[pairSlot(a, b)] == 0) checked_pairs_.emplace_back(a, b);
    }
  }
}

// --- Forward kinematics ---

RobotData RobotModel::makeData() const {
  RobotData data;
  data.X_WL.assign(links_.size(), Eigen::Isometry3d::Identity());
  data.joint_values.assign(joints_.size(), 0.0);
  return data;
}

void RobotModel::forwardKinematics(const double* q, std::size_t q_size, RobotData& data,
                                   const Eigen::Isometry3d& X_WB) const {
  if (q_size != variables_.size()) {
    throw InvalidArgument("forwardKinematics: q has " + std::to_string(q_size) +
                          " values but robot '" + name_ + "' has " +
                          std::to_string(variables_.size()) + " variables");
  }
  if (data.X_WL.size() != links_.size() || data.joint_values.size() != joints_.size()) {
    throw InvalidArgument("forwardKinematics: RobotData was not made by this robot's makeData()");
  }
  for (std::size_t i = 0; i < q_size; ++i) {
    if (!std::isfinite(q[i])) {
      throw InvalidArgument("forwardKinematics: q[" + std::to_string(i) + "] (" +
                            variables_[i].name + ") is not finite");
    }
  }
  data.X_WL[0] = X_WB;
  for (std::size_t j = 0; j < steps_.size(); ++j) {
    const KinematicStep& step = steps_[j];
    const Eigen::Isometry3d& X_WP = data.X_WL[static_cast<std::size_t>(step.parent_link)];
    Eigen::Isometry3d& X_WC = data.X_WL[static_cast<std::size_t>(step.child_link)];
    const double value =
        step.source < 0 ? 0.0
                        : step.multiplier * q[static_cast<std::size_t>(step.source)] + step.offset;
    data.joint_values[j] = value;
    if (step.type == JointType::kFixed) {
      X_WC = X_WP * step.X_PJ;
      continue;
    }
    // Frame J of the joint at value 0, then the motion along/about the axis. makeAffine keeps
    // the bottom row exact even for a RobotData that was not made by makeData.
    X_WC.makeAffine();
    if (step.X_PJ_is_translation) {
      X_WC.linear() = X_WP.linear();
    } else {
      X_WC.linear().noalias() = X_WP.linear() * step.X_PJ.linear();
    }
    X_WC.translation().noalias() = X_WP.linear() * step.X_PJ.translation();
    X_WC.translation() += X_WP.translation();
    if (step.type == JointType::kPrismatic) {
      X_WC.translation().noalias() += X_WC.linear() * (step.axis * value);
    } else if (step.axis_index >= 0) {
      // Right-multiplying by a rotation about e_k mixes columns a = k+1 and b = k+2 (mod 3).
      const double angle = step.axis_sign * value;
      double s, c;
      sinCos(angle, s, c);
      const Eigen::Index a = (step.axis_index + 1) % 3;
      const Eigen::Index b = (step.axis_index + 2) % 3;
      auto R = X_WC.linear();
      const Eigen::Vector3d col_a = R.col(a);
      const Eigen::Vector3d col_b = R.col(b);
      R.col(a) = c * col_a + s * col_b;
      R.col(b) = c * col_b - s * col_a;
    } else {
      X_WC.linear() = X_WC.linear() * Eigen::AngleAxisd(value, step.axis).toRotationMatrix();
    }
  }
  // Finite values can still give a non-finite pose (a huge limit or mimic multiplier along a
  // chain overflows); a collision query could call such a link free, so no caller gets one.
  // x * 0 is 0 for a finite x and NaN otherwise: one sum over every pose tells, without a
  // branch per value; the link is looked for only when it is NaN.
  double zero = 0.0;
  for (const Eigen::Isometry3d& X : data.X_WL) zero += (X.matrix().topRows<3>() * 0.0).sum();
  if (zero == 0.0) return;
  for (std::size_t l = 0; l < data.X_WL.size(); ++l) {
    const Eigen::Isometry3d& X = data.X_WL[l];
    if (!X.translation().allFinite() || !X.linear().allFinite()) {
      throw InvalidArgument("forwardKinematics: the pose of link '" + links_[l].name +
                            "' is not finite");
    }
  }
}

bool RobotModel::withinLimits(const Eigen::VectorXd& q) const {
  if (q.size() != variableCount()) return false;
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    const double v = q[static_cast<Eigen::Index>(i)];
    if (!std::isfinite(v)) return false;
    if (variables_[i].continuous) continue;
    if (v < variables_[i].lower || v > variables_[i].upper) return false;
  }
  return true;
}

// --- Free-flying rigid bodies ---

RobotModel RobotModel::rigidBody(const std::string& name, std::vector<CollisionElement> elements) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::string field = "rigid body '" + name + "' element " + std::to_string(i);
    if (!elements[i].X_LE.matrix().allFinite()) {
      throw InvalidArgument(field + ": X_LE is not finite");
    }
    if (const auto* primitive = std::get_if<Primitive>(&elements[i].geometry)) {
      try {
        validate(*primitive);
      } catch (const Error& e) {
        throw InvalidArgument(field + ": " + e.what());
      }
    } else {
      const MeshRef& mesh = std::get<MeshRef>(elements[i].geometry);
      if (!mesh.scale.allFinite() || (mesh.scale.array() == 0.0).any()) {
        throw InvalidArgument(field + ": mesh scale must be finite and non-zero");
      }
      std::error_code ec;
      if (!std::filesystem::is_regular_file(mesh.path, ec)) {
        throw FileError(mesh.path, "mesh file does not exist (" + field + ")");
      }
    }
  }
  const std::string body_name = name.empty() ? "body" : name;
  Link link;
  link.name = body_name;
  link.collision = std::move(elements);
  std::vector<Link> links;
  links.push_back(std::move(link));
  return RobotModelBuilder::build(body_name, "rigid body '" + body_name + "'",
                                  BaseMotion::kFreeFlying, std::move(links), {});
}

RobotModel RobotModel::fromMesh(const std::string& mesh_path, const Eigen::Vector3d& scale,
                                const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(mesh_path, ec)) throw FileError(mesh_path, "mesh file does not exist");
  const fs::path absolute = fs::absolute(fs::path(mesh_path), ec);
  CollisionElement element;
  element.geometry =
      MeshRef{(ec ? fs::path(mesh_path) : absolute).lexically_normal().string(), scale};
  std::vector<CollisionElement> elements;
  elements.push_back(std::move(element));
  RobotModel model =
      rigidBody(name.empty() ? fs::path(mesh_path).stem().string() : name, std::move(elements));
  model.source_ = mesh_path;
  return model;
}

}  // namespace octomotion
