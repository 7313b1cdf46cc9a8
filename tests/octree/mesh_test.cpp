// Mesh loading (assimp: STL binary/ASCII, OBJ, Collada with <unit> and <up_axis>), the closed-
// manifold check, and the mesh builder: solid fill against the analytic primitives and against
// an independent brute-force oracle, shells for open meshes, rays through edges and vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "dense_grid.h"
#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using test::DenseGrid;

void expectCompact(const Octree& tree) {
  std::string why;
  EXPECT_TRUE(tree.checkInvariants(&why)) << why;
}

Eigen::Isometry3d randomPose(const WorldGrid& grid, std::mt19937_64& rng, double lo = 0.3,
                             double hi = 0.7) {
  std::normal_distribution<double> gauss;
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = grid.origin() + grid.sideMetres() * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& X) {
  TriangleMesh out = mesh;
  for (Eigen::Vector3d& v : out.vertices) v = X * v;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Independent oracle: point-in-mesh by counting Moeller-Trumbore hits along a random direction
// (a generic direction almost surely misses edges and vertices), surface contact by branch and
// bound on the exact point-to-triangle distance (1-Lipschitz).

bool rayHits(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return false;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return false;
  return e2.dot(q) / det > 0;
}

// The oracle's ray direction, and a basis of the plane across it: a triangle can only be hit
// by the ray from p if its projection's bounding box on that plane contains p's projection.
const Eigen::Vector3d kRayDir = Eigen::Vector3d(0.5477, 0.3211, 0.7734).normalized();
const Eigen::Vector3d kAcross1 = kRayDir.unitOrthogonal();
const Eigen::Vector3d kAcross2 = kRayDir.cross(kAcross1);

class InsideOracle {
 public:
  explicit InsideOracle(const TriangleMesh& mesh) : mesh_(mesh) {
    for (const auto& t : mesh.triangles) {
      Eigen::Vector4d b(INFINITY, -INFINITY, INFINITY, -INFINITY);  // (min1, max1, min2, max2)
      for (std::uint32_t i : t) {
        const double u = kAcross1.dot(mesh.vertices[i]), v = kAcross2.dot(mesh.vertices[i]);
        b = Eigen::Vector4d(std::min(b[0], u), std::max(b[1], u), std::min(b[2], v),
                            std::max(b[3], v));
      }
      boxes_.push_back(b);
    }
  }
  bool operator()(const Eigen::Vector3d& p) const {
    const double u = kAcross1.dot(p), v = kAcross2.dot(p);
    bool odd = false;
    for (std::size_t k = 0; k < boxes_.size(); ++k) {
      const Eigen::Vector4d& b = boxes_[k];
      if (u < b[0] - 1e-9 || u > b[1] + 1e-9 || v < b[2] - 1e-9 || v > b[3] + 1e-9) continue;
      const auto& t = mesh_.triangles[k];
      if (rayHits(p, kRayDir, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]])) {
        odd = !odd;
      }
    }
    return odd;
  }

 private:
  const TriangleMesh& mesh_;
  std::vector<Eigen::Vector4d> boxes_;
};

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

enum class Truth { kNo, kYes, kUnknown };

// Does the mesh surface touch the closed cube [lo, hi]? The cube is the Chebyshev ball of its
// half side around its centre: a Euclidean-closest surface point inside it proves contact, a
// Euclidean distance beyond the half diagonal proves there is none, otherwise split. Contacts
// closer than 1e-9 of the cube size to grazing count as touching.
Truth surfaceTouchesBox(const TriangleMesh& mesh, const std::vector<std::uint32_t>& near,
                        const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int budget = 10) {
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double half = 0.5 * (hi - lo).maxCoeff();
  double euclid = INFINITY;
  for (std::uint32_t i : near) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d q =
        closestOnTriangle(centre, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    if ((q - centre).cwiseAbs().maxCoeff() <= half * (1 + 1e-9)) return Truth::kYes;
    euclid = std::min(euclid, (q - centre).norm());
  }
  if (euclid > 0.5 * (hi - lo).norm() * (1 + 1e-9)) return Truth::kNo;
  if (budget == 0) return Truth::kUnknown;
  bool unknown = false;
  for (int k = 0; k < 8; ++k) {
    Eigen::Vector3d a, b;
    for (int i = 0; i < 3; ++i) {
      a[i] = (k >> i & 1) ? centre[i] : lo[i];
      b[i] = (k >> i & 1) ? hi[i] : centre[i];
    }
    const Truth t = surfaceTouchesBox(mesh, near, a, b, budget - 1);
    if (t == Truth::kYes) return Truth::kYes;
    if (t == Truth::kUnknown) unknown = true;
  }
  return unknown ? Truth::kUnknown : Truth::kNo;
}

