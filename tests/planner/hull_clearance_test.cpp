// Exact refine's distances for the certified motion validator from convex hulls
// (planner/src/model/refine_clearance.cpp): a link-object or link-link distance is its hulls'
// certified lower bound, FCL's distance only within an eighth of a voxel of contact. On the real
// Panda in MotionBenchMaker scenes (a grasp near a box on a table, a box, a thin bookshelf), at
// random valid states near obstacles (fixed seeds): each link's refined clearance, capped at a
// random value, never exceeds FCL's exact distance from that link to the environment and, where
// the validator asks for a tight one, is within kClose of it below the cap; each checked self
// pair's refined distance likewise; and edges the certified validator accepts are free for exact
// FCL at 500 states each. A pose restored from an earlier query's link poses answers as
// setPose does. The slabs that come with refined clearances separate each link from its nearest
// objects, and the other objects are as far as they say. Skipped without ../shared/data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>

#include "link_points.h"
#include "mbm_problems.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

// How far below FCL's distance a hull bound may fall on the Panda: its collision meshes are
// nearly convex, the scenes' boxes are exact hulls and their cylinders' outer prisms are wider by
// 0.5 % of the radius (a fraction of a millimetre for these).
constexpr double kClose = 1e-3;

class HullClearance : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const std::string panda = test::MbmProblems::panda();
    const test::MbmProblems& problems = mbm();
    if (problems.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
      GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
    }
    test::MbmProblem problem;
    for (const test::MbmProblem& p : problems.firstOfEachSet()) {
      if (p.set == GetParam()) problem = p;
    }
    ASSERT_FALSE(problem.scene.empty()) << GetParam();
    const std::string path = problems.folder() + "/hull_" + GetParam() + ".yaml";
    test::MbmProblems::writeScene(path, problem);
    SceneOverrides o;
    o.refine = RefineMode::kExact;  // what the default (auto) means here; said explicitly
    scene_ = loadPlanningScene(path, o, [](const std::string&) {});
    si_ = scene_.setup->getSpaceInformation();
    scene_.setup->setup();
    fcl_ = scene_.fclModel();
    octree_ = checkerBackend(scene_);
    ASSERT_TRUE(octree_->exactAnswers());
  }

  std::vector<double> uniformQ() {
    std::vector<double> q;
    for (const Variable& v : scene_.model->robot().variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng_));
    }
    return q;
  }
  // A state both checkers find free, within 3 cm of an obstacle by FCL.
  std::vector<double> freeNearObstacle(BackendScratch& fcl, BackendScratch& octree) {
    const Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    for (;;) {
      const std::vector<double> q = uniformQ();
      if (fcl_->inCollision(q.data(), q.size(), X, fcl)) continue;
      if (fcl_->clearance(fcl) >= 0.03) continue;
      if (octree_->inCollision(q.data(), q.size(), X, octree)) continue;
      return q;
    }
  }

  static const test::MbmProblems& mbm() {
    static const test::MbmProblems problems;
    return problems;
  }
  PlanningScene scene_;
  ompl::base::SpaceInformationPtr si_;
  std::shared_ptr<const FclCollisionModel> fcl_;
  std::shared_ptr<const CollisionBackend> octree_;
  std::mt19937_64 rng_{0x4d11};
};

