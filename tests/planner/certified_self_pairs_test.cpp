// The certified motion validator's self pairs (ompl/certified_motion_validator.h) and what it
// reads of them in robot/motion_bound.h: in the frame of a checked pair's common ancestor, the
// two links' points travel no farther together than the pair's bound (FK on random motions:
// octo7, and the Panda whose fingers move apart through a mimic joint); the pair distance bound
// never exceeds exact FCL's distance between the two links; and on the Panda with every obstacle
// out of reach, edges whose midpoint self-collides are rejected while the edges it accepts are free
// for exact FCL at 400 states each.
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
#include "octomotion/octree/shapes.h"
#include "octomotion/planner/ompl/certified_motion_validator.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/robot/motion_bound.h"
#include "path_fcl.h"

namespace octomotion {
namespace {

using test::linkPoints;

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kPanda = kSource + "/../shared/data/panda";

RobotModel octo7() {
  RobotModelOptions options;
  options.package_paths = {kSource};
  RobotModel robot = RobotModel::fromUrdfFile(kSource + "/robots/octo7/octo7.urdf", options);
  robot.loadSrdfFile(kSource + "/robots/octo7/octo7.srdf");
  return robot;
}

RobotModel panda() {
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  return robot;
}

std::vector<double> uniformQ(const RobotModel& robot, std::mt19937_64& rng) {
  std::vector<double> q;
  for (const Variable& v : robot.variables()) {
    q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
  }
  return q;
}

// The lowest link whose subtree holds both links: the joints above it move both rigidly.
int commonAncestor(const RobotModel& robot, int a, int b) {
  std::vector<int> above_a;
  for (int l = a; l >= 0;) {
    above_a.push_back(l);
    const int j = robot.link(l).parent_joint;
    l = j < 0 ? -1 : robot.joint(j).parent_link;
  }
  for (int l = b; l >= 0;) {
    if (std::find(above_a.begin(), above_a.end(), l) != above_a.end()) return l;
    const int j = robot.link(l).parent_joint;
    l = j < 0 ? -1 : robot.joint(j).parent_link;
  }
  return -1;
}

// For random straight-line motions in q, in the frame of the pair's common ancestor (where the
// distance between the two links is measured as in the world): the longest polyline of a
// sampled point of link a plus the longest of link b (each shorter than its path) stays within
// pairBound, which therefore bounds how much the pair's distance can change; over the first and
// last parts of the motion, within the posed bounds from that part's posed end (pairRate with
// the growth, pairSpeed with the speed growth).
void expectPairBoundHolds(const RobotModel& robot, int motions, std::uint64_t seed) {
  SCOPED_TRACE(robot.name());
  const LinkMotionBound bound(robot);
  ASSERT_EQ(bound.pairs(), robot.checkedPairs());
  ASSERT_FALSE(bound.pairs().empty());
  CollisionMeshes meshes(false, false);
  std::vector<std::vector<Eigen::Vector3d>> points;
  for (const Link& link : robot.links()) points.push_back(linkPoints(link, meshes, 200));
  std::mt19937_64 rng(seed);
  RobotData data = robot.makeData();
  const auto n = static_cast<std::size_t>(robot.variableCount());
  const std::size_t pairs = bound.pairs().size();
  std::vector<int> ancestor;
  for (const auto& [a, b] : bound.pairs()) ancestor.push_back(commonAncestor(robot, a, b));
  constexpr int kSteps = 64;
  int tight = 0, tight_posed = 0, tighter_posed = 0, tight_speed = 0, tighter_speed = 0;
  LinkMotionBound::EdgeTerms terms;
  std::vector<double> arms_start(bound.armCount() * LinkMotionBound::kArmValues),
      arms_end(bound.armCount() * LinkMotionBound::kArmValues);
  for (int m = 0; m < motions; ++m) {
    const std::vector<double> q1 = uniformQ(robot, rng), q2 = uniformQ(robot, rng);
    std::vector<double> dq(n), q(n);
    for (std::size_t v = 0; v < n; ++v) dq[v] = q2[v] - q1[v];
    bound.edgeTerms(dq.data(), terms);
    // Per pair and side (its first link, its second): each point's polyline to each step.
    std::vector<std::vector<std::vector<double>>> travelled(2 * pairs);
    std::vector<std::vector<Eigen::Vector3d>> previous(2 * pairs);
    for (int k = 0; k <= kSteps; ++k) {
      for (std::size_t v = 0; v < n; ++v) q[v] = q1[v] + dq[v] * k / kSteps;
      robot.forwardKinematics(q.data(), n, data);
      if (k == 0) bound.posedArms(data, arms_start.data());
      if (k == kSteps) bound.posedArms(data, arms_end.data());
      for (std::size_t p = 0; p < pairs; ++p) {
        ASSERT_GE(ancestor[p], 0);
        const Eigen::Isometry3d X_CW = data.linkPose(ancestor[p]).inverse();
        for (int side = 0; side < 2; ++side) {
          const int link = side == 0 ? bound.pairs()[p].first : bound.pairs()[p].second;
          const Eigen::Isometry3d X = X_CW * data.linkPose(link);
          const auto& pts = points[static_cast<std::size_t>(link)];
          auto& t = travelled[2 * p + static_cast<std::size_t>(side)];
          auto& prev = previous[2 * p + static_cast<std::size_t>(side)];
          t.resize(pts.size());
          prev.resize(pts.size());
          for (std::size_t i = 0; i < pts.size(); ++i) {
            const Eigen::Vector3d x = X * pts[i];
            t[i].push_back(k > 0 ? t[i].back() + (x - prev[i]).norm() : 0.0);
            prev[i] = x;
          }
        }
      }
    }
    for (std::size_t p = 0; p < pairs; ++p) {
      // The most a point of each side travels between steps k0 and k1, summed.
      auto most = [&](int k0, int k1) {
        double sum = 0;
        for (int side = 0; side < 2; ++side) {
          double longest = 0;
          for (const auto& t : travelled[2 * p + static_cast<std::size_t>(side)]) {
            longest = std::max(longest,
                               t[static_cast<std::size_t>(k1)] - t[static_cast<std::size_t>(k0)]);
          }
          sum += longest;
        }
        return sum;
      };
      const std::string names = robot.link(bound.pairs()[p].first).name + " / " +
                                robot.link(bound.pairs()[p].second).name;
      const double limit = bound.pairBound(p, dq.data());
      EXPECT_LE(most(0, kSteps), limit + 1e-9) << names << " motion " << m;
      tight += most(0, kSteps) > 0.25 * limit ? 1 : 0;
      for (int part : {kSteps / 32, kSteps / 8, kSteps / 2, kSteps}) {
        const double s = static_cast<double>(part) / kSteps;
        for (const bool from_start : {true, false}) {
          const double* arms = from_start ? arms_start.data() : arms_end.data();
          const double posed =
              bound.pairRate(p, terms, arms) * s + 0.5 * terms.pair_growth[p] * s * s;
          const double by_speed =
              bound.pairSpeed(p, terms, arms) * s + 0.5 * terms.pair_speed_growth[p] * s * s;
          // The validator reads the speed from both links' sums, made once per state.
          std::vector<double> sums(bound.armCount() * LinkMotionBound::kSumValues, 0.0);
          bound.speedSums(bound.pairs()[p].first, terms, arms, sums.data());
          bound.speedSums(bound.pairs()[p].second, terms, arms, sums.data());
          const double speed = bound.pairSpeed(p, terms, arms);
          EXPECT_NEAR(bound.pairSpeedFromSums(p, sums.data()), speed, 1e-12 * (1 + speed))
              << names << " motion " << m;
          const double travel = from_start ? most(0, part) : most(kSteps - part, kSteps);
          EXPECT_LE(travel, posed + 1e-9) << names << " motion " << m << " part " << s;
          EXPECT_LE(travel, by_speed + 1e-9)
              << names << " motion " << m << " part " << s << " (speed)";
          tight_posed += travel > 0.5 * posed ? 1 : 0;
          tighter_posed += posed < 0.75 * limit * s ? 1 : 0;
          tight_speed += travel > 0.5 * by_speed ? 1 : 0;
          tighter_speed += by_speed < 0.75 * posed ? 1 : 0;
        }
      }
    }
  }
  // A bound never approached would hide a wrong lever (or a joint wrongly left out); a posed
  // bound never tighter than the levers' would be of no use.
  EXPECT_GT(tight, 0);
  EXPECT_GT(tight_posed, 0);
  EXPECT_GT(tighter_posed, 0);
  EXPECT_GT(tight_speed, 0);
  EXPECT_GT(tighter_speed, 0);
}

TEST(PairMotionBound, Octo7sPairsTravelNoFartherThanTheirBound) {
  expectPairBoundHolds(octo7(), 20, 7);
}

TEST(PairMotionBound, ThePandasPairsTravelNoFartherThanTheirBound) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  const RobotModel robot = panda();
  ASSERT_EQ(robot.variableCount(), 8);  // the mimic finger follows joint 8
  expectPairBoundHolds(robot, 15, 9);
  // The fingers (a pair the SRDF leaves out): moved apart by one variable through two joints,
  // the master's and its mimic's.
  RobotModel fingers = robot;
  fingers.enableCollision("panda_leftfinger", "panda_rightfinger");
  expectPairBoundHolds(fingers, 15, 10);
}

// Per checked pair, the robot with that pair alone checked, so FCL's self distance is the
// pair's: pairDistance stays at or below it, and is positive often enough to matter.
void expectPairDistanceBelowFcl(RobotModel robot, int states, std::uint64_t seed) {
  const LinkMotionBound bound(robot);
  const std::vector<std::pair<int, int>> pairs = robot.checkedPairs();
  std::mt19937_64 rng(seed);
  std::vector<std::vector<double>> qs;
  for (int s = 0; s < states; ++s) qs.push_back(uniformQ(robot, rng));
  RobotData data = robot.makeData();
  const EnvironmentGeometry nothing = EnvironmentGeometry::load({});
  int positive = 0, compared = 0;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    RobotModel alone = robot;
    for (const auto& [a, b] : pairs) {
      if (std::make_pair(a, b) != pairs[p]) alone.disableCollision(a, b);
    }
    ASSERT_EQ(alone.checkedPairs().size(), 1u);
    const FclCollisionModel fcl(alone, nothing);
    auto scratch = fcl.makeScratch();
    for (const std::vector<double>& q : qs) {
      robot.forwardKinematics(q.data(), q.size(), data);
      fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch);
      const double exact = fcl.selfDistance(*scratch);
      const double lower = bound.pairDistance(p, data, 1e9);
      EXPECT_LE(lower, exact + 1e-9)
          << robot.link(pairs[p].first).name << " / " << robot.link(pairs[p].second).name;
      EXPECT_GE(lower, 0.0);
      // The cap: never above it, and the bound itself when below.
      EXPECT_LE(bound.pairDistance(p, data, 0.5 * lower), 0.5 * lower + 1e-12);
      positive += lower > 0 ? 1 : 0;
      ++compared;
    }
  }
  EXPECT_GT(positive, compared / 4);
}

