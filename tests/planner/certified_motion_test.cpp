// The certified motion validator (ompl/certified_motion_validator.h) and the links' motion bound
// (robot/motion_bound.h): no point of a link travels farther than its bound along sampled
// motions (FK, arm with mimic joints and a free-flying body), nor advances along a direction
// farther than its approach rate allows; edges whose midpoint collides are
// rejected (both overloads, the last valid state proven before the collision); edges it accepts
// are free for exact FCL at a dense spacing; answers agree across threads; the scene key picks it
// by default and the discrete validator on request.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "link_points.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/robot/motion_bound.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

using test::linkPoints;

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kPanda = kSource + "/../shared/data/panda";

std::string scenePath(const std::string& name) {
  return kSource + "/robots/scenes/" + name;
}

// Along sampled motions (positions[l][i][k]: point i of link l at step k of kSteps), no point
// advances along a direction u farther than the approach rate from the part's posed end
// (LinkMotionBound::linkApproach, forwards from the start, backwards from the end) with the
// speed growth: u . (p(t) - p(end)) <= rate * s + speed_growth * s^2 / 2 over a part of length s.
// Counts in `tight` the parts where some point advances more than half of it.
void checkApproach(const RobotModel& robot, const LinkMotionBound& bound,
                   const LinkMotionBound::EdgeTerms& terms,
                   const std::vector<std::vector<Eigen::Vector3d>>& points,
                   const std::vector<std::vector<std::vector<Eigen::Vector3d>>>& positions,
                   const std::vector<double>& arms_start, const std::vector<double>& arms_end,
                   std::mt19937_64& rng, int& tight) {
  std::normal_distribution<double> normal;
  std::vector<double> sums(bound.armCount() * LinkMotionBound::kSumValues, 0.0);
  for (std::size_t l = 0; l < points.size(); ++l) {
    if (points[l].empty()) continue;
    const int link = static_cast<int>(l);
    const std::vector<std::vector<Eigen::Vector3d>>& at = positions[l];
    const int steps = static_cast<int>(at[0].size()) - 1;
    std::vector<Eigen::Vector3d> directions;
    for (int d = 0; d < 4; ++d) {
      directions.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
    }
    Eigen::Vector3d moved = at[0][steps] - at[0][0];
    for (const std::vector<Eigen::Vector3d>& p : at) {
      if ((p[steps] - p[0]).norm() > moved.norm()) moved = p[steps] - p[0];
    }
    if (moved.norm() > 0) directions.push_back(moved.normalized());
    const double growth = terms.link_speed_growth[l];
    for (const bool from_start : {true, false}) {
      bound.speedSums(link, terms, from_start ? arms_start.data() : arms_end.data(), sums.data());
      for (const Eigen::Vector3d& u : directions) {
        double toward = 0.0, away = 0.0;
        bound.linkApproach(link, sums.data(), u, toward, away);
        const double rate = from_start ? toward : away;
        for (int part : {steps / 32, steps / 8, steps / 2, steps}) {
          const double s = static_cast<double>(part) / steps;
          const double limit = rate * s + 0.5 * growth * s * s;
          double advance = -std::numeric_limits<double>::infinity();
          for (const std::vector<Eigen::Vector3d>& p : at) {
            const int end = from_start ? 0 : steps;
            const int k = from_start ? part : steps - part;
            advance = std::max(advance, u.dot(p[k] - p[end]));
          }
          EXPECT_LE(advance, limit + 1e-9)
              << robot.link(link).name << " part " << s << " from "
              << (from_start ? "start" : "end") << " along " << u.transpose();
          tight += advance > 0 && advance > 0.5 * limit ? 1 : 0;
        }
      }
    }
  }
}

