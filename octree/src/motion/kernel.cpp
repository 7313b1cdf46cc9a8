#include "internal/kernel.h"

#include <string>

#include "octomotion/error.h"

namespace octomotion::detail {

MotionFrame makeMotionFrame(const Eigen::Isometry3d& X_WS, const WorldGrid& source,
                            const WorldGrid& target, const char* what) {
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
  f.n_cross = -1;
  f.side = static_cast<double>(target.sideVoxels());
  return f;
}

void addEdgeAxes(MotionFrame& f) {
  constexpr int kNext[3] = {1, 2, 0}, kPrev[3] = {2, 0, 1};
  f.n_cross = 0;
  for (int i = 0; i < 3; ++i) {
    const int i1 = kNext[i], i2 = kPrev[i];
    for (int j = 0; j < 3; ++j) {
      // L = e_i x R_j, written out: component i is 0, the other two are R_j's, rotated.
      const double n2 = f.R[i1][j] * f.R[i1][j] + f.R[i2][j] * f.R[i2][j];
      if (n2 < 1e-12) continue;  // |L| < 1e-6: edges (nearly) parallel
      const double inv = 1.0 / std::sqrt(n2);
      MotionFrame::Axis& ax = f.cross[f.n_cross++];
      ax.L[i] = 0.0;
      ax.L[i1] = -f.R[i2][j] * inv;
      ax.L[i2] = f.R[i1][j] * inv;
      ax.rV = 0.5 * (std::fabs(ax.L[i1]) + std::fabs(ax.L[i2]));
      // |u . R_k| over the other two columns; u . R_j is 0 (to the 1e-14 of snappedRotation).
      const int k1 = kNext[j], k2 = kPrev[j];
      ax.cS = std::fabs(ax.L[i1] * f.R[i1][k1] + ax.L[i2] * f.R[i2][k1]) +
              std::fabs(ax.L[i1] * f.R[i1][k2] + ax.L[i2] * f.R[i2][k2]);
    }
  }
}

}  // namespace octomotion::detail
