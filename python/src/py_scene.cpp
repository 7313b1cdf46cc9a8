// The Python module's Scene (py_scene.h) over the planner library's public API.
#include "py_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <shared_mutex>
#include <sstream>
#include <thread>

#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "octomotion/tools/option_table.h"
#include "octomotion/tools/study_options.h"
#include "octomotion/tools/trade_study.h"

namespace octomotion::python {

namespace ob = ompl::base;

namespace {

const char* kindName(InvalidityReason::Kind kind) {
  switch (kind) {
    case InvalidityReason::Kind::kNonFinite:
      return "non-finite";
    case InvalidityReason::Kind::kOutsideLimits:
      return "outside-limits";
    case InvalidityReason::Kind::kEnvironment:
      return "environment";
    case InvalidityReason::Kind::kSelf:
      return "self";
  }
  return "unknown";
}

const char* exactName(ExactContact exact) {
  switch (exact) {
    case ExactContact::kTouching:
      return "touching";
    case ExactContact::kApart:
      return "apart";
    case ExactContact::kUnknown:
      return "unknown";
  }
  return "unknown";
}

// A rigid transform from a 4×4 matrix: finite, last row (0 0 0 1), an orthonormal rotation.
Eigen::Isometry3d toIsometry(const Eigen::Matrix4d& m, const std::string& what) {
  if (!m.allFinite()) throw InvalidArgument(what + ": the pose is not finite");
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    throw InvalidArgument(what + ": the pose's last row is not (0, 0, 0, 1)");
  }
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if ((R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      R.determinant() < 0) {
    throw InvalidArgument(what + ": the pose's rotation is not a rotation matrix");
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = m.topRightCorner<3, 1>();
  return X;
}

EnvironmentObject makeObject(const std::string& name, const ShapeArgs& shape,
                             const Eigen::Isometry3d& X, const std::string& what) {
  EnvironmentObject object;
  object.name = name;
  object.X_WO = X;
  const int given = int(shape.box.has_value()) + int(shape.sphere.has_value()) +
                    int(shape.cylinder.has_value()) + int(shape.mesh.has_value());
  if (given != 1) {
    throw InvalidArgument(what + " '" + name +
                          "': give exactly one of box, sphere, cylinder, mesh");
  }
  if (shape.scale && !shape.mesh) throw InvalidArgument(what + ": scale is for meshes only");
  if (shape.box) {
    if (shape.box->size() != 3) throw InvalidArgument(what + ": box: expected 3 sizes");
    object.primitive =
        Box{0.5 * Eigen::Vector3d((*shape.box)[0], (*shape.box)[1], (*shape.box)[2])};
  } else if (shape.sphere) {
    object.primitive = Sphere{*shape.sphere};
  } else if (shape.cylinder) {
    if (shape.cylinder->size() != 2) {
      throw InvalidArgument(what + ": cylinder: expected (radius, length)");
    }
    object.primitive = Cylinder{(*shape.cylinder)[0], (*shape.cylinder)[1]};
  } else {
    object.kind = EnvironmentObject::Kind::kMesh;
    object.file = std::filesystem::absolute(*shape.mesh).lexically_normal().string();
    if (shape.scale) {
      if (shape.scale->size() != 3) throw InvalidArgument(what + ": scale: expected 3 values");
      object.scale = Eigen::Vector3d((*shape.scale)[0], (*shape.scale)[1], (*shape.scale)[2]);
    }
  }
  if (object.kind == EnvironmentObject::Kind::kPrimitive) validate(object.primitive);
  return object;
}

std::vector<double> stateValues(const ob::State* state, bool free_flying, int dof) {
  if (free_flying) {
    const auto* s = state->as<ob::SE3StateSpace::StateType>();
    return {s->getX(),       s->getY(),       s->getZ(),      s->rotation().x,
            s->rotation().y, s->rotation().z, s->rotation().w};
  }
  const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
  return std::vector<double>(v, v + dof);
}

template <class Options>
void applyFlags(const tools::OptionTable<Options>& table,
                const std::vector<std::pair<std::string, std::string>>& flags, Options& target,
                const std::string& what) {
  for (const auto& [flag, value] : flags) {
    if (!table.parse(
            flag, [&value = value] { return value; }, target)) {
      throw InvalidArgument(what + ": unknown option '" + flag + "'");
    }
  }
}

}  // namespace

Scene::Scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags,
             bool require_free_start_goal, bool fit_universe_to_reach) {
  SceneOverrides overrides;
  applyFlags(tools::sceneOptions(), flags, overrides, "load_scene");
  overrides.require_free_start_goal = require_free_start_goal;
  overrides.fit_universe_to_reach = fit_universe_to_reach;
  scene_ = std::make_shared<PlanningScene>(loadPlanningScene(path, overrides));
  si_ = scene_->setup->getSpaceInformation();
  si_->setup();
  const RobotModel& robot = scene_->model->robot();
  if (robot.isFreeFlying()) {
    names_ = {"x", "y", "z", "qx", "qy", "qz", "qw"};
  } else {
    for (const Variable& v : robot.variables()) names_.push_back(v.name);
  }
  dof_ = static_cast<int>(names_.size());
  const ob::ProblemDefinitionPtr pdef = scene_->setup->getProblemDefinition();
  if (pdef->getStartStateCount() > 0) {
    scene_start_ = stateValues(pdef->getStartState(0), freeFlying(), dof_);
  }
  scene_goal_ = pdef->getGoal();
}

std::pair<std::vector<double>, std::vector<double>> Scene::bounds() const {
  const ob::StateSpace* space = si_->getStateSpace().get();
  const ob::RealVectorBounds* b = nullptr;
  if (freeFlying()) {
    b = &space->as<ob::SE3StateSpace>()->getBounds();
  } else {
    b = &space->as<ob::RealVectorStateSpace>()->getBounds();
  }
  std::vector<double> low = b->low, high = b->high;
  if (freeFlying()) {
    low.insert(low.end(), 4, -1.0);
    high.insert(high.end(), 4, 1.0);
  }
  return {low, high};
}

bool Scene::freeFlying() const {
  return scene_->model->robot().isFreeFlying();
}

void Scene::setState(const double* q, ob::State* state) const {
  if (freeFlying()) {
    auto* s = state->as<ob::SE3StateSpace::StateType>();
    s->setXYZ(q[0], q[1], q[2]);
    s->rotation().x = q[3];
    s->rotation().y = q[4];
    s->rotation().z = q[5];
    s->rotation().w = q[6];
    return;
  }
  double* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  std::copy(q, q + dof_, values);
}

bool Scene::checkUnlocked(const double* q) const {
  ob::ScopedState<> state(si_);
  setState(q, state.get());
  return si_->getStateValidityChecker()->isValid(state.get());
}

void Scene::checkMany(const double* Q, std::size_t rows, std::uint8_t* valid,
                      unsigned threads) const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  const ob::StateValidityCheckerPtr checker = si_->getStateValidityChecker();
  const std::size_t dof = static_cast<std::size_t>(dof_);
  auto run = [&](std::size_t begin, std::size_t end, ob::State* state) {
    for (std::size_t i = begin; i < end; ++i) {
      setState(Q + i * dof, state);
      valid[i] = checker->isValid(state) ? 1 : 0;
    }
  };
  if (threads <= 1 || rows < 2) {
    ob::ScopedState<> state(si_);
    run(0, rows, state.get());
    return;
  }
  // Blocks handed out in turn, so a thread that meets slow (colliding) states takes fewer.
  constexpr std::size_t kBlock = 256;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    ob::ScopedState<> state(si_);
    for (std::size_t b = next.fetch_add(kBlock); b < rows; b = next.fetch_add(kBlock)) {
      run(b, std::min(rows, b + kBlock), state.get());
    }
  };
  std::vector<std::thread> pool;
  const unsigned n =
      static_cast<unsigned>(std::min<std::size_t>(threads, (rows + kBlock - 1) / kBlock));
  for (unsigned t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

double Scene::clearance(const double* q) const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  ob::ScopedState<> state(si_);
  setState(q, state.get());
  return si_->getStateValidityChecker()->clearance(state.get());
}

