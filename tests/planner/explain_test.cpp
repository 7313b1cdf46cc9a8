// CollisionBackend::explain on the real Panda (skipped without ../shared/data/panda): it names the
// right link and object for a hand pushed into a named box, the right pairs for a folded arm, a
// joint beyond its limit and a NaN, on the octree model (both paths, exact primitives) and both
// FCL references; and on fixed-seed random states it agrees with inCollision, the conservative
// octree's contacts holding every one FCL finds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "forwarding_backend.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/reference/fcl_octomap_collision_model.h"

namespace octomotion {
namespace {

using ::testing::HasSubstr;

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

EnvironmentObject box(const std::string& name, const Eigen::Vector3d& size,
                      const Eigen::Isometry3d& X_WO) {
  EnvironmentObject o;
  o.name = name;
  o.primitive = Box{size / 2};
  o.X_WO = X_WO;
  return o;
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

RobotModel loadPanda() {
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  return robot;
}

// The voxel model's options: these tests explain the voxels' answers (refine none), which
// name near misses within the margin as voxel contacts.
CollisionModelOptions voxelOptions() {
  CollisionModelOptions o;
  o.refine = RefineMode::kNone;
  return o;
}

// A bent arm, fingers half open: the hand clear of the other links and the floor.
std::vector<double> bentArm() {
  return {0.3, -0.4, 0.2, -2.2, 0.1, 1.9, 0.7, 0.02};
}

// Every backend over one robot and environment, each with its scratch.
struct Backends {
  std::vector<std::shared_ptr<const CollisionBackend>> all;
  std::vector<std::string> names;
  std::vector<std::unique_ptr<BackendScratch>> scratch;

  Backends(const RobotModel& robot, const std::vector<EnvironmentObject>& objects) {
    const EnvironmentGeometry environment = EnvironmentGeometry::load(objects);
    auto model = std::make_shared<const OctreeCollisionModel>(robot, environment, voxelOptions());
    CollisionModelOptions exact = voxelOptions();
    exact.exact_primitives = true;
    auto exact_model = std::make_shared<const OctreeCollisionModel>(robot, environment, exact);
    add("octree-fused", std::make_shared<const OctreeBackend>(model, CheckerPath::kFused));
    add("octree", std::make_shared<const OctreeBackend>(model, CheckerPath::kMoveTree));
    add("octree exact primitives",
        std::make_shared<const OctreeBackend>(exact_model, CheckerPath::kFused));
    add("fcl", std::make_shared<const FclCollisionModel>(robot, environment));
    add("fcl-octomap", std::make_shared<const FclOctomapCollisionModel>(robot, environment, 0.01));
  }
  void add(const std::string& name, std::shared_ptr<const CollisionBackend> backend) {
    scratch.push_back(backend->makeBackendScratch());
    all.push_back(std::move(backend));
    names.push_back(name);
  }
  StateExplanation explain(std::size_t i, const std::vector<double>& q, bool all_contacts) {
    ExplainOptions options;
    options.all = all_contacts;
    return all[i]->explain(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch[i], options);
  }
  bool inCollision(std::size_t i, const std::vector<double>& q) {
    return all[i]->inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch[i]);
  }
};

bool hasContact(const StateExplanation& e, InvalidityReason::Kind kind, const std::string& link,
                const std::string& other) {
  return std::any_of(e.reasons.begin(), e.reasons.end(), [&](const InvalidityReason& r) {
    return r.kind == kind && r.link == link && r.other == other;
  });
}

// Eight boxes of 5 to 30 cm scattered about the arm.
std::vector<EnvironmentObject> scatteredBoxes(std::mt19937_64& rng) {
  std::vector<EnvironmentObject> objects;
  std::uniform_real_distribution<double> coordinate(-0.7, 0.7), size(0.05, 0.3);
  for (int k = 0; k < 8; ++k) {
    const Eigen::Isometry3d X =
        at(coordinate(rng), coordinate(rng), 0.5 + coordinate(rng) / 1.4 * 0.5);
    objects.push_back(
        box("box" + std::to_string(k), Eigen::Vector3d(size(rng), size(rng), size(rng)), X));
  }
  return objects;
}

std::vector<double> uniformState(const RobotModel& robot, std::mt19937_64& rng) {
  std::vector<double> q;
  for (const Variable& v : robot.variables()) {
    q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
  }
  return q;
}

class Explain : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda in " << kPanda;
  }
};

