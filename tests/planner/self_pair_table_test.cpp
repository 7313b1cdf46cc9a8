// JointSpaceTable and the self-pair tables built on it (docs/planner.md, "Self-pair tables").
// The generic table is checked against analytic regions (a disc, an interval, a ball) whose
// distance function is known: a certified cell must never contain a point of the other kind, and
// the uncertified band must be thin. The octo7 tables are checked against FCL on 10,000 uniform
// states: never a missed collision, and a table only ever removes octree false positives.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>

#include "joint_states.h"
#include "octomotion/error.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/model/joint_space_table.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/reference/fcl_collision_model.h"

namespace octomotion {
namespace {

// A certified cell agrees with the signed distance-like f at the point: free where f > 0,
// colliding where f < 0 (unknown cells claim nothing).
::testing::AssertionResult certifiedRight(JointSpaceTable::Cell c, double f) {
  if (c == JointSpaceTable::kFree && !(f > 0)) {
    return ::testing::AssertionFailure() << "certified free where f = " << f;
  }
  if (c == JointSpaceTable::kColliding && !(f < 0)) {
    return ::testing::AssertionFailure() << "certified colliding where f = " << f;
  }
  return ::testing::AssertionSuccess();
}

// A ball of radius r about the origin in k dimensions, classified the way the self-pair builder
// classifies a pair: d(centre) against the largest change of d within the cell (|grad d| = 1,
// so the sum of half-widths bounds it).
JointSpaceTable ballTable(int k, double r, int depth, std::size_t max_cells = 1u << 20) {
  std::vector<JointSpaceTable::Dim> dims;
  for (int d = 0; d < k; ++d) dims.push_back({d, -1.0, 1.0});
  JointSpaceTable::BuildLimits limits;
  limits.max_depth = depth;
  limits.max_cells = max_cells;
  return JointSpaceTable::build(
      dims,
      [k, r](const double* c, const double* h) -> JointSpaceTable::Verdict {
        double norm2 = 0, bound = 0;
        for (int d = 0; d < k; ++d) {
          norm2 += c[d] * c[d];
          bound += h[d];
        }
        const double distance = std::sqrt(norm2) - r;
        if (distance > bound) return {JointSpaceTable::kFree, false};
        if (-distance > bound) return {JointSpaceTable::kColliding, false};
        return {JointSpaceTable::kUnknown, true};
      },
      limits);
}

void expectBallCells(int k, int depth) {
  const double r = 0.5;
  const JointSpaceTable t = ballTable(k, r, depth);
  const double finest_bound = k * std::ldexp(1.0, -depth);  // k half-widths of 2^-depth * 2 / 2
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int unknown = 0;
  for (int i = 0; i < 20000; ++i) {
    double p[3] = {u(rng), u(rng), u(rng)};
    double norm2 = 0;
    for (int d = 0; d < k; ++d) norm2 += p[d] * p[d];
    const double distance = std::sqrt(norm2) - r;
    switch (t.lookup(p)) {
      case JointSpaceTable::kFree:
        ASSERT_GT(distance, 0) << "certified free inside the ball";
        break;
      case JointSpaceTable::kColliding:
        ASSERT_LT(distance, 0) << "certified colliding outside the ball";
        break;
      case JointSpaceTable::kUnknown:
        ++unknown;
        // Left undecided only in the band the finest cells cannot resolve (a cell's centre is
        // within its bound of the sphere, the point within another bound of the centre).
        ASSERT_LE(std::abs(distance), 2 * finest_bound + 1e-12);
        break;
    }
  }
  EXPECT_LT(unknown, 20000 / 10);
  const auto& f = t.volumeFractions();
  EXPECT_NEAR(f[0] + f[1] + f[2], 1.0, 1e-12);
}

TEST(JointSpaceTable, CertifiedCellsOfAnIntervalDiscAndBallAreRight) {
  expectBallCells(1, 12);
  expectBallCells(2, 9);
  expectBallCells(3, 6);
}

TEST(JointSpaceTable, ValuesOutsideTheRangeOrNaNAreUnknown) {
  const JointSpaceTable t = ballTable(2, 0.5, 6);
  const double inside_ball[2] = {0, 0};
  EXPECT_EQ(t.lookup(inside_ball), JointSpaceTable::kColliding);
  const double outside[2] = {1.5, 0};
  EXPECT_EQ(t.lookup(outside), JointSpaceTable::kUnknown);
  const double at_upper[2] = {1.0, 0};  // the range is half-open: [lower, upper)
  EXPECT_EQ(t.lookup(at_upper), JointSpaceTable::kUnknown);
  const double nan[2] = {std::nan(""), 0};
  EXPECT_EQ(t.lookup(nan), JointSpaceTable::kUnknown);
}

TEST(JointSpaceTable, ARunOutBudgetLeavesCellsUnknownNeverWrong) {
  const JointSpaceTable small = ballTable(2, 0.5, 9, 50);
  EXPECT_LE(small.classified(), 50u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 5000; ++i) {
    const double p[2] = {u(rng), u(rng)};
    const double distance = std::hypot(p[0], p[1]) - 0.5;
    const JointSpaceTable::Cell c = small.lookup(p);
    ASSERT_TRUE(certifiedRight(c, distance));
  }
  EXPECT_GT(small.volumeFractions()[JointSpaceTable::kUnknown],
            ballTable(2, 0.5, 9).volumeFractions()[JointSpaceTable::kUnknown]);
}

TEST(JointSpaceTable, RejectsBadDimensionsAndDepths) {
  const auto never = [](const double*, const double*) { return JointSpaceTable::Verdict{}; };
  EXPECT_THROW(JointSpaceTable::build({}, never, {}), InvalidArgument);
  EXPECT_THROW(JointSpaceTable::build({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}}, never, {}),
               InvalidArgument);
  EXPECT_THROW(JointSpaceTable::build({{0, 1, 1}}, never, {}), InvalidArgument);
  EXPECT_THROW(JointSpaceTable::build({{0, 0, INFINITY}}, never, {}), InvalidArgument);
  JointSpaceTable::BuildLimits deep;
  deep.max_depth = JointSpaceTable::kMaxDepth + 1;
  EXPECT_THROW(JointSpaceTable::build({{0, 0, 1}}, never, deep), InvalidArgument);
}

TEST(JointSpaceTable, PeriodicDimensionsReadEveryTurnAlike) {
  // f(x) = sin(x) - 0.5 over one turn, |f'| <= 1: colliding where f > 0.
  JointSpaceTable::BuildLimits limits;
  limits.max_depth = 12;
  const JointSpaceTable t = JointSpaceTable::build(
      {{0, -M_PI, M_PI, true}},
      [](const double* c, const double* h) -> JointSpaceTable::Verdict {
        const double f = std::sin(c[0]) - 0.5;
        if (f > h[0]) return {JointSpaceTable::kColliding, false};
        if (-f > h[0]) return {JointSpaceTable::kFree, false};
        return {JointSpaceTable::kUnknown, true};
      },
      limits);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3 * M_PI, 3 * M_PI);  // three turns
  int known = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x[1] = {u(rng)};
    const JointSpaceTable::Cell c = t.lookup(x);
    ASSERT_TRUE(certifiedRight(c, 0.5 - std::sin(x[0]))) << x[0];
    known += c != JointSpaceTable::kUnknown;
    const double turned[1] = {x[0] + 2 * M_PI};
    const JointSpaceTable::Cell same = t.lookup(turned);
    if (same != c) {  // only where rounding puts the two values in neighbouring cells
      ASSERT_NE(same, JointSpaceTable::kColliding + JointSpaceTable::kFree - c) << x[0];
    }
  }
  EXPECT_GT(known, 19000);  // values outside [-pi, pi) are in the table
  for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    const double x[1] = {bad};
    EXPECT_EQ(t.lookup(x), JointSpaceTable::kUnknown);
  }
}

