// Exact refine mode (CollisionModelOptions::refine = kExact, docs/validation.md "Exact refine
// mode"): the octree certifies freedom, FCL decides the rest, so the answer is FCL's. Each test
// asserts that the octree checker in this mode agrees with the exact FCL reference on every
// state, environment and self pairs apart (0 false negatives, 0 false positives): on every
// shipped scene, on the real Panda in MotionBenchMaker scenes, and on the randomised
// differential generator's scenes. Fixed seeds. Also: clearance() takes FCL's distance exactly
// when the octree's bound is below the margin, explain() agrees with the refined answer, and
// centre rounding is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "differential.h"
#include "mbm_problems.h"
#include "validation_common.h"

namespace octomotion::validation {
namespace {

constexpr std::uint64_t kSeed = 0x5eed0028;

struct Agreement {
  std::size_t states = 0, fcl_env = 0, fcl_self = 0;
  std::size_t wrong_env = 0, wrong_self = 0;
  // The whole check (both halves, FCL after the octree's pass over both) against FCL's.
  std::size_t wrong_whole = 0;
  // States where the octree answered a certain contact without FCL, and of those the ones FCL
  // calls free of the environment (must be none).
  std::size_t certain = 0, wrong_certain = 0;
  std::string first;
};

// Every sample checked by both; each half and the whole check must give FCL's answer, and a
// contact certain without FCL must be one of FCL's.
Agreement compare(const PlanningScene& scene, const std::vector<Sample>& samples,
                  CheckerPath path = CheckerPath::kFused) {
  EXPECT_EQ(scene.model->refine(), RefineMode::kExact);
  const std::shared_ptr<const FclCollisionModel> reference = exactReference(scene);
  const OctreeBackend checked(scene.model, path);
  const std::unique_ptr<BackendScratch> scratch = checked.makeBackendScratch();
  const std::unique_ptr<BackendScratch> exact = reference->makeBackendScratch();
  Agreement a;
  const CheckScratch& check = checked.scratchOf(*scratch).check;
  for (const Sample& s : samples) {
    const std::uint64_t certain_before = scene.model->refineCounts(check).certain_contacts;
    const auto [fe, fs, oe, os] = answersAt(s, *reference, *exact, checked, *scratch);
    const bool whole = checked.inCollision(s.q.data(), s.q.size(), s.X_WB, *scratch);
    const bool certain = scene.model->refineCounts(check).certain_contacts > certain_before;
    a.certain += certain;
    if (certain && !fe && a.wrong_certain++ == 0 && a.first.empty()) {
      a.first = "certain contact FCL does not find at " + describe(s);
    }
    if (whole != (fe || fs) && a.wrong_whole++ == 0 && a.first.empty()) {
      a.first = std::string("whole check ") + (whole ? "extra" : "missed") + " at " + describe(s);
    }
    ++a.states;
    a.fcl_env += fe;
    a.fcl_self += fs;
    if (fe != oe && a.wrong_env++ == 0 && a.first.empty()) {
      a.first =
          std::string("environment contact ") + (fe ? "missed" : "extra") + " at " + describe(s);
    }
    if (fs != os && a.wrong_self++ == 0 && a.first.empty()) {
      a.first = std::string("self contact ") + (fs ? "missed" : "extra") + " at " + describe(s);
    }
  }
  return a;
}

// Not vacuous: the states the same scene's unrefined octree checker rejects while FCL calls them
// free (the false positives refine removes).
std::size_t unrefinedFalsePositives(const PlanningScene& refined,
                                    const std::vector<Sample>& samples) {
  CollisionModelOptions options;
  options.resolution = refined.model->grid().voxelSize();
  options.X_WB = refined.model->baseMount();
  options.base_position_bounds = refined.spec.problem.bounds;
  options.keep_mesh_root_transform = refined.spec.robot.keep_mesh_root_transform;
  options.center_mesh_vertices = refined.spec.robot.center_mesh_vertices;
  options.refine = RefineMode::kNone;  // the default (auto) would refine too
  const auto plain = std::make_shared<const OctreeCollisionModel>(refined.model->robot(),
                                                                  *refined.environment, options);
  const OctreeBackend checked(plain, CheckerPath::kFused);
  const auto scratch = checked.makeBackendScratch();
  const std::shared_ptr<const FclCollisionModel> reference = exactReference(refined);
  const auto exact = reference->makeBackendScratch();
  std::size_t extra = 0;
  for (const Sample& s : samples) {
    extra += checked.inCollision(s.q.data(), s.q.size(), s.X_WB, *scratch) &&
             !reference->inCollision(s.q.data(), s.q.size(), s.X_WB, *exact);
  }
  return extra;
}

PlanningScene loadExact(const std::string& path, SceneOverrides overrides) {
  overrides.refine = RefineMode::kExact;
  overrides.require_free_start_goal = false;
  return loadPlanningScene(path, overrides, [](const std::string&) {});
}

// The shipped scenes as the other validation tests load them (arms at 2 cm), refined.
PlanningScene loadShippedExact(const std::string& path) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.rounding = Rounding::kConservative;
  overrides.checker = CheckerKind::kOctreeFused;
  const SceneSpec spec = loadScene(path);
  if (!spec.robot.urdf.empty()) {
    RobotModelOptions options;
    options.package_paths = spec.robot.package_paths;
    if (RobotModel::fromUrdfFile(spec.robot.urdf, options).variableCount() > 0) {
      overrides.resolution = 0.02;
    }
  }
  return loadExact(path, overrides);
}

class RefineExactScene : public ::testing::TestWithParam<std::string> {};

TEST_P(RefineExactScene, AgreesWithFclOnEveryState) {
  const PlanningScene scene = loadShippedExact(GetParam());
  const std::vector<Sample> samples = uniformSamples(scene, 1500, kSeed);
  const Agreement a = compare(scene, samples);
  const std::size_t unrefined = unrefinedFalsePositives(scene, samples);
  std::cout << "[ refine   ] " << sceneLabel(GetParam()) << ": FCL env " << a.fcl_env << " self "
            << a.fcl_self << " of " << a.states << "; disagreements env " << a.wrong_env << " self "
            << a.wrong_self << "; unrefined false positives " << unrefined << "\n";
  // Arms at 2 cm carry wide margins; a rigid body's faces may lie on voxel boundaries.
  if (!scene.model->robot().isFreeFlying()) {
    EXPECT_GT(unrefined, 0u) << "nothing for refine to remove";
  }
  EXPECT_EQ(a.wrong_env, 0u) << a.first;
  EXPECT_EQ(a.wrong_self, 0u) << a.first;
  EXPECT_EQ(a.wrong_whole, 0u) << a.first;
  EXPECT_EQ(a.wrong_certain, 0u) << a.first;
  EXPECT_GT(a.fcl_env, 0u) << "no sampled state touches the environment";
}

INSTANTIATE_TEST_SUITE_P(Scenes, RefineExactScene, ::testing::ValuesIn(sceneFiles()),
                         [](const auto& param_info) { return testName(param_info.param); });

TEST(RefineExact, MoveTreePathAgreesWithFclToo) {
  const std::string path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml";
  const PlanningScene scene = loadShippedExact(path);
  const Agreement a = compare(scene, uniformSamples(scene, 500, kSeed + 1), CheckerPath::kMoveTree);
  EXPECT_EQ(a.wrong_env + a.wrong_self + a.wrong_whole + a.wrong_certain, 0u) << a.first;
  EXPECT_GT(a.fcl_env, 0u);
}

// clearance(): below the margin it is FCL's distance, at or above it the octree's bound;
// explain() names a contact exactly when the refined check does.
// (bookshelf: cluttered_table's base stands within the margin of its table's box, so there every
// bound is below it.)
TEST(RefineExact, ClearanceUsesFclBelowTheMarginAndExplainAgrees) {
  const std::string path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml";
  const PlanningScene scene = loadShippedExact(path);
  const FclCollisionModel& fcl = *scene.fcl_model;
  const OctreeBackend checked(scene.model, CheckerPath::kFused);
  const auto scratch = checked.makeBackendScratch();
  const auto exact = fcl.makeScratch();
  constexpr double kMargin = 0.05;  // CollisionModelOptions::refine_clearance_margin's default
  std::size_t below = 0, above = 0;
  for (const Sample& s : uniformSamples(scene, 300, kSeed + 2)) {
    const bool hit = checked.inCollision(s.q.data(), s.q.size(), s.X_WB, *scratch);
    const CheckScratch& check = checked.scratchOf(*scratch).check;
    const double octree_bound = scene.model->clearanceLowerBoundPoints(check);
    const double refined = checked.clearance(*scratch);
    fcl.setConfiguration(s.q.data(), s.q.size(), s.X_WB, *exact);
    const double d = fcl.environmentDistance(*exact);
    if (octree_bound < kMargin) {
      ++below;
      EXPECT_NEAR(refined, d, 1e-6) << describe(s);
    } else {
      ++above;
      EXPECT_EQ(refined, octree_bound);
    }
    EXPECT_EQ(checked.explain(s.q.data(), s.q.size(), s.X_WB, *scratch).inCollision(), hit)
        << describe(s);
  }
  EXPECT_GT(below, 0u);
  EXPECT_GT(above, 0u);
}

// One model shared by four threads, each with its own scratch, gives the answers of one thread
// (the FCL geometry is constant; each thread poses it in its own scratch).
TEST(RefineExact, ThreadsShareTheModel) {
  const std::string path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cage.yaml";
  const PlanningScene scene = loadShippedExact(path);
  const OctreeBackend checked(scene.model, CheckerPath::kFused);
  const std::vector<Sample> samples = uniformSamples(scene, 800, kSeed + 4);
  std::vector<char> expected(samples.size());
  {
    const auto scratch = checked.makeBackendScratch();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      expected[i] =
          checked.inCollision(samples[i].q.data(), samples[i].q.size(), samples[i].X_WB, *scratch);
    }
  }
  std::vector<std::size_t> wrong(4, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < wrong.size(); ++t) {
    threads.emplace_back([&, t] {
      const auto scratch = checked.makeBackendScratch();
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const std::size_t i = (k + 200 * t) % samples.size();  // each thread its own order
        wrong[t] += checked.inCollision(samples[i].q.data(), samples[i].q.size(), samples[i].X_WB,
                                        *scratch) != (expected[i] != 0);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t w : wrong) EXPECT_EQ(w, 0u);
}

TEST(RefineExact, CentreRoundingIsRefused) {
  const std::string path = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cage.yaml";
  SceneOverrides overrides;
  overrides.rounding = Rounding::kCenter;
  EXPECT_THROW(loadExact(path, overrides), InvalidArgument);
  EXPECT_THROW(parseRefineMode("fcl"), InvalidArgument);
  EXPECT_EQ(parseRefineMode(refineModeName(RefineMode::kExact)), RefineMode::kExact);
}

TEST(RefineExact, SceneKeyIsReadAndCheckedByName) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string cage = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/cage.yaml";
  const std::string good = dir + "/refine_key_" + std::to_string(::getpid()) + ".yaml";
  const std::string bad = dir + "/refine_bad_" + std::to_string(::getpid()) + ".yaml";
  std::string text;
  {
    std::ifstream in(cage);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t at = text.find("octree:\n");
  ASSERT_NE(at, std::string::npos);
  std::ofstream(good) << text.substr(0, at + 8) << "  refine: exact\n" << text.substr(at + 8);
  std::ofstream(bad) << text.substr(0, at + 8) << "  refine: fcl\n" << text.substr(at + 8);
  EXPECT_EQ(loadScene(good).octree.refine, RefineMode::kExact);
  // The default: auto, resolved to exact under the scene's conservative rounding.
  EXPECT_EQ(loadScene(cage).octree.refine, RefineMode::kAuto);
  EXPECT_EQ(resolveRefineMode(RefineMode::kAuto, Rounding::kConservative, false),
            RefineMode::kExact);
  EXPECT_EQ(resolveRefineMode(RefineMode::kAuto, Rounding::kCenter, false), RefineMode::kNone);
  EXPECT_EQ(resolveRefineMode(RefineMode::kAuto, Rounding::kConservative, true), RefineMode::kNone);
  EXPECT_EQ(resolveRefineMode(RefineMode::kNone, Rounding::kConservative, false),
            RefineMode::kNone);
  EXPECT_EQ(resolveRefineMode(RefineMode::kExact, Rounding::kConservative, true),
            RefineMode::kExact);
  try {
    loadScene(bad);
    ADD_FAILURE() << "refine: fcl accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("octree.refine"), std::string::npos) << e.what();
  }
  std::filesystem::remove(good);
  std::filesystem::remove(bad);
}

// The real Panda (its URDF, SRDF and meshes) in the first scene of four MotionBenchMaker sets.
TEST(RefineExact, PandaInMotionBenchMakerScenesAgreesWithFcl) {
  const test::MbmProblems set;
  const std::string panda = test::MbmProblems::panda();
  if (set.problems().empty() || !std::filesystem::exists(panda + "/panda.urdf")) {
    GTEST_SKIP() << "no MotionBenchMaker problems or Panda under ../shared/data";
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  std::vector<test::MbmProblem> problems = set.firstOfEachSet();
  problems.resize(std::min<std::size_t>(problems.size(), 4));
  for (const test::MbmProblem& p : problems) {
    SCOPED_TRACE(p.request);
    const std::string scene_path = set.folder() + "/" + p.set + "_refine.yaml";
    test::MbmProblems::writeScene(scene_path, p);
    const PlanningScene scene = loadExact(scene_path, {});
    const std::vector<Sample> samples = uniformSamples(scene, 1000, kSeed + 3);
    const Agreement a = compare(scene, samples);
    const std::size_t unrefined = unrefinedFalsePositives(scene, samples);
    std::cout << "[ refine   ] " << p.set << ": FCL env " << a.fcl_env << " self " << a.fcl_self
              << " of " << a.states << "; disagreements env " << a.wrong_env << " self "
              << a.wrong_self << "; unrefined false positives " << unrefined
              << "; certain contacts " << a.certain << "\n";
    EXPECT_EQ(a.wrong_env + a.wrong_self + a.wrong_whole + a.wrong_certain, 0u) << a.first;
    EXPECT_GT(a.fcl_env + a.fcl_self, 0u);
    EXPECT_GT(unrefined, 0u) << "nothing for refine to remove";
    // The MotionBenchMaker obstacles are boxes and cylinders: the shortcut is exercised.
    EXPECT_GT(a.certain, 0u) << "no contact was certain without FCL";
  }
}

// Scenes nobody authored (tests/support/differential.h): generated rigid bodies and arms, the
// shipped arms and the Panda, generated environments with primitives, meshes and point clouds,
// both checker paths, exact primitives and self-pair tables at random; conservative rounding,
// refined.
TEST(RefineExact, DifferentialScenesAgreeWithFcl) {
  DifferentialOptions options;
  options.seed = kSeed;
  options.source_dir = OCTOMOTION_SOURCE_DIR;
  const std::string panda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
  if (std::filesystem::exists(panda + "/panda.urdf")) options.panda_dir = panda;
  options.work_dir = (std::filesystem::temp_directory_path() /
                      ("octomotion_refine_test_" + std::to_string(::getpid())))
                         .string();
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  std::mt19937_64 rng(options.seed);
  std::size_t cases = 0, states = 0, contacts = 0;
  for (std::size_t index = 0; cases < 20 && index < 60; ++index) {
    differential_detail::Case c = differential_detail::makeCase(rng, options, index);
    const std::uint64_t seed = rng();
    c.overrides.rounding = Rounding::kConservative;
    PlanningScene scene;
    try {
      scene = loadExact(c.scene_file, c.overrides);
    } catch (const Error&) {
      continue;  // a generated case the library refuses: no answer to check
    }
    SCOPED_TRACE(c.scene_file + ": " + c.description);
    const Agreement a =
        compare(scene, uniformSamples(scene, 200, seed), octreeCheckerPath(*c.overrides.checker));
    EXPECT_EQ(a.wrong_env + a.wrong_self + a.wrong_whole + a.wrong_certain, 0u) << a.first;
    ++cases;
    states += a.states;
    contacts += a.fcl_env + a.fcl_self;
  }
  std::cout << "[ refine   ] differential: " << cases << " cases, " << states << " states, "
            << contacts << " FCL contacts\n";
  EXPECT_GE(cases, 20u);
  EXPECT_GT(contacts, states / 20);
  std::filesystem::remove_all(options.work_dir);
}

}  // namespace
}  // namespace octomotion::validation
