// The main demo: the 7-DoF octo7 arm reaches into the middle compartment of a bookshelf.
// Prints what was modelled, plans with RRTConnect on the fused octree checker, re-checks the
// path with FCL (exact meshes), compares the per-check cost of the octree and FCL checkers on
// the same random states, writes the path in OMPL's format to out/plan_arm.path and a viewer
// file (glTF binary: the voxel trees, the robot and the path) to out/plan_arm.glb.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <ompl/util/Console.h>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
#include "octomotion/tools/gltf_export.h"

using namespace octomotion;

namespace {

// Median time of one isValid call over the given states, in nanoseconds.
double medianCheckNs(const ompl::base::StateValidityChecker& checker,
                     const std::vector<ompl::base::State*>& states) {
  std::vector<double> ns;
  ns.reserve(states.size());
  for (const ompl::base::State* s : states) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool valid = checker.isValid(s);
    const auto t1 = std::chrono::steady_clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    volatile bool sink = valid;  // keep the call from being optimised away
    (void)sink;
  }
  std::nth_element(ns.begin(), ns.begin() + static_cast<long>(ns.size() / 2), ns.end());
  return ns[ns.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string scene_file = argc > 1 ? argv[1] : "robots/scenes/bookshelf.yaml";
  try {
    PlanningScene scene = loadPlanningScene(scene_file);
    std::cout << "== " << scene.spec.name << ": what was modelled\n"
              << scene.model->report().toString();

    const PlanResult result = plan(scene);
    if (!result.solved) {
      std::cout << "no solution in " << scene.spec.problem.time << " s\n";
      return 1;
    }
    std::cout << "== planned with " << scene.spec.problem.planner << " ("
              << octomotion::checkerKindName(scene.checker) << ") in " << result.seconds * 1e3
              << " ms: " << result.path->getStateCount() << " states, length "
              << result.path->length() << " rad\n";

    // Re-check the path with FCL at ten times the density.
    ompl::geometric::PathGeometric dense(*result.path);
    dense.interpolate(10 * (result.path->getStateCount() - 1) + 1);
    auto fcl = scene.fcl_model->makeScratch();
    const RobotModel& robot = scene.model->robot();
    std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    std::size_t colliding = 0;
    for (unsigned i = 0; i < dense.getStateCount(); ++i) {
      stateToConfiguration(robot, dense.getState(i), q, X);
      scene.fcl_model->setConfiguration(q.data(), q.size(), X, *fcl);
      colliding += scene.fcl_model->inCollision(*fcl) ? 1 : 0;
    }
    std::cout << "== FCL re-check of " << dense.getStateCount() << " path states: " << colliding
              << " in collision\n";

    // Per-check cost on the same uniform random states.
    const auto si = scene.setup->getSpaceInformation();
    auto sampler = si->allocStateSampler();
    std::vector<ompl::base::State*> states(20000);
    for (auto*& s : states) {
      s = si->allocState();
      sampler->sampleUniform(s);
    }
    const OctreeValidityChecker fused(si, scene.model, CheckerPath::kFused);
    const FclValidityChecker exact(si, scene.fcl_model);
    const double fused_ns = medianCheckNs(fused, states);
    const double fcl_ns = medianCheckNs(exact, states);
    std::cout << "== median check over " << states.size() << " uniform states: octree-fused "
              << fused_ns / 1e3 << " us, FCL " << fcl_ns / 1e3 << " us (" << fcl_ns / fused_ns
              << "x)\n";
    for (auto* s : states) si->freeState(s);

    std::filesystem::create_directories("out");
    std::ofstream out("out/plan_arm.path");
    writePath(scene, *result.path, out);
    std::cout << "== path written to out/plan_arm.path (one state per line, joints in order:";
    for (const Variable& v : robot.variables()) std::cout << ' ' << v.name;
    std::cout << ")\n";

    // The same path for the web viewer (docs/viewer.md): the trees, the robot and the path as
    // an animation, the links' voxel trees at the middle state.
    std::vector<RobotState> path_states(result.path->getStateCount());
    for (unsigned i = 0; i < result.path->getStateCount(); ++i) {
      path_states[i].q.resize(static_cast<std::size_t>(robot.variableCount()));
      stateToConfiguration(robot, result.path->getState(i), path_states[i].q, path_states[i].X_WB);
      if (robot.isFreeFlying()) path_states[i].q.clear();
    }
    GltfExportOptions view;
    view.state_index = path_states.size() / 2;
    view.keep_mesh_root_transform = scene.spec.robot.keep_mesh_root_transform;
    view.center_mesh_vertices = scene.spec.robot.center_mesh_vertices;
    const GltfExportReport exported =
        exportGlb(*scene.model, path_states, view, "out/plan_arm.glb");
    std::cout << "== viewer file written to out/plan_arm.glb (" << exported.trees.size()
              << " voxel trees, " << exported.link_meshes << " link meshes, "
              << exported.path_states << " path states); to view it (after npm ci --prefix "
              << "viewer):\n   python3 -m http.server 8000 -d .\n   then open "
              << "http://localhost:8000/viewer/?model=../out/plan_arm.glb&state="
              << view.state_index << "\n";
    return colliding == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "plan_arm: error: " << e.what() << "\n";
    return 1;
  }
}