// For random straight-line motions in q, the polyline through FK samples of every sampled point
// (shorter than its path) stays within LinkMotionBound::linkBound; over the first and last
// parts of the motion, within the posed bounds from that part's posed end (linkRate with the
// growth, linkSpeed with the speed growth).
void expectArmBoundHolds(const RobotModel& robot, int motions, std::uint64_t seed) {
  const LinkMotionBound bound(robot);
  CollisionMeshes meshes(false, false);
  std::vector<std::vector<Eigen::Vector3d>> points;
  for (const Link& link : robot.links()) points.push_back(linkPoints(link, meshes, 300));
  std::mt19937_64 rng(seed);
  RobotData data = robot.makeData();
  const auto n = static_cast<std::size_t>(robot.variableCount());
  constexpr int kSteps = 64;
  int tight_links = 0, tight_posed = 0, tighter_posed = 0, tight_speed = 0, tighter_speed = 0;
  int approach_tight = 0;
  LinkMotionBound::EdgeTerms terms;
  std::vector<double> arms_start(bound.armCount() * LinkMotionBound::kArmValues),
      arms_end(bound.armCount() * LinkMotionBound::kArmValues);
  for (int m = 0; m < motions; ++m) {
    std::vector<double> q1(n), q2(n), dq(n), q(n);
    for (std::size_t v = 0; v < n; ++v) {
      const Variable& var = robot.variables()[v];
      q1[v] = std::uniform_real_distribution<double>(var.lower, var.upper)(rng);
      q2[v] = std::uniform_real_distribution<double>(var.lower, var.upper)(rng);
      dq[v] = q2[v] - q1[v];
    }
    bound.edgeTerms(dq.data(), terms);
    // Per link and point, its polyline's length from the start to each step.
    std::vector<std::vector<Eigen::Vector3d>> previous(points.size());
    std::vector<std::vector<std::vector<double>>> travelled(points.size());
    // Per link and point, its position at each step.
    std::vector<std::vector<std::vector<Eigen::Vector3d>>> positions(points.size());
    for (int k = 0; k <= kSteps; ++k) {
      for (std::size_t v = 0; v < n; ++v) q[v] = q1[v] + dq[v] * k / kSteps;
      robot.forwardKinematics(q.data(), n, data);
      if (k == 0) bound.posedArms(data, arms_start.data());
      if (k == kSteps) bound.posedArms(data, arms_end.data());
      for (std::size_t l = 0; l < points.size(); ++l) {
        const Eigen::Isometry3d& X_WL = data.linkPose(static_cast<int>(l));
        travelled[l].resize(points[l].size());
        previous[l].resize(points[l].size());
        positions[l].resize(points[l].size());
        for (std::size_t i = 0; i < points[l].size(); ++i) {
          const Eigen::Vector3d p_W = X_WL * points[l][i];
          positions[l][i].push_back(p_W);
          travelled[l][i].push_back(k > 0 ? travelled[l][i].back() + (p_W - previous[l][i]).norm()
                                          : 0.0);
          previous[l][i] = p_W;
        }
      }
    }
    // Per link, directions to test the approach rates along (LinkMotionBound::linkApproach):
    // random ones, and the one along the motion's largest displacement, which a link sliding
    // towards an obstacle approaches it by.
    checkApproach(robot, bound, terms, points, positions, arms_start, arms_end, rng,
                  approach_tight);
    for (std::size_t l = 0; l < points.size(); ++l) {
      if (points[l].empty()) continue;
      const int link = static_cast<int>(l);
      // The most any point travels between steps k0 and k1.
      auto most = [&](int k0, int k1) {
        double longest = 0.0;
        for (const std::vector<double>& t : travelled[l])
          longest = std::max(longest, t[k1] - t[k0]);
        return longest;
      };
      const double limit = bound.linkBound(link, dq.data());
      EXPECT_LE(most(0, kSteps), limit + 1e-9) << robot.link(link).name << " motion " << m;
      tight_links += most(0, kSteps) > 0.25 * limit ? 1 : 0;
      const double growth = terms.link_growth[l];
      const double speed_growth = terms.link_speed_growth[l];
      for (int part : {kSteps / 32, kSteps / 8, kSteps / 2, kSteps}) {
        const double s = static_cast<double>(part) / kSteps;
        for (const bool from_start : {true, false}) {
          const double* arms = from_start ? arms_start.data() : arms_end.data();
          const double posed = bound.linkRate(link, terms, arms) * s + 0.5 * growth * s * s;
          const double by_speed =
              bound.linkSpeed(link, terms, arms) * s + 0.5 * speed_growth * s * s;
          // The validator reads the speed from the sums made once per state.
          std::vector<double> sums(bound.armCount() * LinkMotionBound::kSumValues, 0.0);
          bound.speedSums(link, terms, arms, sums.data());
          const double speed = bound.linkSpeed(link, terms, arms);
          EXPECT_NEAR(bound.linkSpeedFromSums(link, sums.data()), speed, 1e-12 * (1 + speed))
              << robot.link(link).name << " motion " << m;
          const double travel = from_start ? most(0, part) : most(kSteps - part, kSteps);
          EXPECT_LE(travel, posed + 1e-9) << robot.link(link).name << " motion " << m << " part "
                                          << s << " from " << (from_start ? "start" : "end");
          EXPECT_LE(travel, by_speed + 1e-9)
              << robot.link(link).name << " motion " << m << " part " << s << " from "
              << (from_start ? "start" : "end") << " (speed)";
          tight_posed += travel > 0.5 * posed ? 1 : 0;
          tighter_posed += posed < 0.75 * limit * s ? 1 : 0;
          tight_speed += travel > 0.5 * by_speed ? 1 : 0;
          tighter_speed += by_speed < 0.75 * posed ? 1 : 0;
        }
      }
    }
  }
  // A bound that is never approached would hide a wrong lever (e.g. one that ignores a joint);
  // a posed bound never tighter than the lever's would be of no use.
  EXPECT_GT(tight_links, 0);
  EXPECT_GT(tight_posed, 0);
  EXPECT_GT(tighter_posed, 0);
  EXPECT_GT(tight_speed, 0);
  EXPECT_GT(tighter_speed, 0);
  EXPECT_GT(approach_tight, 0);
}

