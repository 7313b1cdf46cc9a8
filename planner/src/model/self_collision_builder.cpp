// CollisionModelBuilder's self-collision steps: the checked pairs, their joint-space tables
// (classified on worker threads) and the broad phase's index.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>
#include <system_error>
#include <thread>

#include "internal/collision_model_builder.h"
#include "internal/sampling.h"

namespace octomotion::detail {

namespace {

using Clock = std::chrono::steady_clock;

// Self-pair table oracles have at least the tolerance's double and at most this many voxels
// across the link's longest side (time and memory stay those of a 256^3 surface).
constexpr double kOracleVoxelsAcross = 256;

}  // namespace

// The tables' inside/outside oracles: conservative trees fine enough that "black and more than
// a voxel diagonal from the surface" certifies shallow contacts too (one per link, on demand).
const Octree* CollisionModelBuilder::oracle(int link) {
  auto it = oracles_.find(link);
  if (it == oracles_.end()) {
    const auto s = static_cast<std::size_t>(link);
    const double extent = boxes_L_[s].sizes().maxCoeff();
    const double res = std::min(
        link_res_, std::max(2 * options_.self_pair_table_tolerance, extent / kOracleVoxelsAcross));
    CollisionModelOptions conservative = options_;
    conservative.rounding = Rounding::kConservative;
    it = oracles_
             .emplace(link, voxelizeLink(robot_.link(link), element_meshes_[s], boxes_L_[s], res,
                                         conservative, false)
                                .source)
             .first;
  }
  return &it->second;
}

// The checked pairs whose links are both modelled, and among them those that get a joint-space
// table: their pose depends on few variables and their tree test runs often enough to be worth
// the build. The oracles are made here, so the jobs only read shared state.
std::vector<CollisionModelBuilder::TableJob> CollisionModelBuilder::collectSelfPairs() {
  const bool tables = options_.self_pair_tables && options_.rounding == Rounding::kConservative;
  std::vector<TableJob> jobs;
  for (const auto& [a, b] : robot_.checkedPairs()) {
    const int sa = links_.link_slot[static_cast<std::size_t>(a)];
    const int sb = links_.link_slot[static_cast<std::size_t>(b)];
    if (sa < 0 || sb < 0 || folded_pairs_.count({a, b}) > 0) continue;
    const double pair_reach =
        SelfCollision::spheresReach(*links_.self_voxels[static_cast<std::size_t>(sa)],
                                    *links_.self_voxels[static_cast<std::size_t>(sb)]);
    SelfPair pair{static_cast<std::size_t>(sa), static_cast<std::size_t>(sb),
                  pair_reach * pair_reach, nullptr};
    const std::vector<int> vars = tables ? pairVariables(robot_, a, b) : std::vector<int>{};
    if (tables && vars.size() <= options_.self_pair_table_max_variables &&
        treeTestShare(pair, vars) >= kSelfPairTableMinShare) {
      auto side = [&](int link) {
        const auto s = static_cast<std::size_t>(link);
        return SelfPairLink{link, element_meshes_[s], oracle(link), geometry_extent_[s]};
      };
      jobs.push_back({self_.pairs.size(), side(a), side(b), std::nullopt, 0, nullptr});
    }
    self_.pairs.push_back(pair);
  }
  report_.self_pairs = self_.pairs.size();
  return jobs;
}

// Classifies the jobs' tables with FCL, on as many threads as the machine offers (fewer when
// threads cannot be had: the same tables). Errors are kept in the jobs.
void CollisionModelBuilder::classifyPairTables(std::vector<TableJob>& jobs) const {
  SelfPairTableOptions table_options;
  table_options.tolerance = options_.self_pair_table_tolerance;
  table_options.max_cells = options_.self_pair_table_max_cells;
  std::atomic<std::size_t> next_job{0};
  auto work = [&] {
    for (std::size_t j; (j = next_job++) < jobs.size();) {
      TableJob& job = jobs[j];
      try {
        const auto t0 = Clock::now();
        job.table = buildSelfPairTable(robot_, job.a, job.b, table_options);
        job.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      } catch (...) {
        job.error = std::current_exception();
      }
    }
  };
  const std::size_t threads_wanted =
      std::min<std::size_t>(jobs.size(), std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < threads_wanted; ++t) {
    try {
      helpers.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: fewer workers, the same tables
    }
  }
  work();
  for (std::thread& t : helpers) t.join();
}

// Attaches the classified tables to their pairs, in the pairs' order, and reports them.
void CollisionModelBuilder::keepPairTables(std::vector<TableJob>& jobs) {
  for (TableJob& job : jobs) {
    if (job.error) std::rethrow_exception(job.error);
    if (!job.table) continue;
    const JointSpaceTable& table = *job.table;
    SelfPairTableReport r;
    r.link_a = robot_.link(job.a.link).name;
    r.link_b = robot_.link(job.b.link).name;
    r.variables = table.dims();
    r.depth = table.depth();
    r.nodes = table.nodeCount();
    r.bytes = table.bytes();
    r.classified = table.classified();
    r.free_fraction = table.volumeFractions()[JointSpaceTable::kFree];
    r.colliding_fraction = table.volumeFractions()[JointSpaceTable::kColliding];
    r.build_seconds = job.seconds;
    self_.pair_tables.push_back(std::make_unique<const JointSpaceTable>(std::move(*job.table)));
    self_.pairs[job.pair].table = self_.pair_tables.back().get();
    report_.self_pair_tables.push_back(std::move(r));
  }
}

double CollisionModelBuilder::treeTestShare(const SelfPair& pair,
                                            const std::vector<int>& vars) const {
  std::vector<double> q = middleConfiguration(robot_);
  RobotData data = robot_.makeData();
  std::mt19937_64 rng(1);
  int reached = 0;
  constexpr int kSamples = 256;
  const LinkVoxels& a = *links_.self_voxels[pair.a];
  const LinkVoxels& b = *links_.self_voxels[pair.b];
  for (int i = 0; i < kSamples; ++i) {
    for (int v : vars) {
      const auto var = static_cast<std::size_t>(v);
      q[var] = uniformIn(robot_.variables()[var], rng);
    }
    robot_.forwardKinematics(q.data(), q.size(), data);
    const Eigen::Isometry3d& X_WA = data.linkPose(links_.links[pair.a].link);
    const Eigen::Isometry3d& X_WB = data.linkPose(links_.links[pair.b].link);
    const Eigen::Vector3d ca_W = X_WA * a.center_L, cb_W = X_WB * b.center_L;
    const Eigen::Matrix3d R_AB = X_WA.linear().transpose() * X_WB.linear();
    if (SelfCollision::spheresMeet(pair, ca_W, cb_W) &&
        SelfCollision::boxesMeet(a, X_WA, R_AB, b, cb_W)) {
      ++reached;
    }
  }
  return static_cast<double>(reached) / kSamples;
}

// The self-collision broad phase's index: the links in some pair, and which of their pairs
// count; its root is the reach box grown by the largest link sphere, so link boxes stay inside
// it (a box leaving it would only cost a re-root, never a wrong answer).
void CollisionModelBuilder::indexSelfBroadPhase() {
  std::vector<int> id_of_slot(links_.links.size(), -1);
  for (const SelfPair& p : self_.pairs) id_of_slot[p.a] = id_of_slot[p.b] = 0;
  for (std::size_t slot = 0; slot < links_.links.size(); ++slot) {
    if (id_of_slot[slot] < 0) continue;
    id_of_slot[slot] = static_cast<int>(self_.self_links.size());
    self_.self_links.push_back(static_cast<int>(slot));
  }
  const std::size_t m = self_.self_links.size();
  self_.pair_of.assign(m * m, -1);
  for (std::size_t i = 0; i < self_.pairs.size(); ++i) {
    const auto a = static_cast<std::size_t>(id_of_slot[self_.pairs[i].a]);
    const auto b = static_cast<std::size_t>(id_of_slot[self_.pairs[i].b]);
    self_.pair_of[a * m + b] = static_cast<std::int32_t>(i);
  }
  double max_radius = 0;
  for (const int slot : self_.self_links) {
    max_radius = std::max(max_radius, links_.self_voxels[static_cast<std::size_t>(slot)]->radius);
  }
  self_.root_box_W = Eigen::AlignedBox3d(report_.reach_W.min().array() - max_radius,
                                         report_.reach_W.max().array() + max_radius);
  report_.self_links = m;
}

// kAuto picks the broad phase from kSelfBroadPhaseAutoLinks links in self pairs.
void CollisionModelBuilder::resolveSelfBroadPhase() {
  switch (options_.self_broad_phase) {
    case SelfBroadPhase::kAuto:
      self_.strategy = static_cast<int>(self_.self_links.size()) >= kSelfBroadPhaseAutoLinks
                           ? SelfBroadPhase::kNObjectsOctree
                           : SelfBroadPhase::kPairs;
      break;
    default:
      self_.strategy = options_.self_broad_phase;
  }
  report_.self_broad_phase = self_.strategy;
}

}  // namespace octomotion::detail
