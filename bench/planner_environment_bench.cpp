// Many separate environment objects: is one merged environment octree (what the planner builds)
// or per-object octrees behind an N-objects octree broad phase over the object and link boxes
// faster for the environment half of a check? Scenes: 1 ... 500 random boxes (2 - 8 cm sides,
// random orientation) in a 1.4 m cube around a 6-link snake (8 x 4 x 4 cm box links, 10 cm
// pitch, +-1.5 rad), 1 cm voxels, 1024 uniform random states, fused query (collides()).
//   merged:     per link, sphere vs. environment box, then collides(link, merged tree);
//   per-object: link boxes move in an N-objects octree (leaf capacity 16) holding the static
//               object boxes; each (link, object) candidate runs collides(link, object tree).
//   merged + filter: the merged tree, tested only for links whose box meets some object box,
//               found with the N-objects octree (method 2) or a plain loop over the boxes (3).
// All stop at the first contact and give the same answers (counted in "hit").
//
//   build/bench/planner_environment_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true  (one command line)
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "octomotion/broadphase/n_objects_octree.h"
#include "octomotion/motion/collides.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/voxelize.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"
#include "snake_robot.h"

namespace {

using namespace octomotion;
using broadphase::Aabb;
using broadphase::NObjectsOctree;

constexpr double kRes = 0.01;

using test::snakeUrdf;

struct LinkTree {
  Octree source{WorldGrid(Eigen::Vector3d::Zero(), 1.0, 1)};
  std::unique_ptr<MovableSource> movable;
  Eigen::Vector3d center_L;
  double radius = 0;
};

struct Scene {
  RobotModel robot = RobotModel::fromUrdfString(snakeUrdf(6, 1.5), "snake.urdf", ".");
  WorldGrid grid = fitGrid(
      Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-0.8), Eigen::Vector3d::Constant(0.8)), kRes);
  std::vector<LinkTree> links;
  std::vector<Octree> objects;
  std::vector<Aabb> object_boxes;
  Octree merged{grid};
  Eigen::AlignedBox3d merged_box;

  explicit Scene(int count) {
    const Box link_box{Eigen::Vector3d(0.04, 0.02, 0.02)};
    const Eigen::Isometry3d X_LE(Eigen::Translation3d(0.05, 0, 0));
    for (int l = 0; l < robot.linkCount(); ++l) {
      LinkTree lt;
      const WorldGrid g = fitGrid(
          Eigen::AlignedBox3d(Eigen::Vector3d(0, -0.03, -0.03), Eigen::Vector3d(0.1, 0.03, 0.03)),
          kRes);
      lt.source = voxelize(g, link_box, X_LE, Rounding::kConservative);
      lt.movable = std::make_unique<MovableSource>(lt.source);
      const auto b = *lt.source.bounds();
      const Eigen::Vector3d lo = g.cubeMin(Cube{0, b.min}), hi = g.cubeMax(Cube{0, b.max});
      lt.center_L = (lo + hi) / 2;
      lt.radius = (hi - lo).norm() / 2;
      links.push_back(std::move(lt));
    }
    std::mt19937_64 rng(static_cast<std::uint64_t>(count));
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < count; ++i) {
      const Box box{Eigen::Vector3d(0.01 + 0.03 * std::abs(u(rng)), 0.01 + 0.03 * std::abs(u(rng)),
                                    0.01 + 0.03 * std::abs(u(rng)))};
      Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
      X_WO.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
      X_WO.translation() = 0.7 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      Octree tree = voxelize(grid, box, X_WO, Rounding::kConservative);
      const auto b = *tree.bounds();
      object_boxes.push_back({grid.cubeMin(Cube{0, b.min}), grid.cubeMax(Cube{0, b.max})});
      merged = unite(merged, tree);
      objects.push_back(std::move(tree));
    }
    const auto b = *merged.bounds();
    merged_box = Eigen::AlignedBox3d(grid.cubeMin(Cube{0, b.min}), grid.cubeMax(Cube{0, b.max}));
  }
};

double distanceToBox(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  return (p - p.cwiseMax(box.min()).cwiseMin(box.max())).norm();
}