TEST(LinkMotionBound, NoPointOfOcto7TravelsFartherThanItsBound) {
  RobotModelOptions options;
  options.package_paths = {kSource};
  const RobotModel robot = RobotModel::fromUrdfFile(kSource + "/robots/octo7/octo7.urdf", options);
  expectArmBoundHolds(robot, 40, 3);
}

// A planar arm whose gripper's right finger mimics the left one with multiplier -1 (a prismatic
// joint: the speed's sign matters).
TEST(LinkMotionBound, NoPointOfTheTestArmTravelsFartherThanItsBound) {
  const RobotModel robot =
      RobotModel::fromUrdfFile(std::string(OCTOMOTION_TEST_DATA_DIR) + "/urdf/arm.urdf");
  expectArmBoundHolds(robot, 40, 13);
}

TEST(LinkMotionBound, NoPointOfThePandaTravelsFartherThanItsBound) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  const RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  ASSERT_EQ(robot.variableCount(), 8);  // the mimic finger follows joint 8
  expectArmBoundHolds(robot, 25, 5);
}

TEST(LinkMotionBound, NoPointOfARigidBodyTravelsFartherThanItsBound) {
  const RobotModel robot = RobotModel::fromMesh(kSource + "/robots/meshes/rigid/l_piece.stl");
  const LinkMotionBound bound(robot);
  CollisionMeshes meshes(false, false);
  const std::vector<Eigen::Vector3d> points = linkPoints(robot.link(0), meshes, 2000);
  ASSERT_FALSE(points.empty());
  const Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2));
  auto space = makeStateSpace(robot, &box);
  space->setup();
  std::mt19937_64 rng(11);
  auto sample = [&](ompl::base::State* state) {
    Eigen::Vector4d v;
    for (int i = 0; i < 4; ++i) v[i] = std::normal_distribution<double>()(rng);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized().toRotationMatrix();
    for (int a = 0; a < 3; ++a)
      X.translation()[a] = std::uniform_real_distribution<double>(-2, 2)(rng);
    configurationToState(robot, {}, X, state);
  };
  ompl::base::ScopedState<> s1(space), s2(space), s(space);
  std::vector<double> q;
  for (int m = 0; m < 40; ++m) {
    sample(s1.get());
    sample(s2.get());
    Eigen::Isometry3d X1, X2, X, previous;
    ASSERT_TRUE(stateToConfiguration(robot, s1.get(), q, X1));
    ASSERT_TRUE(stateToConfiguration(robot, s2.get(), q, X2));
    const double limit = bound.freeFlyingBound(0, LinkMotionBound::RootMotion(X1, X2));
    std::vector<double> travelled(points.size(), 0.0);
    for (int k = 0; k <= 64; ++k) {
      space->interpolate(s1.get(), s2.get(), k / 64.0, s.get());
      ASSERT_TRUE(stateToConfiguration(robot, s.get(), q, X));
      for (std::size_t i = 0; k > 0 && i < points.size(); ++i) {
        travelled[i] += (X * points[i] - previous * points[i]).norm();
      }
      previous = X;
    }
    EXPECT_LE(*std::max_element(travelled.begin(), travelled.end()), limit + 1e-9) << m;
  }
}

