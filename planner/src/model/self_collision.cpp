#include "internal/self_collision.h"

#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/traversal.h"

static_assert(octomotion::kSelfBroadPhaseLeafCapacity ==
                  octomotion::broadphase::NObjectsOctree::kUnlimited,
              "the self broad phase keeps one leaf");

namespace octomotion {

SelfBroadPhaseScratch::SelfBroadPhaseScratch() noexcept = default;
SelfBroadPhaseScratch::SelfBroadPhaseScratch(const SelfBroadPhaseScratch& other)
    : octree_(other.octree_ ? std::make_unique<broadphase::NObjectsOctree>(*other.octree_)
                            : nullptr) {}
SelfBroadPhaseScratch::SelfBroadPhaseScratch(SelfBroadPhaseScratch&&) noexcept = default;
SelfBroadPhaseScratch& SelfBroadPhaseScratch::operator=(const SelfBroadPhaseScratch& other) {
  if (this != &other) *this = SelfBroadPhaseScratch(other);
  return *this;
}
SelfBroadPhaseScratch& SelfBroadPhaseScratch::operator=(SelfBroadPhaseScratch&&) noexcept = default;
SelfBroadPhaseScratch::~SelfBroadPhaseScratch() = default;

void SelfBroadPhaseScratch::reset(broadphase::NObjectsOctree octree) {
  octree_ = std::make_unique<broadphase::NObjectsOctree>(std::move(octree));
}

namespace detail {

broadphase::NObjectsOctree SelfCollision::makeBroadPhase() const {
  broadphase::NObjectsOctree::Options o;
  o.leaf_capacity = leaf_capacity;
  // Links are centimetres to metres across in a universe of a few metres: 8 levels (cells of
  // 1/256 of the reach) are already finer than any link.
  o.max_depth = 8;
  broadphase::Aabb root{root_box_W.min(), root_box_W.max()};
  if (root_box_W.isEmpty()) root = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  broadphase::NObjectsOctree tree(root, o);
  // Every link starts as a point at the root's centre; the first check moves them all.
  const Eigen::Vector3d c = (root.min + root.max) / 2;
  for (std::size_t i = 0; i < self_links.size(); ++i) tree.add({c, c});
  tree.rebalance();
  return tree;
}

void SelfCollision::placeCentres(const LinkModels& links, CheckScratch& scratch) {
  const std::size_t n = links.links.size();
  scratch.centres_W.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    scratch.centres_W[i] =
        scratch.robot.linkPose(links.links[i].link) * links.self_voxels[i]->center_L;
  }
}

bool SelfCollision::linksHit(const LinkVoxels& a, const Eigen::Isometry3d& X_WA,
                             const LinkVoxels& b, const Eigen::Isometry3d& X_WB,
                             const Eigen::Vector3d& cb_W, CheckerPath path,
                             CollisionScratch& fused) const {
  // B's source tree placed in A's frame, tested against A's source tree. A voxel of A that a
  // moved voxel of B overlaps lies in A's box, so the boxes of their black voxels must overlap
  // (much tighter than the spheres for long links). Only the rotation is formed for the test.
  const Eigen::Matrix3d R_AW = X_WA.linear().transpose();
  const Eigen::Matrix3d R_AB = R_AW * X_WB.linear();
  if (!boxesMeet(a, X_WA, R_AB, b, cb_W)) return false;
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  X_AB.linear() = R_AB;
  X_AB.translation() = R_AW * (X_WB.translation() - X_WA.translation());
  if (path == CheckerPath::kFused) {
    return collides(*b.movable, X_AB, a.source, rounding, fused);
  }
  return intersects(moveTree(b.source, X_AB, a.source.grid(), rounding), a.source);
}

bool SelfCollision::pairStagesHit(const SelfPair& p, const LinkModels& links, CheckerPath path,
                                  CheckScratch& scratch) const {
  if (p.table) {
    const JointSpaceTable::Cell cell = p.table->lookup(scratch.robot.joint_values.data());
    if (cell != JointSpaceTable::kUnknown) return cell == JointSpaceTable::kColliding;
  }
  return linksHit(*links.self_voxels[p.a], scratch.robot.linkPose(links.links[p.a].link),
                  *links.self_voxels[p.b], scratch.robot.linkPose(links.links[p.b].link),
                  scratch.centres_W[p.b], path, scratch.fused);
}

bool SelfCollision::pairsInCollision(const LinkModels& links, CheckerPath path,
                                     CheckScratch& scratch) const {
  placeCentres(links, scratch);
  // The sphere test inline, with the centres' address held across the loop: most pairs stop
  // there, so the loop is a few instructions per pair.
  const Eigen::Vector3d* centres = scratch.centres_W.data();
  for (const SelfPair& p : pairs) {
    if (spheresMeet(p, centres[p.a], centres[p.b]) && pairStagesHit(p, links, path, scratch)) {
      return true;
    }
  }
  return false;
}

std::vector<std::size_t> SelfCollision::hitPairs(const LinkModels& links, CheckerPath path,
                                                 CheckScratch& scratch, bool all) const {
  std::vector<std::size_t> hits;
  placeCentres(links, scratch);
  for (std::size_t i = 0; i < pairs.size() && (all || hits.empty()); ++i) {
    if (pairHits(i, links, path, scratch)) hits.push_back(i);
  }
  return hits;
}

bool SelfCollision::broadPhaseInCollision(const LinkModels& links, CheckerPath path,
                                          CheckScratch& scratch) const {
  // Created lazily for scratch made by hand (or for another model): once per thread, not per
  // query.
  broadphase::NObjectsOctree* tree = scratch.self_broad_phase.get();
  if (tree == nullptr || tree->objectCount() != self_links.size()) {
    scratch.self_broad_phase.reset(makeBroadPhase());
    tree = scratch.self_broad_phase.get();
  }
  // Each link's box bounds its bounding sphere grown by its voxel diagonal, slightly padded: two
  // links that pass linksHit's pre-test (centre distance <= r_a + r_b + diagonal) then always have
  // overlapping boxes even after rounding, so every pair the all-pairs loop would test in depth is
  // a candidate here.
  placeCentres(links, scratch);
  for (std::size_t i = 0; i < self_links.size(); ++i) {
    const auto slot = static_cast<std::size_t>(self_links[i]);
    const LinkVoxels& v = *links.self_voxels[slot];
    const Eigen::Vector3d& c = scratch.centres_W[slot];
    const double r = (v.radius + v.source_diagonal) * (1 + 1e-9) + 1e-9;
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(r);
    tree->move(static_cast<std::uint32_t>(i), {c - half, c + half});
  }
  const std::size_t m = self_links.size();
  bool hit = false;
  tree->forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) {
    if (hit) return;
    const std::int32_t pair = pair_of[a * m + b];
    if (pair >= 0) hit = pairHits(static_cast<std::size_t>(pair), links, path, scratch);
  });
  return hit;
}

}  // namespace detail
}  // namespace octomotion