TEST_P(HullClearance, RefinedClearancesAreLowerBoundsCloseToFclsDistances) {
  const RobotModel& robot = scene_.model->robot();
  const auto links = static_cast<std::size_t>(robot.linkCount());
  auto fcl_scratch = fcl_->makeBackendScratch();
  auto octree_scratch = octree_->makeBackendScratch();
  const std::vector<double> no_cap(links, std::numeric_limits<double>::infinity());
  std::vector<double> caps(links), exact(links), refined(links);
  // The validator asks for an exact clearance below two voxels (refineClearancesPerLink).
  const double near = 2 * scene_.model->grid().voxelSize();
  // Caps about the distances asked: about half of them reached (where the hulls can answer).
  std::uniform_real_distribution<double> cap_of(0.0, 0.025);
  int asked = 0, at_cap = 0;
  for (int state = 0; state < 60; ++state) {
    freeNearObstacle(*fcl_scratch, *octree_scratch);
    for (double& c : caps) c = cap_of(rng_);
    fcl_->motionClearances(*fcl_scratch, no_cap.data(), exact.data(), nullptr);
    octree_->motionClearances(*octree_scratch, caps.data(), refined.data(), nullptr);
    for (std::size_t l = 0; l < links; ++l) {
      if (!robot.link(static_cast<int>(l)).hasCollision()) continue;
      const std::string& name = robot.link(static_cast<int>(l)).name;
      // FCL's GJK tolerance aside.
      EXPECT_LE(refined[l], exact[l] + 1e-5) << name << " state " << state;
      if (exact[l] < near - 1e-5) {
        ++asked;
        at_cap += exact[l] >= caps[l];
        EXPECT_GE(std::min(refined[l], caps[l]), std::min(exact[l], caps[l]) - kClose)
            << name << " state " << state;
      }
    }
  }
  EXPECT_GT(asked, 40);   // links near an obstacle
  EXPECT_GT(at_cap, 10);  // and some farther than asked
}

TEST_P(HullClearance, RefinedPairDistancesAreLowerBoundsCloseToFclsDistances) {
  const RobotModel& robot = scene_.model->robot();
  auto fcl_scratch = fcl_->makeBackendScratch();
  auto octree_scratch = octree_->makeBackendScratch();
  const double inf = std::numeric_limits<double>::infinity();
  std::uniform_real_distribution<double> cap_of(0.0, 0.08);
  int below = 0, above = 0;
  for (int state = 0; state < 40; ++state) {
    freeNearObstacle(*fcl_scratch, *octree_scratch);
    for (const auto& [a, b] : robot.checkedPairs()) {
      if (!robot.link(a).hasCollision() || !robot.link(b).hasCollision()) continue;
      const double cap = cap_of(rng_);
      const double exact = fcl_->linkPairDistance(*fcl_scratch, a, b, inf);
      const double refined = octree_->linkPairDistance(*octree_scratch, a, b, cap);
      (exact < cap ? below : above) += 1;
      EXPECT_LE(refined, std::min(exact, cap) + 1e-5)
          << robot.link(a).name << " / " << robot.link(b).name << " state " << state;
      EXPECT_GE(refined, std::min(exact, cap) - kClose)
          << robot.link(a).name << " / " << robot.link(b).name << " state " << state;
    }
  }
  EXPECT_GT(below, 20);
  EXPECT_GT(above, 200);
}

// The certified validator poses a screened state from the link poses its screen query left
// (CollisionBackend::setPosed): every clearance and pair distance must then be what setPose
// gives, bit for bit, even with the scratch last posed elsewhere.
TEST_P(HullClearance, PosesRestoredFromAnEarlierQueryAnswerAsSetPose) {
  const RobotModel& robot = scene_.model->robot();
  const auto links = static_cast<std::size_t>(robot.linkCount());
  auto fcl_scratch = fcl_->makeBackendScratch();
  auto posed_scratch = octree_->makeBackendScratch();
  auto restored_scratch = octree_->makeBackendScratch();
  const Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  std::uniform_real_distribution<double> cap_of(0.0, 0.05);
  std::vector<double> caps(links), posed(links), restored(links);
  for (int state = 0; state < 30; ++state) {
    const std::vector<double> q = freeNearObstacle(*fcl_scratch, *restored_scratch);
    const RobotData* kept = octree_->posedRobot(*restored_scratch);
    ASSERT_NE(kept, nullptr);
    const RobotData copy = *kept;
    const std::vector<double> elsewhere = freeNearObstacle(*fcl_scratch, *restored_scratch);
    ASSERT_NE(elsewhere, q);
    ASSERT_TRUE(octree_->setPosed(copy, *restored_scratch));
    octree_->setPose(q.data(), q.size(), X, *posed_scratch);
    for (double& c : caps) c = cap_of(rng_);
    octree_->motionClearances(*posed_scratch, caps.data(), posed.data(), nullptr);
    octree_->motionClearances(*restored_scratch, caps.data(), restored.data(), nullptr);
    for (std::size_t l = 0; l < links; ++l) {
      if (caps[l] > 0) {
        EXPECT_EQ(restored[l], posed[l]) << "link " << l << " state " << state;
      }
    }
    for (const auto& [a, b] : robot.checkedPairs()) {
      const double cap = cap_of(rng_);
      EXPECT_EQ(octree_->linkPairDistance(*restored_scratch, a, b, cap),
                octree_->linkPairDistance(*posed_scratch, a, b, cap))
          << robot.link(a).name << " / " << robot.link(b).name << " state " << state;
    }
  }
}

