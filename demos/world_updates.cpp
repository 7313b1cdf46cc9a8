// A world that changes between plans (docs/robots.md): plan, add an obstacle, plan, pick up a
// part and plan with it, put it away, plan again -- one model, updated in place. Run from the
// repository root; exits 0 when every plan is solved.
#include <iostream>

#include <octomotion/planner/ompl/planning_scene.h>
using namespace octomotion;

int main() {
  SceneOverrides overrides;
  overrides.fit_universe_to_reach = true;  // objects may appear anywhere the arm reaches
  PlanningScene scene = loadPlanningScene("robots/scenes/bookshelf.yaml", overrides);
  bool solved = plan(scene).solved;

  EnvironmentObject crate;  // a new obstacle: only its region is voxelized again
  crate.name = "crate";
  crate.primitive = Box{Eigen::Vector3d(0.1, 0.1, 0.1)};
  crate.X_WO.translation() = Eigen::Vector3d(0.3, -0.5, 0.3);
  scene.addObject(crate);
  solved = plan(scene).solved && solved;  // the planner's data was cleared

  AttachedObject held;  // a part grasped by the hand, allowed to touch the fingers
  held.object.name = "part";
  held.object.primitive = Box{Eigen::Vector3d(0.01, 0.02, 0.01)};
  held.object.X_WO.translation() = Eigen::Vector3d(0, 0, 0.05);  // X_LO
  held.link = "hand";
  held.touch_links = {"left_finger", "right_finger"};
  scene.attachObject(held);
  solved = plan(scene).solved && solved;

  scene.detachObject("part");  // with &q: left in the world where the hand holds it at q
  scene.removeObject("crate");
  solved = plan(scene).solved && solved;
  std::cout << (solved ? "every plan solved\n" : "a plan failed\n");
  return solved ? 0 : 1;
}