// Random states of the scene's space (one seeded stream), kept when the checker finds them valid.
class SceneEdges {
 public:
  SceneEdges(const std::string& scene, std::uint64_t seed) : rng_(seed) {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    scene_ = loadPlanningScene(scenePath(scene));
    si_ = scene_.setup->getSpaceInformation();
    scene_.setup->setup();
  }
  const ompl::base::SpaceInformationPtr& si() const { return si_; }
  const CertifiedMotionValidator& validator() const {
    const auto* v = dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
    if (!v) throw Error("not the certified validator");
    return *v;
  }
  void sampleValid(ompl::base::State* s) {
    do sampleUniform(s);
    while (!si_->isValid(s));
  }
  // A valid state at most `distance` (the space's metric) from `near`, toward a uniform one.
  void sampleValidNear(const ompl::base::State* near, double distance, ompl::base::State* s) {
    ompl::base::ScopedState<> toward(si_);
    do {
      sampleUniform(toward.get());
      const double d = si_->distance(near, toward.get());
      si_->getStateSpace()->interpolate(near, toward.get(), d > distance ? distance / d : 1.0, s);
    } while (!si_->isValid(s));
  }
  // Exact FCL at `states` evenly spaced states of the edge (ends included): how many collide.
  std::size_t fclCollisions(const ompl::base::State* s1, const ompl::base::State* s2, int states) {
    return test::fclCollisionsOnEdge(*scene_.fclModel(), si_, s1, s2, states);
  }

 private:
  void sampleUniform(ompl::base::State* s) {
    const RobotModel& robot = scene_.model->robot();
    auto uniform = [this](double lo, double hi) {
      return std::uniform_real_distribution<double>(lo, hi)(rng_);
    };
    std::vector<double> q;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (robot.isFreeFlying()) {
      const Eigen::AlignedBox3d& box = *scene_.spec.problem.bounds;
      Eigen::Vector4d v;
      for (int i = 0; i < 4; ++i) v[i] = std::normal_distribution<double>()(rng_);
      X.linear() = Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized().toRotationMatrix();
      for (int a = 0; a < 3; ++a) X.translation()[a] = uniform(box.min()[a], box.max()[a]);
    } else {
      for (const Variable& v : robot.variables()) q.push_back(uniform(v.lower, v.upper));
    }
    configurationToState(robot, q, X, s);
  }

  std::mt19937_64 rng_;
  PlanningScene scene_;
  ompl::base::SpaceInformationPtr si_;
};

