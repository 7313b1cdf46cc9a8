// The conservative builders' contract, checked point by point: every point of a surface lies in
// a closed black voxel of its tree (within the builders' 1e-6-voxel tie). Points are each
// triangle's corners, edge midpoints and centroid, plus random barycentric points.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octree.h"

namespace octomotion::test {

// Whether p_W lies in the closure of a black voxel of `tree`, a voxel counting when p_W is within
// `tie` voxels of it. Points outside the universe are not covered.
inline bool coveredByBlack(const Octree& tree, const Eigen::Vector3d& p_W, double tie = 2e-6) {
  const WorldGrid& grid = tree.grid();
  const Eigen::Vector3d g = grid.toGrid(p_W);
  const double side = static_cast<double>(grid.sideVoxels());
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    if (!(g[a] >= -tie && g[a] <= side + tie)) return false;
    lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(g[a] - tie)));
    hi[a] = std::min<std::int64_t>(static_cast<std::int64_t>(side) - 1,
                                   static_cast<std::int64_t>(std::floor(g[a] + tie)));
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
        if (tree.occupied(Voxel{static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                                static_cast<std::uint32_t>(z)})) {
          return true;
        }
      }
  return false;
}

struct Coverage {
  std::size_t points = 0;
  std::size_t uncovered = 0;
  std::size_t outside = 0;  // points outside the universe (counted apart, not as uncovered)
  std::string first;        // where the first uncovered point is, for the failure message
};

// Samples the mesh (in frame M, placed by X_WM in the tree's world) and counts the points that
// no closed black voxel holds.
inline Coverage surfaceCoverage(const Octree& tree, const TriangleMesh& mesh,
                                const Eigen::Isometry3d& X_WM, int random_per_triangle = 4,
                                std::uint64_t seed = 1) {
  Coverage c;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const WorldGrid& grid = tree.grid();
  const Eigen::Vector3d lo = grid.origin();
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(grid.sideMetres());
  auto check = [&](const Eigen::Vector3d& p_M, std::size_t triangle) {
    const Eigen::Vector3d p = X_WM * p_M;
    ++c.points;
    if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) {
      ++c.outside;
      return;
    }
    if (coveredByBlack(tree, p)) return;
    if (++c.uncovered == 1) {
      std::ostringstream out;
      out.precision(10);
      out << "triangle " << triangle << " point (" << p.transpose() << ") grid ("
          << grid.toGrid(p).transpose() << ")";
      c.first = out.str();
    }
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d& a = mesh.vertices[mesh.triangles[t][0]];
    const Eigen::Vector3d& b = mesh.vertices[mesh.triangles[t][1]];
    const Eigen::Vector3d& d = mesh.vertices[mesh.triangles[t][2]];
    for (const Eigen::Vector3d& p :
         {a, b, d, Eigen::Vector3d((a + b) / 2), Eigen::Vector3d((b + d) / 2),
          Eigen::Vector3d((d + a) / 2), Eigen::Vector3d((a + b + d) / 3)}) {
      check(p, t);
    }
    for (int k = 0; k < random_per_triangle; ++k) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      check(a + u * (b - a) + v * (d - a), t);
    }
  }
  return c;
}

}  // namespace octomotion::test
