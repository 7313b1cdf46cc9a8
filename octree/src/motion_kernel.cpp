#include "motion_kernel.h"

#include <string>

#include "octomotion/error.h"

namespace octomotion::motion_detail {

MotionFrame makeMotionFrame(const Eigen::Isometry3d& X_WS, const WorldGrid& source,
                            const WorldGrid& target, Rounding rounding, const char* what) {
  const Eigen::Matrix3d R = validatedRotation(X_WS, what);
  const Eigen::Vector3d T = X_WS.translation();
  MotionFrame f;  // every field is written below (cross[] up to n_cross)
  f.s = source.voxelSize() / target.voxelSize();
  if (!std::isfinite(f.s))
    throw InvalidArgument(std::string(what) + ": voxel size ratio overflows");
  // Target grid coordinates of the source origin corner; the (possibly large) metric terms are
  // summed before dividing so that a far object brought back by T cancels first.
  const Eigen::Vector3d b = ((R * source.origin() + T) - target.origin()) / target.voxelSize();
  if (!b.allFinite()) throw InvalidArgument(std::string(what) + ": moved origin is not finite");
  for (int i = 0; i < 3; ++i) {
    f.b[i] = b[i];
    f.rowsum[i] = 0;
    f.colsum[i] = 0;
    for (int j = 0; j < 3; ++j) {
      f.R[i][j] = R(i, j);
      f.A[i][j] = f.s * R(i, j);
      f.absA[i][j] = std::fabs(f.A[i][j]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      f.rowsum[i] += std::fabs(R(i, j));
      f.colsum[j] += std::fabs(R(i, j));
    }
  }
  f.n_cross = 0;
  for (int i = 0; i < 3 && rounding == Rounding::kConservative; ++i) {
    for (int j = 0; j < 3; ++j) {
      // L = e_i x R_j, written out: component i is 0, the other two are R_j's, rotated.
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      const double n2 = R(i1, j) * R(i1, j) + R(i2, j) * R(i2, j);
      if (n2 < 1e-12) continue;  // |L| < 1e-6: edges (nearly) parallel
      const double inv = 1.0 / std::sqrt(n2);
      MotionFrame::Axis& ax = f.cross[f.n_cross++];
      ax.L[i] = 0.0;
      ax.L[i1] = -R(i2, j) * inv;
      ax.L[i2] = R(i1, j) * inv;
      ax.rV = 0.5 * (std::fabs(ax.L[i1]) + std::fabs(ax.L[i2]));
      // |u . R_k| over the columns; u . R_j is 0 (to the 1e-14 of snappedRotation).
      ax.cS = 0;
      for (const int k : {(j + 1) % 3, (j + 2) % 3}) {
        ax.cS += std::fabs(ax.L[i1] * R(i1, k) + ax.L[i2] * R(i2, k));
      }
    }
  }
  f.side = static_cast<double>(target.sideVoxels());
  return f;
}

}  // namespace octomotion::motion_detail
