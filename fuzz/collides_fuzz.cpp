// Fuzzes the fused motion query with an oracle: for a pose and two small voxel sets decoded from
// the input, collides(source, X_WS, environment) must equal
// intersects(moveTree(source, X_WS, environment.grid()), environment) (collides.h), with a
// witness voxel black in both trees, for both roundings; non-finite poses must throw
// InvalidArgument from both paths.
//
// Input layout (missing bytes read as 0): rounding, source depth, environment depth, source voxel
// size, source origin (3), rotation mode + parameters, translation (3 x 2), voxel counts, then
// voxel coordinates.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "fuzz_support.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/traversal.h"

namespace {

using namespace octomotion;

// One of the 24 proper rotations that permute the axes: exact entries 0 and +-1.
Eigen::Matrix3d axisPermutation(int index) {
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* p = perms[(index / 8) % 6];
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) m(i, p[i]) = (index >> i) & 1 ? -1.0 : 1.0;
  if (m.determinant() < 0) m.row(0) *= -1.0;
  return m;
}

std::vector<Voxel> voxels(fuzz::ByteReader& in, int count, int depth) {
  std::vector<Voxel> out;
  const std::uint32_t side = std::uint32_t{1} << depth;
  for (int i = 0; i < count; ++i) {
    // Clustered voxels make solid blocks (several levels of the tree), not only scattered leaves.
    out.push_back({in.byte() % side, in.byte() % side, in.byte() % side});
  }
  std::sort(out.begin(), out.end(), [](const Voxel& a, const Voxel& b) {
    return a.z != b.z ? a.z < b.z : (a.y != b.y ? a.y < b.y : a.x < b.x);
  });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const Rounding rounding = in.byte() & 1 ? Rounding::kCenter : Rounding::kConservative;
  const int source_depth = 1 + in.byte() % 4;
  const int env_depth = 1 + in.byte() % 5;
  // Source voxels from a quarter of the environment's to 2.5 times it (the environment's is 1).
  const double source_voxel = in.unit(0.25, 2.5);
  const Eigen::Vector3d source_origin(in.unit(-8, 0), in.unit(-8, 0), in.unit(-8, 0));

  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  const int rotation_mode = in.byte() % 4;
  if (rotation_mode == 1) {
    X_WS.linear() = axisPermutation(in.byte());
  } else if (rotation_mode >= 2) {
    Eigen::Quaterniond q(in.unit(-1, 1), in.unit(-1, 1), in.unit(-1, 1), in.unit(-1, 1));
    if (q.norm() > 1e-3) X_WS.linear() = q.normalized().toRotationMatrix();
  }
  const bool non_finite = rotation_mode == 3 && in.byte() == 0xff;
  for (int a = 0; a < 3; ++a) {
    // Whole voxels (the translation kernel's exact case) or arbitrary fractions of one.
    const double whole = static_cast<std::int8_t>(in.byte()) / 4.0;
    const std::uint8_t frac = in.byte();
    X_WS.translation()[a] = frac & 1 ? whole + frac / 509.0 : std::round(whole);
  }
  if (non_finite) X_WS.translation().x() = std::numeric_limits<double>::quiet_NaN();

  const int source_count = in.byte() % 40;
  const int env_count = in.byte() % 80;
  const WorldGrid source_grid(source_origin, source_voxel, source_depth);
  const WorldGrid env_grid(Eigen::Vector3d::Zero(), 1.0, env_depth);
  const Octree source = Octree::fromVoxels(source_grid, voxels(in, source_count, source_depth));
  // An environment either sparse from the input or full (the root-black special case).
  const Octree environment = env_count == 79
                                 ? Octree::full(env_grid)
                                 : Octree::fromVoxels(env_grid, voxels(in, env_count, env_depth));

  bool fused = false, reference = false;
  bool fused_threw = false, reference_threw = false;
  Cube witness;
  try {
    fused = collides(source, X_WS, environment, rounding, &witness);
  } catch (const InvalidArgument&) {
    fused_threw = true;
  }
  Octree moved(env_grid);
  try {
    moved = moveTree(source, X_WS, env_grid, rounding);
    reference = intersects(moved, environment);
  } catch (const InvalidArgument&) {
    reference_threw = true;
  }
  if (fused_threw != reference_threw) fuzz::fail("only one path rejected the pose");
  if (non_finite && !fused_threw) fuzz::fail("a NaN pose was accepted");
  if (fused_threw) return 0;
  if (fused != reference) fuzz::fail("collides() differs from moveTree + intersects");
  if (fused) {
    if (!environment.occupied(witness.origin) || !moved.occupied(witness.origin)) {
      fuzz::fail("the witness is not black in both trees");
    }
  }
  // The prepared form with a reused scratch gives the same answer, twice.
  static CollisionScratch scratch;
  const MovableSource prepared(source);
  for (int i = 0; i < 2; ++i) {
    if (collides(prepared, X_WS, environment, rounding, scratch) != reference) {
      fuzz::fail("prepared collides() differs from the reference");
    }
  }
  return 0;
}
