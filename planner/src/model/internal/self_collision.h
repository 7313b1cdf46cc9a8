// Private to the planner library: the robot's self-collision pairs as OctreeCollisionModel
// tests them. Each checked pair (SRDF-enabled, both links modelled) is tested in stages,
// cheapest first: bounding spheres, its joint-space table when it has one, the links' oriented
// boxes, then B's self tree placed in A's frame against A's. The pairs worth testing come from
// a loop over all of them (SelfBroadPhase::kPairs) or from an N-objects octree over the links'
// world boxes (kNObjectsOctree), kept per thread in the CheckScratch.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "link_models.h"
#include "octomotion/broadphase/n_objects_octree.h"
#include "octomotion/motion/box_overlap.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/model/joint_space_table.h"

namespace octomotion::detail {

struct SelfPair {
  std::size_t a, b;                        // slots in LinkModels::links
  double reach_squared = 0;                // spheresReach(a, b)^2
  const JointSpaceTable* table = nullptr;  // in SelfCollision::pair_tables, or none
};

class SelfCollision {
 public:
  Rounding rounding = Rounding::kConservative;
  SelfBroadPhase strategy = SelfBroadPhase::kPairs;  // resolved (never kAuto)
  std::vector<SelfPair> pairs;
  std::vector<std::unique_ptr<const JointSpaceTable>> pair_tables;
  // Self broad phase: object id i is links[self_links[i]] (increasing slots, so a < b ids keep
  // the pairs' order); pair_of[a * self_links.size() + b] for ids a < b: the index in pairs of
  // a checked pair, or -1.
  std::vector<int> self_links;
  std::vector<std::int32_t> pair_of;
  Eigen::AlignedBox3d root_box_W;  // the broad phase's root: everything links can reach
  std::uint32_t leaf_capacity = kSelfBroadPhaseLeafCapacity;
  // Per CheckerPath: a pair whose relative pose never changes (CollisionModelOptions::
  // fold_static) met at build time, so every state is in collision.
  std::array<bool, 2> always_hits{};

  // The bounding spheres (centres in W from placeCentres) are close enough for B's voxels
  // placed on A's grid to reach A when their centres are within spheresReach of each other.
  static double spheresReach(const LinkVoxels& a, const LinkVoxels& b) {
    return a.radius + b.radius + a.source_diagonal;
  }
  // The pair's bounding spheres, centred at ca_W and cb_W, are within reach of each other.
  static bool spheresMeet(const SelfPair& p, const Eigen::Vector3d& ca_W,
                          const Eigen::Vector3d& cb_W) {
    return (ca_W - cb_W).squaredNorm() <= p.reach_squared;
  }
  // The boxes of A's and B's black voxels (B's rotation in A: R_AB) overlap.
  static bool boxesMeet(const LinkVoxels& a, const Eigen::Isometry3d& X_WA,
                        const Eigen::Matrix3d& R_AB, const LinkVoxels& b,
                        const Eigen::Vector3d& cb_W) {
    return boxesOverlap(a.center_L, a.half_L, R_AB,
                        X_WA.linear().transpose() * (cb_W - X_WA.translation()), b.half_L,
                        kMotionTieTolerance * a.source.grid().voxelSize());
  }