// f(x, y) = |(x, y / 8)| - 0.5 on [-1, 1]^2: y moves f 8 times less than x, so in cubic cells
// each split along y halves a share of the bound 8 times smaller than x's; stretching y's side
// by 2^3 evens the shares.
JointSpaceTable flatBallTable(int stretch, std::size_t max_cells) {
  JointSpaceTable::BuildLimits limits;
  limits.max_depth = 12;
  limits.max_cells = max_cells;
  JointSpaceTable::Dim x{0, -1.0, 1.0}, y{1, -1.0, 1.0};
  y.stretch = stretch;
  return JointSpaceTable::build(
      {x, y},
      [](const double* c, const double* h) -> JointSpaceTable::Verdict {
        const double f = std::hypot(c[0], c[1] / 8) - 0.5;
        const double bound = h[0] + h[1] / 8;
        if (f > bound) return {JointSpaceTable::kFree, false};
        if (-f > bound) return {JointSpaceTable::kColliding, false};
        return {JointSpaceTable::kUnknown, true};
      },
      limits);
}

TEST(JointSpaceTable, AStretchedSideSpendsTheBudgetWhereItMatters) {
  const JointSpaceTable cubic = flatBallTable(0, 3000), stretched = flatBallTable(3, 3000);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    const double p[2] = {u(rng), u(rng)};
    const double f = std::hypot(p[0], p[1] / 8) - 0.5;
    for (const JointSpaceTable* t : {&cubic, &stretched}) {
      const JointSpaceTable::Cell c = t->lookup(p);
      ASSERT_TRUE(certifiedRight(c, f));
    }
    // Beyond the range, in the stretched side: unknown or a certificate that holds there too.
    const double beyond[2] = {p[0], 1.0 + std::abs(p[1]) * 7};
    const double fb = std::hypot(beyond[0], beyond[1] / 8) - 0.5;
    const JointSpaceTable::Cell cb = stretched.lookup(beyond);
    ASSERT_TRUE(certifiedRight(cb, fb));
  }
  for (const JointSpaceTable* t : {&cubic, &stretched}) {
    const auto& f = t->volumeFractions();
    EXPECT_NEAR(f[0] + f[1] + f[2], 1.0, 1e-12);  // of the range, not of the stretched side
  }
  EXPECT_LT(stretched.volumeFractions()[JointSpaceTable::kUnknown],
            cubic.volumeFractions()[JointSpaceTable::kUnknown] / 2);
  JointSpaceTable::Dim bad{0, 0, 1};
  bad.stretch = 12;  // >= depth
  JointSpaceTable::BuildLimits limits;
  limits.max_depth = 12;
  const auto never = [](const double*, const double*) { return JointSpaceTable::Verdict{}; };
  EXPECT_THROW(JointSpaceTable::build({bad}, never, limits), InvalidArgument);
  bad.stretch = -1;
  EXPECT_THROW(JointSpaceTable::build({bad}, never, limits), InvalidArgument);
}