TEST_F(Explain, NamesTheBoxTheHandIsPushedInto) {
  const RobotModel robot = loadPanda();
  const std::vector<double> q = bentArm();
  RobotData data = robot.makeData();
  robot.forwardKinematics(q.data(), q.size(), data);
  const Eigen::Isometry3d& X_WH = data.linkPose(robot.linkIndex("panda_hand"));
  // A thin plate across the hand, 3 cm below its flange: it cuts the hand's mesh (FCL sees
  // meshes as surfaces, so a box swallowed whole would not count). Two more boxes far away.
  Eigen::Isometry3d X_WP = X_WH;
  X_WP.translation() = X_WH * Eigen::Vector3d(0, 0, 0.03);
  Backends b(robot, {box("far_left", Eigen::Vector3d(0.2, 0.2, 0.2), at(-0.6, 0.6, 0.1)),
                     box("plate", Eigen::Vector3d(0.1, 0.1, 0.01), X_WP),
                     box("far_right", Eigen::Vector3d(0.2, 0.2, 0.2), at(-0.6, -0.6, 0.1))});
  for (std::size_t i = 0; i < b.all.size(); ++i) {
    SCOPED_TRACE(b.names[i]);
    ASSERT_TRUE(b.inCollision(i, q));
    const StateExplanation first = b.explain(i, q, false);
    ASSERT_EQ(first.reasons.size(), 1u);
    EXPECT_EQ(first.reasons[0].kind, InvalidityReason::Kind::kEnvironment);
    EXPECT_EQ(first.reasons[0].other, "plate");
    const StateExplanation every = b.explain(i, q, true);
    EXPECT_TRUE(hasContact(every, InvalidityReason::Kind::kEnvironment, "panda_hand", "plate"))
        << describe(every);
    EXPECT_THAT(describe(every), HasSubstr("link panda_hand with object plate"));
    EXPECT_THAT(describe(every), ::testing::Not(HasSubstr("far_")));
    for (const InvalidityReason& r : every.reasons) {
      if (r.link != "panda_hand") continue;
      // The plate cuts the hand: FCL and the octree's exact test say the shapes touch;
      // fcl-octomap cannot tell.
      EXPECT_EQ(r.exact,
                b.names[i] == "fcl-octomap" ? ExactContact::kUnknown : ExactContact::kTouching);
      EXPECT_FALSE(every.onlyVoxelMargin());
    }
  }
}

TEST_F(Explain, NamesThePairsOfAFoldedArm) {
  const RobotModel robot = loadPanda();
  Backends b(robot, {});
  // Fixed-seed states until FCL finds self contacts: an arm folded into itself.
  std::mt19937_64 rng(27);
  std::vector<double> q(robot.variables().size());
  StateExplanation fcl;
  for (int tries = 0; tries < 2000 && fcl.reasons.empty(); ++tries) {
    for (std::size_t v = 0; v < q.size(); ++v) {
      const Variable& var = robot.variables()[v];
      q[v] = std::uniform_real_distribution<double>(var.lower, var.upper)(rng);
    }
    fcl = b.explain(3, q, true);
  }
  ASSERT_FALSE(fcl.reasons.empty()) << "no folded state found";
  for (const InvalidityReason& r : fcl.reasons) {
    ASSERT_EQ(r.kind, InvalidityReason::Kind::kSelf);
    // A checked pair (the SRDF does not allow it), named in the robot's order.
    EXPECT_FALSE(robot.collisionAllowed(robot.linkIndex(r.link), robot.linkIndex(r.other)));
    EXPECT_LT(robot.linkIndex(r.link), robot.linkIndex(r.other));
  }
  for (std::size_t i = 0; i < b.all.size(); ++i) {
    SCOPED_TRACE(b.names[i] + ": " + describe(fcl));
    const StateExplanation e = b.explain(i, q, true);
    // Conservative voxels hold every pair FCL finds (and the exact shapes of those touch).
    for (const InvalidityReason& r : fcl.reasons) {
      EXPECT_TRUE(hasContact(e, InvalidityReason::Kind::kSelf, r.link, r.other));
    }
    for (const InvalidityReason& r : e.reasons) {
      EXPECT_EQ(r.kind, InvalidityReason::Kind::kSelf);
      if (hasContact(fcl, InvalidityReason::Kind::kSelf, r.link, r.other)) {
        EXPECT_EQ(r.exact, ExactContact::kTouching);
      } else {
        EXPECT_EQ(r.exact, ExactContact::kApart);
      }
    }
    const StateExplanation first = b.explain(i, q, false);
    ASSERT_EQ(first.reasons.size(), 1u);
    EXPECT_TRUE(
        hasContact(e, first.reasons[0].kind, first.reasons[0].link, first.reasons[0].other));
  }
}

