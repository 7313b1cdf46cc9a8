// What the trade study's runner (trade_study.cpp) and its planning runs (trade_study_planning.cpp)
// share; private to tools/src.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "octomotion/tools/trade_study.h"

namespace octomotion::trade_study_internal {

// The scene as loadSceneInputs reads it (the study builds its own models, one per setting) and
// what the study takes from it.
struct StudyScene {
  SceneSpec spec;
  std::optional<RobotModel> robot;
  std::shared_ptr<const EnvironmentGeometry> environment;
  double robot_diagonal = 0;  // boundMotionStep's reach (arms: until a model gives theirs)
  std::optional<Eigen::AlignedBox3d> bounds;  // free-flying: SE(3) position bounds
  double resolution = 0;                      // the scene's own (or auto) resolution
};

// One planning setting: the checker to install and what to call it.
struct PlanSetting {
  CheckerKind checker = CheckerKind::kFcl;
  std::string rounding;
  double resolution = 0;
  std::function<ompl::base::StateValidityCheckerPtr(const ompl::base::SpaceInformationPtr&)> make;
};

// One planning setting run `runs` times with ompl::tools::Benchmark (the Benchmark log written to
// options.log_dir when it is set).
PlanRow runPlanning(const StudyScene& scene, const PlanSetting& setting,
                    const StudyPlanner& planner, double motion_reach,
                    const TradeStudyOptions& options);

}  // namespace octomotion::trade_study_internal