// An environment primitive's extent along a unit direction u (world frame): the largest u . o
// over its points o.
double primitiveSupport(const EnvironmentObject& object, const Eigen::Vector3d& u) {
  const Eigen::Vector3d u_O = object.X_WO.linear().transpose() * u;
  double extent = 0.0;
  if (const auto* box = std::get_if<Box>(&object.primitive)) {
    extent = u_O.cwiseAbs().dot(box->half_extents);
  } else if (const auto* ball = std::get_if<Sphere>(&object.primitive)) {
    extent = ball->radius;
  } else {
    const auto& cylinder = std::get<Cylinder>(object.primitive);
    extent = 0.5 * cylinder.length * std::abs(u_O.z()) +
             cylinder.radius * std::sqrt(std::max(0.0, 1.0 - u_O.z() * u_O.z()));
  }
  return u.dot(object.X_WO.translation()) + extent;
}

// The distance from p (world frame) to an environment primitive's solid.
double primitiveDistance(const EnvironmentObject& object, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p = object.X_WO.inverse() * p_W;
  if (const auto* box = std::get_if<Box>(&object.primitive)) {
    return (p.cwiseAbs() - box->half_extents).cwiseMax(0.0).norm();
  }
  if (const auto* ball = std::get_if<Sphere>(&object.primitive)) {
    return std::max(0.0, p.norm() - ball->radius);
  }
  const auto& cylinder = std::get<Cylinder>(object.primitive);
  const double radial = std::max(0.0, p.head<2>().norm() - cylinder.radius);
  const double axial = std::max(0.0, std::abs(p.z()) - 0.5 * cylinder.length);
  return std::hypot(radial, axial);
}

