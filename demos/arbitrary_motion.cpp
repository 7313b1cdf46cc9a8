// Weng & Ahuja (1987), octrees of objects in arbitrary motion, replayed with moveTree.
//
// Part 1 (§6, Table 2): two synthetic objects are moved by the paper's rotations and
// translations in universes of 2^n voxels per side, n = 4..7, and the target trees' B (black
// leaves), I (internal nodes), M (most builder nodes alive at once) and I/V are printed beside the
// paper's columns. Fig. 5, which shows the paper's objects, is not in our copy of the text, so we
// use objects of the paper's volumes V: (a) a 4 x 4 x 6-voxel block (V = 96 at n = 4) and (b) a
// cylinder of radius 4 and height 3 voxels (V = 16 * 3 * pi = 150.8 at n = 4), both scaled by
// 2^(n-4) with the universe. Shapes and positions differ, so the figures agree in kind (I/V
// small and falling as n grows, about 4x more nodes per level for the same motion of the curved
// object, M within a few percent of I), not digit for digit.
//
// Part 2 (§5, Theorems 1 and 2): cubes of side 2^m, m = 0..6, are moved to random orientations
// and positions, and B and I are checked against the theorems' bounds
//   B_m <= 24.25 * 4^m - 200 * 2^m + 1454                        (Theorem 1)
//   I_m <= 5.76 * 4^m + 17 * 2^m + 8n + 76m - 277   (m >= 3)       (Theorem 2)
//   I_0 <= 8n - 7,  I_1 <= 8n + 12,  I_2 <= 8n + 101.
// The theorems describe the octree of the cube itself, i.e. voxels whose centre is in the moved
// cube (Rounding::kCenter, §3). The program exits 1 if a bound or a checked property fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "octomotion/motion/move_tree.h"
#include "octomotion/octree/voxelize.h"

namespace {

using octomotion::Box;
using octomotion::Cylinder;
using octomotion::MoveStats;
using octomotion::Octree;
using octomotion::Primitive;
using octomotion::Rounding;
using octomotion::WorldGrid;

constexpr double kPi = 3.14159265358979323846;
int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::cout << "  FAILED: " << what << "\n";
    ++failures;
  }
}

// A motion as the paper states it: rotation by phi about the unit axis n0 through the universe
// origin, then translation by T (voxels): X' = R X + T.
Eigen::Isometry3d motion(const Eigen::Vector3d& n0, double phi_degrees, const Eigen::Vector3d& T) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(phi_degrees * kPi / 180.0, n0.normalized()).toRotationMatrix();
  X.translation() = T;
  return X;
}

// Table 2 as printed in the paper: one column per experiment. The 30-degree half of each table
// has pairs of columns T_1, T_2 (the paper calls T_1 the source and T_2 the target tree); we
// replay each column's motion on the original object. Columns whose printed I/V does not equal
// I / V with the paper's V (our copy of that half is partly garbled) are left out.
struct PaperColumn {
  int n;
  Eigen::Vector3d n0;
  double phi;
  Eigen::Vector3d T;
  int B, I, M;
  double i_over_v;
};

struct Object {
  const char* name;
  Primitive shape;
  // Where the object's centre is at n = 4 (voxels), for the quarter turns and for the turns about
  // the diagonal (the paper's translations must bring the object back into the universe).
  Eigen::Vector3d centre, centre_diagonal;
  double volume;  // V at n = 4, in voxels
  std::vector<PaperColumn> paper;
};