TEST(JointSpaceTable, CellsSplitLaterWaitForTheBudgetTheOthersLeave) {
  // A disc whose inside is never certified (as a pair whose contacts are too shallow for the
  // sampled points): split at once, it takes the budget; split later, the outside (where the
  // false positives are) is refined further.
  auto disc = [](bool inside_later) {
    JointSpaceTable::BuildLimits limits;
    limits.max_depth = 10;
    limits.max_cells = 1500;
    return JointSpaceTable::build(
        {{0, -1.0, 1.0}, {1, -1.0, 1.0}},
        [inside_later](const double* c, const double* h) -> JointSpaceTable::Verdict {
          const double f = std::hypot(c[0], c[1]) - 0.5;
          if (f > h[0] + h[1]) return {JointSpaceTable::kFree, false};
          return {JointSpaceTable::kUnknown, true, inside_later && f <= 0};
        },
        limits);
  };
  const JointSpaceTable even = disc(false), outside_first = disc(true);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  int unknown_outside[2] = {0, 0};
  for (int i = 0; i < 20000; ++i) {
    const double p[2] = {u(rng), u(rng)};
    const double f = std::hypot(p[0], p[1]) - 0.5;
    int k = 0;
    for (const JointSpaceTable* t : {&even, &outside_first}) {
      const JointSpaceTable::Cell c = t->lookup(p);
      ASSERT_TRUE(certifiedRight(c, f));
      unknown_outside[k++] += f > 0 && c == JointSpaceTable::kUnknown;
    }
  }
  EXPECT_LT(unknown_outside[1], unknown_outside[0]);
}

// --- The octo7 tables against FCL ---

struct Octo7 {
  PlanningScene scene;
  std::unique_ptr<OctreeCollisionModel> plain, tabled;
};

std::unique_ptr<OctreeCollisionModel> octo7Model(const PlanningScene& scene, bool tables,
                                                 Rounding rounding = Rounding::kConservative) {
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.X_WB = scene.model->baseMount();
  o.self_pair_tables = tables;
  o.rounding = rounding;
  return std::make_unique<OctreeCollisionModel>(scene.model->robot(), *scene.environment, o);
}

const Octo7& bookshelf() {
  static const Octo7 models = [] {
    SceneOverrides overrides;
    overrides.resolution = 0.01;
    Octo7 m{loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml",
                              overrides),
            nullptr, nullptr};
    m.plain = octo7Model(m.scene, false);
    m.tabled = octo7Model(m.scene, true);
    return m;
  }();
  return models;
}

TEST(SelfPairTables, TheWristPairGetsATableAndTheReportSaysSo) {
  const CollisionModelReport& r = bookshelf().tabled->report();
  ASSERT_FALSE(r.self_pair_tables.empty());
  bool wrist = false;
  for (const SelfPairTableReport& t : r.self_pair_tables) {
    EXPECT_GE(t.variables, 1);
    EXPECT_LE(t.variables, 2);
    EXPECT_GT(t.nodes + t.classified, 0u);
    EXPECT_GE(t.free_fraction + t.colliding_fraction, 0.5) << t.link_a << "-" << t.link_b;
    wrist |= t.link_a == "link5" && t.link_b == "link7";
  }
  EXPECT_TRUE(wrist);
  EXPECT_NE(r.toString().find("self-pair tables"), std::string::npos);
  EXPECT_TRUE(bookshelf().plain->report().self_pair_tables.empty());
  // Centre rounding has no conservative trees to use as the inside/outside oracle.
  EXPECT_TRUE(
      octo7Model(bookshelf().scene, true, Rounding::kCenter)->report().self_pair_tables.empty());
}