TEST(PairDistanceBound, NeverExceedsFclsDistanceOnOcto7) {
  expectPairDistanceBelowFcl(octo7(), 150, 13);
}

TEST(PairDistanceBound, NeverExceedsFclsDistanceOnThePanda) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  expectPairDistanceBelowFcl(panda(), 150, 17);
}

// Per link, the clearances the certified validator reads (CollisionBackend::motionClearances):
// FCL's are exact (their least is FCL's distance of the whole robot) and the octree's, with and
// without a cap, never exceed them, and a cap changes no value below it (bookshelf, octo7 among
// boxes, random valid states): the voxels' bounds (refine none), and exact refine's, which are
// FCL's distances below the cap.
TEST(MotionClearances, PerLinkOctreeBoundsStayBelowFclsExactDistances) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides voxels, exact_refine;
  voxels.refine = RefineMode::kNone;
  exact_refine.refine = RefineMode::kExact;
  PlanningScene scene = loadPlanningScene(kSource + "/robots/scenes/bookshelf.yaml", voxels);
  PlanningScene refined =
      loadPlanningScene(kSource + "/robots/scenes/bookshelf.yaml", exact_refine);
  const std::shared_ptr<const CollisionBackend> octree = checkerBackend(scene);
  const std::shared_ptr<const CollisionBackend> refine = checkerBackend(refined);
  EXPECT_FALSE(octree->exactAnswers());
  EXPECT_TRUE(refine->exactAnswers());
  auto refine_scratch = refine->makeBackendScratch();
  std::vector<double> refined_capped(static_cast<std::size_t>(scene.model->robot().linkCount()));
  const FclCollisionModel& fcl = *scene.fclModel();
  const RobotModel& robot = scene.model->robot();
  auto octree_scratch = octree->makeBackendScratch();
  auto fcl_scratch = fcl.makeBackendScratch();
  const auto links = static_cast<std::size_t>(robot.linkCount());
  const std::vector<double> no_cap(links, std::numeric_limits<double>::infinity());
  const std::vector<double> cap(links, 0.05);
  std::vector<double> exact(links), bound(links), capped(links);
  std::mt19937_64 rng(37);
  int states = 0, positive = 0;
  while (states < 200) {
    const std::vector<double> q = uniformQ(robot, rng);
    const Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (fcl.inCollision(q.data(), q.size(), X, *fcl_scratch)) continue;
    if (octree->inCollision(q.data(), q.size(), X, *octree_scratch)) continue;
    ++states;
    fcl.motionClearances(*fcl_scratch, no_cap.data(), exact.data(), nullptr);
    octree->motionClearances(*octree_scratch, no_cap.data(), bound.data(), nullptr);
    octree->motionClearances(*octree_scratch, cap.data(), capped.data(), nullptr);
    ASSERT_FALSE(refine->inCollision(q.data(), q.size(), X, *refine_scratch));
    refine->motionClearances(*refine_scratch, cap.data(), refined_capped.data(), nullptr);
    EXPECT_NEAR(*std::min_element(exact.begin(), exact.end()), fcl.clearance(*fcl_scratch), 1e-9);
    for (std::size_t l = 0; l < links; ++l) {
      if (!robot.link(static_cast<int>(l)).hasCollision()) continue;
      EXPECT_LE(bound[l], exact[l] + 1e-9) << robot.link(static_cast<int>(l)).name;
      EXPECT_LE(capped[l], exact[l] + 1e-9) << robot.link(static_cast<int>(l)).name;
      // Exact refine: FCL's distance where below the cap (its own GJK tolerance aside).
      EXPECT_LE(refined_capped[l], exact[l] + 1e-5) << robot.link(static_cast<int>(l)).name;
      if (exact[l] < 0.02 - 1e-5) {  // near contact (two voxels): FCL's own distance
        EXPECT_NEAR(refined_capped[l], exact[l], 1e-5) << robot.link(static_cast<int>(l)).name;
      }
      // A cap only saves work above it: below, the value is the uncapped one.
      EXPECT_EQ(std::min(capped[l], cap[l]), std::min(bound[l], cap[l]))
          << robot.link(static_cast<int>(l)).name;
      positive += bound[l] > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(positive, states);  // bounds that say something, on several links per state
}

// The Panda with one small box far out of its reach: every collision is a self-collision.
class PandaAlone : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const std::string path =
        (std::filesystem::temp_directory_path() / "octomotion_certified_self_pairs.yaml").string();
    std::ofstream(path) << "robot: {urdf: " << kPanda << "/panda.urdf, srdf: " << kPanda
                        << "/panda.srdf}\n"
                        << "environment:\n"
                        << "  - {name: far, box: {size: [0.1, 0.1, 0.1]}, pose: {xyz: [5, 5, 5]}}\n"
                        << "octree: {resolution: 0.01}\n";
    scene_ = loadPlanningScene(path);
    si_ = scene_.setup->getSpaceInformation();
    scene_.setup->setup();
    validator_ = dynamic_cast<const CertifiedMotionValidator*>(si_->getMotionValidator().get());
    ASSERT_NE(validator_, nullptr);
  }
  void sampleValid(ompl::base::State* s) {
    do {
      configurationToState(scene_.model->robot(), uniformQ(scene_.model->robot(), rng_),
                           Eigen::Isometry3d::Identity(), s);
    } while (!si_->isValid(s));
  }
  std::size_t fclCollisions(const ompl::base::State* s1, const ompl::base::State* s2, int states) {
    return test::fclCollisionsOnEdge(*scene_.fclModel(), si_, s1, s2, states);
  }

  std::mt19937_64 rng_{31};
  PlanningScene scene_;
  ompl::base::SpaceInformationPtr si_;
  const CertifiedMotionValidator* validator_ = nullptr;
};