  // The self half of a check, with the strategy resolved at build time.
  bool inCollision(const LinkModels& links, CheckerPath path, CheckScratch& scratch) const {
    if (always_hits[static_cast<std::size_t>(path)]) return true;
    if (pairs.empty()) return false;
    if (strategy == SelfBroadPhase::kNObjectsOctree) {
      return broadPhaseInCollision(links, path, scratch);
    }
    return pairsInCollision(links, path, scratch);
  }
  // What exact geometry says of a pair before its voxels (RefineMode::kExact).
  enum class ExactVerdict { kFree, kContact, kUnknown };
  // RefineMode::kExact: like inCollision, but a pair whose spheres meet is first decided by
  // `exact(pair index)` (exact geometry): skipped when free, the answer when a contact; a pair
  // left unknown whose stages hit counts only when `confirm(pair)` (FCL on the two links) says
  // so; the loop goes on past unconfirmed pairs. Always the pairs loop (the broad phase gives
  // the same candidates).
  template <class Exact, class Confirm>
  bool confirmedInCollision(const LinkModels& links, CheckerPath path, CheckScratch& scratch,
                            const Exact& exact, const Confirm& confirm) const {
    placeCentres(links, scratch);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const SelfPair& p = pairs[i];
      if (!spheresMeet(p, scratch.centres_W[p.a], scratch.centres_W[p.b]) ||
          !pairBoxesMeet(p, links, scratch)) {
        continue;
      }
      const ExactVerdict verdict = exact(i);
      if (verdict == ExactVerdict::kContact) return true;
      if (verdict == ExactVerdict::kUnknown && pairStagesHit(p, links, path, scratch) &&
          confirm(p)) {
        return true;
      }
    }
    return false;
  }
  // For explanations: the indices in `pairs` of every checked pair that meets (the first only
  // unless `all`), by the same stages as inCollision, over all pairs.
  std::vector<std::size_t> hitPairs(const LinkModels& links, CheckerPath path,
                                    CheckScratch& scratch, bool all) const;
  // Build time: one pair's stages (spheres, table, boxes, trees) at the poses in the scratch.
  bool pairHitsOnce(const SelfPair& p, const LinkModels& links, CheckerPath path,
                    CheckScratch& scratch) const {
    placeCentres(links, scratch);
    return spheresMeet(p, scratch.centres_W[p.a], scratch.centres_W[p.b]) &&
           pairStagesHit(p, links, path, scratch);
  }
  // A new broad-phase octree for this model's self links (each CheckScratch owns one).
  broadphase::NObjectsOctree makeBroadPhase() const;

 private:
  // scratch.centres_W[slot]: every modelled link's self-collision sphere centre.
  static void placeCentres(const LinkModels& links, CheckScratch& scratch);
  bool pairsInCollision(const LinkModels& links, CheckerPath path, CheckScratch& scratch) const;
  bool broadPhaseInCollision(const LinkModels& links, CheckerPath path,
                             CheckScratch& scratch) const;
  // Self pair `pair` (index into pairs): the spheres (centres from placeCentres), then
  // pairStagesHit.
  bool pairHits(std::size_t pair, const LinkModels& links, CheckerPath path,
                CheckScratch& scratch) const {
    const SelfPair& p = pairs[pair];
    return spheresMeet(p, scratch.centres_W[p.a], scratch.centres_W[p.b]) &&
           pairStagesHit(p, links, path, scratch);
  }
  // The boxes of the pair's black voxels overlap (linksHit's first test).
  bool pairBoxesMeet(const SelfPair& p, const LinkModels& links,
                     const CheckScratch& scratch) const {
    const Eigen::Isometry3d& X_WA = scratch.robot.linkPose(links.links[p.a].link);
    const Eigen::Matrix3d R_AB =
        X_WA.linear().transpose() * scratch.robot.linkPose(links.links[p.b].link).linear();
    return boxesMeet(*links.self_voxels[p.a], X_WA, R_AB, *links.self_voxels[p.b],
                     scratch.centres_W[p.b]);
  }
  // A pair whose spheres meet: its joint-space table when it has one, then the boxes and trees
  // of the self trees.
  bool pairStagesHit(const SelfPair& p, const LinkModels& links, CheckerPath path,
                     CheckScratch& scratch) const;
  // For pairs whose spheres meet: the oriented boxes, then the trees.
  bool linksHit(const LinkVoxels& a, const Eigen::Isometry3d& X_WA, const LinkVoxels& b,
                const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& cb_W, CheckerPath path,
                CollisionScratch& fused) const;
};

}  // namespace octomotion::detail
