// Brute-force oracle for the motion tests: the colour rule of moveTree written the naive way
// (world-space transforms with Eigen, every target voxel near every moved black cube).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "dense_grid.h"
#include "octomotion/motion/pose.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"

namespace octomotion::test {

struct OracleCube {
  Eigen::Vector3d u_c;     // centre, source grid coordinates
  double half_src;         // half side, source voxels
  Eigen::Vector3d g;       // moved centre, target grid coordinates
  Eigen::Matrix3d R;       // axes
  double hs;               // half side, target voxels
  Eigen::Isometry3d X_SW;  // inverse pose
  // Separating axes of the unit voxel box and the moved cube (edge axes normalised, skipped
  // when nearly degenerate: parallel edges), with both half-projections.
  Eigen::Vector3d axes[15];
  double rv[15], rc[15];
  int n_axes = 0;
};

inline std::vector<OracleCube> oracleCubes(const Octree& src, const Eigen::Isometry3d& X,
                                           const WorldGrid& target) {
  std::vector<OracleCube> out;
  const double s = src.grid().voxelSize() / target.voxelSize();
  src.forEachBlackLeaf([&](const Cube& c) {
    OracleCube o;
    const double h = 0.5 * c.side();
    o.u_c = Eigen::Vector3d(c.origin.x + h, c.origin.y + h, c.origin.z + h);
    o.half_src = h;
    o.g = target.toGrid(X * src.grid().toWorld(o.u_c));
    o.R = X.linear();
    o.hs = h * s;
    o.X_SW = X.inverse();
    auto add = [&o](const Eigen::Vector3d& L) {
      o.axes[o.n_axes] = L;
      o.rv[o.n_axes] = 0.5 * L.cwiseAbs().sum();
      o.rc[o.n_axes] = o.hs * (o.R.transpose() * L).cwiseAbs().sum();
      ++o.n_axes;
    };
    for (int i = 0; i < 3; ++i) add(Eigen::Vector3d::Unit(i));
    for (int j = 0; j < 3; ++j) add(o.R.col(j));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d L = Eigen::Vector3d::Unit(i).cross(o.R.col(j));
        if (L.norm() >= 1e-6) add(L.normalized());
      }
    out.push_back(o);
  });
  return out;
}

// Target voxel v against one moved cube, per the documented rule.
inline bool oracleAccepts(const Octree& src, const Eigen::Isometry3d& /*X_WS*/,
                          const WorldGrid& target, const OracleCube& c, const Voxel& v,
                          Rounding rounding) {
  const double tol = kMotionTieTolerance;
  if (rounding == Rounding::kCenter) {
    const Eigen::Vector3d p_S = c.X_SW * target.voxelCenter(v);
    const Eigen::Vector3d u = src.grid().toGrid(p_S);
    const double tol_src = tol * target.voxelSize() / src.grid().voxelSize();
    return ((u - c.u_c).cwiseAbs().array() <= c.half_src + tol_src).all();
  }
  const Eigen::Vector3d d = Eigen::Vector3d(v.x + 0.5, v.y + 0.5, v.z + 0.5) - c.g;
  for (int a = 0; a < c.n_axes; ++a) {
    if (!(std::abs(c.axes[a].dot(d)) < c.rv[a] + c.rc[a] - tol)) return false;
  }
  return true;
}

// Every target voxel near a moved black cube that the rule accepts, passed to `out(v)` (maybe
// more than once).
template <class Out>
void forEachBruteForceVoxel(const Octree& src, const Eigen::Isometry3d& X, const WorldGrid& target,
                            Rounding rounding, Out&& out) {
  const long side = static_cast<long>(target.sideVoxels());
  for (const OracleCube& c : oracleCubes(src, X, target)) {
    const double r = c.hs * std::sqrt(3.0) + 1.0;
    long lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0L, static_cast<long>(std::floor(std::max(-1.0, c.g[a] - r))));
      hi[a] = std::min(side - 1, static_cast<long>(std::floor(std::min(1e12, c.g[a] + r))));
    }
    for (long z = lo[2]; z <= hi[2]; ++z)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long x = lo[0]; x <= hi[0]; ++x) {
          const Voxel v{static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                        static_cast<std::uint32_t>(z)};
          if (oracleAccepts(src, X, target, c, v, rounding)) out(v);
        }
  }
}

// Dense voxelization of the moved black cubes (small depths).
inline DenseGrid bruteForceMove(const Octree& src, const Eigen::Isometry3d& X,
                                const WorldGrid& target, Rounding rounding) {
  DenseGrid out(target.depth());
  forEachBruteForceVoxel(src, X, target, rounding, [&](const Voxel& v) { out.set(v); });
  return out;
}

// The same as a tree, for any depth (sparse).
inline Octree bruteForceMoveTree(const Octree& src, const Eigen::Isometry3d& X,
                                 const WorldGrid& target, Rounding rounding) {
  std::vector<Voxel> voxels;
  forEachBruteForceVoxel(src, X, target, rounding, [&](const Voxel& v) { voxels.push_back(v); });
  return Octree::fromVoxels(target, voxels);
}

inline Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized();
}

// A pose taking the point c_S (frame S) to c_W (world) with a random rotation.
inline Eigen::Isometry3d randomPoseAbout(std::mt19937_64& rng, const Eigen::Vector3d& c_S,
                                         const Eigen::Vector3d& c_W) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = randomRotation(rng).toRotationMatrix();
  X.translation() = c_W - X.linear() * c_S;
  return X;
}

inline Eigen::Vector3d gridCentre(const WorldGrid& g) {
  return g.origin() + Eigen::Vector3d::Constant(0.5 * g.sideMetres());
}

}  // namespace octomotion::test