TEST_F(PandaAlone, RejectsEveryEdgeWhoseMidpointSelfCollides) {
  ompl::base::ScopedState<> s1(si_), s2(si_), mid(si_), last(si_);
  int tested = 0;
  for (int attempt = 0; attempt < 4000 && tested < 25; ++attempt) {
    sampleValid(s1.get());
    sampleValid(s2.get());
    si_->getStateSpace()->interpolate(s1.get(), s2.get(), 0.5, mid.get());
    if (si_->isValid(mid.get())) continue;
    ++tested;
    EXPECT_FALSE(validator_->checkMotion(s1.get(), s2.get()));
    std::pair<ompl::base::State*, double> last_valid(last.get(), -1.0);
    EXPECT_FALSE(validator_->checkMotion(s1.get(), s2.get(), last_valid));
    EXPECT_GE(last_valid.second, 0.0);
    EXPECT_LT(last_valid.second, 0.5);
    EXPECT_TRUE(validator_->checkMotion(s1.get(), last.get()));
  }
  EXPECT_EQ(tested, 25);
}

TEST_F(PandaAlone, EdgesItAcceptsAreFreeForFclAtADenseSpacing) {
  const double reach = 0.2 * si_->getMaximumExtent();
  ompl::base::ScopedState<> s1(si_), s2(si_), toward(si_);
  int accepted = 0;
  for (int k = 0; k < 60; ++k) {
    sampleValid(s1.get());
    do {
      sampleValid(toward.get());
      const double d = si_->distance(s1.get(), toward.get());
      si_->getStateSpace()->interpolate(s1.get(), toward.get(), d > reach ? reach / d : 1.0,
                                        s2.get());
    } while (!si_->isValid(s2.get()));
    if (!validator_->checkMotion(s1.get(), s2.get())) continue;
    ++accepted;
    EXPECT_EQ(fclCollisions(s1.get(), s2.get(), 400), 0u) << "edge " << k;
  }
  EXPECT_GT(accepted, 10);
}

}  // namespace
}  // namespace octomotion
