// The fixed world tessellation every tree lives in: a cube of 2^depth voxels per side whose
// minimum corner is `origin` (metres, world frame W) and whose voxels are `voxel_size` metres.
// Octant labels follow Ahuja & Nash (1984) Fig. 1: bit 0 = +x, bit 1 = +y, bit 2 = +z.
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace octomotion {

// Deep enough for a 1 mm voxel over 2 km (Weng & Ahuja's n); voxel coordinates stay in 32 bits.
inline constexpr int kMaxDepth = 21;

// Integer voxel coordinates in [0, 2^depth).
struct Voxel {
  std::uint32_t x = 0, y = 0, z = 0;
  friend bool operator==(const Voxel& a, const Voxel& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  }
  friend bool operator!=(const Voxel& a, const Voxel& b) { return !(a == b); }
};

// An upright cube of the tessellation: side 2^level voxels, minimum corner `origin` (a multiple
// of 2^level). Level 0 is a voxel; level depth is the universe (the papers' "k-cube").
struct Cube {
  int level = 0;
  Voxel origin;
  std::uint32_t side() const { return std::uint32_t{1} << level; }
  // Child `label` (0..7) of this cube, per the octant labels above.
  Cube child(int label) const {
    const std::uint32_t h = std::uint32_t{1} << (level - 1);
    return {level - 1,
            {origin.x + ((label & 1) ? h : 0u), origin.y + ((label & 2) ? h : 0u),
             origin.z + ((label & 4) ? h : 0u)}};
  }
  bool contains(const Voxel& v) const {
    const std::uint32_t s = side();
    return v.x - origin.x < s && v.y - origin.y < s && v.z - origin.z < s;
  }
  friend bool operator==(const Cube& a, const Cube& b) {
    return a.level == b.level && a.origin == b.origin;
  }
};

class WorldGrid {
 public:
  // Throws InvalidArgument for a non-finite origin, a voxel size that is not finite and > 0, or a
  // depth outside [1, kMaxDepth].
  WorldGrid(const Eigen::Vector3d& origin, double voxel_size, int depth);

  const Eigen::Vector3d& origin() const { return origin_; }
  double voxelSize() const { return voxel_size_; }
  int depth() const { return depth_; }
  std::uint32_t sideVoxels() const { return std::uint32_t{1} << depth_; }
  double sideMetres() const { return voxel_size_ * static_cast<double>(sideVoxels()); }
  Cube universe() const { return {depth_, {0, 0, 0}}; }

  // Continuous grid coordinates (voxel units, 0 at the origin corner) of a world point, and back.
  Eigen::Vector3d toGrid(const Eigen::Vector3d& p_W) const { return (p_W - origin_) / voxel_size_; }
  Eigen::Vector3d toWorld(const Eigen::Vector3d& p_G) const { return origin_ + p_G * voxel_size_; }
  // The voxel containing a world point (half-open voxels); false when outside the universe.
  bool voxelAt(const Eigen::Vector3d& p_W, Voxel* voxel) const;
  Eigen::Vector3d voxelCenter(const Voxel& v) const;
  // World-frame minimum and maximum corners of a cube.
  Eigen::Vector3d cubeMin(const Cube& c) const;
  Eigen::Vector3d cubeMax(const Cube& c) const;

  friend bool operator==(const WorldGrid& a, const WorldGrid& b) {
    return a.origin_ == b.origin_ && a.voxel_size_ == b.voxel_size_ && a.depth_ == b.depth_;
  }
  friend bool operator!=(const WorldGrid& a, const WorldGrid& b) { return !(a == b); }

 private:
  Eigen::Vector3d origin_;
  double voxel_size_;
  int depth_;
};

}  // namespace octomotion
