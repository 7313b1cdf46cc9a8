#include "octomotion/planner/ompl/state_space.h"

#include <cmath>
#include <limits>
#include <string>
#include <typeinfo>

#include "octomotion/error.h"

namespace octomotion {

namespace ob = ompl::base;

ob::StateSpacePtr makeStateSpace(const RobotModel& robot,
                                 const Eigen::AlignedBox3d* position_bounds) {
  if (robot.isFreeFlying()) {
    if (!position_bounds) {
      throw InvalidArgument(robot.name() + ": a free-flying robot needs SE(3) position bounds");
    }
    auto space = std::make_shared<ob::SE3StateSpace>();
    ob::RealVectorBounds bounds(3);
    for (unsigned i = 0; i < 3; ++i) {
      bounds.setLow(i, position_bounds->min()[i]);
      bounds.setHigh(i, position_bounds->max()[i]);
    }
    space->setBounds(bounds);
    return space;
  }
  const auto n = static_cast<unsigned>(robot.variableCount());
  if (n == 0) throw InvalidArgument(robot.name() + ": the robot has no movable joint");
  auto space = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (unsigned i = 0; i < n; ++i) {
    const Variable& v = robot.variables()[i];
    bounds.setLow(i, v.lower);
    bounds.setHigh(i, v.upper);
    space->setDimensionName(i, v.name);
  }
  space->setBounds(bounds);
  return space;
}

bool stateToConfiguration(const RobotModel& robot, const ob::State* state, std::vector<double>& q,
                          Eigen::Isometry3d& X_WB) {
  if (robot.isFreeFlying()) {
    const auto* s = state->as<ob::SE3StateSpace::StateType>();
    const auto& r = s->rotation();
    const Eigen::Vector3d t(s->getX(), s->getY(), s->getZ());
    const double norm = std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
    if (!t.allFinite() || !std::isfinite(norm) || norm < 1e-9) return false;
    X_WB.linear() =
        Eigen::Quaterniond(r.w / norm, r.x / norm, r.y / norm, r.z / norm).toRotationMatrix();
    X_WB.translation() = t;
    return true;
  }
  const double* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!std::isfinite(values[i])) return false;
    q[i] = values[i];
  }
  return true;
}

namespace {

// OMPL's rules (RealVectorStateSpace::satisfiesBounds, SO3StateSpace::satisfiesBounds).
bool withinBounds(const double* values, const ob::RealVectorBounds& bounds) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (std::size_t i = 0; i < bounds.low.size(); ++i) {
    if (values[i] - eps > bounds.high[i] || values[i] + eps < bounds.low[i]) return false;
  }
  return true;
}

bool unitQuaternion(const ob::SO3StateSpace::StateType& r) {
  constexpr double kMaxNormError = 1e-9;  // OMPL's MAX_QUATERNION_NORM_ERROR
  const double n2 = r.x * r.x + r.y * r.y + r.z * r.z + r.w * r.w;
  const double norm =
      std::fabs(n2 - 1.0) > std::numeric_limits<double>::epsilon() ? std::sqrt(n2) : 1.0;
  return std::fabs(norm - 1.0) < kMaxNormError;
}

}  // namespace

BoundsCheck::BoundsCheck(const ob::SpaceInformationPtr& si) : si_(si.get()) {
  const ob::StateSpace* space = si->getStateSpace().get();
  if (typeid(*space) == typeid(ob::SE3StateSpace)) {
    position_ = static_cast<const ob::SE3StateSpace*>(space)->as<ob::RealVectorStateSpace>(0);
  } else if (typeid(*space) == typeid(ob::RealVectorStateSpace)) {
    joints_ = static_cast<const ob::RealVectorStateSpace*>(space);
  }
}

bool BoundsCheck::operator()(const ob::State* state) const {
  if (joints_) {
    return withinBounds(state->as<ob::RealVectorStateSpace::StateType>()->values,
                        joints_->getBounds());
  }
  if (position_) {
    const auto* s = state->as<ob::SE3StateSpace::StateType>();
    return withinBounds(s->as<ob::RealVectorStateSpace::StateType>(0)->values,
                        position_->getBounds()) &&
           unitQuaternion(s->rotation());
  }
  return si_->satisfiesBounds(state);
}

void configurationToState(const RobotModel& robot, const std::vector<double>& q,
                          const Eigen::Isometry3d& X_WB, ob::State* state) {
  if (robot.isFreeFlying()) {
    auto* s = state->as<ob::SE3StateSpace::StateType>();
    s->setXYZ(X_WB.translation().x(), X_WB.translation().y(), X_WB.translation().z());
    const Eigen::Quaterniond quat(X_WB.linear());
    s->rotation().w = quat.w();
    s->rotation().x = quat.x();
    s->rotation().y = quat.y();
    s->rotation().z = quat.z();
    return;
  }
  if (q.size() != static_cast<std::size_t>(robot.variableCount())) {
    throw InvalidArgument(robot.name() + ": expected " + std::to_string(robot.variableCount()) +
                          " joint values, got " + std::to_string(q.size()));
  }
  auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  for (std::size_t i = 0; i < q.size(); ++i) s->values[i] = q[i];
}

}  // namespace octomotion
