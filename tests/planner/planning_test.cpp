// OMPL integration: RRTConnect solves a rigid-body narrow passage and an arm-in-shelf problem with
// both octree checker paths, and the paths, re-checked by FCL at ten times the planner's state
// density, never collide (conservative rounding never under-approximates).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"

namespace octomotion {
namespace {

struct Case {
  const char* scene;
  CheckerKind checker;
};

class Planning : public ::testing::TestWithParam<Case> {};

TEST_P(Planning, SolvesAndFclFindsThePathFree) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.checker = GetParam().checker;
  overrides.time = 60;  // a cap for slow (sanitizer) builds; the planner stops when it solves
  overrides.seed = 7;
  // The moveTree path re-voxelises each moved link, so a state between two that the certified
  // validator checked half a voxel apart may touch a voxel it did not (docs/validation.md §4):
  // the per-state assertion below holds for states the validator checked, which the discrete
  // validator's interpolation reproduces.
  // The discrete validator's states carry the voxels' margin only without exact refine (a
  // density choice, not a proof: docs/validation.md §4), so this case keeps refine none.
  if (GetParam().checker == CheckerKind::kOctree) {
    overrides.motion_validator = MotionValidatorKind::kDiscrete;
    overrides.refine = RefineMode::kNone;
  }
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + GetParam().scene, overrides);
  EXPECT_EQ(scene.checker, GetParam().checker);
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved) << GetParam().scene << " with " << checkerKindName(GetParam().checker);
  ASSERT_TRUE(result.path);

  // The planner's own checker accepts every state of the path.
  const auto& si = scene.setup->getSpaceInformation();
  for (std::size_t i = 0; i < result.path->getStateCount(); ++i) {
    ASSERT_TRUE(si->isValid(result.path->getState(static_cast<unsigned>(i))));
  }
  // FCL, at ten times the density.
  ompl::geometric::PathGeometric dense(*result.path);
  dense.interpolate(static_cast<unsigned>(10 * (result.path->getStateCount() - 1) + 1));
  const RobotModel& robot = scene.fcl_model->robot();
  auto fcl = scene.fcl_model->makeScratch();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
    ASSERT_TRUE(stateToConfiguration(robot, dense.getState(static_cast<unsigned>(i)), q, X_WB));
    scene.fcl_model->setConfiguration(q.data(), q.size(), X_WB, *fcl);
    colliding += scene.fcl_model->inCollision(*fcl) ? 1 : 0;
  }
  EXPECT_EQ(colliding, 0u) << "of " << dense.getStateCount() << " states";
  // The path starts and ends where the scene says.
  EXPECT_LT(si->distance(dense.getState(0), scene.setup->getProblemDefinition()->getStartState(0)),
            1e-9);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Planning,
                         ::testing::Values(Case{"narrow_passage.yaml", CheckerKind::kOctreeFused},
                                           Case{"narrow_passage.yaml", CheckerKind::kOctree},
                                           Case{"bookshelf.yaml", CheckerKind::kOctreeFused},
                                           Case{"bookshelf.yaml", CheckerKind::kOctree}),
                         [](const auto& param_info) {
                           std::string name = std::string(param_info.param.scene) + "_" +
                                              checkerKindName(param_info.param.checker);
                           for (char& c : name) {
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(Planning, OneLinkUrdfIsAFreeFlyingBody) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.seed = 5;
  PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/l_piece_urdf.yaml", overrides);
  EXPECT_TRUE(scene.model->robot().isFreeFlying());
  // auto resolution for a rigid body: max(scene diagonal / 1024, robot diagonal / 32).
  EXPECT_GT(*scene.spec.octree.resolution, 0.005);
  EXPECT_LT(*scene.spec.octree.resolution, 0.02);
  const auto si = scene.setup->getSpaceInformation();
  const auto pdef = scene.setup->getProblemDefinition();
  EXPECT_TRUE(si->isValid(pdef->getStartState(0)));
  ompl::base::ScopedState<> in_wall(si);
  si->copyState(in_wall.get(), pdef->getStartState(0));
  in_wall->as<ompl::base::SE3StateSpace::StateType>()->setX(0.0);  // upright, inside the wall
  EXPECT_FALSE(si->isValid(in_wall.get()));
}

TEST(Planning, CheckerRejectsNonFiniteAndOutOfBoundsStates) {
  PlanningScene scene =
      loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml");
  const auto& si = scene.setup->getSpaceInformation();
  ompl::base::ScopedState<> state(si);
  const auto start = scene.setup->getProblemDefinition()->getStartState(0);
  si->copyState(state.get(), start);
  EXPECT_TRUE(si->isValid(state.get()));
  auto* values = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  values[1] = std::nan("");
  EXPECT_FALSE(si->isValid(state.get()));
  values[1] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(si->isValid(state.get()));
  values[1] = 100.0;  // beyond the joint limit
  EXPECT_FALSE(si->isValid(state.get()));
  EXPECT_EQ(si->getStateValidityChecker()->clearance(state.get()), 0.0);
}

// BoundsCheck applies OMPL's bounds rules inline; it must give SpaceInformation::satisfiesBounds's
// answer on every state, including those a few machine epsilons either side of a bound and
// quaternions whose norm is near the 1e-9 tolerance.
TEST(Planning, BoundsCheckGivesOmplsAnswer) {
  namespace ob = ompl::base;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double eps = std::numeric_limits<double>::epsilon();
  // A value in [lo, hi] widened by 10 %, or (one draw in four) a bound nudged by -3..3 epsilons.
  auto draw = [&](double lo, double hi) {
    if (unit(rng) < 0.25) {
      const double bound = unit(rng) < 0.5 ? lo : hi;
      const int k = static_cast<int>(rng() % 7) - 3;
      return bound + k * eps * std::max(1.0, std::fabs(bound));
    }
    const double w = hi - lo;
    return lo - 0.1 * w + 1.2 * w * unit(rng);
  };
  auto compare = [&](const ob::SpaceInformationPtr& si, auto&& fill, const char* what) {
    const BoundsCheck check(si);
    ob::ScopedState<> state(si);
    int inside = 0;
    for (int i = 0; i < 20000; ++i) {
      fill(state.get());
      const bool ompl = si->satisfiesBounds(state.get());
      ASSERT_EQ(check(state.get()), ompl) << what << ", state " << i;
      inside += ompl;
    }
    // Both answers occur often, so the comparison tests something.
    EXPECT_GT(inside, 2000) << what;
    EXPECT_LT(inside, 18000) << what;
  };

  auto joints = std::make_shared<ob::RealVectorStateSpace>(4);
  ob::RealVectorBounds jb(4);
  const double lows[4] = {-2.9, 0.0, -1e-3, 5.0}, highs[4] = {2.9, 1.5, 1e-3, 1e4};
  for (unsigned i = 0; i < 4; ++i) {
    jb.setLow(i, lows[i]);
    jb.setHigh(i, highs[i]);
  }
  joints->setBounds(jb);
  compare(
      std::make_shared<ob::SpaceInformation>(joints),
      [&](ob::State* s) {
        auto* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        const unsigned d =
            static_cast<unsigned>(rng() % 4);  // one coordinate varies, others inside
        for (unsigned i = 0; i < 4; ++i)
          v[i] = i == d ? draw(lows[i], highs[i]) : 0.5 * (lows[i] + highs[i]);
      },
      "joint space");

  auto se3 = std::make_shared<ob::SE3StateSpace>();
  ob::RealVectorBounds pb(3);
  pb.setLow(-1.0);
  pb.setHigh(2.0);
  se3->setBounds(pb);
  compare(
      std::make_shared<ob::SpaceInformation>(se3),
      [&](ob::State* s) {
        auto* x = s->as<ob::SE3StateSpace::StateType>();
        x->setXYZ(draw(-1, 2), unit(rng) < 0.8 ? 0.5 : draw(-1, 2), 0.5);
        Eigen::Vector4d q(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        q.normalize();
        // Norm 1 + delta, delta around the 1e-9 tolerance (or 0).
        const double deltas[6] = {0.0, 0.0, 5e-10, -5e-10, 2e-9, -2e-9};
        q *= 1.0 + deltas[rng() % 6];
        x->rotation().x = q[0];
        x->rotation().y = q[1];
        x->rotation().z = q[2];
        x->rotation().w = q[3];
      },
      "SE(3)");
}

}  // namespace
}  // namespace octomotion