// Brute force over every voxel of the grid, for a world-frame mesh. Returns the number of
// voxels the oracle could not decide (grazing contacts).
std::size_t compareWithOracle(const WorldGrid& grid, const TriangleMesh& mesh_W, bool solid,
                              Rounding rounding, const Octree& tree) {
  const DenseGrid dense = DenseGrid::fromTree(tree);
  const std::uint32_t side = grid.sideVoxels();
  const double vs = grid.voxelSize();
  // Triangles near each voxel (bounding box within one voxel), listed per voxel.
  auto index = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    return (std::size_t{z} * side + y) * side + x;
  };
  std::vector<std::vector<std::uint32_t>> near_lists(std::size_t{side} * side * side);
  for (std::uint32_t i = 0; i < mesh_W.triangles.size(); ++i) {
    const auto& t = mesh_W.triangles[i];
    const Eigen::Vector3d &a = mesh_W.vertices[t[0]], &b = mesh_W.vertices[t[1]],
                          &c = mesh_W.vertices[t[2]];
    const Eigen::Vector3d lo = grid.toGrid(a.cwiseMin(b).cwiseMin(c)).array() - 1.0;
    const Eigen::Vector3d hi = grid.toGrid(a.cwiseMax(b).cwiseMax(c)).array() + 1.0;
    std::uint32_t from[3], to[3];
    bool outside = false;
    for (int k = 0; k < 3; ++k) {
      const double l = std::max(std::floor(lo[k]) - 1, 0.0),
                   h = std::min(std::floor(hi[k]) + 1, side - 1.0);
      outside |= l > h;
      from[k] = static_cast<std::uint32_t>(l);
      to[k] = static_cast<std::uint32_t>(std::max(h, 0.0));
    }
    if (outside) continue;
    for (std::uint32_t z = from[2]; z <= to[2]; ++z)
      for (std::uint32_t y = from[1]; y <= to[1]; ++y)
        for (std::uint32_t x = from[0]; x <= to[0]; ++x) near_lists[index(x, y, z)].push_back(i);
  }
  std::size_t unknown = 0, mismatches = 0;
  const InsideOracle insideOracle(mesh_W);
  const Eigen::Vector3d slack = Eigen::Vector3d::Constant(vs);
  for (std::uint32_t z = 0; z < side; ++z)
    for (std::uint32_t y = 0; y < side; ++y)
      for (std::uint32_t x = 0; x < side; ++x) {
        const Cube c{0, {x, y, z}};
        const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
        const Eigen::Vector3d centre = 0.5 * (lo + hi);
        const std::vector<std::uint32_t>& near = near_lists[index(x, y, z)];
        Truth truth;
        if (rounding == Rounding::kCenter && solid) {
          truth = insideOracle(centre) ? Truth::kYes : Truth::kNo;
          // A centre within 1e-9 voxel of the surface is a tie the two rays may break apart.
          if (!near.empty() && surfaceTouchesBox(mesh_W, near, centre - slack * 1e-9,
                                                 centre + slack * 1e-9, 0) != Truth::kNo) {
            truth = Truth::kUnknown;
          }
        } else {
          truth = near.empty() ? Truth::kNo : surfaceTouchesBox(mesh_W, near, lo, hi);
          if (truth != Truth::kYes && solid && insideOracle(centre)) truth = Truth::kYes;
        }
        if (truth == Truth::kUnknown) {
          ++unknown;
        } else if (dense.get(x, y, z) != (truth == Truth::kYes)) {
          if (++mismatches < 5) ADD_FAILURE() << "voxel " << x << "," << y << "," << z;
        }
      }
  EXPECT_EQ(mismatches, 0u);
  return unknown;
}

// ---------------------------------------------------------------------------------------------

