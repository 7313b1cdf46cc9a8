// Conservative mesh voxels hold the whole surface (docs/validation.md §1, "Surfaces on voxel
// boundaries"): every point of every triangle lies in a closed black voxel, whatever the mesh —
// closed solids, double-sided faces (no inside by ray parity), open sheets, triangle soups — and
// wherever it lies, in particular on voxel boundaries, where a face reaches into no voxel's
// interior. A closed solid's face on a boundary still adds no layer outside it.
#include <gtest/gtest.h>

#include <random>

#include "generated_meshes.h"
#include "octomotion/octree/voxelize.h"
#include "surface_coverage.h"

namespace octomotion {
namespace {

using test::PolyMesh;

void expectCovered(const Octree& tree, const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                   const std::string& what) {
  const test::Coverage c = test::surfaceCoverage(tree, mesh, X_WM, 8);
  EXPECT_EQ(c.uncovered, 0u) << what << ": " << c.uncovered << " of " << c.points
                             << " surface points in no black voxel, first " << c.first;
}

Octree conservative(const WorldGrid& grid, const TriangleMesh& mesh, const Eigen::Isometry3d& X) {
  return voxelizeMesh(grid, mesh, X, Rounding::kConservative);
}

TEST(MeshSurface, DoubleSidedBoxOnVoxelBoundariesIsCovered) {
  // The shape of the OMPL.app robots that once lost faces: every face twice, once reversed, so
  // ray parity finds no inside, and faces at whole voxels.
  const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, 5);
  const TriangleMesh box =
      test::triangulated(test::doubleSided(test::boxQuads({3, 4, 5}, {11, 9, 20})));
  const Octree tree = conservative(grid, box, Eigen::Isometry3d::Identity());
  expectCovered(tree, box, Eigen::Isometry3d::Identity(), "double-sided box");
}

TEST(MeshSurface, OpenSheetOnVoxelPlaneIsCovered) {
  const WorldGrid grid(Eigen::Vector3d(-8, -8, -8), 0.5, 5);
  const TriangleMesh plane = test::triangulated(test::sheet(3.0, 3));  // z = 0: a voxel plane
  for (const Eigen::Isometry3d& X :
       {Eigen::Isometry3d::Identity(),
        Eigen::Isometry3d(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())),
        Eigen::Isometry3d(Eigen::Translation3d(0.5, 1.0, -2.5))}) {
    const Octree tree = conservative(grid, plane, X);
    expectCovered(tree, plane, X, "open sheet");
    EXPECT_GT(tree.blackVoxelCount(), 0u);
  }
}

TEST(MeshSurface, ClosedBoxOnVoxelBoundariesAddsNoLayer) {
  // The inside is known, so the face's voxel is the one inside it: exactly the box's voxels.
  const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, 5);
  const TriangleMesh box = test::triangulated(test::boxQuads({3, 4, 5}, {11, 9, 20}));
  const Octree tree = conservative(grid, box, Eigen::Isometry3d::Identity());
  EXPECT_EQ(tree.blackVoxelCount(), 8u * 5u * 15u);
  expectCovered(tree, box, Eigen::Isometry3d::Identity(), "closed box");
}

// Random meshes of many kinds, placed either on the grid (quarter turns, whole-voxel offsets and
// sizes: faces on voxel boundaries) or anywhere, at several depths.
TEST(MeshSurface, RandomMeshesAreCoveredWherever) {
  std::mt19937_64 rng(0x5eed24);
  std::uniform_int_distribution<int> pick(0, 5), coin(0, 1), quarter(0, 3), cell(1, 9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t grid_aligned = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int depth = 4 + trial % 3;
    const double voxel = trial % 2 ? 1.0 : 0.03;
    const WorldGrid grid(Eigen::Vector3d(-0.5, 0.25, 1.0) * voxel * (trial % 5), voxel, depth);
    const double side = grid.sideMetres();
    const bool aligned = coin(rng) == 1;
    PolyMesh poly;
    switch (pick(rng)) {
      case 0:    // a closed box
      case 1: {  // a double-sided box
        const Eigen::Vector3d lo(cell(rng), cell(rng), cell(rng));
        const Eigen::Vector3d hi = lo + Eigen::Vector3d(cell(rng), cell(rng), cell(rng));
        poly = test::boxQuads(-hi / 2 * voxel, hi / 2 * voxel);
        if (coin(rng)) poly = test::doubleSided(poly);
        break;
      }
      case 2:  // an open sheet, one or two sides
        poly = test::sheet(voxel * cell(rng), 1 + quarter(rng));
        if (coin(rng)) poly = test::doubleSided(poly);
        break;
      case 3: {  // a closed blob, or a double-sided one
        poly = test::fromTriangles(test::blobMesh(voxel * (1 + 4 * unit(rng)), 0.3, rng));
        if (coin(rng)) poly = test::doubleSided(poly);
        break;
      }
      case 4: {  // an open box (a lid missing)
        poly = test::boxQuads(Eigen::Vector3d::Constant(-voxel * cell(rng)),
                              Eigen::Vector3d::Constant(voxel * cell(rng)));
        poly.faces.pop_back();
        break;
      }
      default: {  // a soup of triangles
        for (int k = 0; k < 12; ++k) {
          const auto base = static_cast<std::uint32_t>(poly.vertices.size());
          for (int c = 0; c < 3; ++c) {
            poly.vertices.emplace_back(
                voxel * (aligned ? cell(rng) - 5.0 : 10 * unit(rng) - 5),
                voxel * (aligned ? cell(rng) - 5.0 : 10 * unit(rng) - 5),
                voxel * (aligned ? (c == 2 ? cell(rng) - 5.0 : 0.0) : 10 * unit(rng) - 5));
          }
          poly.faces.push_back({base, base + 1, base + 2});
        }
      }
    }
    const TriangleMesh mesh = test::triangulated(poly);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (aligned) {
      ++grid_aligned;
      X.linear() = (Eigen::AngleAxisd(M_PI / 2 * quarter(rng), Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(M_PI / 2 * quarter(rng), Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
      // Whole voxels from the grid's origin (box sides of odd voxels give half-voxel faces:
      // those are still on voxel boundaries after the extra half voxel here, or midway).
      X.translation() = grid.origin() + voxel * Eigen::Vector3d(std::floor(side / voxel / 2),
                                                                std::floor(side / voxel / 2),
                                                                std::floor(side / voxel / 2));
      if (coin(rng)) X.translation() += Eigen::Vector3d::Constant(voxel / 2);
    } else {
      Eigen::Quaterniond q(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
      X.linear() = q.normalized().toRotationMatrix();
      X.translation() =
          grid.origin() + side * Eigen::Vector3d(0.3 + 0.4 * unit(rng), 0.3 + 0.4 * unit(rng),
                                                 0.3 + 0.4 * unit(rng));
    }
    const Octree tree = conservative(grid, mesh, X);
    expectCovered(tree, mesh, X, "trial " + std::to_string(trial));
    if (HasFailure()) break;
  }
  EXPECT_GT(grid_aligned, 100u);
}

}  // namespace
}  // namespace octomotion
