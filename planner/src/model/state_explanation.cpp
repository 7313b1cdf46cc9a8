// CollisionBackend::explain's common part (inputs and joint limits) and the explanations' text.
#include "octomotion/planner/model/state_explanation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "octomotion/error.h"
#include "octomotion/planner/model/collision_backend.h"

namespace octomotion {

namespace {

bool isContact(const InvalidityReason& r) {
  return r.kind == InvalidityReason::Kind::kEnvironment || r.kind == InvalidityReason::Kind::kSelf;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

bool StateExplanation::inCollision() const {
  return std::any_of(reasons.begin(), reasons.end(), isContact);
}

bool StateExplanation::onlyVoxelMargin() const {
  bool any = false;
  for (const InvalidityReason& r : reasons) {
    if (!isContact(r)) continue;
    if (r.exact != ExactContact::kApart) return false;
    any = true;
  }
  return any;
}

std::string describe(const InvalidityReason& r) {
  switch (r.kind) {
    case InvalidityReason::Kind::kNonFinite:
      return r.link + " is not finite";
    case InvalidityReason::Kind::kOutsideLimits:
      return "joint '" + r.link + "' = " + number(r.value) + " is outside its limits [" +
             number(r.lower) + ", " + number(r.upper) + "]";
    case InvalidityReason::Kind::kEnvironment:
      return (r.link.empty() ? std::string("the robot") : "link " + r.link) + " with " +
             (r.other.empty() ? std::string("the environment") : "object " + r.other);
    case InvalidityReason::Kind::kSelf:
      return r.link.empty() ? std::string("a self-collision")
                            : "link " + r.link + " with link " + r.other;
  }
  return "";
}

std::string describe(const StateExplanation& explanation) {
  std::string text;
  for (const InvalidityReason& r : explanation.reasons) {
    text += (text.empty() ? "" : "; ") + describe(r);
  }
  return text;
}

StateExplanation CollisionBackend::explain(const double* q, std::size_t q_size,
                                           const Eigen::Isometry3d& X_WB, BackendScratch& scratch,
                                           const ExplainOptions& options) const {
  const RobotModel& model = robot();
  const std::vector<Variable>& variables = model.variables();
  if (q_size != variables.size()) {
    throw InvalidArgument("explain: q has " + std::to_string(q_size) + " values but robot '" +
                          model.name() + "' has " + std::to_string(variables.size()) +
                          " variables");
  }
  StateExplanation e;
  auto add = [&](InvalidityReason::Kind kind, const std::string& what) {
    InvalidityReason r;
    r.kind = kind;
    r.link = what;
    e.reasons.push_back(r);
    return &e.reasons.back();
  };
  for (std::size_t i = 0; i < q_size; ++i) {
    if (!std::isfinite(q[i])) {
      add(InvalidityReason::Kind::kNonFinite,
          "q[" + std::to_string(i) + "] (" + variables[i].name + ")");
    }
  }
  if (model.isFreeFlying() && !(X_WB.matrix().allFinite())) {
    add(InvalidityReason::Kind::kNonFinite, "base pose");
  }
  if (!e.reasons.empty()) return e;  // nothing to pose
  if (options.check_limits) {
    for (std::size_t i = 0; i < q_size; ++i) {
      const Variable& v = variables[i];
      if (v.continuous || (q[i] >= v.lower && q[i] <= v.upper)) continue;
      InvalidityReason* r = add(InvalidityReason::Kind::kOutsideLimits, v.name);
      r->value = q[i];
      r->lower = v.lower;
      r->upper = v.upper;
    }
  }
  explainContacts(q, q_size, X_WB, scratch, options.all, e);
  return e;
}

void CollisionBackend::explainContacts(const double* q, std::size_t q_size,
                                       const Eigen::Isometry3d& X_WB, BackendScratch& scratch,
                                       bool all, StateExplanation& explanation) const {
  auto add = [&](InvalidityReason::Kind kind) {
    InvalidityReason r;
    r.kind = kind;
    r.exact = ExactContact::kUnknown;
    explanation.reasons.push_back(r);
  };
  RobotData data = robot().makeData();
  if (!poseForExplain(robot(), q, q_size, X_WB, data, explanation)) return;
  const bool environment = environmentInCollision(q, q_size, X_WB, scratch);
  if (environment) add(InvalidityReason::Kind::kEnvironment);
  if ((all || !environment) && selfInCollision(q, q_size, X_WB, scratch)) {
    add(InvalidityReason::Kind::kSelf);
  }
}

void CollisionBackend::motionClearances(BackendScratch& scratch, const double* /*caps*/,
                                        double* per_link, NearestObstacle* nearest) const {
  const double c = motionClearance(scratch);
  for (int l = 0; l < robot().linkCount(); ++l) per_link[l] = c;
  if (nearest) std::fill_n(nearest, robot().linkCount(), NearestObstacle{});
}

bool CollisionBackend::poseForExplain(const RobotModel& robot, const double* q, std::size_t q_size,
                                      const Eigen::Isometry3d& X_WB, RobotData& data,
                                      StateExplanation& explanation) {
  // Finite values can still give a non-finite pose: forwardKinematics throws after posing
  // every link, so the culprit is found in `data` rather than parsed from the message.
  try {
    robot.forwardKinematics(q, q_size, data, X_WB);
  } catch (const InvalidArgument&) {
    for (int l = 0; l < robot.linkCount(); ++l) {
      if (data.linkPose(l).matrix().allFinite()) continue;
      InvalidityReason r;
      r.kind = InvalidityReason::Kind::kNonFinite;
      r.link = "link '" + robot.link(l).name + "' pose";
      explanation.reasons.push_back(r);
      return false;
    }
    throw;
  }
  return true;
}

}  // namespace octomotion