void BM_EnvironmentCheck(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const int method = static_cast<int>(state.range(1));
  const bool per_object = method == 1;
  const Scene scene(count);
  const RobotModel& robot = scene.robot;
  std::mt19937_64 rng(5);
  std::vector<RobotData> poses;
  for (int k = 0; k < 1024; ++k) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    RobotData d = robot.makeData();
    robot.forwardKinematics(q.data(), q.size(), d);
    poses.push_back(std::move(d));
  }
  CollisionScratch fused;
  // Per-object broad phase: objects 0..count-1 static, links after them.
  NObjectsOctree::Options o;
  o.leaf_capacity = 16;
  NObjectsOctree tree(Aabb{Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)}, o);
  for (const Aabb& b : scene.object_boxes) tree.add(b);
  const auto first_link = static_cast<std::uint32_t>(scene.object_boxes.size());
  for (std::size_t l = 0; l < scene.links.size(); ++l)
    tree.add({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  std::size_t i = 0;
  std::int64_t hits = 0;
  for (auto _ : state) {
    const RobotData& d = poses[i];
    bool hit = false;
    if (method == 2 || method == 3) {
      // Merged tree, but a link is tested only if its box meets some object's box: found with
      // the N-objects octree (2) or a plain loop over the object boxes (3).
      std::uint64_t near = 0;  // bit l: link l meets an object box
      if (method == 2) {
        for (std::size_t l = 0; l < scene.links.size(); ++l) {
          const LinkTree& lt = scene.links[l];
          const Eigen::Vector3d c = d.linkPose(static_cast<int>(l)) * lt.center_L;
          const Eigen::Vector3d r = Eigen::Vector3d::Constant(lt.radius + std::sqrt(3.0) * kRes);
          tree.move(first_link + static_cast<std::uint32_t>(l), {c - r, c + r});
        }
        tree.forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) {
          if (a < first_link && b >= first_link) near |= std::uint64_t{1} << (b - first_link);
        });
      } else {
        for (std::size_t l = 0; l < scene.links.size(); ++l) {
          const LinkTree& lt = scene.links[l];
          const Eigen::Vector3d c = d.linkPose(static_cast<int>(l)) * lt.center_L;
          const Eigen::Vector3d r = Eigen::Vector3d::Constant(lt.radius + std::sqrt(3.0) * kRes);
          const Aabb box{c - r, c + r};
          for (const Aabb& ob : scene.object_boxes) {
            if (broadphase::overlaps(box, ob)) {
              near |= std::uint64_t{1} << l;
              break;
            }
          }
        }
      }
      for (std::size_t l = 0; l < scene.links.size() && !hit; ++l) {
        if (!((near >> l) & 1)) continue;
        hit = collides(*scene.links[l].movable, d.linkPose(static_cast<int>(l)), scene.merged,
                       Rounding::kConservative, fused);
      }
    } else if (!per_object) {
      for (std::size_t l = 0; l < scene.links.size() && !hit; ++l) {
        const LinkTree& lt = scene.links[l];
        const Eigen::Isometry3d& X_WL = d.linkPose(static_cast<int>(l));
        if (distanceToBox(X_WL * lt.center_L, scene.merged_box) > lt.radius) continue;
        hit = collides(*lt.movable, X_WL, scene.merged, Rounding::kConservative, fused);
      }
    } else {
      for (std::size_t l = 0; l < scene.links.size(); ++l) {
        const LinkTree& lt = scene.links[l];
        const Eigen::Vector3d c = d.linkPose(static_cast<int>(l)) * lt.center_L;
        const Eigen::Vector3d r = Eigen::Vector3d::Constant(lt.radius + std::sqrt(3.0) * kRes);
        tree.move(first_link + static_cast<std::uint32_t>(l), {c - r, c + r});
      }
      tree.forEachCandidatePair([&](std::uint32_t a, std::uint32_t b) {
        if (hit || a >= first_link || b < first_link) return;  // object-object or link-link
        const std::size_t l = b - first_link;
        hit = collides(*scene.links[l].movable, d.linkPose(static_cast<int>(l)), scene.objects[a],
                       Rounding::kConservative, fused);
      });
    }
    hits += hit;
    benchmark::DoNotOptimize(hit);
    i = (i + 1) % poses.size();
  }
  state.counters["objects"] = count;
  state.counters["hit"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  const char* labels[] = {"merged tree", "per-object trees + N-objects octree",
                          "merged tree + N-objects octree link filter",
                          "merged tree + object-box loop link filter"};
  state.SetLabel(labels[method]);
}

BENCHMARK(BM_EnvironmentCheck)
    ->ArgsProduct({{1, 10, 20, 50, 100, 250, 500}, {0, 1, 2, 3}})
    ->ArgNames({"objects", "method"});

}  // namespace

BENCHMARK_MAIN();