TEST(MeshTopology, ClosedManifoldCheck) {
  const TriangleMesh box = boxMesh(Eigen::Vector3d(1, 2, 3), 3);
  EXPECT_TRUE(isClosedManifold(box));
  EXPECT_TRUE(isClosedManifold(sphereMesh(1.0, 12, 7)));
  EXPECT_TRUE(isClosedManifold(torusMesh(2.0, 0.5, 16, 9)));
  TriangleMesh open = box;
  open.triangles.pop_back();
  EXPECT_FALSE(isClosedManifold(open));
  TriangleMesh flipped = box;
  std::swap(flipped.triangles[5][0], flipped.triangles[5][1]);
  EXPECT_FALSE(isClosedManifold(flipped));
  EXPECT_FALSE(isClosedManifold(TriangleMesh{}));
  // A triangle soup (every triangle with its own corners, as STL stores it) is welded by position.
  TriangleMesh soup;
  for (const auto& t : box.triangles) {
    const std::uint32_t base = static_cast<std::uint32_t>(soup.vertices.size());
    for (std::uint32_t i : t) soup.vertices.push_back(box.vertices[i]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(isClosedManifold(soup));
  // Three triangles on one edge: not a manifold.
  TriangleMesh fin = box;
  fin.vertices.push_back(Eigen::Vector3d(5, 5, 5));
  fin.triangles.push_back({box.triangles[0][0], box.triangles[0][1],
                           static_cast<std::uint32_t>(fin.vertices.size() - 1)});
  EXPECT_FALSE(isClosedManifold(fin));
}

TEST(VoxelizeMesh, BoxMeshEqualsAnalyticBox) {
  std::mt19937_64 rng(314);
  for (int depth = 3; depth <= 6; ++depth) {
    const WorldGrid grid(Eigen::Vector3d(0.2, -0.4, 0.1), 0.05, depth);
    for (int trial = 0; trial < 8; ++trial) {
      std::uniform_real_distribution<double> size(0.02, 0.3 * grid.sideMetres());
      const Eigen::Vector3d half(size(rng), size(rng), size(rng));
      const Eigen::Isometry3d X = randomPose(grid, rng);
      const TriangleMesh mesh = boxMesh(half, 1 + trial % 3);
      for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
        int warnings = 0;
        const Octree from_mesh =
            voxelizeMesh(grid, mesh, X, r, [&](const std::string&) { ++warnings; });
        expectCompact(from_mesh);
        EXPECT_EQ(warnings, 0);
        EXPECT_EQ(from_mesh, voxelize(grid, Box{half}, X, r))
            << "depth " << depth << " trial " << trial << " " << toString(r);
      }
    }
  }
}

TEST(VoxelizeMesh, RaysThroughEdgesAndVerticesAreCountedOnce) {
  // Box faces and their subdividing vertices lie exactly on voxel centre coordinates, so centre
  // queries (vertical rays through x, y of voxel centres) run along faces, through edges and
  // through vertices. Faces on voxel faces as well (second case): conservative touches them.
  const WorldGrid grid(Eigen::Vector3d::Zero(), 1.0, 5);
  for (double offset : {0.5, 0.0}) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(13 + offset, 15 + offset, 11 + offset);
    const Eigen::Vector3d half(6, 4, 5);  // vertex spacing 2 or 1 with the subdivisions below
    for (int n : {1, 2, 4}) {
      TriangleMesh mesh = boxMesh(half, n);
      for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
        const Octree from_mesh = voxelizeMesh(grid, mesh, X, r);
        expectCompact(from_mesh);
        EXPECT_EQ(from_mesh, voxelize(grid, Box{half}, X, r))
            << "offset " << offset << " n " << n << " " << toString(r);
      }
    }
    // Exact quarter turns put other faces and other diagonals of the face triangulation
    // under the vertical rays.
    Eigen::Matrix3d quarter_z, quarter_x;
    quarter_z << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    quarter_x << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    for (const Eigen::Matrix3d& R : {Eigen::Matrix3d(quarter_z), Eigen::Matrix3d(quarter_x),
                                     Eigen::Matrix3d(quarter_x * quarter_z)}) {
      Eigen::Isometry3d turned = X;
      turned.linear() = R;
      const TriangleMesh mesh = boxMesh(half, 2);
      for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
        const Octree from_mesh = voxelizeMesh(grid, mesh, turned, r);
        expectCompact(from_mesh);
        EXPECT_EQ(from_mesh, voxelize(grid, Box{half}, turned, r))
            << "offset " << offset << " turned " << toString(r);
      }
    }
  }
}

