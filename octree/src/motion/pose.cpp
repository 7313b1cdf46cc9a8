#include "octomotion/motion/pose.h"

#include <cmath>
#include <string>

#include "octomotion/error.h"

namespace octomotion {

namespace {

double orthonormalityError(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
}

// Validates X (see validatePose) and returns max |R^T R - I|.
double checkedOrthonormalityError(const Eigen::Isometry3d& X, const char* what) {
  const Eigen::Matrix3d R = X.linear();
  if (!R.allFinite() || !X.translation().allFinite()) {
    throw InvalidArgument(std::string(what) + ": pose has a NaN or infinite entry");
  }
  const double err = orthonormalityError(R);
  if (!(err <= kRotationTolerance)) {
    throw InvalidArgument(std::string(what) + ": rotation is not orthonormal (max |R^T R - I| = " +
                          std::to_string(err) + " > " + std::to_string(kRotationTolerance) + ")");
  }
  if (!(R.determinant() > 0.0)) {
    throw InvalidArgument(std::string(what) + ": rotation is a reflection (det R < 0)");
  }
  return err;
}

Eigen::Matrix3d snapped(const Eigen::Matrix3d& R, double orthonormality_error) {
  if (orthonormality_error <= 1e-14) return R;
  return Eigen::Quaterniond(R).normalized().toRotationMatrix();
}

}  // namespace

void validatePose(const Eigen::Isometry3d& X, const char* what) {
  checkedOrthonormalityError(X, what);
}

Eigen::Matrix3d snappedRotation(const Eigen::Matrix3d& R) {
  return snapped(R, orthonormalityError(R));
}

Eigen::Matrix3d validatedRotation(const Eigen::Isometry3d& X, const char* what) {
  return snapped(X.linear(), checkedOrthonormalityError(X, what));
}

Eigen::Isometry3d poseFromQuaternion(const Eigen::Quaterniond& q, const Eigen::Vector3d& T) {
  if (!q.coeffs().allFinite() || !T.allFinite()) {
    throw InvalidArgument(
        "poseFromQuaternion: quaternion or translation has a NaN or infinite entry");
  }
  const double norm = q.coeffs().stableNorm();
  if (!(norm >= 1e-12) || !std::isfinite(norm)) {
    throw InvalidArgument("poseFromQuaternion: quaternion norm " + std::to_string(norm) +
                          " is too small to normalise (needs >= 1e-12)");
  }
  const Eigen::Quaterniond unit(q.coeffs() / norm);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = unit.toRotationMatrix();
  X.translation() = T;
  return X;
}

Eigen::Isometry3d compose(const Eigen::Isometry3d& X_second, const Eigen::Isometry3d& X_first) {
  validatePose(X_second, "compose: X_second");
  validatePose(X_first, "compose: X_first");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = X_second.linear() * X_first.linear();
  X.translation() = X_second.linear() * X_first.translation() + X_second.translation();
  return X;
}

}  // namespace octomotion
