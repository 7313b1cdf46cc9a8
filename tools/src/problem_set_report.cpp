// The planning benchmark's outputs: per-set summaries, the CSV and the OMPL benchmark logs.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Time.h>

#include "octomotion/error.h"
#include "octomotion/tools/experiment_name.h"
#include "octomotion/tools/problem_set.h"

namespace octomotion::tools {

namespace {

double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  // Nearest rank: a value that was measured.
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(9) << v;
  return s.str();
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string milliseconds(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(seconds < 0.01 ? 2 : 1) << seconds * 1e3 << " ms";
  return s.str();
}

// A run as the summaries count it: an unsolved run costs the whole limit.
double chargedSeconds(const ProblemRun& r) {
  return r.solved ? std::min(r.seconds, r.time_limit) : r.time_limit;
}

// ompl::tools::Benchmark's own writer, fed with runs made elsewhere (one per problem), so the
// logs are exactly the format its parser reads.
class SetLog : public ompl::tools::Benchmark {
 public:
  explicit SetLog(ompl::geometric::SimpleSetup& unused) : Benchmark(unused) {}
  CompleteExperiment& experiment() { return exp_; }
};

}  // namespace

std::vector<SetSummary> summarize(const ProblemSetResult& result) {
  // Keyed by (set, checker) in order of first appearance; "all" last per checker.
  std::vector<SetSummary> out;
  std::vector<std::vector<const ProblemRun*>> members;
  auto slot = [&](const std::string& set, const ProblemRun& r) -> std::size_t {
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (out[i].set == set && out[i].checker == r.checker) return i;
    }
    SetSummary s;
    s.set = set;
    s.checker = r.checker;
    out.push_back(s);
    members.emplace_back();
    return out.size() - 1;
  };
  std::vector<std::string> sets;
  for (const ProblemRun& r : result.runs) {
    members[slot(r.set, r)].push_back(&r);
    if (std::find(sets.begin(), sets.end(), r.set) == sets.end()) sets.push_back(r.set);
  }
  if (sets.size() > 1) {
    for (const ProblemRun& r : result.runs) members[slot("all", r)].push_back(&r);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    SetSummary& s = out[i];
    std::vector<double> seconds;
    std::map<std::string, bool> problems;
    double states = 0, motions = 0;
    for (const ProblemRun* r : members[i]) {
      problems[r->set + "/" + r->problem] = true;
      ++s.runs;
      if (r->resolution > 0) s.resolution = r->resolution;
      if (!r->error.empty()) ++s.load_errors;
      seconds.push_back(chargedSeconds(*r));
      states += static_cast<double>(r->state_checks);
      motions += static_cast<double>(r->motion_checks);
      if (!r->solved) continue;
      ++s.solved;
      s.recheck_states += r->recheck_states;
      s.recheck_colliding += r->recheck_colliding;
    }
    s.problems = problems.size();
    s.median_seconds = quantile(seconds, 0.5);
    s.p90_seconds = quantile(seconds, 0.9);
    const double plans = static_cast<double>(std::max<std::size_t>(1, s.runs - s.load_errors));
    s.state_checks = states / plans;
    s.motion_checks = motions / plans;
  }
  // Per set, the checkers side by side; "all" last.
  std::vector<std::size_t> order(out.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto set_rank = [&](const std::string& set) {
    const auto it = std::find(sets.begin(), sets.end(), set);
    return static_cast<std::size_t>(it - sets.begin());
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return set_rank(out[a].set) < set_rank(out[b].set);
  });
  std::vector<SetSummary> sorted;
  for (std::size_t i : order) sorted.push_back(out[i]);
  return sorted;
}

void writeSummaryMarkdown(const std::vector<SetSummary>& summary, std::ostream& out) {
  out << "| set | checker | resolution | problems | solved | median time | p90 time | state "
         "checks / plan | motion checks / plan | FCL re-check: states in collision |\n"
      << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SetSummary& s : summary) {
    out << "| " << s.set << " | " << checkerKindName(s.checker) << " | " << number(s.resolution)
        << " m | " << s.problems << " | " << s.solved << "/" << s.runs;
    if (s.load_errors) out << " (" << s.load_errors << " not loaded)";
    out << " | " << milliseconds(s.median_seconds) << " | " << milliseconds(s.p90_seconds) << " | "
        << std::llround(s.state_checks) << " | " << std::llround(s.motion_checks) << " | "
        << s.recheck_colliding << " of " << s.recheck_states << " |\n";
  }
}

