// A start or goal in collision: refused when the scene is loaded, naming the contact
// (CollisionBackend::explain), instead of OMPL's "no solution" after the whole time limit.
#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/base/goals/GoalState.h>

#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"

namespace octomotion {

namespace {

// At most this many contacts are named in the one-line message; the rest are counted.
constexpr std::size_t kNamedContacts = 3;

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::shared_ptr<const CollisionBackend> checkerBackend(const PlanningScene& scene) {
  if (scene.checker == CheckerKind::kFcl) return scene.fclModel();
  if (scene.checker == CheckerKind::kFclOctomap) return scene.fclOctomapModel();
  return std::make_shared<const OctreeBackend>(scene.model, octreeCheckerPath(scene.checker));
}

std::string describeCollision(const StateExplanation& explanation) {
  std::string text;
  std::size_t named = 0, contacts = 0;
  bool environment_margin = false, self_margin = false;
  double margin = 0;
  for (const InvalidityReason& r : explanation.reasons) {
    const bool environment = r.kind == InvalidityReason::Kind::kEnvironment;
    if (!environment && r.kind != InvalidityReason::Kind::kSelf) continue;
    ++contacts;
    if (named < kNamedContacts) {
      text += (named++ ? "; " : "") + describe(r);
    }
    if (r.exact == ExactContact::kApart) {
      (environment ? environment_margin : self_margin) = true;
      margin = std::max(margin, r.margin);
    }
  }
  if (contacts > named) text += " (and " + std::to_string(contacts - named) + " more)";
  if (explanation.onlyVoxelMargin()) {
    text += "; the exact shapes do not touch: within the voxel margin of resolution " +
            number(margin) + " m, try a finer " +
            (environment_margin ? std::string("--resolution") : std::string("")) +
            (environment_margin && self_margin ? " or " : "") +
            (self_margin ? "--self-link-resolution" : "");
  }
  return text;
}

void requireFreeStartAndGoal(const PlanningScene& scene) {
  if (!scene.setup) return;
  const auto& pdef = scene.setup->getProblemDefinition();
  if (!pdef || pdef->getStartStateCount() == 0 || !pdef->getGoal()) return;
  const auto* goal = dynamic_cast<const ompl::base::GoalState*>(pdef->getGoal().get());
  const bool cfg = std::filesystem::path(scene.spec.path).extension() == ".cfg";
  const std::shared_ptr<const CollisionBackend> backend = checkerBackend(scene);
  const RobotModel& robot = backend->robot();
  const std::unique_ptr<BackendScratch> scratch = backend->makeBackendScratch();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  for (const auto& [state, which] :
       {std::pair<const ompl::base::State*, const char*>{pdef->getStartState(0), "start"},
        {goal ? goal->getState() : nullptr, "goal"}}) {
    if (state == nullptr || !stateToConfiguration(robot, state, q, X_WB)) continue;
    // The plain check first: explaining builds per-object data a free state does not need.
    if (!backend->inCollision(q.data(), q.size(), X_WB, *scratch)) continue;
    ExplainOptions options;
    options.all = true;
    options.check_limits = false;  // requireWithinBounds' job, with the scene's field names
    const StateExplanation e = backend->explain(q.data(), q.size(), X_WB, *scratch, options);
    if (!e.inCollision()) continue;
    const std::string field =
        cfg ? "[problem] " + std::string(which) + ".*" : "problem." + std::string(which);
    throw FileError(scene.spec.path, field + " is in collision for the " +
                                         checkerKindName(scene.checker) +
                                         " checker: " + describeCollision(e));
  }
}

}  // namespace octomotion
