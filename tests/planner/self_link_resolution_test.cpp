// CollisionModelOptions::self_link_resolution: links in self pairs keep a second, finer source
// tree used only against the other links. A model built that way must answer the environment
// half exactly like a model whose link trees are all at link_resolution, and the self half
// exactly like a model whose link trees are all at self_link_resolution (same trees, same
// queries), on both checker paths and with both self broad phases.
#include <gtest/gtest.h>

#include <random>

#include "joint_states.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

constexpr double kResolution = 0.02;
constexpr double kSelfResolution = 0.005;

struct Models {
  PlanningScene scene;
  std::unique_ptr<OctreeCollisionModel> coarse, fine, split;
};

std::unique_ptr<OctreeCollisionModel> build(const PlanningScene& scene, double link,
                                            std::optional<double> self,
                                            SelfBroadPhase broad_phase = SelfBroadPhase::kAuto) {
  CollisionModelOptions o;
  o.resolution = kResolution;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.link_resolution = link;
  o.self_link_resolution = self;
  o.self_broad_phase = broad_phase;
  o.X_WB = scene.model->baseMount();
  return std::make_unique<OctreeCollisionModel>(scene.model->robot(), *scene.environment, o);
}

const Models& bookshelf() {
  static const Models models = [] {
    SceneOverrides overrides;
    overrides.resolution = kResolution;
    Models m{loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/bookshelf.yaml",
                               overrides),
             nullptr, nullptr, nullptr};
    m.coarse = build(m.scene, kResolution, std::nullopt);
    m.fine = build(m.scene, kSelfResolution, std::nullopt);
    m.split = build(m.scene, kResolution, kSelfResolution);
    return m;
  }();
  return models;
}

struct Answers {
  std::vector<char> env, self;
};
Answers answers(const OctreeCollisionModel& m, const std::vector<std::vector<double>>& states,
                CheckerPath path) {
  CheckScratch scratch = m.makeScratch();
  Answers a;
  for (const auto& q : states) {
    m.robot().forwardKinematics(q.data(), q.size(), scratch.robot, m.baseMount());
    a.env.push_back(m.environmentInCollision(path, scratch));
    a.self.push_back(m.selfInCollision(path, scratch));
  }
  return a;
}

TEST(SelfLinkResolution, ReportsTheSecondTreesOfPairedLinksOnly) {
  const Models& m = bookshelf();
  const CollisionModelReport& r = m.split->report();
  EXPECT_DOUBLE_EQ(r.link_resolution, kResolution);
  EXPECT_DOUBLE_EQ(r.self_link_resolution, kSelfResolution);
  EXPECT_DOUBLE_EQ(m.coarse->report().self_link_resolution, kResolution);
  std::vector<bool> in_pair(r.links.size(), false);
  for (const auto& [a, b] : m.split->robot().checkedPairs()) {
    in_pair[static_cast<std::size_t>(a)] = in_pair[static_cast<std::size_t>(b)] = true;
  }
  int second_trees = 0;
  for (std::size_t i = 0; i < r.links.size(); ++i) {
    // The environment tree is the coarse model's; the self tree, where built, the fine one's.
    EXPECT_EQ(r.links[i].source_bytes, m.coarse->report().links[i].source_bytes) << i;
    EXPECT_EQ(m.coarse->report().links[i].self_source_bytes, 0u) << i;
    if (!r.links[i].modelled) continue;
    if (in_pair[i]) {
      EXPECT_EQ(r.links[i].self_source_bytes, m.fine->report().links[i].source_bytes) << i;
      ++second_trees;
    } else {
      EXPECT_EQ(r.links[i].self_source_bytes, 0u) << r.links[i].name;
    }
  }
  EXPECT_GT(second_trees, 2);
  EXPECT_NE(r.toString().find("self-collision trees"), std::string::npos);
}

TEST(SelfLinkResolution, EnvironmentFromLinkTreesSelfFromFinerTrees) {
  const Models& m = bookshelf();
  const auto states = test::uniformJointStates(m.split->robot(), 1500, 0x5e1f);
  for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    // The moveTree path is slow at 5 mm: a subset of the states.
    const std::vector<std::vector<double>> subset(
        states.begin(), states.begin() + (path == CheckerPath::kFused ? 1500 : 150));
    const Answers coarse = answers(*m.coarse, subset, path);
    const Answers fine = answers(*m.fine, subset, path);
    const Answers split = answers(*m.split, subset, path);
    EXPECT_EQ(split.env, coarse.env) << "path " << static_cast<int>(path);
    EXPECT_EQ(split.self, fine.self) << "path " << static_cast<int>(path);
    if (path == CheckerPath::kFused) {
      // The comparison means something: both answers occur, and the finer self trees clear
      // states the coarse ones reject (their smaller margin).
      const auto self_hits = std::count(split.self.begin(), split.self.end(), 1);
      EXPECT_GT(self_hits, 20);
      EXPECT_LT(self_hits, static_cast<long>(subset.size()) - 20);
      int cleared = 0;
      for (std::size_t i = 0; i < subset.size(); ++i) cleared += coarse.self[i] && !fine.self[i];
      EXPECT_GT(cleared, 0);
    }
  }
}

TEST(SelfLinkResolution, BroadPhaseUsesTheSelfTreesToo) {
  const Models& m = bookshelf();
  const auto octree = build(m.scene, kResolution, kSelfResolution, SelfBroadPhase::kNObjectsOctree);
  ASSERT_EQ(octree->selfBroadPhase(), SelfBroadPhase::kNObjectsOctree);
  const auto states = test::uniformJointStates(octree->robot(), 800, 0xb0ad);
  EXPECT_EQ(answers(*octree, states, CheckerPath::kFused).self,
            answers(*m.fine, states, CheckerPath::kFused).self);
}

TEST(SelfLinkResolution, RejectsNonPositiveResolution) {
  const Models& m = bookshelf();
  for (const double bad : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THROW(build(m.scene, kResolution, bad), InvalidArgument) << bad;
  }
}

}  // namespace
}  // namespace octomotion
