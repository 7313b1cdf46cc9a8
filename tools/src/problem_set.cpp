// The planning benchmark over a folder of problems: finding the problems and planning them.
// Summaries, the CSV and the OMPL logs are in problem_set_report.cpp.
#include "octomotion/tools/problem_set.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/StateValidityChecker.h>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/validity_checker.h"

namespace octomotion::tools {

namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

// A problem's own seed, from the benchmark's and the problem's set and name: with one seed for
// all, every problem's planner would draw the same samples, and the set's times would move
// together with that one sequence. The same for every checker of the problem (their plans stay
// comparable), the same whatever --limit keeps, and never 0 (OMPL ignores a zero seed).
std::uint64_t problemSeed(std::uint64_t seed, const SetProblem& p) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over "set/name"
  for (const char c : p.set + "/" + p.name) {
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  }
  hash ^= seed * 0x9E3779B97F4A7C15ull;
  return hash % 2147483647u + 1;  // within OMPL's 32-bit seeds
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

bool isYaml(const fs::path& p) {
  return p.extension() == ".yaml" || p.extension() == ".yml";
}

// The problems of one folder (not its sub-folders), appended to `out`; true when it has any.
bool folderProblems(const fs::path& folder, std::vector<SetProblem>& out) {
  std::vector<fs::path> files;
  bool pairs = false;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    files.push_back(entry.path());
    const std::string name = entry.path().filename().string();
    if (isYaml(entry.path()) && startsWith(name, "request")) pairs = true;
  }
  std::sort(files.begin(), files.end());
  fs::path normal = fs::absolute(folder).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();  // "DIR/"
  const std::string set = normal.filename().string();
  const std::size_t before = out.size();
  for (const fs::path& f : files) {
    const std::string name = f.filename().string();
    if (pairs) {
      if (!isYaml(f) || !startsWith(name, "request")) continue;
      const std::string number = name.substr(7);  // "NNNN.yaml"
      fs::path scene = folder / ("scene" + number);
      if (!fs::exists(scene)) scene = folder / ("scene_sensed" + number);
      if (!fs::exists(scene)) {
        throw FileError(f.string(), "no scene" + number + " (or scene_sensed" + number +
                                        ") beside this MoveIt request");
      }
      out.push_back(
          {set, f.stem().string(), "", fs::absolute(scene).string(), fs::absolute(f).string()});
    } else if (isYaml(f) || f.extension() == ".cfg") {
      out.push_back({set, f.stem().string(), fs::absolute(f).string(), "", ""});
    }
  }
  return out.size() > before;
}

void collect(const fs::path& folder, int depth, std::vector<SetProblem>& out) {
  if (folderProblems(folder, out) || depth == 0) return;
  std::vector<fs::path> subfolders;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_directory()) subfolders.push_back(entry.path());
  }
  std::sort(subfolders.begin(), subfolders.end());
  for (const fs::path& sub : subfolders) collect(sub, depth - 1, out);
}

// Counts the checks a plan makes, forwarding everything else to the scene's own checker.
class CountingStateChecker final : public ob::StateValidityChecker {
 public:
  CountingStateChecker(const ob::SpaceInformationPtr& si, ob::StateValidityCheckerPtr inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {
    specs_ = inner_->getSpecs();
  }
  using ob::StateValidityChecker::isValid;
  bool isValid(const ob::State* state) const override {
    count_.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state);
  }
  bool isValid(const ob::State* state, double& dist) const override {
    count_.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state, dist);
  }
  double clearance(const ob::State* state) const override { return inner_->clearance(state); }
  std::size_t take() const { return count_.exchange(0); }

 private:
  ob::StateValidityCheckerPtr inner_;
  mutable std::atomic<std::size_t> count_{0};
};

