// CollisionModelBuilder's folding step (CollisionModelOptions::fold_static): what no joint
// variable can move is tested once, at build time, instead of in every state.
#include <array>
#include <string>
#include <vector>

#include "internal/collision_model_builder.h"
#include "internal/self_pair_tables.h"

namespace octomotion::detail {

namespace {

constexpr CheckerPath kPaths[] = {CheckerPath::kMoveTree, CheckerPath::kFused};

// Whether any joint from `link` up to (not including) `ancestor` moves.
bool movesBelow(const RobotModel& robot, int link, int ancestor) {
  for (int l = link; l != ancestor && l > 0; l = robot.link(l).parent_link) {
    if (robot.joint(robot.link(l).parent_joint).movable()) return true;
  }
  return false;
}

int commonAncestor(const RobotModel& robot, int a, int b) {
  // Parents have smaller indices (depth-first order): climb the larger one.
  while (a != b) {
    if (a > b) {
      a = robot.link(a).parent_link;
    } else {
      b = robot.link(b).parent_link;
    }
  }
  return a;
}

// "(moveTree path only)" when the two paths disagree; empty when both hit.
std::string whichPaths(const std::array<bool, 2>& hits) {
  if (hits[0] && hits[1]) return "";
  return hits[0] ? " (moveTree path only)" : " (fused path only)";
}

}  // namespace

void CollisionModelBuilder::foldStaticLinks() {
  if (!options_.fold_static) return;
  // Any configuration: the folded tests do not depend on it.
  const std::vector<double> q = middleConfiguration(robot_);
  CheckScratch scratch;
  scratch.robot = robot_.makeData();
  robot_.forwardKinematics(q.data(), q.size(), scratch.robot, options_.X_WB);
  auto always = [&](std::array<bool, 2>& always_hits, const std::array<bool, 2>& hits,
                    const std::string& what) {
    if (!hits[0] && !hits[1]) return;
    for (std::size_t p = 0; p < 2; ++p) always_hits[p] = always_hits[p] || hits[p];
    report_.static_collisions.push_back(what + whichPaths(hits));
    warn(options_.warnings,
         "every state is in collision: " + what + whichPaths(hits) + ", and no joint moves it");
  };
  // Links that do not move (fixed-base robots): against the environment, once per path.
  if (!robot_.isFreeFlying()) {
    const double voxel = environment_.tree.grid().voxelSize();
    const bool exact = !environment_.exact_primitives.empty();
    for (std::size_t slot = 0; slot < links_.links.size(); ++slot) {
      LinkTree& lt = links_.links[slot];
      if (!lt.touches_environment || movesBelow(robot_, lt.link, -1)) continue;
      const EnvironmentLinkTest t = links_.environmentTest(slot, voxel, exact);
      const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(lt.link);
      std::array<bool, 2> hits{};
      for (CheckerPath path : kPaths) {
        hits[static_cast<std::size_t>(path)] =
            sphereMeetsBox(t, X_WL, environment_.box_W) &&
            environment_.linkHits(t, lt.voxels, X_WL, path, scratch.fused);
      }
      lt.folded = true;
      report_.static_links.push_back(robot_.link(lt.link).name);
      always(environment_.always_hits, hits,
             "link '" + robot_.link(lt.link).name + "' meets the environment");
    }
  }
  // Checked pairs whose relative pose is constant: once per path, then dropped.
  for (const auto& [a, b] : robot_.checkedPairs()) {
    const int sa = links_.link_slot[static_cast<std::size_t>(a)];
    const int sb = links_.link_slot[static_cast<std::size_t>(b)];
    if (sa < 0 || sb < 0) continue;
    const int common = commonAncestor(robot_, a, b);
    if (movesBelow(robot_, a, common) || movesBelow(robot_, b, common)) continue;
    const double reach =
        SelfCollision::spheresReach(*links_.self_voxels[static_cast<std::size_t>(sa)],
                                    *links_.self_voxels[static_cast<std::size_t>(sb)]);
    const SelfPair pair{static_cast<std::size_t>(sa), static_cast<std::size_t>(sb), reach * reach,
                        nullptr};
    std::array<bool, 2> hits{};
    for (CheckerPath path : kPaths) {
      hits[static_cast<std::size_t>(path)] = self_.pairHitsOnce(pair, links_, path, scratch);
    }
    folded_pairs_.insert({a, b});
    report_.constant_pairs.emplace_back(robot_.link(a).name, robot_.link(b).name);
    always(self_.always_hits, hits,
           "links '" + robot_.link(a).name + "' and '" + robot_.link(b).name + "' meet");
  }
}

}  // namespace octomotion::detail