std::vector<double> Scene::configuration(const double* q, Eigen::Isometry3d& X_WB,
                                         bool& finite) const {
  X_WB = Eigen::Isometry3d::Identity();
  finite = true;
  if (!freeFlying()) return std::vector<double>(q, q + dof_);
  ob::ScopedState<> state(si_);
  setState(q, state.get());
  std::vector<double> config;
  finite = stateToConfiguration(scene_->model->robot(), state.get(), config, X_WB);
  return config;
}

bool Scene::check(const double* q) const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  return checkUnlocked(q);
}

std::vector<Reason> Scene::explain(const double* q) const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  return explainUnlocked(q);
}

std::vector<Reason> Scene::explainUnlocked(const double* q) const {
  std::vector<Reason> reasons;
  Eigen::Isometry3d X_WB;
  bool finite = true;
  const std::vector<double> config = configuration(q, X_WB, finite);
  if (!finite) {
    Reason r;
    r.kind = "non-finite";
    r.link = "base pose";
    r.text = "the pose is not finite or its quaternion is zero";
    reasons.push_back(r);
    return reasons;
  }
  const std::shared_ptr<const CollisionBackend> backend = checkerBackend(*scene_);
  const std::unique_ptr<BackendScratch> scratch = backend->makeBackendScratch();
  ExplainOptions options;
  options.all = true;
  const StateExplanation e =
      backend->explain(config.data(), config.size(), X_WB, *scratch, options);
  for (const InvalidityReason& reason : e.reasons) {
    Reason r;
    r.kind = kindName(reason.kind);
    r.link = reason.link;
    r.other = reason.other;
    r.exact = exactName(reason.exact);
    r.margin = reason.margin;
    r.value = reason.value;
    r.lower = reason.lower;
    r.upper = reason.upper;
    r.text = describe(reason);
    reasons.push_back(r);
  }
  if (reasons.empty()) {
    ob::ScopedState<> state(si_);
    setState(q, state.get());
    if (!si_->satisfiesBounds(state.get())) {
      Reason r;
      r.kind = "bounds";
      r.text = "outside the state space's bounds";
      reasons.push_back(r);
    }
  }
  return reasons;
}