class CertifiedMotion : public ::testing::TestWithParam<const char*> {};

TEST_P(CertifiedMotion, RejectsEveryEdgeWhoseMidpointCollides) {
  SceneEdges edges(GetParam(), 17);
  const ompl::base::SpaceInformationPtr& si = edges.si();
  const CertifiedMotionValidator& validator = edges.validator();
  ompl::base::ScopedState<> s1(si), s2(si), mid(si), last(si);
  int tested = 0;
  for (int attempt = 0; attempt < 2000 && tested < 30; ++attempt) {
    edges.sampleValid(s1.get());
    edges.sampleValid(s2.get());
    si->getStateSpace()->interpolate(s1.get(), s2.get(), 0.5, mid.get());
    if (si->isValid(mid.get())) continue;
    ++tested;
    EXPECT_FALSE(validator.checkMotion(s1.get(), s2.get()));
    std::pair<ompl::base::State*, double> last_valid(last.get(), -1.0);
    EXPECT_FALSE(validator.checkMotion(s1.get(), s2.get(), last_valid));
    EXPECT_GE(last_valid.second, 0.0);
    EXPECT_LT(last_valid.second, 0.5);
    EXPECT_TRUE(si->isValid(last.get()));
    // The part before it is proven free: the validator accepts it.
    EXPECT_TRUE(validator.checkMotion(s1.get(), last.get()));
  }
  EXPECT_EQ(tested, 30);
}

TEST_P(CertifiedMotion, EdgesItAcceptsAreFreeForFclAtADenseSpacing) {
  SceneEdges edges(GetParam(), 23);
  const ompl::base::SpaceInformationPtr& si = edges.si();
  const CertifiedMotionValidator& validator = edges.validator();
  const double reach = 0.2 * si->getMaximumExtent();
  ompl::base::ScopedState<> s1(si), s2(si);
  int accepted = 0, rejected = 0;
  for (int k = 0; k < 60; ++k) {
    edges.sampleValid(s1.get());
    edges.sampleValidNear(s1.get(), reach, s2.get());
    if (!validator.checkMotion(s1.get(), s2.get())) {
      ++rejected;
      continue;
    }
    ++accepted;
    EXPECT_EQ(edges.fclCollisions(s1.get(), s2.get(), 400), 0u) << "edge " << k;
  }
  EXPECT_GT(accepted, 0);
}

TEST_P(CertifiedMotion, GivesTheSameAnswersOnSeveralThreads) {
  SceneEdges edges(GetParam(), 29);
  const ompl::base::SpaceInformationPtr& si = edges.si();
  const CertifiedMotionValidator& validator = edges.validator();
  std::vector<std::unique_ptr<ompl::base::ScopedState<>>> from, to;
  for (int k = 0; k < 40; ++k) {
    from.push_back(std::make_unique<ompl::base::ScopedState<>>(si));
    to.push_back(std::make_unique<ompl::base::ScopedState<>>(si));
    edges.sampleValid(from.back()->get());
    edges.sampleValidNear(from.back()->get(), 0.2 * si->getMaximumExtent(), to.back()->get());
  }
  auto answers = [&] {
    std::vector<int> out;
    for (std::size_t k = 0; k < from.size(); ++k) {
      std::pair<ompl::base::State*, double> last(nullptr, 0.0);
      out.push_back(validator.checkMotion(from[k]->get(), to[k]->get()) ? 1 : 0);
      out.push_back(validator.checkMotion(from[k]->get(), to[k]->get(), last) ? 1 : 0);
    }
    return out;
  };
  const std::vector<int> expected = answers();
  EXPECT_GT(std::count(expected.begin(), expected.end(), 1), 0);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 0), 0);
  std::vector<std::vector<int>> got(4);
  std::vector<std::thread> threads;
  for (auto& g : got) threads.emplace_back([&g, &answers] { g = answers(); });
  for (auto& t : threads) t.join();
  for (const auto& g : got) EXPECT_EQ(g, expected);
}

