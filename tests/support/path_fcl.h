// Exact FCL along motions: how many evenly spaced states of an edge, or of a path interpolated
// densely, collide. The planner tests use it to re-check what a motion validator accepted.
#pragma once

#include <cstddef>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>
#include <Eigen/Geometry>

#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace octomotion::test {

// FCL at `states` (at least 2) evenly spaced states of the edge s1-s2, ends included; a state
// that does not read as a configuration counts as colliding.
inline std::size_t fclCollisionsOnEdge(const FclCollisionModel& fcl,
                                       const ompl::base::SpaceInformationPtr& si,
                                       const ompl::base::State* s1, const ompl::base::State* s2,
                                       int states) {
  auto scratch = fcl.makeScratch();
  ompl::base::ScopedState<> s(si);
  std::vector<double> q(static_cast<std::size_t>(fcl.robot().variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (int k = 0; k < states; ++k) {
    si->getStateSpace()->interpolate(s1, s2, k / double(states - 1), s.get());
    if (!stateToConfiguration(fcl.robot(), s.get(), q, X_WB)) {
      ++colliding;
      continue;
    }
    fcl.setConfiguration(q.data(), q.size(), X_WB, *scratch);
    colliding += fcl.inCollision(*scratch) ? 1 : 0;
  }
  return colliding;
}

// FCL at every state of `path` interpolated to `density` times as many segments; `checked`
// receives the number of states tested.
inline std::size_t fclCollisionsOnPath(const FclCollisionModel& fcl,
                                       const ompl::geometric::PathGeometric& path, int density,
                                       std::size_t* checked = nullptr) {
  ompl::geometric::PathGeometric dense(path);
  dense.interpolate(static_cast<unsigned>(density * (path.getStateCount() - 1) + 1));
  auto scratch = fcl.makeScratch();
  std::vector<double> q(static_cast<std::size_t>(fcl.robot().variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    if (!stateToConfiguration(fcl.robot(), dense.getState(static_cast<unsigned>(i)), q, X_WB)) {
      ++colliding;
      continue;
    }
    fcl.setConfiguration(q.data(), q.size(), X_WB, *scratch);
    colliding += fcl.inCollision(*scratch) ? 1 : 0;
  }
  if (checked) *checked = dense.getStateCount();
  return colliding;
}

}  // namespace octomotion::test