// The slabs refined clearances come with (NearestObstacle): each separates the link's points
// from some object by its gap along its direction, the first gap is at most the link's FCL
// distance, every object no slab separates is at least `others` from the link's points, and
// `others` is at least the first gap (the slabs' objects are the nearest).
TEST_P(HullClearance, NearestObjectSlabsSeparateTheLinkFromThoseObjects) {
  const RobotModel& robot = scene_.model->robot();
  const auto links = static_cast<std::size_t>(robot.linkCount());
  for (const EnvironmentGeometry::Item& item : scene_.environment->items()) {
    ASSERT_EQ(item.spec.kind, EnvironmentObject::Kind::kPrimitive) << item.spec.name;
  }
  CollisionMeshes meshes(false, false);
  std::vector<std::vector<Eigen::Vector3d>> points_L;
  for (const Link& link : robot.links())
    points_L.push_back(test::linkPoints(link, meshes, 1u << 20));
  auto fcl_scratch = fcl_->makeBackendScratch();
  auto octree_scratch = octree_->makeBackendScratch();
  const std::vector<double> no_cap(links, std::numeric_limits<double>::infinity());
  std::vector<double> caps(links), exact(links), refined(links);
  std::vector<NearestObstacle> nearest(links);
  std::uniform_real_distribution<double> cap_of(0.0, 0.025);
  int slabs = 0, second = 0;
  for (int state = 0; state < 60; ++state) {
    freeNearObstacle(*fcl_scratch, *octree_scratch);
    for (double& c : caps) c = cap_of(rng_);
    fcl_->motionClearances(*fcl_scratch, no_cap.data(), exact.data(), nullptr);
    octree_->motionClearances(*octree_scratch, caps.data(), refined.data(), nearest.data());
    const RobotData* posed = fcl_->posedRobot(*fcl_scratch);
    ASSERT_NE(posed, nullptr);
    for (std::size_t l = 0; l < links; ++l) {
      const NearestObstacle& o = nearest[l];
      if (!o.valid() || points_L[l].empty()) continue;
      const std::string& name = robot.link(static_cast<int>(l)).name;
      ++slabs;
      EXPECT_LE(o.gap[0], exact[l] + 1e-5) << name << " state " << state;
      // The slabs' objects are the nearest by their bounds, which the gaps are below.
      EXPECT_GE(o.others, o.gap[0]) << name << " state " << state;
      std::vector<Eigen::Vector3d> points_W;
      for (const Eigen::Vector3d& p : points_L[l]) {
        points_W.push_back(posed->linkPose(static_cast<int>(l)) * p);
      }
      // Per slab, whether some object lies beyond it; per object, whether a slab holds it.
      std::vector<bool> slab_found(NearestObstacle::kSlabs, false);
      for (const EnvironmentGeometry::Item& item : scene_.environment->items()) {
        bool held = false;
        for (std::size_t k = 0; k < NearestObstacle::kSlabs && o.valid(k); ++k) {
          const Eigen::Vector3d& u = o.toward_W[k];
          EXPECT_NEAR(u.norm(), 1.0, 1e-9);
          double link_extent = -std::numeric_limits<double>::infinity();
          for (const Eigen::Vector3d& p : points_W) link_extent = std::max(link_extent, u.dot(p));
          const double beyond = -primitiveSupport(item.spec, -u) - link_extent;
          if (beyond >= o.gap[k] - 1e-9) {
            held = true;
            slab_found[k] = true;
          }
        }
        if (held) continue;
        double distance = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& p : points_W) {
          distance = std::min(distance, primitiveDistance(item.spec, p));
        }
        EXPECT_GE(distance, o.others - 1e-9) << name << " state " << state << " " << item.spec.name;
      }
      for (std::size_t k = 0; k < NearestObstacle::kSlabs && o.valid(k); ++k) {
        EXPECT_TRUE(slab_found[k]) << name << " state " << state << " slab " << k;
        second += k == 1 ? 1 : 0;
      }
    }
  }
  EXPECT_GT(slabs, 20);  // links near an obstacle, below their caps, with a hull
  // Only the bookshelf has objects near enough to each other for two slabs.
  if (std::string(GetParam()) == "bookshelf_thin_panda") {
    EXPECT_GT(second, 0);
  }
}

TEST_P(HullClearance, AcceptedEdgesNearObstaclesAreFreeForFcl) {
  const auto* validator =
      dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
  ASSERT_NE(validator, nullptr);
  auto fcl_scratch = fcl_->makeBackendScratch();
  auto octree_scratch = octree_->makeBackendScratch();
  const RobotModel& robot = scene_.model->robot();
  ompl::base::ScopedState<> s1(si_), s2(si_), toward(si_);
  const double reach = 0.15 * si_->getMaximumExtent();
  int accepted = 0;
  for (int k = 0; k < 20; ++k) {
    configurationToState(robot, freeNearObstacle(*fcl_scratch, *octree_scratch),
                         Eigen::Isometry3d::Identity(), s1.get());
    configurationToState(robot, uniformQ(), Eigen::Isometry3d::Identity(), toward.get());
    const double d = si_->distance(s1.get(), toward.get());
    const double step = reach * std::uniform_real_distribution<double>(0.2, 1.0)(rng_);
    si_->getStateSpace()->interpolate(s1.get(), toward.get(), d > step ? step / d : 1.0, s2.get());
    if (!si_->isValid(s2.get()) || !validator->checkMotion(s1.get(), s2.get())) continue;
    ++accepted;
    EXPECT_EQ(test::fclCollisionsOnEdge(*fcl_, si_, s1.get(), s2.get(), 500), 0u) << "edge " << k;
  }
  EXPECT_GT(accepted, 3);
}

INSTANTIATE_TEST_SUITE_P(Mbm, HullClearance,
                         ::testing::Values("table_pick_panda", "box_panda",
                                           "bookshelf_thin_panda"));

}  // namespace
}  // namespace octomotion