void writeProblemCsv(const ProblemSetResult& result, std::ostream& out) {
  out << "set,problem,checker,resolution,planner,run,solved,time,time_limit,state_checks,"
         "motion_checks,waypoints,length,fcl_recheck_states,fcl_recheck_colliding,seed,error\n";
  for (const ProblemRun& r : result.runs) {
    out << csvField(r.set) << ',' << csvField(r.problem) << ',' << checkerKindName(r.checker) << ','
        << number(r.resolution) << ',' << csvField(result.planner) << ',' << r.run << ','
        << (r.solved ? 1 : 0) << ',' << number(r.seconds) << ',' << number(r.time_limit) << ','
        << r.state_checks << ',' << r.motion_checks << ',' << r.waypoints << ',' << number(r.length)
        << ',' << r.recheck_states << ',' << r.recheck_colliding << ',' << r.seed << ','
        << csvField(r.error) << '\n';
  }
}

std::vector<std::string> writeOmplLogs(const ProblemSetResult& result,
                                       const ProblemSetOptions& options, const std::string& dir) {
  std::filesystem::create_directories(dir);
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  std::vector<std::string> written;
  for (const SetSummary& s : summarize(result)) {
    if (s.set == "all") continue;
    ompl::geometric::SimpleSetup unused(std::make_shared<ompl::base::RealVectorStateSpace>(1));
    SetLog log(unused);
    auto& e = log.experiment();
    e.name = experimentName(s.set, checkerKindName(s.checker), s.resolution);
    e.maxTime = 0;
    e.maxMem = 0;
    e.runCount = static_cast<unsigned>(s.runs);
    e.startTime = ompl::time::now();
    e.totalDuration = 0;
    e.setupInfo = "octomotion bench-set " + options.dir + ": set " + s.set + ", checker " +
                  checkerKindName(s.checker) + "; one run per problem and repetition\n";
    e.seed = static_cast<std::uint_fast32_t>(options.overrides.seed.value_or(0));
    e.host = host[0] ? host : "UNKNOWN";
    e.cpuInfo = "";
    ompl::tools::Benchmark::PlannerExperiment planner;
    planner.name = "geometric_" + result.planner;
    std::size_t index = 0;
    for (const ProblemRun& r : result.runs) {
      if (r.set != s.set || r.checker != s.checker) continue;
      e.maxTime = std::max(e.maxTime, r.time_limit);
      e.totalDuration += r.seconds;
      ompl::tools::Benchmark::RunProperties run;
      run["problem INTEGER"] = std::to_string(index++ / options.runs);
      run["time REAL"] = number(chargedSeconds(r));
      run["solved BOOLEAN"] = r.solved ? "1" : "0";
      run["approximate solution BOOLEAN"] = "0";
      run["correct solution BOOLEAN"] = r.solved && r.recheck_colliding == 0 ? "1" : "0";
      run["state checks INTEGER"] = std::to_string(r.state_checks);
      run["motion checks INTEGER"] = std::to_string(r.motion_checks);
      run["loaded BOOLEAN"] = r.error.empty() ? "1" : "0";
      if (r.solved) {
        run["simplified solution length REAL"] = number(r.length);
        run["simplified solution segments INTEGER"] = std::to_string(r.waypoints - 1);
        run["fcl recheck states INTEGER"] = std::to_string(r.recheck_states);
        run["fcl recheck collisions INTEGER"] = std::to_string(r.recheck_colliding);
      }
      planner.runs.push_back(std::move(run));
    }
    e.planners.push_back(std::move(planner));
    const std::string path = (std::filesystem::path(dir) / (e.name + ".log")).string();
    std::ofstream out(path);
    if (!out || !log.saveResultsToStream(out)) throw FileError(path, "cannot write the log");
    out.close();
    if (!out) throw FileError(path, "write error (disk full?)");
    written.push_back(path);
  }
  return written;
}

}  // namespace octomotion::tools