TEST(VoxelizeMesh, SolidFillMatchesBruteForceOracle) {
  std::mt19937_64 rng(2718);
  const std::vector<TriangleMesh> meshes = {sphereMesh(1.0, 14, 9), torusMesh(1.0, 0.4, 18, 10),
                                            boxMesh(Eigen::Vector3d(0.9, 0.5, 0.3), 2)};
  std::size_t unknown = 0, voxels = 0;
  for (int depth = 3; depth <= 6; ++depth) {
    const WorldGrid grid(Eigen::Vector3d(-2, -2, -2), 4.0 / (1 << depth), depth);
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const Eigen::Isometry3d X = randomPose(grid, rng, 0.45, 0.55);
      const TriangleMesh mesh_W = transformed(meshes[m], X);
      for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
        SCOPED_TRACE("depth " + std::to_string(depth) + " mesh " + std::to_string(m) + " " +
                     toString(r));
        const Octree tree = voxelizeMesh(grid, meshes[m], X, r);
        expectCompact(tree);
        unknown += compareWithOracle(grid, mesh_W, true, r, tree);
        voxels += std::size_t{1} << (3 * depth);
      }
    }
  }
  EXPECT_LT(unknown, voxels / 10000 + 5);
}

TEST(VoxelizeMesh, TessellatedSphereApproximatesTheSphere) {
  // The mesh is inscribed in the sphere: its centre-mode voxels are a subset of the sphere's,
  // and the difference is confined to the thin shell the chords cut off.
  const WorldGrid grid(Eigen::Vector3d(-1.6, -1.6, -1.6), 3.2 / 64, 6);
  const double radius = 1.3;
  const TriangleMesh mesh = sphereMesh(radius, 64, 32);
  const Eigen::Isometry3d X =
      Eigen::Isometry3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Octree from_mesh = voxelizeMesh(grid, mesh, X, Rounding::kCenter);
  const Octree analytic = voxelize(grid, Sphere{radius}, X, Rounding::kCenter);
  expectCompact(from_mesh);
  const double sagitta = radius * (1 - std::cos(M_PI / 32));  // deepest chord-to-arc gap
  std::size_t missing = 0;
  for (const Voxel& v : analytic.blackVoxels()) {
    if (from_mesh.occupied(v)) continue;
    ++missing;
    EXPECT_GT((grid.voxelCenter(v) - X.translation()).norm(), radius - sagitta - 1e-9);
  }
  for (const Voxel& v : from_mesh.blackVoxels()) ASSERT_TRUE(analytic.occupied(v));
  EXPECT_LT(static_cast<double>(missing), 0.05 * static_cast<double>(analytic.blackVoxelCount()));
  // Conservative: the mesh's voxels cover the mesh and lie within the sphere's voxels.
  const Octree cons_mesh = voxelizeMesh(grid, mesh, X, Rounding::kConservative);
  const Octree cons_sphere = voxelize(grid, Sphere{radius}, X, Rounding::kConservative);
  for (const Voxel& v : cons_mesh.blackVoxels()) ASSERT_TRUE(cons_sphere.occupied(v));
  EXPECT_NEAR(cons_mesh.volume(), cons_sphere.volume(), 0.05 * cons_sphere.volume());
}

TEST(VoxelizeMesh, OpenMeshIsAShellAndWarns) {
  const WorldGrid grid(Eigen::Vector3d(-2, -2, -2), 4.0 / 32, 5);
  TriangleMesh open = boxMesh(Eigen::Vector3d(1.1, 0.8, 0.6), 2);
  open.triangles.resize(open.triangles.size() - 8);  // drop the +z face (the last 8)
  std::mt19937_64 rng(8);
  const Eigen::Isometry3d X = randomPose(grid, rng, 0.45, 0.55);
  for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
    std::vector<std::string> messages;
    const Octree shell =
        voxelizeMesh(grid, open, X, r, [&](const std::string& m) { messages.push_back(m); });
    expectCompact(shell);
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_NE(messages[0].find("not closed"), std::string::npos) << messages[0];
    EXPECT_NE(messages[0].find("shell"), std::string::npos) << messages[0];
    // The shell is exactly the voxels the triangles touch: the box's middle stays white.
    EXPECT_LT(compareWithOracle(grid, transformed(open, X), false, r, shell), 20u);
    Voxel middle;
    ASSERT_TRUE(grid.voxelAt(X.translation(), &middle));
    EXPECT_FALSE(shell.occupied(middle));
  }
}

