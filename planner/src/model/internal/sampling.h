// Private to the planner library: the build-time joint-state samples of OctreeCollisionModel.
#pragma once

#include <random>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::detail {

// A value uniform in the variable's range from the top 53 bits of one draw: the same sequence on
// every standard library (unlike std::uniform_real_distribution), so build-time samples are.
inline double uniformIn(const Variable& var, std::mt19937_64& rng) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return var.lower + u * (var.upper - var.lower);
}

}  // namespace octomotion::detail