std::vector<Object> objects() {
  const Eigen::Vector3d y(0, 1, 0), diagonal(1, 1, 1);
  return {
      {"(a) 4 x 4 x 6 block",
       Box{Eigen::Vector3d(2, 2, 3)},
       Eigen::Vector3d(4, 4, 5),
       Eigen::Vector3d(4, 4, 5),
       96.0,
       {{4, y, -90, {16, 0, 0}, 12, 7, 7, 0.073},
        {5, y, -90, {16, 0, 0}, 12, 7, 7, 0.0091},
        {6, y, -90, {64, 0, 0}, 12, 7, 7, 0.0011},
        {7, y, -90, {128, 0, 0}, 12, 7, 7, 0.00014},
        {4, diagonal, 30, {2, 2, 0}, 47, 21, 25, 0.22},
        {4, diagonal, 30, {4, 4, 0}, 85, 39, 42, 0.41},
        {5, diagonal, 30, {8, 8, 0}, 183, 64, 69, 0.083},
        {5, diagonal, 30, {16, 16, 0}, 441, 170, 174, 0.22}}},
      {"(b) cylinder r 4, h 3",
       Cylinder{4.0, 3.0},
       Eigen::Vector3d(5, 5, 2),
       Eigen::Vector3d(7, 8, 8),
       16.0 * 3.0 * kPi,
       {{4, y, -90, {16, 0, 0}, 40, 17, 21, 0.11},
        {5, y, -90, {8, 0, 0}, 376, 97, 97, 0.0080},
        {6, y, -90, {16, 0, 0}, 1288, 337, 337, 0.035},
        {7, y, -90, {128, 0, 0}, 4904, 1457, 1457, 0.019},
        {4, diagonal, 30, {4, 0, 0}, 152, 55, 58, 0.36},
        {6, diagonal, 30, {4, -4, 0}, 2928, 907, 913, 0.094},
        {6, diagonal, 30, {4, -4, 0}, 3114, 1007, 1010, 0.10},
        {7, diagonal, 30, {4, -4, 0}, 4904, 1457, 1464, 0.019},
        {7, diagonal, 30, {4, -4, 0}, 12622, 3667, 3673, 0.047}}},
  };
}

Primitive scaled(const Primitive& shape, double s) {
  if (const auto* b = std::get_if<Box>(&shape)) return Box{b->half_extents * s};
  const auto& c = std::get<Cylinder>(shape);
  return Cylinder{c.radius * s, c.length * s};
}

void tableTwo() {
  std::cout << "Part 1: Table 2 of Weng & Ahuja (1987), the paper's figures beside ours\n"
               "(rotation phi about n0 through the universe origin, then translation T; "
               "kCenter rounding)\n\n";
  for (const Object& object : objects()) {
    std::cout << "Object " << object.name << "\n";
    std::printf("  %2s %-9s %5s %-11s | %6s %5s %5s %8s | %6s %5s %5s %8s %8s\n", "n", "n0", "phi",
                "T", "B", "I", "M", "I/V", "ours B", "I", "M", "I/V", "V");
    for (const PaperColumn& col : object.paper) {
      const double s = std::ldexp(1.0, col.n - 4);  // the object grows with the universe
      const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, col.n);
      Eigen::Isometry3d X_object = Eigen::Isometry3d::Identity();
      X_object.translation() = (col.phi == -90 ? object.centre : object.centre_diagonal) * s;
      const Octree source =
          octomotion::voxelize(grid, scaled(object.shape, s), X_object, Rounding::kCenter);
      MoveStats stats;
      const Octree target = octomotion::moveTree(source, motion(col.n0, col.phi, col.T), grid,
                                                 Rounding::kCenter, &stats);
      const double volume = object.volume * s * s * s;
      char axis[48], shift[48];
      std::snprintf(axis, sizeof axis, "%g,%g,%g", col.n0.x(), col.n0.y(), col.n0.z());
      std::snprintf(shift, sizeof shift, "%g,%g,%g", col.T.x(), col.T.y(), col.T.z());
      std::printf("  %2d %-9s %5g %-11s | %6d %5d %5d %8.2g | %6zu %5zu %5zu %8.2g %8.1f%s\n",
                  col.n, axis, col.phi, shift, col.B, col.I, col.M, col.i_over_v,
                  stats.black_leaves, stats.internal_nodes, stats.peak_nodes,
                  static_cast<double>(stats.internal_nodes) / volume, volume,
                  stats.clipped ? "  (clipped)" : "");
      check(!stats.clipped, std::string(object.name) + ": the moved object stays in the universe");
      check(stats.black_leaves == target.blackLeafCount() &&
                stats.internal_nodes == target.internalNodeCount(),
            "MoveStats counts the target tree");
      check(stats.peak_nodes >= stats.internal_nodes, "M >= I");
      check(target.checkInvariants(), "the target tree is a canonical octree");
      if (col.phi == -90) {
        // A quarter turn with an integer translation maps voxels onto voxels: nothing is gained
        // or lost, as in the paper's first half of the table (B and I unchanged by the move).
        check(target.blackVoxelCount() == source.blackVoxelCount(),
              "a quarter turn keeps the voxel count");
        check(target.blackLeafCount() == source.blackLeafCount(),
              "a quarter turn of voxel-aligned leaves keeps B");
      }
    }
    std::cout << "\n";
  }
}