TEST(VoxelizeMesh, ParityHandlesFlippedFacesSharedEdgesAndCavities) {
  const WorldGrid grid(Eigen::Vector3d(-2, -2, -2), 4.0 / 32, 5);
  std::mt19937_64 rng(77);
  int warnings = 0;
  const WarningSink count = [&](const std::string&) { ++warnings; };
  for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
    // A closed box with one triangle wound the wrong way: not a manifold, still a solid.
    const Eigen::Isometry3d X = randomPose(grid, rng, 0.45, 0.55);
    TriangleMesh flipped = boxMesh(Eigen::Vector3d(0.7, 0.5, 0.3), 2);
    std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
    EXPECT_FALSE(isClosedManifold(flipped));
    EXPECT_EQ(voxelizeMesh(grid, flipped, X, r, count),
              voxelize(grid, Box{Eigen::Vector3d(0.7, 0.5, 0.3)}, X, r));
    // Two boxes sharing an edge (four triangles on it): the union of the two boxes.
    TriangleMesh pair = boxMesh(Eigen::Vector3d(0.5, 0.5, 0.5));
    const TriangleMesh other = boxMesh(Eigen::Vector3d(0.5, 0.5, 0.5));
    for (Eigen::Vector3d& v : pair.vertices) v += Eigen::Vector3d(-0.5, -0.5, 0);
    const std::uint32_t base = static_cast<std::uint32_t>(pair.vertices.size());
    for (const Eigen::Vector3d& v : other.vertices)
      pair.vertices.push_back(v + Eigen::Vector3d(0.5, 0.5, 0));
    for (auto t : other.triangles)
      pair.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    EXPECT_FALSE(isClosedManifold(pair));
    Eigen::Isometry3d A = X, B = X;
    A.translation() += X.linear() * Eigen::Vector3d(-0.5, -0.5, 0);
    B.translation() += X.linear() * Eigen::Vector3d(0.5, 0.5, 0);
    const Octree pair_tree = voxelizeMesh(grid, pair, X, r, count);
    expectCompact(pair_tree);
    const DenseGrid a =
        DenseGrid::fromTree(voxelize(grid, Box{Eigen::Vector3d::Constant(0.5)}, A, r));
    const DenseGrid b =
        DenseGrid::fromTree(voxelize(grid, Box{Eigen::Vector3d::Constant(0.5)}, B, r));
    const DenseGrid got = DenseGrid::fromTree(pair_tree);
    for (std::uint32_t z = 0; z < 32; ++z)
      for (std::uint32_t y = 0; y < 32; ++y)
        for (std::uint32_t x = 0; x < 32; ++x) {
          ASSERT_EQ(got.get(x, y, z), a.get(x, y, z) || b.get(x, y, z))
              << x << "," << y << "," << z;
        }
  }
  EXPECT_EQ(warnings, 0);
  // A box with a box-shaped cavity (the inner shell's orientation does not matter to parity).
  const Eigen::Isometry3d X = randomPose(grid, rng, 0.45, 0.55);
  TriangleMesh hollow = boxMesh(Eigen::Vector3d(1.2, 1.0, 0.9), 2);
  const TriangleMesh inner = boxMesh(Eigen::Vector3d(0.6, 0.5, 0.4), 1);
  const std::uint32_t base = static_cast<std::uint32_t>(hollow.vertices.size());
  hollow.vertices.insert(hollow.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  for (auto t : inner.triangles)
    hollow.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
  EXPECT_TRUE(isClosedManifold(hollow));
  const DenseGrid got = DenseGrid::fromTree(voxelizeMesh(grid, hollow, X, Rounding::kCenter));
  const DenseGrid outer_voxels = DenseGrid::fromTree(
      voxelize(grid, Box{Eigen::Vector3d(1.2, 1.0, 0.9)}, X, Rounding::kCenter));
  const DenseGrid inner_voxels = DenseGrid::fromTree(
      voxelize(grid, Box{Eigen::Vector3d(0.6, 0.5, 0.4)}, X, Rounding::kCenter));
  std::size_t cavity = 0;
  for (std::uint32_t z = 0; z < 32; ++z)
    for (std::uint32_t y = 0; y < 32; ++y)
      for (std::uint32_t x = 0; x < 32; ++x) {
        cavity += inner_voxels.get(x, y, z);
        ASSERT_EQ(got.get(x, y, z), outer_voxels.get(x, y, z) && !inner_voxels.get(x, y, z))
            << x << "," << y << "," << z;
      }
  EXPECT_GT(cavity, 100u);
}

