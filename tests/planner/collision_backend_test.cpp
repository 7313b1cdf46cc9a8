// CollisionBackend and ValidityChecker<Backend>: on shipped scenes and fixed-seed uniform states,
// each backend answers through the interface exactly as through its own API, and the checker
// instantiated over the concrete backend, over CollisionBackend, the named checkers and the
// checks the checkers used to make by hand all agree on every state (in and out of bounds,
// non-finite).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include "fcl_reference.h"
#include "forwarding_backend.h"
#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"

namespace octomotion {
namespace {

namespace ob = ompl::base;
using validation::Sample;

constexpr std::size_t kStates = 200;
constexpr std::uint64_t kSeed = 11;

PlanningScene loadScene(const std::string& name) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + name + ".yaml");
}

// A backend's answers at one sample: whole check, halves, clearance at the check's poses.
struct Answers {
  bool collides = false, environment = false, self = false;
  double clearance = 0;
};

void expectSame(const Answers& a, const Answers& b, const std::string& what) {
  EXPECT_EQ(a.collides, b.collides) << what;
  EXPECT_EQ(a.environment, b.environment) << what;
  EXPECT_EQ(a.self, b.self) << what;
  EXPECT_EQ(a.clearance, b.clearance) << what;
}

Answers throughInterface(const CollisionBackend& backend, BackendScratch& scratch,
                         const Sample& s) {
  Answers a;
  a.environment = backend.environmentInCollision(s.q.data(), s.q.size(), s.X_WB, scratch);
  a.self = backend.selfInCollision(s.q.data(), s.q.size(), s.X_WB, scratch);
  a.collides = backend.inCollision(s.q.data(), s.q.size(), s.X_WB, scratch);
  a.clearance = backend.clearance(scratch);
  return a;
}

Answers octreeDirect(const OctreeCollisionModel& model, CheckerPath path, CheckScratch& scratch,
                     const Sample& s) {
  Answers a;
  model.robot().forwardKinematics(s.q.data(), s.q.size(), scratch.robot,
                                  model.robot().isFreeFlying() ? s.X_WB : model.baseMount());
  a.environment = model.environmentInCollision(path, scratch);
  a.self = model.selfInCollision(path, scratch);
  a.collides = model.inCollision(s.q.data(), s.q.size(), s.X_WB, path, scratch);
  a.clearance = model.clearanceLowerBound(scratch);
  return a;
}

template <class Model>
Answers fclDirect(const Model& model, typename Model::Scratch& scratch, const Sample& s,
                  const std::function<double(typename Model::Scratch&)>& clearance) {
  Answers a;
  model.setConfiguration(s.q.data(), s.q.size(), s.X_WB, scratch);
  a.environment = model.environmentInCollision(scratch);
  a.self = model.selfInCollision(scratch);
  a.collides = model.inCollision(scratch);
  a.clearance = clearance(scratch);
  return a;
}

class CollisionBackendTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CollisionBackendTest, InterfaceGivesTheDirectAnswers) {
  const PlanningScene scene = loadScene(GetParam());
  const std::vector<Sample> samples = validation::uniformSamples(scene, kStates, kSeed);
  const OctreeCollisionModel& model = *scene.model;
  const auto fcl = scene.fclModel();
  const auto octomap = scene.fclOctomapModel();

  int colliding = 0;
  for (CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    const OctreeBackend backend(scene.model, path);
    EXPECT_EQ(backend.id(), model.id());
    EXPECT_EQ(&backend.robot(), &model.robot());
    EXPECT_EQ(octreeCheckerPath(backend.kind()), path);
    EXPECT_EQ(backend.clearanceBound(), ClearanceBound::kLowerBound);
    const std::unique_ptr<BackendScratch> scratch = backend.makeBackendScratch();
    CheckScratch direct = model.makeScratch();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Answers a = throughInterface(backend, *scratch, samples[i]);
      expectSame(a, octreeDirect(model, path, direct, samples[i]),
                 std::string(backend.name()) + " state " + std::to_string(i));
      colliding += a.collides;
    }
  }
  EXPECT_GT(colliding, 0);
  EXPECT_LT(colliding, static_cast<int>(2 * samples.size()));

  {
    const CollisionBackend& backend = *fcl;
    EXPECT_STREQ(backend.name(), "fcl");
    EXPECT_EQ(backend.clearanceBound(), ClearanceBound::kExact);
    const std::unique_ptr<BackendScratch> scratch = backend.makeBackendScratch();
    auto direct = fcl->makeScratch();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      expectSame(throughInterface(backend, *scratch, samples[i]),
                 fclDirect<FclCollisionModel>(
                     *fcl, *direct, samples[i],
                     [&](FclCollisionModel::Scratch& s) { return fcl->environmentDistance(s); }),
                 "fcl state " + std::to_string(i));
    }
  }
  {
    const CollisionBackend& backend = *octomap;
    EXPECT_STREQ(backend.name(), "fcl-octomap");
    EXPECT_EQ(backend.clearanceBound(), ClearanceBound::kNone);
    const std::unique_ptr<BackendScratch> scratch = backend.makeBackendScratch();
    auto direct = octomap->makeScratch();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      expectSame(throughInterface(backend, *scratch, samples[i]),
                 fclDirect<FclOctomapCollisionModel>(
                     *octomap, *direct, samples[i],
                     [](FclOctomapCollisionModel::Scratch&) { return 0.0; }),
                 "fcl-octomap state " + std::to_string(i));
    }
  }
}

