// Poses of moving objects (Weng & Ahuja 1987 §3): X_WS maps a point p_S of the source tree's
// frame S to p_W = X_WS * p_S = R p_S + T in the world frame W of the target grid.
// Successive motions are composed and always applied to the source tree (never to a moved
// tree), so quantization errors cannot accumulate.
#pragma once

#include <Eigen/Geometry>

namespace octomotion {

// A rotation is accepted when max |R^T R - I| <= kRotationTolerance and det R > 0. The tolerance
// admits matrices computed in single precision; moveTree/collides then use the nearest exact
// rotation (see snappedRotation), so the forward and backward maps stay consistent.
inline constexpr double kRotationTolerance = 1e-6;

// Voxel-boundary ties (in target voxels): a voxel centre within kMotionTieTolerance outside a
// moved black cube counts as inside it (the paper's "on or inside"), and in conservative mode a
// voxel must overlap a moved cube by more than kMotionTieTolerance on every separating axis, so
// mere face contact does not count. This makes rotations given as floating-point matrices
// (cos 90° = 6e-17) and integer translations reproduce exactly what the exact motion gives.
// Rounding errors of the pose arithmetic stay below ~1e-9 voxel even at depth 21.
inline constexpr double kMotionTieTolerance = 1e-6;

// Throws InvalidArgument (naming `what`) if the pose has a NaN/Inf entry, or its linear part is
// not a rotation within kRotationTolerance (scaled, sheared or reflecting matrices).
void validatePose(const Eigen::Isometry3d& X, const char* what = "pose");

// The rotation moveTree/collides use for a validated pose: R itself when it is orthonormal to
// within 1e-14 (so exact floating-point 90° matrices are kept bit for bit), else the nearest
// rotation (re-normalised quaternion of R).
Eigen::Matrix3d snappedRotation(const Eigen::Matrix3d& R);

// validatePose then snappedRotation, sharing their R^T R (the per-query set-up of moveTree and
// collides).
Eigen::Matrix3d validatedRotation(const Eigen::Isometry3d& X, const char* what = "pose");

// X from a possibly non-normalised quaternion (w, x, y, z) and a translation: the quaternion is
// divided by its norm. Throws InvalidArgument when a coefficient or the translation is NaN/Inf or
// the quaternion's norm is below 1e-12 (no direction to normalise).
Eigen::Isometry3d poseFromQuaternion(const Eigen::Quaterniond& q, const Eigen::Vector3d& T);

// §3: X' = R X + T followed by X'' = R' X' + T' is the single motion X'' = (R'R) X + (R'T + T').
// compose(X_second, X_first) returns that motion; both inputs are validated.
Eigen::Isometry3d compose(const Eigen::Isometry3d& X_second, const Eigen::Isometry3d& X_first);

}  // namespace octomotion
