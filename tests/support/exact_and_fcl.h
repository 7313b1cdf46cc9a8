// An exact-refine octree model of a robot among obstacles beside its FCL reference, with a
// scratch for each: what the tests that hold refine's answers to FCL's set up.
#pragma once

#include <utility>

#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::test {

struct ExactAndFcl {
  // `robot` must outlive this; the obstacles are kept here.
  ExactAndFcl(const RobotModel& robot, EnvironmentGeometry obstacles)
      : environment(std::move(obstacles)),
        model(robot, environment, exactOptions()),
        fcl(robot, environment),
        exact(fcl.makeScratch()),
        scratch(model.makeScratch()) {}
  // The robot alone, every contact a self contact.
  explicit ExactAndFcl(const RobotModel& robot)
      : ExactAndFcl(robot, EnvironmentGeometry::load({})) {}

  static CollisionModelOptions exactOptions() {
    CollisionModelOptions options;
    options.refine = RefineMode::kExact;
    return options;
  }

  const EnvironmentGeometry environment;
  const OctreeCollisionModel model;
  const FclCollisionModel fcl;
  FclCollisionModel::ScratchPtr exact;
  CheckScratch scratch;
};

}  // namespace octomotion::test