TEST_P(CollisionBackendTest, ForeignScratchIsRefused) {
  const PlanningScene scene = loadScene(GetParam());
  const OctreeBackend octree(scene.model, CheckerPath::kFused);
  const auto fcl = scene.fclModel();
  const Sample s = validation::uniformSamples(scene, 1, kSeed).front();
  const auto octree_scratch = octree.makeBackendScratch();
  const auto fcl_scratch = fcl->makeBackendScratch();
  EXPECT_THROW(octree.inCollision(s.q.data(), s.q.size(), s.X_WB, *fcl_scratch), InvalidArgument);
  EXPECT_THROW(fcl->inCollision(s.q.data(), s.q.size(), s.X_WB, *octree_scratch), InvalidArgument);
  EXPECT_THROW(
      scene.fclOctomapModel()->selfInCollision(s.q.data(), s.q.size(), s.X_WB, *octree_scratch),
      InvalidArgument);
}

// The uniform samples as states, then states just outside the bounds and non-finite ones.
std::vector<ob::ScopedState<>> testStates(const PlanningScene& scene) {
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const RobotModel& robot = scene.model->robot();
  std::vector<ob::ScopedState<>> states;
  for (const Sample& s : validation::uniformSamples(scene, kStates, kSeed)) {
    states.emplace_back(si);
    configurationToState(robot, s.q, s.X_WB, states.back().get());
  }
  for (int k = 0; k < 3; ++k) {
    ob::ScopedState<> state(states[static_cast<std::size_t>(k)]);
    double* value = robot.isFreeFlying()
                        ? &state->as<ob::SE3StateSpace::StateType>()
                               ->as<ob::RealVectorStateSpace::StateType>(0)
                               ->values[0]
                        : &state->as<ob::RealVectorStateSpace::StateType>()->values[0];
    *value = k == 0 ? std::nan("") : k == 1 ? std::numeric_limits<double>::infinity() : 1e6;
    states.push_back(state);
  }
  if (robot.isFreeFlying()) {
    ob::ScopedState<> state(states.front());
    state->as<ob::SE3StateSpace::StateType>()->rotation().w = 0.5;  // not a unit quaternion
    states.push_back(state);
  }
  return states;
}

// What the checkers computed by hand before ValidityChecker: bounds, conversion, the model's
// own check, and its clearance at valid states.
struct OldCheck {
  std::function<bool(const std::vector<double>&, const Eigen::Isometry3d&)> valid;
  std::function<double()> clearance;  // at the poses of the last valid check
};

void expectCheckersAgree(const PlanningScene& scene,
                         const std::vector<const ob::StateValidityChecker*>& checkers,
                         const OldCheck& old, const std::string& what) {
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const BoundsCheck in_bounds(si);
  const RobotModel& robot = scene.model->robot();
  std::vector<double> q(static_cast<std::size_t>(robot.variableCount()), 0.0);
  int valid = 0, invalid = 0;
  const std::vector<ob::ScopedState<>> states = testStates(scene);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const ob::State* state = states[i].get();
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    const bool expected =
        in_bounds(state) && stateToConfiguration(robot, state, q, X_WB) && old.valid(q, X_WB);
    const double expected_clearance = expected ? old.clearance() : 0.0;
    valid += expected;
    invalid += !expected;
    for (std::size_t c = 0; c < checkers.size(); ++c) {
      EXPECT_EQ(checkers[c]->isValid(state), expected)
          << what << " checker " << c << " state " << i;
      EXPECT_EQ(checkers[c]->clearance(state), expected_clearance)
          << what << " checker " << c << " state " << i;
      EXPECT_EQ(checkers[c]->getSpecs().clearanceComputationType,
                checkers[0]->getSpecs().clearanceComputationType);
    }
  }
  EXPECT_GT(valid, 0) << what;
  EXPECT_GT(invalid, 3) << what;
}

