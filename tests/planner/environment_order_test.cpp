// The environment half's link order (OctreeCollisionModel: links most often hit at build time
// are tested first). Reordering may only change how soon a colliding state stops, never an
// answer: checked against each link's own fused query on independent states, and the measured
// shares against an independent estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "joint_states.h"
#include "octomotion/motion/collides.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {
namespace {

PlanningScene loadScene(const std::string& name, double resolution) {
  SceneOverrides o;
  o.refine = RefineMode::kNone;  // the voxels' own answer, link by link
  o.resolution = resolution;
  return loadPlanningScene(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes/" + name, o);
}

TEST(EnvironmentOrder, MostOftenHitLinksFirst) {
  const PlanningScene scene = loadScene("bookshelf.yaml", 0.01);
  const CollisionModelReport& r = scene.model->report();
  ASSERT_GE(r.environment_order.size(), 2u);
  std::map<std::string, const LinkReport*> by_name;
  for (const LinkReport& l : r.links) by_name[l.name] = &l;
  std::set<std::string> seen;
  double previous = 1.0;
  for (const std::string& name : r.environment_order) {
    EXPECT_TRUE(seen.insert(name).second) << name << " listed twice";
    ASSERT_EQ(by_name.count(name), 1u) << name;
    const LinkReport& l = *by_name[name];
    EXPECT_TRUE(l.modelled) << name;
    EXPECT_GE(l.environment_hit_share, 0.0) << name;
    EXPECT_LE(l.environment_hit_share, previous) << name << " out of order";
    previous = l.environment_hit_share;
  }
  // The hand and the wrist reach into the shelf; the base cannot.
  EXPECT_GT(by_name.at(r.environment_order.front())->environment_hit_share, 0.02);
}

TEST(EnvironmentOrder, SameAnswersAsEveryLinkOnItsOwn) {
  const PlanningScene scene = loadScene("bookshelf.yaml", 0.01);
  const OctreeCollisionModel& model = *scene.model;
  const CollisionModelReport& r = model.report();
  std::vector<std::unique_ptr<const MovableSource>> movable;
  std::vector<int> link_of;
  for (const auto& t : model.linkSourceTrees()) {
    movable.push_back(std::make_unique<const MovableSource>(*t.source));
    link_of.push_back(t.link);
  }
  std::vector<int> hits(movable.size(), 0);
  CheckScratch scratch = model.makeScratch();
  CollisionScratch fused;
  const int count = 3000;
  int colliding = 0;
  for (const auto& q : test::uniformJointStates(model.robot(), count, 11)) {
    model.robot().forwardKinematics(q.data(), q.size(), scratch.robot, model.baseMount());
    bool any = false;
    for (std::size_t i = 0; i < movable.size(); ++i) {
      if (movable[i]->rootColor() == Color::kWhite) continue;
      if (collides(*movable[i], scratch.robot.linkPose(link_of[i]), model.environment(),
                   model.rounding(), fused)) {
        ++hits[i];
        any = true;
      }
    }
    colliding += any;
    ASSERT_EQ(model.environmentInCollision(CheckerPath::kFused, scratch), any);
  }
  EXPECT_GT(colliding, count / 50);  // the comparison saw contacts
  // The build-time shares (512 states of another stream) agree with these within sampling error
  // (binomial standard deviation <= 0.023 for 512 states): 0.08 is over 3 of them.
  for (std::size_t i = 0; i < movable.size(); ++i) {
    const std::string& name = model.robot().link(link_of[i]).name;
    const double share = static_cast<double>(hits[i]) / count;
    const auto in_order = std::find(r.environment_order.begin(), r.environment_order.end(), name);
    if (in_order == r.environment_order.end()) {
      EXPECT_EQ(hits[i], 0) << name << " is not tested against the environment but meets it";
      continue;
    }
    const LinkReport& l = r.links[static_cast<std::size_t>(link_of[i])];
    EXPECT_NEAR(l.environment_hit_share, share, 0.08) << name;
  }
}

TEST(EnvironmentOrder, FreeFlyingBodiesKeepModelOrder) {
  const PlanningScene scene = loadScene("rooms.yaml", 0.04);
  const CollisionModelReport& r = scene.model->report();
  EXPECT_FALSE(r.environment_order.empty());
  for (const LinkReport& l : r.links) EXPECT_EQ(l.environment_hit_share, -1.0) << l.name;
}

}  // namespace
}  // namespace octomotion