TEST(VoxelizeMesh, DepthOneUniverse) {
  const WorldGrid grid(Eigen::Vector3d(-1, -1, -1), 1.0, 1);
  const TriangleMesh ball = sphereMesh(0.6, 16, 9);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_EQ(voxelizeMesh(grid, ball, I, Rounding::kConservative), Octree::full(grid));
  EXPECT_TRUE(voxelizeMesh(grid, ball, I, Rounding::kCenter).empty());
  EXPECT_EQ(voxelize(grid, Sphere{0.6}, I, Rounding::kConservative), Octree::full(grid));
  EXPECT_TRUE(voxelize(grid, Sphere{0.6}, I, Rounding::kCenter).empty());
  // Bigger than the universe: everything is inside, no triangle touches it.
  EXPECT_EQ(voxelizeMesh(grid, sphereMesh(5.0, 16, 9), I, Rounding::kCenter), Octree::full(grid));
  EXPECT_EQ(voxelizeMesh(grid, sphereMesh(5.0, 16, 9), I, Rounding::kConservative),
            Octree::full(grid));
}

TEST(VoxelizeMesh, RejectsBadMeshes) {
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.1, 4);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto message = [&](const TriangleMesh& mesh) -> std::string {
    try {
      voxelizeMesh(grid, mesh, I, Rounding::kCenter);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message(TriangleMesh{}).find("no triangles"), std::string::npos);
  TriangleMesh nan = boxMesh(Eigen::Vector3d::Ones());
  nan.vertices[3].y() = std::nan("");
  EXPECT_NE(message(nan).find("vertices[3]"), std::string::npos);
  TriangleMesh bad_index = boxMesh(Eigen::Vector3d::Ones());
  bad_index.triangles[2][1] = 1000;
  EXPECT_NE(message(bad_index).find("triangles[2]"), std::string::npos);
  Eigen::Isometry3d scaled = I;
  scaled.linear() *= 3.0;
  EXPECT_THROW(voxelizeMesh(grid, boxMesh(Eigen::Vector3d::Ones()), scaled, Rounding::kCenter),
               InvalidArgument);
}