class CountingMotionValidator final : public ob::MotionValidator {
 public:
  CountingMotionValidator(const ob::SpaceInformationPtr& si, ob::MotionValidatorPtr inner)
      : ob::MotionValidator(si), inner_(std::move(inner)) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    count_.fetch_add(1, std::memory_order_relaxed);
    return inner_->checkMotion(s1, s2);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    count_.fetch_add(1, std::memory_order_relaxed);
    return inner_->checkMotion(s1, s2, last_valid);
  }
  std::size_t take() const { return count_.exchange(0); }

 private:
  ob::MotionValidatorPtr inner_;
  mutable std::atomic<std::size_t> count_{0};
};

std::string yamlString(const std::string& s) {
  std::string quoted = "\"";
  for (char c : s) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return quoted + "\"";
}

// A scene file for a MoveIt pair: the options' robot, the pair's objects and request.
std::string writePairScene(const SetProblem& p, const ProblemSetOptions& options) {
  fs::create_directories(options.scene_dir);
  const std::string path =
      (fs::path(options.scene_dir) / (p.set + "_" + p.name + ".yaml")).string();
  std::ofstream out(path);
  out << "robot: {urdf: " << yamlString(fs::absolute(options.urdf).string());
  if (!options.srdf.empty()) out << ", srdf: " << yamlString(fs::absolute(options.srdf).string());
  out << "}\nenvironment:\n  - moveit_scene: " << yamlString(p.moveit_scene)
      << "\nproblem:\n  moveit_request: " << yamlString(p.moveit_request) << "\n";
  if (!options.fixed.empty()) {
    out << "  fixed: {";
    for (const auto& [joint, value] : options.fixed) {
      out << (joint == options.fixed.begin()->first ? "" : ", ") << joint << ": " << value;
    }
    out << "}\n";
  }
  out.close();
  if (!out) throw FileError(path, "cannot write the problem's scene file");
  return path;
}

// Every state of the path's segments, each cut into `density` times the pieces the space's
// motion step gives it, checked with exact FCL: adds to the row's re-check counts.
void recheckWithFcl(const PlanningScene& scene, const og::PathGeometric& path, double density,
                    ProblemRun& row) {
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const FclValidityChecker fcl(si, scene.fclModel());
  const ob::StateSpacePtr& space = si->getStateSpace();
  ob::State* between = space->allocState();
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    const ob::State* a = path.getState(static_cast<unsigned>(i));
    const ob::State* b = path.getState(static_cast<unsigned>(i + 1));
    const std::size_t pieces =
        std::max<std::size_t>(1, static_cast<std::size_t>(space->validSegmentCount(a, b)) *
                                     static_cast<std::size_t>(std::max(1.0, density)));
    const bool last = i + 2 == path.getStateCount();
    for (std::size_t k = 0; k < pieces + (last ? 1 : 0); ++k) {
      space->interpolate(a, b, static_cast<double>(k) / static_cast<double>(pieces), between);
      ++row.recheck_states;
      if (!fcl.isValid(between)) ++row.recheck_colliding;
    }
  }
  space->freeState(between);
}

void planOnce(PlanningScene& scene, const CountingStateChecker& states,
              const CountingMotionValidator& motions, double density, ProblemRun& row) {
  og::SimpleSetup& ss = *scene.setup;
  ss.clear();
  states.take();
  motions.take();
  // The time limit checked in this thread, as `plan` does (planWithOmpl): the plan's time is
  // the planner's, not rounded up to a helper thread's next millisecond wake-up.
  const ob::PlannerStatus status =
      ss.solve(ob::timedPlannerTerminationCondition(scene.spec.problem.time));
  row.seconds = ss.getLastPlanComputationTime();
  row.state_checks = states.take();
  row.motion_checks = motions.take();
  row.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  if (!row.solved) return;
  ss.simplifySolution();
  const og::PathGeometric& path = ss.getSolutionPath();
  row.waypoints = path.getStateCount();
  row.length = path.length();
  recheckWithFcl(scene, path, density, row);
}

}  // namespace

