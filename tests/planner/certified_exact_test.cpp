// The certified motion validator is a proof for exact checkers (issue 29, item 3): with the FCL
// checker and with the octree's exact refine, whose free states carry no voxel margin, random
// edges near obstacles — on the shipped bookshelf scene and on the real Panda in a
// MotionBenchMaker scene — are accepted only when exact FCL finds every one of many evenly
// spaced states free, and every edge whose midpoint FCL finds colliding is rejected. The Panda
// cases skip without ../shared/data.
#include <gtest/gtest.h>

#include <algorithm>
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
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

const std::string kSource = OCTOMOTION_SOURCE_DIR;

struct Case {
  const char* name;
  bool mbm;  // the Panda in the first box_panda problem's scene, else the shipped bookshelf
  CheckerKind checker;
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
  return out << c.name;
}

class CertifiedExact : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    std::string path = kSource + "/robots/scenes/bookshelf.yaml";
    if (GetParam().mbm) {
      const std::string panda = test::MbmProblems::panda();
      const test::MbmProblems& problems = mbm();
      if (problems.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
        GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
      }
      test::MbmProblem problem;
      for (const test::MbmProblem& p : problems.firstOfEachSet()) {
        if (p.set == "box_panda") problem = p;
      }
      ASSERT_FALSE(problem.scene.empty());
      path = problems.folder() + "/exact.yaml";
      test::MbmProblems::writeScene(path, problem);
    }
    SceneOverrides o;
    o.checker = GetParam().checker;
    o.refine = RefineMode::kExact;  // what the default (auto) means here; said explicitly
    scene_ = loadPlanningScene(path, o, [](const std::string&) {});
    si_ = scene_.setup->getSpaceInformation();
    scene_.setup->setup();
    fcl_ = scene_.fclModel();
    fcl_scratch_ = fcl_->makeScratch();
  }

  void sampleUniform(ompl::base::State* s) {
    std::vector<double> q;
    for (const Variable& v : scene_.model->robot().variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng_));
    }
    configurationToState(scene_.model->robot(), q, Eigen::Isometry3d::Identity(), s);
  }
  double fclClearance(const ompl::base::State* s) {
    std::vector<double> q(static_cast<std::size_t>(fcl_->robot().variableCount()));
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (!stateToConfiguration(fcl_->robot(), s, q, X)) return -1;
    fcl_->setConfiguration(q.data(), q.size(), X, *fcl_scratch_);
    return fcl_->inCollision(*fcl_scratch_) ? -1 : fcl_->environmentDistance(*fcl_scratch_);
  }
  // A state FCL finds free within 3 cm of an obstacle.
  void sampleNearObstacle(ompl::base::State* s) {
    do sampleUniform(s);
    while (!(fclClearance(s) >= 0 && fclClearance(s) < 0.03));
  }
  // A state FCL finds free, a random fraction of `reach` from `from` toward a uniform one.
  void sampleFreeNear(const ompl::base::State* from, double reach, ompl::base::State* s) {
    ompl::base::ScopedState<> toward(si_);
    do {
      sampleUniform(toward.get());
      const double d = si_->distance(from, toward.get());
      const double step = reach * std::uniform_real_distribution<double>(0.2, 1.0)(rng_);
      si_->getStateSpace()->interpolate(from, toward.get(), d > step ? step / d : 1.0, s);
    } while (fclClearance(s) < 0);
  }

  // A state FCL finds colliding within micrometres of contact: along the ray from a free state
  // toward a uniform one, the first colliding state (steps of `step` of the motion bound, then
  // bisection). False when the ray meets nothing.
  bool sampleAtContact(const CertifiedMotionValidator& validator, double step,
                       ompl::base::State* s) {
    ompl::base::ScopedState<> from(si_), toward(si_);
    do sampleUniform(from.get());
    while (fclClearance(from.get()) < 0);
    sampleUniform(toward.get());
    const int steps = static_cast<int>(validator.motionBound(from.get(), toward.get()) / step) + 1;
    double free = 0, colliding = -1;
    for (int k = 1; k <= steps && colliding < 0; ++k) {
      si_->getStateSpace()->interpolate(from.get(), toward.get(), k / double(steps), s);
      (fclClearance(s) < 0 ? colliding : free) = k / double(steps);
    }
    if (colliding < 0) return false;
    for (int i = 0; i < 30; ++i) {
      const double m = 0.5 * (free + colliding);
      si_->getStateSpace()->interpolate(from.get(), toward.get(), m, s);
      (fclClearance(s) < 0 ? colliding : free) = m;
    }
    si_->getStateSpace()->interpolate(from.get(), toward.get(), colliding, s);
    // The environment distance's gradient in q a little before the contact (central
    // differences), about the contact's normal in joint space; zero when that state collides.
    ompl::base::ScopedState<> before(si_);
    const double back = 0.002 / validator.motionBound(from.get(), toward.get());
    si_->getStateSpace()->interpolate(from.get(), toward.get(), std::max(0.0, colliding - back),
                                      before.get());
    const RobotModel& robot = fcl_->robot();
    std::vector<double> q(static_cast<std::size_t>(robot.variableCount()));
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    stateToConfiguration(robot, before.get(), q, X);
    gradient_.assign(q.size(), 0.0);
    for (std::size_t i = 0; i < q.size(); ++i) {
      double d[2];
      for (int side = 0; side < 2; ++side) {
        std::vector<double> qi = q;
        qi[i] += side ? 1e-5 : -1e-5;
        fcl_->setConfiguration(qi.data(), qi.size(), X, *fcl_scratch_);
        d[side] = fcl_->environmentDistance(*fcl_scratch_);
      }
      if (!(d[0] > 0 && d[1] > 0)) return true;  // no gradient: gradient_ stays zero
      gradient_[i] = (d[1] - d[0]) / 2e-5;
    }
    return true;
  }
  std::vector<double> gradient_;  // of sampleAtContact's last contact

  // Extracted once per program.
  static const test::MbmProblems& mbm() {
    static const test::MbmProblems problems;
    return problems;
  }
  PlanningScene scene_;
  ompl::base::SpaceInformationPtr si_;
  std::shared_ptr<const FclCollisionModel> fcl_;
  FclCollisionModel::ScratchPtr fcl_scratch_;
  std::mt19937_64 rng_{41};
};