// ---------------------------------------------------------------------------------------------
// Loaders. Files are written into a fresh temporary directory.

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("octomotion_mesh_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string writeText(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

  std::string writeBinaryStl(const std::string& name, const TriangleMesh& mesh) const {
    std::ofstream out(path(name), std::ios::binary);
    char header[80] = "octomotion test mesh";
    out.write(header, 80);
    const std::uint32_t count = static_cast<std::uint32_t>(mesh.triangles.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : mesh.triangles) {
      float data[12] = {0, 0, 0};
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i)
          data[3 + 3 * k + i] = static_cast<float>(mesh.vertices[t[k]][i]);
      out.write(reinterpret_cast<const char*>(data), sizeof data);
      const std::uint16_t attributes = 0;
      out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
    return path(name);
  }

  std::string writeAsciiStl(const std::string& name, const TriangleMesh& mesh) const {
    std::string s = "solid test\n";
    for (const auto& t : mesh.triangles) {
      s += " facet normal 0 0 0\n  outer loop\n";
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d& v = mesh.vertices[t[k]];
        s += "   vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
             std::to_string(v.z()) + "\n";
      }
      s += "  endloop\n endfacet\n";
    }
    return writeText(name, s + "endsolid test\n");
  }

  std::string writeObj(const std::string& name, const TriangleMesh& mesh) const {
    std::string s = "# test\no box\n";
    for (const Eigen::Vector3d& v : mesh.vertices) {
      s += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
           std::to_string(v.z()) + "\n";
    }
    for (const auto& t : mesh.triangles) {
      s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
           std::to_string(t[2] + 1) + "\n";
    }
    return writeText(name, s);
  }

  // One triangle (1,2,3) (4,5,6) (7,8,10) under a node translated by (100, 0, 0).
  std::string writeCollada(const std::string& name, const std::string& unit_name, double metres,
                           const std::string& up_axis) const {
    const std::string s =
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
        "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
        "  <asset><unit name=\"" +
        unit_name + "\" meter=\"" + std::to_string(metres) + "\"/><up_axis>" + up_axis +
        "</up_axis></asset>\n"
        "  <library_geometries><geometry id=\"g\"><mesh>\n"
        "    <source id=\"p\"><float_array id=\"pa\" count=\"9\">1 2 3 4 5 6 7 8 10</float_array>\n"
        "      <technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\">\n"
        "        <param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
        "<param name=\"Z\" type=\"float\"/>\n"
        "      </accessor></technique_common></source>\n"
        "    <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
        "    <triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
        "<p>0 1 2</p></triangles>\n"
        "  </mesh></geometry></library_geometries>\n"
        "  <library_visual_scenes><visual_scene id=\"s\">\n"
        "    <node id=\"n\"><matrix>1 0 0 100 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
        "<instance_geometry url=\"#g\"/></node>\n"
        "  </visual_scene></library_visual_scenes>\n"
        "  <scene><instance_visual_scene url=\"#s\"/></scene>\n"
        "</COLLADA>\n";
    return writeText(name, s);
  }

  fs::path dir_;
};

Eigen::AlignedBox3d boundsOf(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
  return box;
}

TEST_F(MeshFiles, StlBinaryAsciiAndObjLoadTheSameClosedBox) {
  const TriangleMesh box = boxMesh(Eigen::Vector3d(0.5, 0.25, 0.125), 2);
  for (const std::string& file : {writeBinaryStl("box.stl", box),
                                  writeAsciiStl("box_ascii.stl", box), writeObj("box.obj", box)}) {
    SCOPED_TRACE(file);
    const TriangleMesh loaded = loadMesh(file);
    EXPECT_EQ(loaded.triangles.size(), box.triangles.size());
    EXPECT_TRUE(isClosedManifold(loaded));
    const Eigen::AlignedBox3d b = boundsOf(loaded);
    EXPECT_TRUE(b.min().isApprox(Eigen::Vector3d(-0.5, -0.25, -0.125), 1e-6));
    EXPECT_TRUE(b.max().isApprox(Eigen::Vector3d(0.5, 0.25, 0.125), 1e-6));
    // Same solid as the analytic box (vertices are exact in float and in decimal here).
    const WorldGrid grid(Eigen::Vector3d(-1, -1, -1), 2.0 / 32, 5);
    EXPECT_EQ(voxelizeMesh(grid, loaded, Eigen::Isometry3d::Identity(), Rounding::kCenter),
              voxelize(grid, Box{Eigen::Vector3d(0.5, 0.25, 0.125)}, Eigen::Isometry3d::Identity(),
                       Rounding::kCenter));
    // URDF <mesh scale>: applied after everything else.
    MeshLoadOptions options;
    options.scale = Eigen::Vector3d(2, 3, -1);
    const Eigen::AlignedBox3d scaled = boundsOf(loadMesh(file, options));
    EXPECT_TRUE(scaled.max().isApprox(Eigen::Vector3d(1.0, 0.75, 0.125), 1e-6));
  }
}