std::vector<SetProblem> findProblems(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw FileError(dir, "not a folder of problems (scene files or MoveIt scene/request pairs)");
  }
  std::vector<SetProblem> problems;
  try {
    collect(dir, 2, problems);
  } catch (const fs::filesystem_error& e) {
    throw FileError(dir, std::string("cannot read the folder: ") + e.what());
  }
  if (problems.empty()) {
    throw FileError(dir,
                    "no problems: expected scene files (*.yaml, *.cfg) or MoveIt "
                    "sceneNNNN.yaml/requestNNNN.yaml pairs, here or in sub-folders");
  }
  std::stable_sort(problems.begin(), problems.end(),
                   [](const SetProblem& a, const SetProblem& b) { return a.set < b.set; });
  return problems;
}

ProblemSetResult runProblemSet(const ProblemSetOptions& options) {
  if (options.checkers.empty()) throw InvalidArgument("bench-set: no checker to run");
  if (options.runs == 0) throw InvalidArgument("bench-set: --runs must be at least 1");
  std::vector<SetProblem> problems = findProblems(options.dir);
  if (options.limit > 0) {
    std::vector<SetProblem> kept;
    std::map<std::string, std::size_t> per_set;
    for (SetProblem& p : problems) {
      if (per_set[p.set]++ < options.limit) kept.push_back(std::move(p));
    }
    problems = std::move(kept);
  }
  for (const SetProblem& p : problems) {
    if (!p.moveit_request.empty() && options.urdf.empty()) {
      throw InvalidArgument("bench-set: " + p.moveit_request +
                            ": MoveIt problems need the robot: give --robot URDF (and --srdf SRDF "
                            "for the request's group)");
    }
    if (!p.moveit_request.empty() && options.scene_dir.empty()) {
      throw InvalidArgument("bench-set: MoveIt problems need a folder for their scene files");
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  ProblemSetResult result;
  result.planner = options.overrides.planner.value_or("");
  const std::size_t total = problems.size() * options.checkers.size();
  std::size_t done = 0;
  for (const SetProblem& p : problems) {
    const std::string scene_path = p.scene.empty() ? writePairScene(p, options) : p.scene;
    for (const CheckerKind checker : options.checkers) {
      if (options.progress) {
        options.progress(done, total, p.set + "/" + p.name + " " + checkerKindName(checker));
      }
      ++done;
      SceneOverrides overrides = options.overrides;
      overrides.checker = checker;
      if (options.overrides.seed) overrides.seed = problemSeed(*options.overrides.seed, p);
      ProblemRun row;
      row.set = p.set;
      row.problem = p.name;
      row.checker = checker;
      row.seed = overrides.seed.value_or(0);
      std::optional<PlanningScene> scene;
      try {
        scene.emplace(loadPlanningScene(scene_path, overrides, [](const std::string&) {}));
      } catch (const std::exception& e) {
        row.error = e.what();
        row.time_limit = options.overrides.time.value_or(0);
        row.seconds = row.time_limit;
        for (std::size_t r = 0; r < options.runs; ++r) {
          row.run = r;
          result.runs.push_back(row);
        }
        continue;
      }
      if (result.planner.empty()) result.planner = scene->spec.problem.planner;
      row.resolution = scene->spec.octree.resolution.value_or(0);
      row.time_limit = scene->spec.problem.time;
      const ob::SpaceInformationPtr& si = scene->setup->getSpaceInformation();
      if (!si->isSetup()) si->setup();  // makes the motion validator when the scene has none
      auto states = std::make_shared<CountingStateChecker>(si, si->getStateValidityChecker());
      auto motions = std::make_shared<CountingMotionValidator>(si, si->getMotionValidator());
      si->setStateValidityChecker(states);
      si->setMotionValidator(motions);
      for (std::size_t r = 0; r < options.runs; ++r) {
        ProblemRun run = row;
        run.run = r;
        if (!scene->spec.problem.start || !scene->spec.problem.goal) {
          run.error = "no start or goal to plan between";
        } else {
          try {
            planOnce(*scene, *states, *motions, options.recheck_density, run);
          } catch (const std::exception& e) {  // OMPL's own exceptions included
            run.error = e.what();
            run.solved = false;
          }
        }
        result.runs.push_back(run);
      }
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (options.progress) options.progress(total, total, "done");
  return result;
}

}  // namespace octomotion::tools
