// Joint vectors drawn uniformly within a robot's variable limits, one seeded stream, for tests
// that compare checkers or models state by state.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::test {

inline std::vector<std::vector<double>> uniformJointStates(const RobotModel& robot, int count,
                                                           std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<double>> states;
  states.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    states.push_back(std::move(q));
  }
  return states;
}

}  // namespace octomotion::test
