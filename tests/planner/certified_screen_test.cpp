// The certified motion validator's collision screen (CertifiedMotionValidator::kScreenLevels):
// on the real Panda in a MotionBenchMaker scene, with the octree at its defaults (exact refine)
// and with the FCL checker, random edges of the planner's default range from valid states are
// checked; every edge the screen rejects has a state the scene's state checker finds colliding
// among the ones the screen may visit (the end and the midpoints of its levels), and the proof
// alone (no screen) rejects it too; every accepted edge is free for exact FCL at 400 states and
// accepted by the proof alone. Skips without ../shared/data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>

#include "mbm_problems.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

struct Case {
  const char* name;
  const char* set;  // the MotionBenchMaker set whose first problem's scene is used
  CheckerKind checker;
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
  return out << c.name;
}

class CertifiedScreen : public ::testing::TestWithParam<Case> {
 protected:
  static const test::MbmProblems& mbm() {
    static const test::MbmProblems problems;
    return problems;
  }
};

TEST_P(CertifiedScreen, RejectsOnlyEdgesThroughACollidingStateAndKeepsTheProof) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string panda = test::MbmProblems::panda();
  if (mbm().problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
    GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
  }
  test::MbmProblem problem;
  for (const test::MbmProblem& p : mbm().firstOfEachSet()) {
    if (p.set == GetParam().set) problem = p;
  }
  ASSERT_FALSE(problem.scene.empty());
  const std::string path = mbm().folder() + "/screen_" + GetParam().name + ".yaml";
  test::MbmProblems::writeScene(path, problem);
  SceneOverrides o;
  o.checker = GetParam().checker;
  PlanningScene scene = loadPlanningScene(path, o, [](const std::string&) {});
  const ompl::base::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  scene.setup->setup();
  const auto* screened =
      dynamic_cast<const CertifiedMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(screened, nullptr);
  ASSERT_EQ(screened->screenLevels(), CertifiedMotionValidator::kScreenLevels);
  const std::shared_ptr<const CollisionBackend> backend = checkerBackend(scene);
  CertifiedMotionValidator proof_only(
      si, backend,
      makeLinkMotionBound(backend->robot(), scene.spec.robot.keep_mesh_root_transform,
                          scene.spec.robot.center_mesh_vertices),
      screened->resolution());
  proof_only.setScreenLevels(0);
  const std::shared_ptr<const FclCollisionModel> fcl = scene.fclModel();

  const RobotModel& robot = scene.model->robot();
  std::mt19937_64 rng(29);
  auto uniform = [&](ompl::base::State* s) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    configurationToState(robot, q, Eigen::Isometry3d::Identity(), s);
  };
  const double range = 0.2 * si->getMaximumExtent();  // RRTConnect's default
  const int screen_states = 1 << CertifiedMotionValidator::kScreenLevels;
  ompl::base::ScopedState<> s1(si), s2(si), between(si);
  int accepted = 0, screened_out = 0;
  for (int k = 0; k < 60; ++k) {
    do uniform(s1.get());
    while (!si->isValid(s1.get()));
    uniform(s2.get());
    const double d = si->distance(s1.get(), s2.get());
    if (d > range) si->getStateSpace()->interpolate(s1.get(), s2.get(), range / d, s2.get());
    const std::size_t before = screened->counts().rejected_by_screen;
    const bool free = screened->checkMotion(s1.get(), s2.get());
    const bool by_screen = screened->counts().rejected_by_screen > before;
    EXPECT_FALSE(free && by_screen) << "edge " << k;
    EXPECT_EQ(proof_only.checkMotion(s1.get(), s2.get()), free) << "edge " << k;
    if (by_screen) {
      ++screened_out;
      int colliding = 0;
      for (int j = 1; j <= screen_states; ++j) {
        si->getStateSpace()->interpolate(s1.get(), s2.get(), j / double(screen_states),
                                         between.get());
        colliding += si->isValid(between.get()) ? 0 : 1;
      }
      EXPECT_GT(colliding, 0) << "edge " << k << " was rejected by the screen";
    }
    if (!free) continue;
    ++accepted;
    EXPECT_EQ(test::fclCollisionsOnEdge(*fcl, si, s1.get(), s2.get(), 400), 0u) << "edge " << k;
  }
  EXPECT_GT(screened_out, 5);
  EXPECT_GT(accepted, 3);
}

INSTANTIATE_TEST_SUITE_P(
    Panda, CertifiedScreen,
    ::testing::Values(Case{"octree_table_pick", "table_pick_panda", CheckerKind::kOctreeFused},
                      Case{"octree_bookshelf", "bookshelf_small_panda", CheckerKind::kOctreeFused},
                      Case{"fcl_box", "box_panda", CheckerKind::kFcl}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace octomotion
