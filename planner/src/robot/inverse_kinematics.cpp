#include "octomotion/planner/robot/inverse_kinematics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>

namespace octomotion {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Levenberg-Marquardt damping: the start, its bounds, and how it moves after an accepted
// (shrink) or a rejected (grow) step. A damping past kMaxDamping means no step helps any more: a
// local minimum or a limit, so the attempt restarts.
constexpr double kInitialDamping = 1e-2;
constexpr double kMinDamping = 1e-9;
constexpr double kMaxDamping = 1e4;
constexpr double kShrink = 0.3;
constexpr double kGrow = 10.0;
// Accepted steps that each lower the error by less than this fraction count as no progress;
// this many in a row end the attempt (a slow crawl along a limit rarely gets anywhere).
constexpr double kMinProgress = 1e-3;
constexpr int kMaxSlowSteps = 10;

// The link's error towards the target: position (world, metres) in the head, and, with a target
// orientation, the rotation vector taking the link's orientation to it (world, radians).
struct TargetFrame {
  Eigen::Vector3d position;
  Eigen::Matrix3d R_WT;
  bool has_orientation;
};

Vector6d poseError(const TargetFrame& target, const Eigen::Isometry3d& X_WL) {
  Vector6d e = Vector6d::Zero();
  e.head<3>() = target.position - X_WL.translation();
  if (target.has_orientation) {
    Eigen::Quaterniond r(target.R_WT * X_WL.linear().transpose());
    if (r.w() < 0) r.coeffs() = -r.coeffs();  // the short way round
    const double s = r.vec().norm();
    // angle = 2 atan2(s, w); near zero angle / s tends to 2.
    const double scale = s > 1e-12 ? 2.0 * std::atan2(s, r.w()) / s : 2.0;
    e.tail<3>() = scale * r.vec();
  }
  return e;
}

TargetFrame frameOf(const LinkPoseTarget& target) {
  TargetFrame f;
  f.position = target.position;
  f.has_orientation = target.orientation.has_value();
  f.R_WT = f.has_orientation ? target.orientation->normalized().toRotationMatrix()
                             : Eigen::Matrix3d::Identity();
  return f;
}

// The Jacobian of the link at the configuration whose kinematics s.data holds, into s.J:
// column of variable v = sum over the chain's joints it drives of multiplier * [axis x (p - o);
// axis] (revolute, continuous) or [axis; 0] (prismatic), in the world frame. Without an
// orientation the angular rows stay zero.
void linkJacobian(const RobotModel& robot, int link, bool orientation, IkScratch& s) {
  const Eigen::Vector3d p = s.data.linkPose(link).translation();
  s.J.setZero();
  for (const int j : s.chain) {
    const Joint& joint = robot.joint(j);
    const Eigen::Isometry3d& X_WC = s.data.linkPose(joint.child_link);
    const Eigen::Vector3d axis = X_WC.linear() * joint.axis;
    double multiplier = 1.0;
    int variable = joint.variable;
    if (joint.isMimic()) {
      multiplier = joint.mimic_multiplier;
      variable = robot.joint(joint.mimic_master).variable;
    }
    auto column = s.J.col(variable);
    if (joint.type == JointType::kPrismatic) {
      column.head<3>() += multiplier * axis;
    } else {
      column.head<3>() += multiplier * axis.cross(p - X_WC.translation());
      if (orientation) column.tail<3>() += multiplier * axis;
    }
  }
}

// The movable joints on the way from the link to the root; held (fixed) joints have no column.
void chainOf(const RobotModel& robot, int link, std::vector<int>& chain) {
  chain.clear();
  for (int l = link; robot.link(l).parent_joint >= 0; l = robot.link(l).parent_link) {
    const Joint& joint = robot.joint(robot.link(l).parent_joint);
    const int variable =
        joint.isMimic() ? robot.joint(joint.mimic_master).variable : joint.variable;
    if (joint.movable() && variable >= 0) chain.push_back(robot.link(l).parent_joint);
  }
}

std::string number(double v) {
  return std::to_string(v);
}

}  // namespace

