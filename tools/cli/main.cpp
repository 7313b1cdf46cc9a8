// The octomotion command: plan, check and describe scenes from the shell.
// Results go to stdout (or --out), progress and timings to stderr; any error is one line on
// stderr and a non-zero exit status.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"

namespace {

using namespace octomotion;

const char* kUsage = R"(usage:
  octomotion plan SCENE [--out PATH] [--planner NAME] [--time SECONDS] [--seed N] [options]
  octomotion check SCENE --states STATES.csv [--explain] [options]
  octomotion info SCENE [options]
  octomotion bench SCENE [bench options] [options]   (octomotion bench --help)
  octomotion bench-set DIR [bench-set options] [options]   (octomotion bench-set --help)
  octomotion view SCENE [--path PATH] [view options] [options]   (octomotion view --help)
  octomotion make-building DIR [options]   (octomotion make-building --help)
SCENE is a YAML scene (docs/scenes.md) or an OMPL.app .cfg problem.
options:
)";

// After the scene options (tools::sceneOptions()).
const char* kUsageTail =
    R"(  --interpolation METRES   plan: write states at this spacing (default: the simplified
                           path's waypoints, as OMPL.app writes them)
  --explain                check: a reason column (why each invalid state is invalid)
  --verbose                OMPL's log messages on stderr
)";

struct Args {
  std::string command, scene, out, states;
  double interpolation = 0;
  bool verbose = false;
  bool explain = false;
  SceneOverrides overrides;
};

Args parseArgs(int argc, char** argv) {
  Args a;
  std::vector<std::string> positional;
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (cli::parseSceneOption(arg, value, a.overrides)) {
      continue;
    } else if (arg == "--out") {
      a.out = value();
    } else if (arg == "--states") {
      a.states = value();
    } else if (arg == "--interpolation") {
      a.interpolation = cli::parseNumber(arg, value());
      if (!(a.interpolation > 0)) throw InvalidArgument("--interpolation: must be > 0");
    } else if (arg == "--explain") {
      a.explain = true;
    } else if (arg == "--verbose") {
      a.verbose = true;
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      tools::sceneOptions().writeHelp(std::cout);
      std::cout << kUsageTail;
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("unknown option " + arg);
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 2) throw InvalidArgument("expected a command and a scene (see --help)");
  a.command = positional[0];
  a.scene = positional[1];
  if (a.command != "plan" && a.command != "check" && a.command != "info") {
    throw InvalidArgument("unknown command '" + a.command + "' (plan, check, info)");
  }
  if (a.command == "check" && a.states.empty())
    throw InvalidArgument("check: --states is required");
  if (a.explain && a.command != "check") throw InvalidArgument("--explain: check only");
  // check looks at any state, the scene's start and goal too.
  if (a.command == "check") a.overrides.require_free_start_goal = false;
  return a;
}

PlanningScene load(const Args& a) {
  return cli::loadSceneVerbose(a.scene, a.overrides);
}

int plan(const Args& a) {
  PlanningScene scene = load(a);
  if (!scene.spec.problem.start || !scene.spec.problem.goal) {
    throw FileError(a.scene, "problem: a start and a goal are needed to plan");
  }
  std::cerr << "octomotion: planning with " << scene.spec.problem.planner << " for at most "
            << scene.spec.problem.time << " s\n";
  const PlanResult r = octomotion::plan(scene, a.interpolation);
  if (!r.solved) {
    std::cerr << "octomotion: no solution found in " << r.seconds << " s\n";
    return 2;
  }
  // The simplified waypoints unless --interpolation asks for states at a spacing.
  const ompl::geometric::PathGeometric& path = a.interpolation > 0 ? *r.path : *r.waypoints;
  std::cerr << "octomotion: solved in " << r.seconds << " s; path of " << path.getStateCount()
            << " states, length " << path.length() << "\n";
  if (a.out.empty()) {
    writePath(scene, path, std::cout);
  } else {
    std::ofstream out(a.out);
    if (!out) throw FileError(a.out, "cannot write the path");
    writePath(scene, path, out);
    out.close();  // a full disk shows when the buffer is flushed
    if (!out) throw FileError(a.out, "write error (disk full?): the path was not written");
    std::cerr << "octomotion: path written to " << a.out << "\n";
  }
  return 0;
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) {
    const auto b = f.find_first_not_of(" \t\r"), e = f.find_last_not_of(" \t\r");
    fields.push_back(b == std::string::npos ? "" : f.substr(b, e - b + 1));
  }
  return fields;
}

