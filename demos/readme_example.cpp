// The README's "Plugging it into OMPL" example, compiled and run as the demo_readme_example test;
// tests/demos/readme_test.cpp checks that the README shows exactly the lines between the markers.
#include <memory>

// README example begin
#include <octomotion/planner/ompl/planning_scene.h>
#include <ompl/geometric/SimpleSetup.h>

int main() {
  // One call: the scene's robot (URDF + SRDF), environment, resolution, checker, planner, start
  // and goal, and the certified motion validator (every edge proven free, docs/validation.md §4).
  const ompl::geometric::SimpleSetupPtr ss =
      octomotion::makeSimpleSetup("robots/scenes/bookshelf.yaml");
  const bool solved = ss->solve(5.0) == ompl::base::PlannerStatus::EXACT_SOLUTION;
  return solved ? 0 : 1;  // the demo_readme_example test needs a solution
}
// README example end
