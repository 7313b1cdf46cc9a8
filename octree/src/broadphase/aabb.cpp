// Separating-axis test for two oriented boxes (Gottschalk et al.'s 15 axes), closed boxes.
#include <cmath>

#include "octomotion/broadphase/aabb.h"

namespace octomotion::broadphase {

bool overlaps(const OrientedBox& a, const OrientedBox& b) {
  // Work in a's frame: R = a's axes . b's axes, t = centre offset.
  const Eigen::Matrix3d R = a.R_WB.transpose() * b.R_WB;
  const Eigen::Vector3d t = a.R_WB.transpose() * (b.center - a.center);
  // Tolerance on |R| so nearly parallel edges (cross product ~ 0) never separate falsely.
  constexpr double kEps = 1e-12;
  const Eigen::Matrix3d abs_R = R.cwiseAbs().array() + kEps;
  const Eigen::Vector3d& ea = a.half;
  const Eigen::Vector3d& eb = b.half;
  // a's face normals.
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + abs_R.row(i).dot(eb)) return false;
  }
  // b's face normals.
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(R.col(j))) > abs_R.col(j).dot(ea) + eb[j]) return false;
  }
  // Edge-edge cross products a_i x b_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * abs_R(i2, j) + ea[i2] * abs_R(i1, j);
      const double rb = eb[j1] * abs_R(i, j2) + eb[j2] * abs_R(i, j1);
      const double dist = std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j));
      if (dist > ra + rb) return false;
    }
  }
  return true;
}

}  // namespace octomotion::broadphase
