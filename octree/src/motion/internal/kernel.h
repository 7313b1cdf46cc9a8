// Private geometry shared by moveTree and collides. Both decide a target voxel's colour with the
// SAME inline predicate on the SAME moved cube centre (computed by the same expression), so the
// fused query answers bit for bit what moveTree + intersects would. Pruning tests keep a margin
// of a few kMotionTieTolerance on the safe side, far above the ~1e-9 voxel rounding noise.
//
// Numerics: voxel and cube coordinates are exact integers (cube centres are exact halves), so
// the only rounding is in the pose: the moved centre g = A u + b carries an absolute error of a
// few ulps of max(|A u|, |b|) <= 2^21 voxels, i.e. < 1e-9 voxel even at depth 21, and every test
// then works on the small difference d = (target point - g), rotated by R only — never on large
// rotated coordinates. A 90° rotation given as a floating-point matrix (entries 6e-17) moves a
// point by < 2^21 * 6e-17 ~ 1e-10 voxel: far inside the tie tolerance.
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "octomotion/motion/pose.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/octree/world_grid.h"

namespace octomotion::detail {

// Everything about one pose that the per-cube tests need, in target-grid voxel units:
// a source grid point u (source voxels) moves to g = A u + b (target voxels), A = s R.
struct MotionFrame {
  double R[3][3];     // rotation S -> W, R[i][j] = row i, column j
  double A[3][3];     // s R
  double absA[3][3];  // |A_ij|: moved source box half-extents on the target axes
  double b[3];        // target grid coordinates of the source grid's origin corner
  double s;           // source voxel size / target voxel size
  double rowsum[3];   // sum_j |R_ij|: half-extent on target axis i of a moved cube of half 1
  double colsum[3];   // sum_i |R_ij|: half-extent on source axis j of an upright cube of half 1
  // The nine edge-edge axes e_i x R_j of the separating-axis test, unit length; axes shorter
  // than 1e-6 before normalisation (edges parallel, e.g. 90° rotations) are skipped: the face
  // axes then decide. Filled by addEdgeAxes (n_cross < 0 until then).
  struct Axis {
    double L[3];
    double rV;  // half-projection of a unit target voxel
    double cS;  // half-projection of a moved cube of half 1
  };
  Axis cross[9];
  int n_cross;
  double side;  // target universe side, voxels
};

// Validates the pose (throws InvalidArgument naming `what`). Without the edge axes (n_cross = -1):
// conservative voxelAccepts needs addEdgeAxes first. collides adds them at its first probe, as
// most near-miss queries never probe a voxel; moveTree adds them at once.
MotionFrame makeMotionFrame(const Eigen::Isometry3d& X_WS, const WorldGrid& source,
                            const WorldGrid& target, const char* what);
// Fills the edge axes (same values whenever called).
void addEdgeAxes(MotionFrame& f);

// Half the side of a cube of `level` (0 <= level <= kMaxDepth + 1), exactly.
inline double halfSide(int level) {
  return 0.5 * static_cast<double>(std::uint32_t{1} << level);
}

// Centre of a cube in its grid's voxel coordinates (exact in double).
inline void cubeCentre(const Cube& c, double u[3]) {
  const double h = halfSide(c.level);
  u[0] = static_cast<double>(c.origin.x) + h;
  u[1] = static_cast<double>(c.origin.y) + h;
  u[2] = static_cast<double>(c.origin.z) + h;
}

// Half side, in target voxels, of a moved source cube of `level`.
inline double movedHalf(const MotionFrame& f, int level) {
  return f.s * halfSide(level);
}

// g = A u + b, always evaluated in this order.
inline void movePoint(const MotionFrame& f, const double u[3], double g[3]) {
  for (int i = 0; i < 3; ++i)
    g[i] = f.A[i][0] * u[0] + f.A[i][1] * u[1] + f.A[i][2] * u[2] + f.b[i];
}

// The colour rule (§3 for kCenter) for target voxel v and one moved black cube with centre g
// and half side hs (target voxels).
inline bool voxelAccepts(const MotionFrame& f, Rounding rounding, const Voxel& v, const double g[3],
                         double hs) {
  const double d[3] = {static_cast<double>(v.x) + 0.5 - g[0], static_cast<double>(v.y) + 0.5 - g[1],
                       static_cast<double>(v.z) + 0.5 - g[2]};
  if (rounding == Rounding::kCenter) {
    // Centre on or inside the moved cube: test in the cube's own (source) axes.
    const double lim = hs + kMotionTieTolerance;
    for (int j = 0; j < 3; ++j) {
      const double q = f.R[0][j] * d[0] + f.R[1][j] * d[1] + f.R[2][j] * d[2];
      if (!(std::fabs(q) <= lim)) return false;
    }
    return true;
  }
  // Conservative: the voxel and the moved cube overlap by more than the tolerance on every
  // separating axis (exact box-box SAT: 3 + 3 face axes, 9 edge axes).
  constexpr double tol = kMotionTieTolerance;
  for (int i = 0; i < 3; ++i) {
    if (!(std::fabs(d[i]) < 0.5 + hs * f.rowsum[i] - tol)) return false;
  }
  for (int j = 0; j < 3; ++j) {
    const double q = f.R[0][j] * d[0] + f.R[1][j] * d[1] + f.R[2][j] * d[2];
    if (!(std::fabs(q) < 0.5 * f.colsum[j] + hs - tol)) return false;
  }
  // The edge axes must have been added (n_cross >= 0; see makeMotionFrame).
  for (int a = 0; a < f.n_cross; ++a) {
    const MotionFrame::Axis& ax = f.cross[a];
    const double p = ax.L[0] * d[0] + ax.L[1] * d[1] + ax.L[2] * d[2];
    if (!(std::fabs(p) < ax.rV + hs * ax.cS - tol)) return false;
  }
  return true;
}

// Margin added to the face-axis rejection bounds so that a rejected target cube surely holds
// no voxel the predicate above accepts: centre mode accepts up to tol outside (projected on a
// target axis up to sqrt(3) tol), plus half a tolerance of slack; conservative mode needs an
// overlap of tol, so a cube overlapping by at most tol/2 is rejected.
inline double rejectMargin(Rounding rounding) {
  return rounding == Rounding::kCenter ? 2.5 * kMotionTieTolerance : -0.5 * kMotionTieTolerance;
}

// Half side of the region of a target cube of `level` that matters: the box of its voxel
// centres (centre mode) or the whole cube (conservative).
inline double cellReach(Rounding rounding, int level) {
  const double h = halfSide(level);
  return rounding == Rounding::kCenter ? h - 0.5 : h;
}

}  // namespace octomotion::detail