TEST_F(MeshFiles, ColladaUnitAndUpAxis) {
  // assimp 5.2 puts the unit scale and the rotation from the file's up axis to Y-up into the
  // root node: Z_UP maps (x, y, z) to (x, z, -y). The node's own translation always applies.
  const Eigen::Vector3d first(1 + 100, 2, 3);  // first vertex after the node transform
  {
    const TriangleMesh y_up = loadMesh(writeCollada("y.dae", "centimeter", 0.01, "Y_UP"));
    ASSERT_EQ(y_up.triangles.size(), 1u);
    EXPECT_TRUE(y_up.vertices[y_up.triangles[0][0]].isApprox(0.01 * first, 1e-6));
  }
  {
    const TriangleMesh z_up = loadMesh(writeCollada("z.dae", "centimeter", 0.01, "Z_UP"));
    ASSERT_EQ(z_up.triangles.size(), 1u);
    EXPECT_TRUE(z_up.vertices[z_up.triangles[0][0]].isApprox(
        0.01 * Eigen::Vector3d(first.x(), first.z(), -first.y()), 1e-6));
  }
  {
    const TriangleMesh mm = loadMesh(writeCollada("mm.dae", "millimeter", 0.001, "Y_UP"));
    EXPECT_TRUE(mm.vertices[mm.triangles[0][0]].isApprox(0.001 * first, 1e-6));
  }
  // ROS convention: the root transform is reset, so neither the unit nor the up axis applies.
  MeshLoadOptions ros;
  ros.keep_root_transform = false;
  ros.scale = Eigen::Vector3d(0.5, 0.5, 0.5);
  for (const char* axis : {"Y_UP", "Z_UP"}) {
    const TriangleMesh m =
        loadMesh(writeCollada(std::string(axis) + ".dae", "centimeter", 0.01, axis), ros);
    EXPECT_TRUE(m.vertices[m.triangles[0][0]].isApprox(0.5 * first, 1e-6)) << axis;
  }
}

TEST_F(MeshFiles, BadFilesThrowFileErrorNamingTheFile) {
  auto expectFileError = [](const std::string& file, const std::string& what) {
    try {
      loadMesh(file);
      ADD_FAILURE() << "no exception for " << file;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expectFileError(path("missing.stl"), "cannot open");
  static const char kGarbage[] = "\x01\x02 this is not a mesh \xff\xfe";
  expectFileError(writeText("garbage.stl", std::string(kGarbage, sizeof kGarbage - 1)), "");
  expectFileError(writeText("garbage.dae", "<COLLADA><broken"), "");
  expectFileError(writeText("empty.obj", "# nothing here\n"), "");
  expectFileError(writeText("zero.stl", ""), "");
  expectFileError(writeText("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\n"), "");
  expectFileError(writeText("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "");
  // A directory is not a mesh file either.
  expectFileError(dir_.string(), "");
  MeshLoadOptions zero_scale;
  zero_scale.scale.y() = 0.0;
  EXPECT_THROW(loadMesh(writeObj("ok.obj", boxMesh(Eigen::Vector3d::Ones())), zero_scale),
               InvalidArgument);
}

TEST_F(MeshFiles, CommittedTestMeshesLoad) {
  const std::string dir = std::string(OCTOMOTION_TEST_DATA_DIR) + "/meshes/";
  const TriangleMesh cube = loadMesh(dir + "unit_cube.stl");
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_TRUE(isClosedManifold(cube));
  const TriangleMesh tetra = loadMesh(dir + "tetra_cm_zup.dae");
  EXPECT_EQ(tetra.triangles.size(), 4u);
  EXPECT_TRUE(isClosedManifold(tetra));
  // 10 cm, and Z-up turned to assimp's Y-up: the apex (0, 0, 10) cm ends at (0, 0.1, 0) m.
  const Eigen::AlignedBox3d b = boundsOf(tetra);
  EXPECT_LT((b.min() - Eigen::Vector3d(0, 0, -0.1)).norm(), 1e-7) << b.min().transpose();
  EXPECT_LT((b.max() - Eigen::Vector3d(0.1, 0.1, 0)).norm(), 1e-7) << b.max().transpose();
  MeshLoadOptions ros;
  ros.keep_root_transform = false;
  const Eigen::AlignedBox3d raw = boundsOf(loadMesh(dir + "tetra_cm_zup.dae", ros));
  EXPECT_TRUE(raw.max().isApprox(Eigen::Vector3d(10, 10, 10), 1e-6));
  // Solid fill of the loaded tetrahedron: 1/6 of the 10 cm cube, within the voxel rounding.
  const WorldGrid grid(Eigen::Vector3d(-0.01, -0.01, -0.11), 0.125 / 64, 6);
  const Octree solid = voxelizeMesh(grid, tetra, Eigen::Isometry3d::Identity(), Rounding::kCenter);
  expectCompact(solid);
  EXPECT_NEAR(solid.volume(), 1e-3 / 6, 0.1 * 1e-3 / 6);
}

}  // namespace
}  // namespace octomotion