TEST_F(Explain, NamesAJointBeyondItsLimitAndANaN) {
  const RobotModel robot = loadPanda();
  Backends b(robot, {});
  const int joint4 = robot.variableIndex("panda_joint4");
  std::vector<double> beyond = bentArm();
  beyond[static_cast<std::size_t>(joint4)] = 0.5;  // upper limit 0.0873
  std::vector<double> nan = bentArm();
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < b.all.size(); ++i) {
    SCOPED_TRACE(b.names[i]);
    const StateExplanation e = b.explain(i, beyond, true);
    ASSERT_FALSE(e.reasons.empty());
    const InvalidityReason& r = e.reasons[0];
    EXPECT_EQ(r.kind, InvalidityReason::Kind::kOutsideLimits);
    EXPECT_EQ(r.link, "panda_joint4");
    EXPECT_EQ(r.value, 0.5);
    EXPECT_EQ(r.upper, robot.variables()[static_cast<std::size_t>(joint4)].upper);
    EXPECT_THAT(describe(r), HasSubstr("joint 'panda_joint4' = 0.5 is outside its limits"));
    // Without the limits the joint is not a reason; contacts, if any, still are.
    ExplainOptions no_limits;
    no_limits.check_limits = false;
    const StateExplanation contacts_only = b.all[i]->explain(
        beyond.data(), beyond.size(), Eigen::Isometry3d::Identity(), *b.scratch[i], no_limits);
    EXPECT_EQ(contacts_only.valid(), !b.inCollision(i, beyond));

    // NaN: explained, not thrown (inCollision throws).
    StateExplanation n;
    ASSERT_NO_THROW(n = b.explain(i, nan, true));
    ASSERT_EQ(n.reasons.size(), 1u);
    EXPECT_EQ(n.reasons[0].kind, InvalidityReason::Kind::kNonFinite);
    EXPECT_THAT(describe(n), HasSubstr("q[2] (panda_joint3) is not finite"));
    EXPECT_FALSE(n.inCollision());
    EXPECT_THROW(b.inCollision(i, nan), InvalidArgument);
  }
}

// The property: on fixed-seed random states among scattered boxes, a state is explained as
// colliding iff inCollision says so, for every backend; every contact FCL finds (link and object,
// or pair) is among the conservative octree's; and the first contact is one of all of them.
TEST_F(Explain, AgreesWithInCollisionOnRandomStates) {
  const RobotModel robot = loadPanda();
  std::mt19937_64 rng(2027);
  Backends b(robot, scatteredBoxes(rng));
  const std::size_t fcl = 3;
  ASSERT_EQ(b.names[fcl], "fcl");
  std::size_t colliding = 0, environment = 0, self = 0;
  std::vector<double> q(robot.variables().size());
  for (int s = 0; s < 150; ++s) {
    q = uniformState(robot, rng);
    const StateExplanation exact = b.explain(fcl, q, true);
    for (const InvalidityReason& r : exact.reasons) {
      (r.kind == InvalidityReason::Kind::kSelf ? self : environment) += 1;
    }
    for (std::size_t i = 0; i < b.all.size(); ++i) {
      SCOPED_TRACE(b.names[i] + " at state " + std::to_string(s));
      const bool hit = b.inCollision(i, q);
      const StateExplanation e = b.explain(i, q, true);
      ASSERT_EQ(e.inCollision(), hit) << describe(e);
      ASSERT_EQ(e.valid(), !hit);  // within the limits, finite
      colliding += hit ? 1 : 0;
      const StateExplanation first = b.explain(i, q, false);
      ASSERT_EQ(first.reasons.size(), hit ? 1u : 0u);
      if (hit) {
        EXPECT_TRUE(
            hasContact(e, first.reasons[0].kind, first.reasons[0].link, first.reasons[0].other));
      }
      if (b.names[i].rfind("octree", 0) != 0) continue;
      for (const InvalidityReason& r : exact.reasons) {
        EXPECT_TRUE(hasContact(e, r.kind, r.link, r.other))
            << describe(r) << " missing from " << describe(e);
      }
    }
  }
  // Not vacuous: contacts of both kinds were there to explain.
  EXPECT_GT(colliding, 0u);
  EXPECT_GT(environment, 0u);
  EXPECT_GT(self, 0u);
}