// The shipped arm scene and a rigid body's (its step was 500 times finer than needed before).
INSTANTIATE_TEST_SUITE_P(Scenes, CertifiedMotion,
                         ::testing::Values("bookshelf.yaml", "narrow_passage.yaml"));

// A path planned with the certified validator, re-checked by exact FCL at 100 times its
// states' density.
void expectPlannedPathFree(PlanningScene& scene) {
  ASSERT_TRUE(dynamic_cast<const CertifiedMotionValidator*>(
      scene.setup->getSpaceInformation()->getMotionValidator().get()));
  const PlanResult result = plan(scene);
  ASSERT_TRUE(result.solved);
  std::size_t checked = 0;
  const std::size_t colliding =
      test::fclCollisionsOnPath(*scene.fclModel(), *result.path, 100, &checked);
  EXPECT_EQ(colliding, 0u) << "of " << checked << " states";
}

TEST(CertifiedMotionPlanning, ShippedArmAndRigidScenesPlanFreePaths) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  for (const char* name : {"bookshelf.yaml", "narrow_passage.yaml"}) {
    SCOPED_TRACE(name);
    SceneOverrides overrides;
    overrides.time = 60;  // a cap for sanitizer builds; RRTConnect stops when it solves
    overrides.seed = 3;
    PlanningScene scene = loadPlanningScene(scenePath(name), overrides);
    expectPlannedPathFree(scene);
  }
}

TEST(CertifiedMotionPlanning, MakeSimpleSetupUsesTheScenesSettingsAndTheCertifiedValidator) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const ompl::geometric::SimpleSetupPtr ss = makeSimpleSetup(scenePath("bookshelf.yaml"));
  ASSERT_TRUE(ss);
  const auto* validator = dynamic_cast<const CertifiedMotionValidator*>(
      ss->getSpaceInformation()->getMotionValidator().get());
  ASSERT_TRUE(validator);
  const SceneSpec spec = loadScene(scenePath("bookshelf.yaml"));
  ASSERT_TRUE(spec.octree.resolution);
  EXPECT_EQ(validator->resolution(), *spec.octree.resolution);
  EXPECT_TRUE(ss->getProblemDefinition()->getStartStateCount() == 1);
  EXPECT_TRUE(ss->getPlanner());
}

TEST(CertifiedMotionPlanning, TheDiscreteValidatorIsStillSelectable) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.motion_validator = MotionValidatorKind::kDiscrete;
  overrides.seed = 3;
  PlanningScene scene = loadPlanningScene(scenePath("bookshelf.yaml"), overrides);
  const auto& si = scene.setup->getSpaceInformation();
  EXPECT_TRUE(
      dynamic_cast<const ompl::base::DiscreteMotionValidator*>(si->getMotionValidator().get()));
  EXPECT_EQ(scene.spec.problem.motion_validator, MotionValidatorKind::kDiscrete);
  EXPECT_TRUE(plan(scene).solved);
}

TEST(CertifiedMotionPlanning, TheSceneKeyIsReadAndCheckedByName) {
  const std::string robot = "robot: {mesh: " + kSource + "/robots/meshes/rigid/l_piece.stl}\n";
  EXPECT_EQ(parseSceneYaml(robot + "problem: {motion_validator: discrete}\n", "s.yaml")
                .problem.motion_validator,
            MotionValidatorKind::kDiscrete);
  EXPECT_EQ(parseSceneYaml(robot, "s.yaml").problem.motion_validator,
            MotionValidatorKind::kCertified);
  try {
    parseSceneYaml(robot + "problem: {motion_validator: exact}\n", "s.yaml");
    FAIL() << "accepted an unknown motion validator";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("problem.motion_validator"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("certified or discrete"), std::string::npos);
  }
}

}  // namespace
}  // namespace octomotion
