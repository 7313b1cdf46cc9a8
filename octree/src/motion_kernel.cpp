#include "motion_kernel.h"

#include <string>

#include "octomotion/error.h"

namespace octomotion::motion_detail {

MotionFrame makeMotionFrame(const Eigen::Isometry3d& X_WS, const WorldGrid& source,
                            const WorldGrid& target, Rounding rounding, const char* what) {
  validatePose(X_WS, what);
  const Eigen::Matrix3d R = snappedRotation(X_WS.linear());
  const Eigen::Vector3d T = X_WS.translation();
  MotionFrame f{};
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
      const Eigen::Vector3d L = Eigen::Vector3d::Unit(i).cross(R.col(j));
      const double n = L.norm();
      if (n < 1e-6) continue;
      MotionFrame::Axis& ax = f.cross[f.n_cross++];
      const Eigen::Vector3d u = L / n;
      ax.L[0] = u[0];
      ax.L[1] = u[1];
      ax.L[2] = u[2];
      ax.rV = 0.5 * u.cwiseAbs().sum();
      ax.cS = std::fabs(u.dot(R.col(0))) + std::fabs(u.dot(R.col(1))) + std::fabs(u.dot(R.col(2)));
    }
  }
  f.side = static_cast<double>(target.sideVoxels());
  return f;
}

}  // namespace octomotion::motion_detail