double theorem1(int m) {
  return 24.25 * std::ldexp(1.0, 2 * m) - 200 * std::ldexp(1.0, m) + 1454;
}

double theorem2(int m, int n) {
  switch (m) {
    case 0:
      return 8.0 * n - 7;
    case 1:
      return 8.0 * n + 12;
    case 2:
      return 8.0 * n + 101;
    default:
      return 5.76 * std::ldexp(1.0, 2 * m) + 17 * std::ldexp(1.0, m) + 8.0 * n + 76.0 * m - 277;
  }
}

void theorems() {
  constexpr int kN = 8;           // a 256^3 universe
  constexpr int kPoses = 24;      // random orientations and positions per cube size
  std::mt19937_64 rng(20240607);  // fixed: the run is reproducible
  std::uniform_real_distribution<double> unit(-1.0, 1.0), offset(-0.5, 0.5);
  const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, kN);
  const double centre = std::ldexp(1.0, kN - 1);
  std::cout << "Part 2: Theorems 1 and 2, cubes of side 2^m at " << kPoses
            << " random orientations and positions each, n = " << kN << " (kCenter)\n";
  std::printf("  %2s %7s | %7s %9s %7s | %7s %9s %7s | %6s\n", "m", "V", "max B", "Thm 1", "B/V",
              "max I", "Thm 2", "I/V", "max M");
  for (int m = 0; m <= 6; ++m) {
    const double side = std::ldexp(1.0, m);
    // The source: the cube upright about the universe centre, on voxel boundaries.
    Eigen::Isometry3d X_cube = Eigen::Isometry3d::Identity();
    X_cube.translation() = Eigen::Vector3d::Constant(centre + (m == 0 ? 0.5 : 0.0));
    const Octree source = octomotion::voxelize(grid, Box{Eigen::Vector3d::Constant(side / 2)},
                                               X_cube, Rounding::kCenter);
    std::size_t max_b = 0, max_i = 0, max_m = 0;
    for (int k = 0; k < kPoses; ++k) {
      Eigen::Vector3d axis(unit(rng), unit(rng), unit(rng));
      if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitZ();
      const double angle = kPi * unit(rng);
      const Eigen::Vector3d shift(offset(rng), offset(rng), offset(rng));
      // Rotate about the cube's centre, then shift by a fraction of a voxel.
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
      const Eigen::Vector3d c = X_cube.translation();
      X.translation() = c - X.linear() * c + shift;
      MoveStats stats;
      octomotion::moveTree(source, X, grid, Rounding::kCenter, &stats);
      max_b = std::max(max_b, stats.black_leaves);
      max_i = std::max(max_i, stats.internal_nodes);
      max_m = std::max(max_m, stats.peak_nodes);
    }
    const double volume = side * side * side;
    std::printf("  %2d %7.0f | %7zu %9.0f %7.3f | %7zu %9.0f %7.3f | %6zu\n", m, volume, max_b,
                theorem1(m), static_cast<double>(max_b) / volume, max_i, theorem2(m, kN),
                static_cast<double>(max_i) / volume, max_m);
    check(static_cast<double>(max_b) <= theorem1(m), "Theorem 1 at m = " + std::to_string(m));
    check(static_cast<double>(max_i) <= theorem2(m, kN), "Theorem 2 at m = " + std::to_string(m));
  }
}

}  // namespace

int main() {
  try {
    tableTwo();
    theorems();
  } catch (const std::exception& e) {
    std::cerr << "arbitrary_motion: error: " << e.what() << "\n";
    return 1;
  }
  if (failures > 0) {
    std::cout << failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "\nAll bounds and checks hold.\n";
  return 0;
}
