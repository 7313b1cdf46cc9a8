// Overlap of an axis-aligned box A and an oriented box B, by the separating-axis theorem
// (Gottschalk, Lin & Manocha 1996: 3 face axes of each box, 9 edge-edge axes). Used as the
// cheap pre-test before a tree-vs-tree query: a black voxel of one tree can only meet a moved
// black voxel of the other where the tight boxes of their black voxels overlap.
#pragma once

#include <cmath>

#include <Eigen/Geometry>

namespace octomotion {

// A: centre a_c, half-extents a_h, axis-aligned in its frame. B: centre b_c (in A's frame),
// half-extents b_h along the columns of R_AB. Returns false only when some axis separates the
// boxes by more than `margin` (so margin > 0 answers "overlap" for boxes that nearly touch).
inline bool boxesOverlap(const Eigen::Vector3d& a_c, const Eigen::Vector3d& a_h,
                         const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& b_c,
                         const Eigen::Vector3d& b_h, double margin = 0.0) {
  const Eigen::Vector3d t = b_c - a_c;
  // The small constant keeps the edge axes safe when two edges are (nearly) parallel and their
  // cross product degenerates (Ericson, Real-Time Collision Detection §4.4.1).
  const Eigen::Matrix3d absR = R_AB.cwiseAbs().array() + 1e-12;
  for (int i = 0; i < 3; ++i) {  // A's faces
    if (std::fabs(t[i]) > a_h[i] + absR.row(i).dot(b_h) + margin) return false;
  }
  for (int j = 0; j < 3; ++j) {  // B's faces
    if (std::fabs(t.dot(R_AB.col(j))) > absR.col(j).dot(a_h) + b_h[j] + margin) return false;
  }
  for (int i = 0; i < 3; ++i) {  // edges: A_i x B_j
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = a_h[i1] * absR(i2, j) + a_h[i2] * absR(i1, j);
      const double rb = b_h[j1] * absR(i, j2) + b_h[j2] * absR(i, j1);
      const double d = t[i2] * R_AB(i1, j) - t[i1] * R_AB(i2, j);
      if (std::fabs(d) > ra + rb + margin) return false;
    }
  }
  return true;
}

}  // namespace octomotion