// A CSV field as written: quoted (quotes doubled) when it holds a comma, a quote or a newline.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// check --explain: why an invalid state is invalid (every reason, "; "-separated).
std::string whyInvalid(const CollisionBackend& backend, BackendScratch& scratch,
                       const ompl::base::SpaceInformation& si, const ompl::base::State* state,
                       const std::vector<double>& values) {
  const RobotModel& robot = backend.robot();
  std::vector<double> q = values;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  if (robot.isFreeFlying()) {
    q.clear();
    if (!stateToConfiguration(robot, state, q, X_WB)) {
      return "the pose is not finite or its quaternion is zero";
    }
  }
  ExplainOptions options;
  options.all = true;
  const StateExplanation e = backend.explain(q.data(), q.size(), X_WB, scratch, options);
  if (!e.valid()) return describe(e);
  if (!si.satisfiesBounds(state)) return "outside the state space's bounds";
  return "invalid";  // not expected: the checker and explain agree
}

int check(const Args& a) {
  PlanningScene scene = load(a);
  const RobotModel& robot = scene.model->robot();
  // Read line by line, so only the regular-file check matters (a FIFO would block).
  requireRegularFile(a.states, "states file", std::numeric_limits<std::uintmax_t>::max());
  std::ifstream in(a.states);
  if (!in) throw FileError(a.states, "cannot open the states file");
  std::string line;
  if (!std::getline(in, line)) throw FileError(a.states, "empty file: expected a header");
  const std::vector<std::string> header = splitCsv(line);
  // Column of each value the state needs, found by name.
  std::vector<std::string> wanted;
  if (robot.isFreeFlying()) {
    wanted = {"x", "y", "z", "qx", "qy", "qz", "qw"};
  } else {
    for (const Variable& v : robot.variables()) wanted.push_back(v.name);
  }
  std::vector<std::size_t> column;
  for (const std::string& w : wanted) {
    const auto it = std::find(header.begin(), header.end(), w);
    if (it == header.end()) throw FileError(a.states, "header: missing column '" + w + "'");
    column.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  const auto si = scene.setup->getSpaceInformation();
  si->setup();
  ompl::base::ScopedState<> state(si);
  std::vector<double> values(wanted.size());
  std::cout << (a.explain ? "index,valid,time_ns,reason\n" : "index,valid,time_ns\n");
  std::shared_ptr<const CollisionBackend> backend;
  std::unique_ptr<BackendScratch> scratch;
  if (a.explain) {
    backend = checkerBackend(scene);
    scratch = backend->makeBackendScratch();
  }
  std::size_t index = 0, row = 1, valid_count = 0;
  while (std::getline(in, line)) {
    ++row;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = splitCsv(line);
    if (fields.size() != header.size()) {
      throw FileError(a.states, "row " + std::to_string(row) + ": expected " +
                                    std::to_string(header.size()) + " fields, got " +
                                    std::to_string(fields.size()));
    }
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      char* end = nullptr;
      const std::string& f = fields[column[k]];
      values[k] = std::strtod(f.c_str(), &end);  // NaN/Inf parse, and are invalid states
      if (f.empty() || *end != '\0') {
        throw FileError(a.states, "row " + std::to_string(row) + ", column " + wanted[k] +
                                      ": expected a number, got '" + f + "'");
      }
    }
    if (robot.isFreeFlying()) {
      auto* s = state->as<ompl::base::SE3StateSpace::StateType>();
      s->setXYZ(values[0], values[1], values[2]);
      s->rotation().x = values[3];
      s->rotation().y = values[4];
      s->rotation().z = values[5];
      s->rotation().w = values[6];
    } else {
      configurationToState(robot, values, Eigen::Isometry3d::Identity(), state.get());
    }
    const auto t0 = std::chrono::steady_clock::now();
    const bool valid = si->isValid(state.get());
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0)
            .count();
    valid_count += valid ? 1 : 0;
    std::cout << index++ << ',' << (valid ? 1 : 0) << ',' << ns;
    if (a.explain) {
      std::cout << ','
                << (valid ? ""
                          : csvField(whyInvalid(*backend, *scratch, *si, state.get(), values)));
    }
    std::cout << '\n';
  }
  std::cerr << "octomotion: " << valid_count << " of " << index << " states valid\n";
  return 0;
}