InverseKinematics::InverseKinematics(const RobotModel& robot, const Eigen::Isometry3d& X_WB,
                                     const IkOptions& options)
    : robot_(&robot), X_WB_(X_WB), options_(options) {
  if (robot.isFreeFlying()) {
    throw InvalidArgument("inverse kinematics: robot '" + robot.name() +
                          "' is a free-flying body; give its goal as a pose");
  }
  if (robot.variableCount() == 0) {
    throw InvalidArgument("inverse kinematics: robot '" + robot.name() +
                          "' has no joint variables to solve for");
  }
  if (!X_WB.matrix().allFinite()) {
    throw InvalidArgument("inverse kinematics: the base pose is not finite");
  }
  auto positive = [](double v, const char* what) {
    if (!(std::isfinite(v) && v > 0)) {
      throw InvalidArgument(std::string("inverse kinematics: ") + what + " must be > 0, got " +
                            number(v));
    }
  };
  positive(options.position_tolerance, "the position tolerance");
  positive(options.orientation_tolerance, "the orientation tolerance");
  positive(options.max_step, "the step limit");
  if (options.max_iterations < 1 || options.max_attempts < 1) {
    throw InvalidArgument("inverse kinematics: max_iterations and max_attempts must be >= 1");
  }
}

IkScratch InverseKinematics::makeScratch() const {
  IkScratch s;
  const auto n = static_cast<std::size_t>(robot_->variableCount());
  s.data = robot_->makeData();
  s.J.setZero(6, robot_->variableCount());
  s.q.resize(n);
  s.trial.resize(n);
  s.best.resize(n);
  s.chain.reserve(static_cast<std::size_t>(robot_->jointCount()));
  return s;
}

LinkPoseTarget InverseKinematics::target(
    const std::string& link, const Eigen::Vector3d& position,
    const std::optional<Eigen::Quaterniond>& orientation) const {
  LinkPoseTarget t;
  t.link = robot_->linkIndex(link);
  t.position = position;
  t.orientation = orientation;
  checkTarget(t);
  if (t.orientation) t.orientation->normalize();
  return t;
}

void InverseKinematics::checkTarget(const LinkPoseTarget& target) const {
  if (target.link < 0 || target.link >= robot_->linkCount()) {
    throw InvalidArgument("inverse kinematics: link index " + std::to_string(target.link) +
                          " is not a link of robot '" + robot_->name() + "'");
  }
  const std::string& name = robot_->link(target.link).name;
  if (!target.position.allFinite()) {
    throw InvalidArgument("inverse kinematics: the target position of link '" + name +
                          "' is not finite");
  }
  if (target.orientation) {
    const Eigen::Vector4d c = target.orientation->coeffs();
    if (!c.allFinite() || !(c.norm() > 1e-12)) {
      throw InvalidArgument("inverse kinematics: the target orientation of link '" + name +
                            "' is not a finite, non-zero quaternion");
    }
  }
}

void InverseKinematics::randomConfiguration(std::mt19937_64& rng, std::vector<double>& q) const {
  const std::vector<Variable>& vars = robot_->variables();
  q.resize(vars.size());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < vars.size(); ++i) {
    q[i] = vars[i].lower + (vars[i].upper - vars[i].lower) * unit(rng);
  }
}

std::pair<double, double> InverseKinematics::errors(const LinkPoseTarget& target,
                                                    const std::vector<double>& q,
                                                    RobotData& data) const {
  checkTarget(target);
  robot_->forwardKinematics(q.data(), q.size(), data, X_WB_);
  const Vector6d e = poseError(frameOf(target), data.linkPose(target.link));
  return {e.head<3>().norm(), e.tail<3>().norm()};
}

IkResult InverseKinematics::solve(const LinkPoseTarget& target, const std::vector<double>& seed,
                                  std::uint64_t rng_seed) const {
  std::mt19937_64 rng(rng_seed);
  IkScratch scratch = makeScratch();
  return solve(target, seed, rng, scratch);
}

