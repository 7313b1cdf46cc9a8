// problem.range and --range: the planner's extension range (docs/planner.md, "The planner's
// range"), read from scenes, applied to planners that have one and refused by those without.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/scene/scene.h"

namespace {

using namespace octomotion;
using ::testing::HasSubstr;
namespace ob = ompl::base;
namespace og = ompl::geometric;

const std::string kSource = OCTOMOTION_SOURCE_DIR;

ob::SpaceInformationPtr unitSquare() {
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(0.0, 1.0);
  return std::make_shared<ob::SpaceInformation>(space);
}

TEST(PlannerRange, SceneKeyIsReadAndMustBePositive) {
  const SceneSpec s =
      parseSceneYaml("robot: {mesh: m.stl}\nproblem: {range: 0.25}\n", "/s/range.yaml");
  ASSERT_TRUE(s.problem.range.has_value());
  EXPECT_DOUBLE_EQ(*s.problem.range, 0.25);
  EXPECT_FALSE(parseSceneYaml("robot: {mesh: m.stl}\n", "/s/none.yaml").problem.range);
  for (const char* bad : {"0", "-1", "fast"}) {
    try {
      parseSceneYaml(std::string("robot: {mesh: m.stl}\nproblem: {range: ") + bad + "}\n",
                     "/s/bad.yaml");
      ADD_FAILURE() << "accepted range " << bad;
    } catch (const FileError& e) {
      EXPECT_THAT(e.what(), HasSubstr("problem.range"));
      EXPECT_THAT(e.what(), HasSubstr("/s/bad.yaml"));
    }
  }
}

TEST(PlannerRange, SetsPlannersThatHaveOneAndRefusesOthers) {
  const ob::SpaceInformationPtr si = unitSquare();
  og::RRTConnect rrt(si);
  const double before = rrt.getRange();
  setPlannerRange(rrt, std::nullopt);
  EXPECT_EQ(rrt.getRange(), before);  // no range given: the planner's own
  setPlannerRange(rrt, 0.125);
  EXPECT_DOUBLE_EQ(rrt.getRange(), 0.125);
  EXPECT_THROW(setPlannerRange(rrt, 0.0), InvalidArgument);
  EXPECT_THROW(setPlannerRange(rrt, std::numeric_limits<double>::infinity()), InvalidArgument);
  og::PRM prm(si);
  setPlannerRange(prm, std::nullopt);  // nothing asked, nothing refused
  try {
    setPlannerRange(prm, 0.5);
    ADD_FAILURE() << "PRM took a range";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("PRM"));
  }
}

TEST(PlannerRange, TheCommandLineSetsTheRangeAndPlannersWithoutOneRefuseIt) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string scene = kSource + "/robots/scenes/bookshelf.yaml";
  auto range = [](const PlanningScene& s) {
    return std::dynamic_pointer_cast<og::RRTConnect>(s.setup->getPlanner())->getRange();
  };
  // Without a range an arm's planner reaches a tenth of the joint space's extent (OMPL's own
  // would be a fifth: 0 until setup() sets it).
  const PlanningScene arm = loadPlanningScene(scene);
  const double extent = arm.setup->getStateSpace()->getMaximumExtent();
  EXPECT_GT(extent, 0.0);
  EXPECT_DOUBLE_EQ(range(arm), kArmRangeShare * extent);
  // A rigid body keeps OMPL's, and so does the ompl-default validator, the baseline.
  EXPECT_EQ(range(loadPlanningScene(kSource + "/robots/scenes/rooms.yaml")), 0.0);
  SceneOverrides baseline;
  baseline.motion_validator = MotionValidatorKind::kOmplDefault;
  EXPECT_EQ(range(loadPlanningScene(scene, baseline)), 0.0);
  SceneOverrides overrides;
  overrides.range = 0.3;
  EXPECT_DOUBLE_EQ(range(loadPlanningScene(scene, overrides)), 0.3);
  // A planner without a range: planned with its own settings, unless a range is asked for.
  SceneOverrides prm;
  prm.planner = "PRM";
  EXPECT_NO_THROW(loadPlanningScene(scene, prm));
  prm.range = 0.3;
  try {
    loadPlanningScene(scene, prm);
    ADD_FAILURE() << "PRM took a range";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("problem.range"));
    EXPECT_THAT(e.what(), HasSubstr("bookshelf.yaml"));
  }
}

}  // namespace
