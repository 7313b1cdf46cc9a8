// State-by-state comparison of two models' environment halves, for tests of changes that must
// keep every answer (pre-tests, certain contacts).
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "octomotion/planner/model/collision_model.h"

namespace octomotion::test {

// The number of states `reference` finds in collision with the environment, or -1 after a
// test failure naming the first state on which `model` answers otherwise.
inline int environmentHitsIfSame(const OctreeCollisionModel& model,
                                 const OctreeCollisionModel& reference,
                                 const std::vector<std::vector<double>>& states, CheckerPath path,
                                 const std::string& what) {
  const RobotModel& robot = reference.robot();
  CheckScratch a = model.makeScratch(), b = reference.makeScratch();
  int hits = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const std::vector<double>& q = states[i];
    robot.forwardKinematics(q.data(), q.size(), a.robot);
    robot.forwardKinematics(q.data(), q.size(), b.robot);
    const bool expected = reference.environmentInCollision(path, b);
    if (model.environmentInCollision(path, a) != expected) {
      ADD_FAILURE() << "state " << i << " answers " << !expected << ", expected " << expected
                    << ": " << what;
      return -1;
    }
    hits += expected;
  }
  return hits;
}

}  // namespace octomotion::test