std::vector<std::pair<std::string, Eigen::Matrix4d>> Scene::forwardKinematics(
    const double* q) const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  const RobotModel& robot = scene_->model->robot();
  Eigen::Isometry3d X_WB;
  bool finite = true;
  const std::vector<double> config = configuration(q, X_WB, finite);
  if (!finite) throw InvalidArgument("forward_kinematics: the pose is not finite");
  if (!robot.isFreeFlying()) X_WB = scene_->spec.robot.pose.value_or(Eigen::Isometry3d::Identity());
  RobotData data = robot.makeData();
  robot.forwardKinematics(config.data(), config.size(), data, X_WB);
  std::vector<std::pair<std::string, Eigen::Matrix4d>> poses;
  for (int l = 0; l < robot.linkCount(); ++l)
    poses.emplace_back(robot.link(l).name, data.linkPose(l).matrix());
  return poses;
}

std::vector<double> Scene::plan(const std::string& planner, std::optional<double> time,
                                std::optional<std::uint64_t> seed, const std::vector<double>* start,
                                const std::vector<double>* goal, double interpolation,
                                std::size_t& states) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  ompl::geometric::SimpleSetup& ss = *scene_->setup;
  const ob::ProblemDefinitionPtr pdef = ss.getProblemDefinition();
  if (time) {
    if (!std::isfinite(*time) || *time <= 0 || *time > kMaxPlanningSeconds) {
      throw InvalidArgument("plan: time must be in (0, " + std::to_string(kMaxPlanningSeconds) +
                            "] seconds");
    }
    scene_->spec.problem.time = *time;
  }
  if (seed) {
    // OMPL logs an error when its seed changes after the first random number: expected here,
    // where each plan reseeds before it makes its planner.
    const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(*seed));
    ompl::msg::setLogLevel(level);
  }
  // A fresh planner each time: no roadmap or tree from an earlier plan, and seeded as asked.
  ss.setPlanner(makePlanner(planner, si_));
  scene_->spec.problem.planner = planner;
  auto checkGiven = [&](const std::vector<double>& q, const char* what) {
    if (q.size() != static_cast<std::size_t>(dof_)) {
      throw InvalidArgument(std::string("plan: ") + what + " has " + std::to_string(q.size()) +
                            " values, expected " + std::to_string(dof_));
    }
    if (!checkUnlocked(q.data())) {
      std::string why;
      for (const Reason& r : explainUnlocked(q.data())) why += (why.empty() ? "" : "; ") + r.text;
      throw InvalidArgument(std::string("plan: ") + what + " is invalid" +
                            (why.empty() ? "" : ": " + why));
    }
  };
  const std::vector<double>& start_q = start ? *start : scene_start_;
  if (start_q.empty()) throw InvalidArgument("plan: the scene has no start: give start=");
  if (!goal && !scene_goal_) throw InvalidArgument("plan: the scene has no goal: give goal=");
  checkGiven(start_q, "start");
  ob::ScopedState<> start_state(si_);
  setState(start_q.data(), start_state.get());
  ss.clear();
  pdef->clearStartStates();
  pdef->addStartState(start_state);
  if (goal) {
    checkGiven(*goal, "goal");
    auto goal_state = std::make_shared<ob::GoalState>(si_);
    ob::ScopedState<> g(si_);
    setState(goal->data(), g.get());
    goal_state->setState(g);
    ss.setGoal(goal_state);
  } else {
    ss.setGoal(scene_goal_);
  }
  const PlanResult result = octomotion::plan(*scene_, interpolation);
  states = 0;
  std::vector<double> path;
  if (!result.solved || !result.path) return path;
  for (const ob::State* s : result.path->getStates()) {
    const std::vector<double> v = stateValues(s, freeFlying(), dof_);
    path.insert(path.end(), v.begin(), v.end());
    ++states;
  }
  return path;
}

