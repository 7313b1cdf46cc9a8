// The README's "Plugging it into OMPL" example, compiled and run as the demo_readme_example test;
// tests/demos/readme_test.cpp checks that the README shows exactly the lines between the markers.
#include <memory>

// README example begin
#include <octomotion/planner/ompl/state_space.h>
#include <octomotion/planner/ompl/validity_checker.h>
#include <octomotion/planner/scene/scene.h>
#include <ompl/geometric/SimpleSetup.h>
using namespace octomotion;

int main() {
  RobotModelOptions options;
  options.package_paths = {"."};  // where robots/package.xml lives (or OCTOMOTION_PACKAGE_PATH)
  RobotModel robot = RobotModel::fromUrdfFile("robots/octo7/octo7.urdf", options);
  robot.loadSrdfFile("robots/octo7/octo7.srdf");  // disabled self-collision pairs
  const SceneSpec scene = loadScene("robots/scenes/bookshelf.yaml");  // environment + problem
  auto model = std::make_shared<const OctreeCollisionModel>(
      robot, EnvironmentGeometry::load(scene.environment), CollisionModelOptions{});  // 1 cm

  ompl::geometric::SimpleSetup ss(makeStateSpace(model->robot()));
  ss.setStateValidityChecker(std::make_shared<OctreeValidityChecker>(ss.getSpaceInformation(),
                                                                     model, CheckerPath::kFused));
  ompl::base::ScopedState<> start(ss.getStateSpace()), goal(ss.getStateSpace());
  configurationToState(robot, scene.problem.start->joints, Eigen::Isometry3d::Identity(),
                       start.get());
  configurationToState(robot, scene.problem.goal->joints, Eigen::Isometry3d::Identity(),
                       goal.get());
  ss.setStartAndGoalStates(start, goal);
  const bool solved = ss.solve(5.0) == ompl::base::PlannerStatus::EXACT_SOLUTION;
  return solved ? 0 : 1;  // the demo_readme_example test needs a solution
}
// README example end
