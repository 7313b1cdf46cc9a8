// Axis-aligned bounding boxes and the exact narrow phase used by the broad-phase comparison: AABB
// overlap (the report's first, "divergent bounding boxes" test, §1.4) and the separating-axis
// test for two oriented boxes (cubes) — the exact test every broad phase here feeds.
// Boxes are closed: touching boxes overlap.
#pragma once

#include <Eigen/Core>

namespace octomotion::broadphase {

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();

  bool valid() const {
    return min.allFinite() && max.allFinite() && (min.array() <= max.array()).all();
  }
  bool contains(const Aabb& b) const {
    return (min.array() <= b.min.array()).all() && (b.max.array() <= max.array()).all();
  }
};

inline bool overlaps(const Aabb& a, const Aabb& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() &&
         b.min.y() <= a.max.y() && a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

// A box of half side lengths `half` centred at `center`, rotated by R_WB (columns = box axes in
// the world frame W).
struct OrientedBox {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5);

  Aabb aabb() const {
    const Eigen::Vector3d extent = R_WB.cwiseAbs() * half;
    return {center - extent, center + extent};
  }
};

// Exact overlap of two closed oriented boxes by the 15-axis separating-axis test (3 + 3 face
// normals, 9 edge-edge cross products). Near-parallel edge pairs get a tiny tolerance so the
// degenerate cross products never report a false separation.
bool overlaps(const OrientedBox& a, const OrientedBox& b);

}  // namespace octomotion::broadphase
