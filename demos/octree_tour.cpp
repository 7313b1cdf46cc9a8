// A short tour of the octree library: voxelize a small scene and an object, compare the compact
// tree's size with a dense voxel array and with OctoMap's node layout, test the object against
// the scene at a few placements, and write/read the tree as an octomotion file and as an OctoMap
// .bt file. Exits 0 when every check holds.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "octomotion/error.h"
#include "octomotion/octree/io.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/traversal.h"
#include "octomotion/octree/voxelize.h"

using namespace octomotion;

namespace {

Eigen::Isometry3d at(double x, double y, double z, double yaw_deg = 0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translate(Eigen::Vector3d(x, y, z));
  X.rotate(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  return X;
}

std::string kib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f KiB", bytes / 1024.0);
  return buf;
}

void describe(const char* name, const Octree& t) {
  const double side = t.grid().sideVoxels();
  const double dense_bits = side * side * side / 8.0;  // one bit per voxel, the densest array
  const OctoMapFootprint om = octomapFootprint(t);
  std::printf("%-12s %8zu internal nodes, %8zu black leaves, %10llu black voxels\n", name,
              t.internalNodeCount(), t.blackLeafCount(),
              static_cast<unsigned long long>(t.blackVoxelCount()));
  std::printf("%-12s compact %s (8 B/node) | dense bit array %s | OctoMap layout %s (%zu nodes)\n",
              "", kib(static_cast<double>(t.internalNodeCount() * sizeof(OctreeNode))).c_str(),
              kib(dense_bits).c_str(), kib(static_cast<double>(om.bytes)).c_str(), om.nodes);
}

}  // namespace

int main() {
  try {
    // A 5.12 m universe of 2 cm voxels (depth 8), minimum corner at the world origin.
    const WorldGrid grid(Eigen::Vector3d::Zero(), 0.02, 8);
    const Rounding rounding = Rounding::kConservative;
    std::printf("universe: %u^3 voxels of %.0f mm, %.2f m per side, rounding %s\n",
                grid.sideVoxels(), grid.voxelSize() * 1000, grid.sideMetres(), toString(rounding));

    // The scene: a floor slab, a table top on a post, a ball on the table, a wall.
    Octree env(grid);
    env = unite(env, voxelize(grid, Box{{2.5, 2.5, 0.05}}, at(2.56, 2.56, 0.05), rounding));
    env = unite(env, voxelize(grid, Box{{0.6, 0.4, 0.03}}, at(2.0, 2.0, 0.80, 20), rounding));
    env = unite(env, voxelize(grid, Cylinder{0.05, 0.7}, at(2.0, 2.0, 0.43), rounding));
    env = unite(env, voxelize(grid, Sphere{0.15}, at(2.2, 2.1, 0.98), rounding));
    env = unite(env, voxelize(grid, Box{{0.05, 1.5, 1.0}}, at(3.6, 2.5, 1.1, 5), rounding));
    describe("environment", env);

    // The object, voxelized at each placement from its exact shape (never from a moved tree):
    // a 30 cm x 10 cm x 10 cm bar with a ball at one end.
    auto object = [&](const Eigen::Isometry3d& X_WO) {
      return unite(voxelize(grid, Box{{0.15, 0.05, 0.05}}, X_WO, rounding),
                   voxelize(grid, Sphere{0.08}, X_WO * at(0.15, 0, 0), rounding));
    };
    describe("object", object(at(1.0, 1.0, 1.5)));

    struct Placement {
      const char* what;
      Eigen::Isometry3d X_WO;
      bool expect_hit;
    };
    const Placement placements[] = {
        {"in free air above the table", at(2.0, 2.0, 1.6, 10), false},
        {"through the ball on the table", at(2.1, 2.1, 1.0, 30), true},
        {"4 cm above the table top", at(1.7, 1.9, 0.95, 20), false},
        {"sunk into the floor", at(1.0, 3.0, 0.08, 45), true},
        {"4 cm short of the wall", at(3.28, 2.5, 1.2, 5), false},
    };
    bool all_ok = true;
    std::printf("placements:\n");
    for (const Placement& p : placements) {
      const Octree obj = object(p.X_WO);
      const bool hit = intersects(obj, env);
      std::uint64_t shared = 0;
      for (const Cube& c : overlappingCubes(obj, env)) shared += std::uint64_t{1} << (3 * c.level);
      std::printf("  %-30s %-9s %6llu shared voxels%s\n", p.what, hit ? "COLLIDES" : "free",
                  static_cast<unsigned long long>(shared),
                  hit == p.expect_hit ? "" : "   <-- unexpected");
      all_ok = all_ok && hit == p.expect_hit;
    }

    // Files: our own format (the node array as it is in memory) and OctoMap's .bt.
    const std::filesystem::path dir = std::filesystem::temp_directory_path();
    const std::string omt = (dir / "octree_tour_environment.omt").string();
    const std::string bt = (dir / "octree_tour_environment.bt").string();
    saveOctree(env, omt);
    const bool omt_same = loadOctree(omt) == env;
    exportOctoMap(env, bt);
    const Octree from_bt = importOctoMap(bt, grid, Rounding::kCenter);
    const bool bt_same = from_bt == env;
    std::printf("files: %s %s (%s), %s %s (%s)\n", omt.c_str(),
                kib(static_cast<double>(std::filesystem::file_size(omt))).c_str(),
                omt_same ? "reloads identical" : "RELOAD DIFFERS", bt.c_str(),
                kib(static_cast<double>(std::filesystem::file_size(bt))).c_str(),
                bt_same ? "reimports identical" : "REIMPORT DIFFERS");
    std::filesystem::remove(omt);
    std::filesystem::remove(bt);
    all_ok = all_ok && omt_same && bt_same;
    std::printf("%s\n", all_ok ? "tour complete: all checks hold" : "tour FAILED");
    return all_ok ? 0 : 1;
  } catch (const Error& e) {
    std::fprintf(stderr, "octree_tour: %s\n", e.what());
    return 1;
  }
}
