// `octomotion bench-set DIR`: the planning benchmark over a folder of problems
// (docs/benchmarking.md). Prints the per-set summary on stdout and writes results.csv, the MoveIt
// pairs' scene files (scenes/) and the OMPL benchmark logs (logs/*.log) to --out-dir.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <ompl/util/Console.h>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/tools/problem_set.h"

namespace octomotion::cli {

namespace {

const char* kBenchSetUsage = R"(usage: octomotion bench-set DIR [options]
Plans every problem of DIR with each checker in turn (same process, back to back per problem) and
re-checks every solved path with exact FCL. DIR holds scene files (*.yaml, *.cfg) or MoveIt
sceneNNNN.yaml/requestNNNN.yaml pairs (MotionBenchMaker), or sub-folders of them (one set each).
options:
  --checkers LIST          checkers to compare (default: octree-fused,fcl)
  --runs N                 plans per problem and checker (default: 1)
  --limit N                the first N problems of each set (default: all)
  --out-dir DIR            results.csv, logs/*.log, scenes/ (default: bench_set)
  --robot URDF             MoveIt pairs: the robot (required for them)
  --srdf SRDF              MoveIt pairs: its SRDF (for the request's group)
  --fixed JOINT=VALUE      MoveIt pairs: a joint held at a value (repeatable)
  --recheck-density N      FCL re-check states per motion-step state (default: 100)
scene options (--planner, --time, --seed apply to every problem):
)";

void writeFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ofstream out(path);
  if (!out) throw FileError(path, "cannot write");
  write(out);
  out.close();  // a full disk shows when the buffer is flushed
  if (!out) throw FileError(path, "write error (disk full?)");
}

// A bar redrawn in place on a terminal; one line per problem otherwise (logs, CI).
void showProgress(std::size_t done, std::size_t total, const std::string& what) {
  static const bool terminal = ::isatty(STDERR_FILENO) != 0;
  if (!terminal) {
    if (done < total)
      std::cerr << "octomotion: [" << done + 1 << "/" << total << "] " << what << "\n";
    return;
  }
  constexpr std::size_t kWidth = 30;
  const std::size_t filled = total ? done * kWidth / total : kWidth;
  std::cerr << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] "
            << done << "/" << total << " " << what << "\033[K";
  if (done == total) std::cerr << "\n";
  std::cerr.flush();
}

}  // namespace

int benchSetCommand(const std::vector<std::string>& args) {
  tools::ProblemSetOptions options;
  std::string out_dir = "bench_set";
  std::optional<std::vector<CheckerKind>> checkers;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (arg == "-h" || arg == "--help") {
      std::cout << kBenchSetUsage;
      tools::sceneOptions().writeHelp(std::cout);
      return 0;
    } else if (arg == "--checkers") {
      checkers.emplace();
      for (const std::string& name : tools::parseList(arg, value())) {
        checkers->push_back(parseCheckerKind(name));
      }
    } else if (arg == "--runs") {
      options.runs = tools::parseCount(arg, value());
      if (options.runs == 0) throw InvalidArgument("--runs: must be at least 1");
    } else if (arg == "--limit") {
      options.limit = tools::parseCount(arg, value());
    } else if (arg == "--out-dir") {
      out_dir = value();
    } else if (arg == "--robot") {
      options.urdf = value();
    } else if (arg == "--srdf") {
      options.srdf = value();
    } else if (arg == "--fixed") {
      const std::string v = value();
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw InvalidArgument("--fixed: expected JOINT=VALUE, got '" + v + "'");
      }
      options.fixed[v.substr(0, eq)] = parseNumber(arg, v.substr(eq + 1));
    } else if (arg == "--recheck-density") {
      options.recheck_density = static_cast<double>(tools::parseCount(arg, value()));
      if (options.recheck_density < 1) throw InvalidArgument("--recheck-density: at least 1");
    } else if (tools::sceneOptions().parse(arg, value, options.overrides)) {
      continue;
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("bench-set: unknown option " + arg + " (octomotion bench-set --help)");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 1) throw InvalidArgument("bench-set: expected one folder (see --help)");
  options.dir = positional.front();
  // --checker X alone means that one checker; --checkers wins.
  if (checkers) {
    options.checkers = *checkers;
  } else if (options.overrides.checker) {
    options.checkers = {*options.overrides.checker};
  }
  if (options.checkers.empty()) throw InvalidArgument("--checkers: no checker given");
  // OMPL's messages repeat per problem (every load sets the seed again, which OMPL reports as an
  // error once sampling has started; a failed plan logs why): the CSV says what happened.
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  std::filesystem::create_directories(out_dir);
  options.scene_dir = out_dir + "/scenes";
  options.progress = showProgress;

  const tools::ProblemSetResult result = tools::runProblemSet(options);
  writeFile(out_dir + "/results.csv", [&](std::ostream& o) { tools::writeProblemCsv(result, o); });
  const auto logs = tools::writeOmplLogs(result, options, out_dir + "/logs");
  const auto summary = tools::summarize(result);
  writeFile(out_dir + "/summary.md",
            [&](std::ostream& o) { tools::writeSummaryMarkdown(summary, o); });
  tools::writeSummaryMarkdown(summary, std::cout);
  std::size_t not_loaded = 0;
  for (const tools::ProblemRun& r : result.runs) {
    if (r.error.empty()) continue;
    if (not_loaded++ == 0) std::cerr << "octomotion: warning: " << r.error << "\n";
  }
  if (not_loaded > 1) {
    std::cerr << "octomotion: warning: " << not_loaded
              << " plans failed (the error column of results.csv says why)\n";
  }
  std::size_t colliding = 0;
  for (const auto& s : summary) colliding += s.set == "all" ? 0 : s.recheck_colliding;
  std::cerr << "octomotion: " << result.runs.size() << " plans in " << result.seconds
            << " s; FCL re-check: " << colliding << " path states in collision; results in "
            << out_dir << " (results.csv, summary.md, " << logs.size()
            << " OMPL logs in logs/: ompl_benchmark_statistics.py " << out_dir << "/logs/*.log)\n";
  return 0;
}

}  // namespace octomotion::cli