void Scene::addObject(const std::string& name, const ShapeArgs& shape,
                      const Eigen::Matrix4d& X_WO) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  scene_->addObject(makeObject(name, shape, toIsometry(X_WO, "add_object"), "add_object"));
}

void Scene::removeObject(const std::string& name) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  scene_->removeObject(name);
}

void Scene::moveObject(const std::string& name, const Eigen::Matrix4d& X_WO) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  scene_->moveObject(name, toIsometry(X_WO, "move_object"));
}

void Scene::attachObject(const std::string& name, const std::string& link, const ShapeArgs& shape,
                         const Eigen::Matrix4d& X_LO, const std::vector<std::string>& touch_links) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  AttachedObject attached;
  attached.object = makeObject(name, shape, toIsometry(X_LO, "attach_object"), "attach_object");
  attached.link = link;
  attached.touch_links = touch_links;
  scene_->attachObject(attached);
}

void Scene::detachObject(const std::string& name, const std::vector<double>* leave_at) {
  const std::unique_lock<std::shared_mutex> lock(mutex_);
  if (!leave_at) {
    scene_->detachObject(name);
    return;
  }
  if (freeFlying()) throw InvalidArgument("detach_object: leave_at is for fixed-base robots");
  if (leave_at->size() != static_cast<std::size_t>(dof_)) {
    throw InvalidArgument("detach_object: leave_at has " + std::to_string(leave_at->size()) +
                          " values, expected " + std::to_string(dof_));
  }
  scene_->detachObject(name, leave_at);
}

std::vector<std::string> Scene::objectNames() const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  std::vector<std::string> names;
  if (scene_->environment) {
    for (const EnvironmentGeometry::Item& item : scene_->environment->items()) {
      names.push_back(item.spec.name);
    }
  }
  return names;
}

std::vector<std::string> Scene::attachedNames() const {
  const std::shared_lock<std::shared_mutex> lock(mutex_);
  std::vector<std::string> names;
  for (const AttachedObject& a : scene_->attached) names.push_back(a.object.name);
  return names;
}

std::pair<std::string, std::string> tradeStudy(
    const std::string& path, const std::vector<std::pair<std::string, std::string>>& flags) {
  tools::StudyCommandOptions options;
  options.study.scene_path = path;
  applyFlags(tools::studyOptions(), flags, options, "trade_study");
  tools::finishStudyOptions(options);
  const TradeStudyResult result = runTradeStudy(options.study);
  std::ostringstream checks, planning;
  writeCheckCsv(result.checks, checks);
  writePlanCsv(result.planning, planning);
  return {checks.str(), planning.str()};
}

BenchSetResult benchSet(tools::ProblemSetOptions options,
                        const std::vector<std::pair<std::string, std::string>>& flags,
                        const std::string& log_dir) {
  applyFlags(tools::sceneOptions(), flags, options.overrides, "bench_set");
  if (options.checkers.empty()) throw InvalidArgument("bench_set: checkers: no checker given");
  if (options.runs == 0) throw InvalidArgument("bench_set: runs: must be at least 1");
  if (!(options.recheck_density >= 1)) {
    throw InvalidArgument("bench_set: recheck_density: must be at least 1");
  }
  // The pairs' generated scene files live as long as the call.
  std::string pattern =
      (std::filesystem::temp_directory_path() / "octomotion-bench-set-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw FileError(pattern, "cannot create a temporary folder");
  struct RemoveOnExit {
    std::string dir;
    ~RemoveOnExit() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } scene_dir{pattern};
  options.scene_dir = scene_dir.dir;
  // Every load sets the seed again, which OMPL reports once sampling has started: the rows say
  // what happened, as the command's CSV does.
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  BenchSetResult out;
  try {
    const tools::ProblemSetResult result = tools::runProblemSet(options);
    std::ostringstream csv;
    tools::writeProblemCsv(result, csv);
    out.runs_csv = csv.str();
    out.summary = tools::summarize(result);
    out.seconds = result.seconds;
    if (!log_dir.empty()) out.logs = tools::writeOmplLogs(result, options, log_dir);
  } catch (...) {
    ompl::msg::setLogLevel(level);
    throw;
  }
  ompl::msg::setLogLevel(level);
  return out;
}

}  // namespace octomotion::python