IkResult InverseKinematics::solve(const LinkPoseTarget& target, const std::vector<double>& seed,
                                  std::mt19937_64& rng, IkScratch& s) const {
  checkTarget(target);
  const RobotModel& robot = *robot_;
  const std::vector<Variable>& vars = robot.variables();
  const std::size_t n = vars.size();
  if (seed.size() != n) {
    throw InvalidArgument("inverse kinematics: the seed has " + std::to_string(seed.size()) +
                          " values but robot '" + robot.name() + "' has " + std::to_string(n) +
                          " variables");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(seed[i])) {
      throw InvalidArgument("inverse kinematics: seed[" + std::to_string(i) + "] (" + vars[i].name +
                            ") is not finite");
    }
  }
  if (s.q.size() != n || s.J.cols() != static_cast<Eigen::Index>(n)) s = makeScratch();

  const TargetFrame frame = frameOf(target);
  chainOf(robot, target.link, s.chain);

  // Into the limits: bounded variables clamped, continuous ones wrapped into [-pi, pi].
  auto limit = [&](std::vector<double>& q) {
    for (std::size_t i = 0; i < n; ++i) {
      q[i] = vars[i].continuous ? std::remainder(q[i], 2 * M_PI)
                                : std::clamp(q[i], vars[i].lower, vars[i].upper);
    }
  };
  auto within = [&](const Vector6d& e) {
    return e.head<3>().squaredNorm() <= options_.position_tolerance * options_.position_tolerance &&
           e.tail<3>().squaredNorm() <=
               options_.orientation_tolerance * options_.orientation_tolerance;
  };

  IkResult result;
  double best_cost = std::numeric_limits<double>::infinity();
  Vector6d best_error = Vector6d::Constant(std::numeric_limits<double>::infinity());
  for (int attempt = 0; attempt < options_.max_attempts; ++attempt) {
    ++result.attempts;
    if (attempt == 0) {
      s.q = seed;  // sizes match: no allocation
    } else {
      randomConfiguration(rng, s.q);
    }
    limit(s.q);
    robot.forwardKinematics(s.q.data(), n, s.data, X_WB_);
    ++result.iterations;
    Vector6d e = poseError(frame, s.data.linkPose(target.link));
    double cost = e.squaredNorm();
    double damping = kInitialDamping;
    int slow_steps = 0;
    bool jacobian_current = false;  // a rejected step leaves q, hence J, as they were
    for (int it = 1; it < options_.max_iterations && !within(e); ++it) {
      if (!jacobian_current) linkJacobian(robot, target.link, frame.has_orientation, s);
      jacobian_current = true;
      // dq = J^T (J J^T + damping I)^-1 e: a 6x6 solve whatever the number of variables.
      Matrix6d A;
      A.noalias() = s.J.lazyProduct(s.J.transpose());  // coefficient-wise: no blocking buffers
      A.diagonal().array() += damping;
      const Vector6d y = A.ldlt().solve(e);
      double largest = 0;
      for (std::size_t i = 0; i < n; ++i) {
        largest = std::max(largest, std::abs(s.J.col(static_cast<Eigen::Index>(i)).dot(y)));
      }
      const double scale = largest > options_.max_step ? options_.max_step / largest : 1.0;
      for (std::size_t i = 0; i < n; ++i) {
        s.trial[i] = s.q[i] + scale * s.J.col(static_cast<Eigen::Index>(i)).dot(y);
      }
      limit(s.trial);
      robot.forwardKinematics(s.trial.data(), n, s.data, X_WB_);
      ++result.iterations;
      const Vector6d trial_error = poseError(frame, s.data.linkPose(target.link));
      const double trial_cost = trial_error.squaredNorm();
      if (trial_cost < cost) {
        slow_steps = trial_cost > (1 - kMinProgress) * cost ? slow_steps + 1 : 0;
        std::swap(s.q, s.trial);
        e = trial_error;
        cost = trial_cost;
        damping = std::max(damping * kShrink, kMinDamping);
        jacobian_current = false;
        if (slow_steps >= kMaxSlowSteps && !within(e)) break;
      } else {
        damping *= kGrow;
        if (damping > kMaxDamping) break;
      }
    }
    const bool success = within(e);
    // A success is the answer even when a failed attempt came closer in the summed error.
    if (success || cost < best_cost) {
      best_cost = cost;
      best_error = e;
      s.best = s.q;
    }
    if (success) {
      result.success = true;
      break;
    }
  }
  result.q = s.best;
  result.position_error = best_error.head<3>().norm();
  result.orientation_error = best_error.tail<3>().norm();
  return result;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> InverseKinematics::jacobian(
    int link, const std::vector<double>& q) const {
  checkTarget(LinkPoseTarget{link, Eigen::Vector3d::Zero(), std::nullopt});
  IkScratch s = makeScratch();
  robot_->forwardKinematics(q.data(), q.size(), s.data, X_WB_);
  chainOf(*robot_, link, s.chain);
  linkJacobian(*robot_, link, true, s);
  return s.J;
}

}  // namespace octomotion
