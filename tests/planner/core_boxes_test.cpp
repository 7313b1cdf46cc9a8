// Certain contacts (CollisionModelOptions::core_boxes): a link's core box overlapping the box
// inscribed in a primitive obstacle answers "in collision" without the tree query. The answers
// must be exactly those of the same model without core boxes, on both checker paths, at several
// resolutions, with boards thin and thick, rods and balls, axis-aligned and rotated, and
// objects reaching out of the universe.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "environment_answers.h"
#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "primitive_scenes.h"
#include "snake_robot.h"

namespace octomotion {
namespace {

using test::boards;
using test::rodsAndBalls;

RobotModel snake(int links, double limit) {
  return RobotModel::fromUrdfString(test::snakeUrdf(links, limit), "snake.urdf", ".");
}

// The environment half of `with` answers as `without` (no core boxes) on every state, on both
// checker paths; returns whether `with` has both solids and link cores (certain contacts can
// fire).
bool expectSameEnvironmentAnswers(const RobotModel& robot, const EnvironmentGeometry& env,
                                  double res, std::size_t max_solids, const std::string& what) {
  const auto states = test::uniformJointStates(robot, 1500, 9);
  CollisionModelOptions o;
  o.resolution = res;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.link_resolution = res;       // the moveTree path materialises every link leaf
  const OctreeCollisionModel with(robot, env, o);
  o.core_boxes = false;
  const OctreeCollisionModel without(robot, env, o);
  EXPECT_EQ(without.report().environment_solid_boxes, 0u);
  for (const LinkReport& l : without.report().links) EXPECT_EQ(l.core_boxes, 0);
  const std::size_t solids = with.report().environment_solid_boxes;
  EXPECT_LE(solids, max_solids) << what;  // never the tilted object leaving the universe
  int cores = 0;
  for (const LinkReport& l : with.report().links) cores += l.core_boxes;
  for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    if (path == CheckerPath::kMoveTree && res < 0.01) continue;  // slow, same code path
    const std::string where = what + ", resolution " + std::to_string(res);
    const int hits = test::environmentHitsIfSame(with, without, states, path, where);
    if (hits < 0) return false;
    EXPECT_GT(hits, 150) << where;  // both answers are exercised
    EXPECT_LT(hits, 1350) << where;
  }
  return solids > 0 && cores > 0;
}

TEST(CoreBoxes, SameAnswersAsTheTreeQueries) {
  const RobotModel robot = snake(6, 1.6);
  int certain_models = 0;
  for (const bool rotated : {false, true}) {
    const EnvironmentGeometry env = EnvironmentGeometry::load(boards(rotated ? 5 : 6, rotated));
    for (const double res : {0.02, 0.01, 0.005}) {
      certain_models +=
          expectSameEnvironmentAnswers(robot, env, res, 13, rotated ? "rotated boards" : "boards");
    }
  }
  EXPECT_EQ(certain_models, 6);
}

TEST(CoreBoxes, RodsAndBallsGiveTheSameAnswers) {
  const RobotModel robot = snake(6, 1.6);
  const std::vector<EnvironmentObject> objects = rodsAndBalls(11);
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  int certain_models = 0;
  for (const double res : {0.02, 0.01, 0.005}) {
    certain_models += expectSameEnvironmentAnswers(robot, env, res, objects.size() - 1, "rods");
  }
  EXPECT_EQ(certain_models, 3);
}

TEST(CoreBoxes, OnlyUnderConservativeRounding) {
  const RobotModel robot = snake(5, 1.0);
  const EnvironmentGeometry env = EnvironmentGeometry::load(boards(7, false));
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.rounding = Rounding::kCenter;
  const OctreeCollisionModel centre(robot, env, o);
  EXPECT_EQ(centre.report().environment_solid_boxes, 0u);
  for (const LinkReport& l : centre.report().links) EXPECT_EQ(l.core_boxes, 0);
  o.rounding = Rounding::kConservative;
  const OctreeCollisionModel conservative(robot, env, o);
  EXPECT_GT(conservative.report().environment_solid_boxes, 0u);
  EXPECT_NE(conservative.report().toString().find("core boxes"), std::string::npos);
}

}  // namespace
}  // namespace octomotion