TEST_P(CollisionBackendTest, CheckersAgree) {
  const PlanningScene scene = loadScene(GetParam());
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const OctreeCollisionModel& model = *scene.model;

  for (CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    const auto backend = std::make_shared<const OctreeBackend>(scene.model, path);
    const ValidityChecker<OctreeBackend> concrete(si, backend);
    const ValidityChecker<CollisionBackend> generic(si, backend);
    const OctreeValidityChecker named(si, scene.model, path);
    EXPECT_EQ(&named.model(), &model);
    EXPECT_EQ(named.path(), path);
    const ob::StateValidityCheckerPtr made = makeValidityChecker(si, backend);
    EXPECT_NE(dynamic_cast<const OctreeValidityChecker*>(made.get()), nullptr);
    CheckScratch scratch = model.makeScratch();
    OldCheck old;
    old.valid = [&](const std::vector<double>& q, const Eigen::Isometry3d& X_WB) {
      model.robot().forwardKinematics(q.data(), q.size(), scratch.robot,
                                      model.robot().isFreeFlying() ? X_WB : model.baseMount());
      return !model.linksInCollision(path, scratch);
    };
    old.clearance = [&] { return model.clearanceLowerBound(scratch); };
    EXPECT_EQ(concrete.getSpecs().clearanceComputationType,
              ob::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE);
    expectCheckersAgree(scene, {&concrete, &generic, &named, made.get()}, old, backend->name());
  }
  {
    const auto fcl = scene.fclModel();
    const ValidityChecker<FclCollisionModel> concrete(si, fcl);
    const ValidityChecker<CollisionBackend> generic(si, fcl);
    const FclValidityChecker named(si, fcl);
    EXPECT_EQ(&named.model(), fcl.get());
    const ob::StateValidityCheckerPtr made = makeValidityChecker(si, fcl);
    EXPECT_NE(dynamic_cast<const FclValidityChecker*>(made.get()), nullptr);
    auto scratch = fcl->makeScratch();
    OldCheck old;
    old.valid = [&](const std::vector<double>& q, const Eigen::Isometry3d& X_WB) {
      fcl->setConfiguration(q.data(), q.size(), X_WB, *scratch);
      return !fcl->inCollision(*scratch);
    };
    old.clearance = [&] { return fcl->environmentDistance(*scratch); };
    EXPECT_EQ(concrete.getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::EXACT);
    expectCheckersAgree(scene, {&concrete, &generic, &named, made.get()}, old, "fcl");
  }
  {
    const auto octomap = scene.fclOctomapModel();
    const ValidityChecker<FclOctomapCollisionModel> concrete(si, octomap);
    const ValidityChecker<CollisionBackend> generic(si, octomap);
    const FclOctomapValidityChecker named(si, octomap);
    EXPECT_EQ(&named.model(), octomap.get());
    const ob::StateValidityCheckerPtr made = makeValidityChecker(si, octomap);
    EXPECT_NE(dynamic_cast<const FclOctomapValidityChecker*>(made.get()), nullptr);
    auto scratch = octomap->makeScratch();
    OldCheck old;
    old.valid = [&](const std::vector<double>& q, const Eigen::Isometry3d& X_WB) {
      octomap->setConfiguration(q.data(), q.size(), X_WB, *scratch);
      return !octomap->inCollision(*scratch);
    };
    old.clearance = [] { return 0.0; };
    EXPECT_EQ(concrete.getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::NONE);
    expectCheckersAgree(scene, {&concrete, &generic, &named, made.get()}, old, "fcl-octomap");
  }
}

// A backend the library does not know gets the generic checker.
TEST(CollisionBackend, UnknownBackendGetsTheGenericChecker) {
  const PlanningScene scene = loadScene("bookshelf");
  using Wrapped = test::ForwardingBackend;
  const auto backend = std::make_shared<const Wrapped>(
      std::make_shared<const OctreeBackend>(scene.model, CheckerPath::kFused));
  const ob::SpaceInformationPtr& si = scene.setup->getSpaceInformation();
  const ob::StateValidityCheckerPtr made = makeValidityChecker(si, backend);
  EXPECT_NE(dynamic_cast<const ValidityChecker<CollisionBackend>*>(made.get()), nullptr);
  const OctreeValidityChecker reference(si, scene.model, CheckerPath::kFused);
  for (const ob::ScopedState<>& state : testStates(scene)) {
    EXPECT_EQ(made->isValid(state.get()), reference.isValid(state.get()));
  }
  EXPECT_THROW(makeValidityChecker(si, nullptr), InvalidArgument);
}

INSTANTIATE_TEST_SUITE_P(Scenes, CollisionBackendTest,
                         ::testing::Values("bookshelf", "cage", "rooms"),
                         [](const auto& param_info) { return std::string(param_info.param); });

}  // namespace
}  // namespace octomotion