// explain is const and thread-safe: threads sharing a fresh model (its per-object data built on
// first use, by whichever thread gets there) give the answers one thread gives.
TEST_F(Explain, ThreadsSharingAModelGetTheSameExplanations) {
  const RobotModel robot = loadPanda();
  std::mt19937_64 rng(2029);
  const std::vector<EnvironmentObject> objects = scatteredBoxes(rng);
  std::vector<std::vector<double>> states;
  for (int s = 0; s < 40; ++s) states.push_back(uniformState(robot, rng));
  ExplainOptions options;
  options.all = true;
  auto explainAll = [&](const CollisionBackend& backend) {
    std::vector<std::string> out;
    const auto scratch = backend.makeBackendScratch();
    for (const std::vector<double>& q : states) {
      out.push_back(describe(
          backend.explain(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch, options)));
    }
    return out;
  };
  const EnvironmentGeometry environment = EnvironmentGeometry::load(objects);
  const OctreeBackend alone(
      std::make_shared<const OctreeCollisionModel>(robot, environment, voxelOptions()),
      CheckerPath::kFused);
  const std::vector<std::string> expected = explainAll(alone);
  const OctreeBackend shared(
      std::make_shared<const OctreeCollisionModel>(robot, environment, voxelOptions()),
      CheckerPath::kFused);
  std::vector<std::vector<std::string>> got(4);
  std::vector<std::thread> threads;
  for (auto& g : got) threads.emplace_back([&] { g = explainAll(shared); });
  for (std::thread& t : threads) t.join();
  for (const auto& g : got) EXPECT_EQ(g, expected);
  EXPECT_TRUE(std::any_of(expected.begin(), expected.end(),
                          [](const std::string& e) { return !e.empty(); }));
}

// A backend of the user's own, which only answers the halves: the default explanation says which
// half collides, without names, and agrees with inCollision too.
TEST_F(Explain, ABackendThatCannotNameContactsExplainsItsHalves) {
  using Wrapped = test::ForwardingBackend;
  const RobotModel robot = loadPanda();
  std::mt19937_64 rng(2028);
  Backends b(robot, scatteredBoxes(rng));
  const Wrapped wrapped(b.all[0]);
  const auto scratch = wrapped.makeBackendScratch();
  ExplainOptions options;
  options.all = true;
  std::size_t both = 0;
  for (int s = 0; s < 60; ++s) {
    const std::vector<double> q = uniformState(robot, rng);
    const StateExplanation e =
        wrapped.explain(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch, options);
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    ASSERT_EQ(e.inCollision(), wrapped.inCollision(q.data(), q.size(), I, *scratch));
    const bool environment = wrapped.environmentInCollision(q.data(), q.size(), I, *scratch);
    const bool self = wrapped.selfInCollision(q.data(), q.size(), I, *scratch);
    ASSERT_EQ(e.reasons.size(), (environment ? 1u : 0u) + (self ? 1u : 0u));
    both += environment && self ? 1 : 0;
    for (const InvalidityReason& r : e.reasons) {
      EXPECT_TRUE(r.link.empty() && r.other.empty());
      EXPECT_EQ(r.exact, ExactContact::kUnknown);
      EXPECT_THAT(describe(r),
                  ::testing::AnyOf("the robot with the environment", "a self-collision"));
    }
  }
  EXPECT_GT(both, 0u);  // not vacuous
}

}  // namespace
}  // namespace octomotion