TEST(SelfPairTables, NeverMissACollisionAndOnlyRemoveFalsePositives) {
  const Octo7& m = bookshelf();
  const RobotModel& robot = m.tabled->robot();
  const auto fcl = m.scene.fclModel();
  auto exact = fcl->makeScratch();
  const auto states = test::uniformJointStates(robot, 10000, 21);
  for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    CheckScratch plain = m.plain->makeScratch(), tabled = m.tabled->makeScratch();
    int fp_plain = 0, fp_tabled = 0;
    const std::size_t n = path == CheckerPath::kFused ? states.size() : 300;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& q = states[i];
      fcl->setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
      const bool truth = fcl->inCollision(*exact);
      const bool a = m.plain->inCollision(q.data(), q.size(), {}, path, plain);
      const bool b = m.tabled->inCollision(q.data(), q.size(), {}, path, tabled);
      ASSERT_TRUE(!truth || b) << "missed collision at state " << i;
      // A certified-colliding cell is a real overlap, which the conservative trees also find.
      ASSERT_TRUE(!b || a) << "the table added a contact at state " << i;
      fp_plain += a && !truth;
      fp_tabled += b && !truth;
    }
    EXPECT_LE(fp_tabled, fp_plain);
    if (path == CheckerPath::kFused) {
      EXPECT_LT(fp_tabled, fp_plain);  // the wrist's margins go
    }
  }
}

// octo6 (cluttered_table): every checked pair of up to three variables gets a table, coarse
// (3,000 classifications each) so the test stays quick; the certificates must hold anyway.
TEST(SelfPairTables, Octo6TablesDropTheFlangeTurnAndNeverMissACollision) {
  SceneOverrides overrides;
  overrides.resolution = 0.02;
  const PlanningScene scene = loadPlanningScene(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cluttered_table.yaml", overrides);
  CollisionModelOptions o;
  o.resolution = 0.02;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.X_WB = scene.model->baseMount();
  const OctreeCollisionModel plain(scene.model->robot(), *scene.environment, o);
  o.self_pair_tables = true;
  o.self_pair_table_max_variables = 3;
  o.self_pair_table_max_cells = 3000;
  const OctreeCollisionModel tabled(scene.model->robot(), *scene.environment, o);
  std::map<std::string, int> variables;
  for (const SelfPairTableReport& t : tabled.report().self_pair_tables) {
    variables[t.link_a + "-" + t.link_b] = t.variables;
  }
  // wrist_3 is a cylinder and a ball on its joint's axis: turning it moves none of its solid,
  // so its pairs' tables leave wrist_3_joint out. wrist_2 is a mesh: it keeps wrist_2_joint.
  EXPECT_EQ(variables["forearm_link-wrist_3_link"], 2);
  EXPECT_EQ(variables["forearm_link-wrist_2_link"], 2);
  EXPECT_EQ(variables["upper_arm_link-wrist_3_link"], 3);
  EXPECT_EQ(variables["upper_arm_link-wrist_2_link"], 3);
  EXPECT_EQ(variables.count("shoulder_link-wrist_3_link"), 0u);  // four variables
  const RobotModel& robot = scene.model->robot();
  const auto fcl = scene.fclModel();
  auto exact = fcl->makeScratch();
  CheckScratch plain_scratch = plain.makeScratch(), tabled_scratch = tabled.makeScratch();
  const auto states = test::uniformJointStates(robot, 10000, 23);
  int fp_plain = 0, fp_tabled = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const auto& q = states[i];
    fcl->setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
    const bool truth = fcl->inCollision(*exact);
    const bool a = plain.inCollision(q.data(), q.size(), {}, CheckerPath::kFused, plain_scratch);
    const bool b = tabled.inCollision(q.data(), q.size(), {}, CheckerPath::kFused, tabled_scratch);
    ASSERT_TRUE(!truth || b) << "missed collision at state " << i;
    ASSERT_TRUE(!b || a) << "the table added a contact at state " << i;
    fp_plain += a && !truth;
    fp_tabled += b && !truth;
  }
  EXPECT_LT(fp_tabled, fp_plain);
}

TEST(SelfPairTables, BadToleranceIsRejected) {
  CollisionModelOptions o;
  o.resolution = 0.02;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.X_WB = bookshelf().scene.model->baseMount();
  o.self_pair_tables = true;
  o.self_pair_table_tolerance = 0;
  EXPECT_THROW(
      OctreeCollisionModel(bookshelf().scene.model->robot(), *bookshelf().scene.environment, o),
      InvalidArgument);
}

}  // namespace
}  // namespace octomotion