// The group planned and the joints held at a value (problem.group, problem.fixed).
void printPlanningGroup(const PlanningScene& scene, std::ostream& out) {
  const RobotModel& robot = scene.model->robot();
  const std::string& group = scene.spec.problem.group;
  out << "group: " << (group.empty() ? "(none: every joint not held)" : group) << ", "
      << robot.variableCount() << " planned joints\n";
  out << "held joints:";
  if (robot.heldJoints().empty()) out << " none";
  for (const HeldJoint& h : robot.heldJoints()) {
    out << (&h == &robot.heldJoints().front() ? " " : ", ") << robot.joint(h.joint).name << '='
        << h.value << (h.mimic ? " (mimic)" : "");
  }
  out << "\n";
}

int info(const Args& a) {
  PlanningScene scene = load(a);
  const RobotModel& robot = scene.model->robot();
  std::cout << "scene: " << scene.spec.name << " (" << scene.spec.path << ")\n"
            << "robot: " << robot.name() << ", " << robot.linkCount() << " links, "
            << (robot.isFreeFlying() ? std::string("free-flying (SE(3))")
                                     : std::to_string(robot.variableCount()) + " joints")
            << "\n";
  if (!robot.isFreeFlying()) {
    std::cout << "joint order:";
    for (const Variable& v : robot.variables()) std::cout << ' ' << v.name;
    std::cout << "\n";
    printPlanningGroup(scene, std::cout);
  }
  std::cout << "resolution: " << *scene.spec.octree.resolution << " m, rounding "
            << toString(scene.spec.octree.rounding) << ", checker "
            << checkerKindName(scene.checker) << ", refine "
            << refineModeName(scene.model->refine()) << "\n"
            << scene.model->report().toString();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    // Commands with options of their own parse their arguments themselves.
    if (argc >= 2 && std::string(argv[1]) == "bench-set") {
      return cli::finishStdout(cli::benchSetCommand({argv + 2, argv + argc}));
    }
    if (argc >= 2 && std::string(argv[1]) == "make-building") {
      return cli::finishStdout(cli::makeBuildingCommand({argv + 2, argv + argc}));
    }
    if (argc >= 2 && (std::string(argv[1]) == "bench" || std::string(argv[1]) == "view")) {
      ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
      const std::vector<std::string> rest(argv + 2, argv + argc);
      return cli::finishStdout(std::string(argv[1]) == "bench" ? cli::benchCommand(rest)
                                                               : cli::viewCommand(rest));
    }
    const Args args = parseArgs(argc, argv);
    ompl::msg::setLogLevel(args.verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
    const int status = args.command == "plan"    ? plan(args)
                       : args.command == "check" ? check(args)
                                                 : info(args);
    return cli::finishStdout(status);
  } catch (const std::exception& e) {
    std::cerr << "octomotion: error: " << e.what() << "\n";
    return 1;
  }
}