TEST_P(CertifiedExact, AcceptedEdgesNearObstaclesAreFreeForFclAndCollidingOnesAreRejected) {
  const auto* validator =
      dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  ASSERT_TRUE(validator->backend().exactAnswers());
  const double reach = 0.15 * si_->getMaximumExtent();
  ompl::base::ScopedState<> s1(si_), s2(si_), mid(si_);
  int accepted = 0, midpoint_colliding = 0;
  for (int k = 0; k < 20; ++k) {
    sampleNearObstacle(s1.get());
    sampleFreeNear(s1.get(), reach, s2.get());
    si_->getStateSpace()->interpolate(s1.get(), s2.get(), 0.5, mid.get());
    const bool free = validator->checkMotion(s1.get(), s2.get());
    if (fclClearance(mid.get()) < 0) {
      ++midpoint_colliding;
      EXPECT_FALSE(free) << "edge " << k;
    }
    if (!free) continue;
    ++accepted;
    EXPECT_EQ(test::fclCollisionsOnEdge(*fcl_, si_, s1.get(), s2.get(), 500), 0u) << "edge " << k;
  }
  EXPECT_GT(accepted, 5);
  EXPECT_GT(midpoint_colliding, 0);
}

// OMPL promises a valid first state, but a caller may break that; the edge is then not free.
TEST_P(CertifiedExact, EdgesFromACollidingStateAreRejected) {
  const auto* validator =
      dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  const double reach = 0.15 * si_->getMaximumExtent();
  ompl::base::ScopedState<> s1(si_), s2(si_);
  for (int k = 0; k < 10; ++k) {
    do sampleUniform(s1.get());
    while (fclClearance(s1.get()) >= 0);
    sampleFreeNear(s1.get(), reach, s2.get());
    EXPECT_FALSE(validator->checkMotion(s1.get(), s2.get())) << "edge " << k;
  }
}

// Edges that graze: two free states symmetric about a state just inside an obstacle (or another
// link), their motion bound below a voxel, which voxel answers decide by the ends alone. The
// edge's midpoint is that state, so every such edge must be rejected.
TEST_P(CertifiedExact, ShortEdgesThroughAContactAreRejected) {
  const auto* validator =
      dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  const RobotModel& robot = scene_.model->robot();
  const double resolution = validator->resolution();
  ompl::base::ScopedState<> contact(si_), toward(si_), s1(si_), s2(si_);
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount())), q1(q), q2(q);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  int grazing = 0;
  for (int k = 0; k < 8; ++k) {
    if (!sampleAtContact(*validator, resolution, contact.get())) continue;
    ASSERT_TRUE(stateToConfiguration(robot, contact.get(), q, X));
    for (int j = 0; j < 10; ++j) {
      sampleUniform(toward.get());
      const double bound = validator->motionBound(contact.get(), toward.get());
      const double half = 0.5 * resolution * std::uniform_real_distribution<double>(0.2, 1.0)(rng_);
      si_->getStateSpace()->interpolate(contact.get(), toward.get(), std::min(1.0, half / bound),
                                        s1.get());
      ASSERT_TRUE(stateToConfiguration(robot, s1.get(), q1, X));
      // Along the contact's tangent (the distance gradient projected out), so that both ends
      // can clear it.
      double gg = 0, gw = 0;
      for (std::size_t i = 0; i < q.size(); ++i) {
        gg += gradient_[i] * gradient_[i];
        gw += gradient_[i] * (q1[i] - q[i]);
      }
      for (std::size_t i = 0; gg > 0 && i < q.size(); ++i) q1[i] -= gw / gg * gradient_[i];
      configurationToState(robot, q1, X, s1.get());
      for (std::size_t i = 0; i < q.size(); ++i) q2[i] = 2 * q[i] - q1[i];
      configurationToState(robot, q2, X, s2.get());
      if (!si_->satisfiesBounds(s1.get()) || !si_->satisfiesBounds(s2.get()) ||
          fclClearance(s1.get()) < 0 || fclClearance(s2.get()) < 0) {
        continue;
      }
      ++grazing;
      EXPECT_FALSE(validator->checkMotion(s1.get(), s2.get())) << "contact " << k << " edge " << j;
    }
  }
  EXPECT_GT(grazing, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Checkers, CertifiedExact,
    ::testing::Values(Case{"BookshelfFcl", false, CheckerKind::kFcl},
                      Case{"BookshelfRefineExact", false, CheckerKind::kOctreeFused},
                      Case{"MbmPandaFcl", true, CheckerKind::kFcl},
                      Case{"MbmPandaRefineExact", true, CheckerKind::kOctreeFused}),
    [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace octomotion
