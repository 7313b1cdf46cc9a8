// Shared by the validation tests (docs/validation.md): which scenes, at which resolution, and
// uniform random states of a scene's robot drawn with a fixed seed.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/util/Console.h>
#include <Eigen/Geometry>

#include "fcl_reference.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace octomotion::validation {

// Every scene in robots/scenes (the directory is listed, so scenes added later are validated
// too), plus the one-link-URDF rigid body of the test data.
inline std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  files.push_back(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/l_piece_urdf.yaml");
  return files;
}

// The scenes with primitives among their obstacles (CollisionModelOptions::exact_primitives
// applies), and a table with meshes among its primitives.
inline std::vector<std::string> primitiveSceneFiles() {
  std::vector<std::string> files;
  for (const std::string& f : sceneFiles()) {
    const SceneSpec spec = loadScene(f);
    if (std::any_of(spec.environment.begin(), spec.environment.end(),
                    [](const EnvironmentObject& o) {
                      return o.kind == EnvironmentObject::Kind::kPrimitive;
                    })) {
      files.push_back(f);
    }
  }
  files.push_back(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/mixed_table.yaml");
  return files;
}

inline std::string sceneLabel(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

// gtest parameter names: letters, digits and underscores only.
inline std::string testName(const std::string& path) {
  std::string name = sceneLabel(path);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

// Arms at 2 cm (fast to build, and coarse enough that the margins matter); rigid bodies at
// their scene's resolution (auto when it has none), since they are small next to 2 cm.
inline PlanningScene loadValidationScene(const std::string& path, Rounding rounding,
                                         CheckerKind checker = CheckerKind::kOctreeFused,
                                         std::optional<double> self_link_resolution = {},
                                         bool exact_primitives = false) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.rounding = rounding;
  overrides.checker = checker;
  overrides.self_link_resolution = self_link_resolution;
  overrides.exact_primitives = exact_primitives;
  // The voxels' own answers (the margins validated here), not the default exact refine.
  overrides.refine = RefineMode::kNone;
  const SceneSpec spec = loadScene(path);
  bool arm = !spec.robot.urdf.empty();
  if (arm) {
    // A URDF without movable joints is a rigid body (loadPlanningScene makes it free-flying).
    RobotModelOptions options;
    options.package_paths = spec.robot.package_paths;
    arm = RobotModel::fromUrdfFile(spec.robot.urdf, options).variableCount() > 0;
  }
  if (arm) overrides.resolution = 0.02;
  // Validation checks uniform states, not the problem: a start within the voxels' margin at
  // 2 cm (cluttered_table on the moveTree path) is no reason to refuse the scene.
  overrides.require_free_start_goal = false;
  return loadPlanningScene(path, overrides);
}

}  // namespace octomotion::validation
