// One inverse-kinematics solve on the Panda (../shared/data/panda): the hand's pose (position +
// orientation) or position at 256 random in-limit configurations from a fixed seed, each solved
// from another random configuration, one target per iteration (restarts included, as a goal
// sampler pays them). Reported as the median of repetitions.
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "joint_states.h"
#include "octomotion/planner/robot/inverse_kinematics.h"

namespace {

using namespace octomotion;

void BM_PandaIk(benchmark::State& state) {
  const std::string dir = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
  if (!std::filesystem::exists(dir + "/panda.urdf")) {
    state.SkipWithError(("no " + dir).c_str());
    return;
  }
  const bool with_orientation = state.range(0) != 0;
  const RobotModel robot = RobotModel::fromUrdfFile(dir + "/panda.urdf");
  const InverseKinematics ik(robot);
  const int hand = robot.linkIndex("panda_hand");
  RobotData data = robot.makeData();
  std::vector<LinkPoseTarget> targets;
  for (const std::vector<double>& q : test::uniformJointStates(robot, 256, 1)) {
    robot.forwardKinematics(q.data(), q.size(), data);
    const Eigen::Isometry3d& X = data.linkPose(hand);
    std::optional<Eigen::Quaterniond> orientation;
    if (with_orientation) orientation = Eigen::Quaterniond(X.linear());
    targets.push_back(ik.target("panda_hand", X.translation(), orientation));
  }
  const auto seeds = test::uniformJointStates(robot, 256, 2);
  IkScratch scratch = ik.makeScratch();
  std::mt19937_64 rng(3);
  std::size_t i = 0, solved = 0;
  for (auto _ : state) {
    const IkResult r = ik.solve(targets[i], seeds[i], rng, scratch);
    solved += r.success ? 1 : 0;
    benchmark::DoNotOptimize(r.q.data());
    i = (i + 1) % targets.size();
  }
  state.counters["solved"] =
      benchmark::Counter(static_cast<double>(solved) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PandaIk)
    ->ArgName("orientation")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
