// Property tests of the primitive and point builders (Weng & Ahuja 1987 §3-§4 rounding rule and
// top-down construction) against brute force over the dense voxel grid, depths 3-7, fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "dense_grid.h"
#include "octomotion/error.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace {

using test::DenseGrid;

constexpr double kVoxel = 0.1;
WorldGrid gridOfDepth(int depth) {
  return WorldGrid(Eigen::Vector3d(-0.3, 0.1, -0.7), kVoxel, depth);
}

void expectCompact(const Octree& tree) {
  std::string why;
  EXPECT_TRUE(tree.checkInvariants(&why)) << why;
}

Eigen::Isometry3d randomPose(const WorldGrid& grid, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  std::uniform_real_distribution<double> u(0.1, 0.9);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = grid.origin() + grid.sideMetres() * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

// Sizes from a fraction of a voxel up to a good part of the universe, so that both tiny shapes
// (fewer voxels than the rounding matters for) and big ones (deep compaction) occur.
Primitive randomPrimitive(const WorldGrid& grid, std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> logsize(std::log(0.3 * kVoxel),
                                                 std::log(0.35 * grid.sideMetres()));
  auto size = [&] { return std::exp(logsize(rng)); };
  switch (kind % 3) {
    case 0:
      return Box{Eigen::Vector3d(size(), size(), size())};
    case 1:
      return Sphere{size()};
    default:
      return Cylinder{size(), 2.0 * size()};
  }
}

// A 1-Lipschitz function of the shape-frame point that is <= 0 exactly on and inside the shape.
double boundDistance(const Primitive& shape, const Eigen::Vector3d& p) {
  if (const Box* box = std::get_if<Box>(&shape)) {
    return (p.cwiseAbs() - box->half_extents).maxCoeff();
  }
  if (const Sphere* sphere = std::get_if<Sphere>(&shape)) return p.norm() - sphere->radius;
  const Cylinder& c = std::get<Cylinder>(shape);
  return std::max(p.head<2>().norm() - c.radius, std::abs(p.z()) - 0.5 * c.length);
}

enum class Truth { kNo, kYes, kUnknown };

// Independent oracle for "the shape touches the closed world box [lo, hi]": branch and bound on
// the Lipschitz bound (never uses the library's geometry). Unknown only for true grazing contacts
// (closer than ~1e-9 of a voxel to touching or not).
Truth touchesBox(const Primitive& shape, const Eigen::Isometry3d& X_SW, const Eigen::Vector3d& lo,
                 const Eigen::Vector3d& hi, int budget = 30) {
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double f = boundDistance(shape, X_SW * centre);
  if (f <= 0.0) return Truth::kYes;
  const double half_diagonal = 0.5 * (hi - lo).norm();
  if (f > half_diagonal * (1 + 1e-12)) return Truth::kNo;
  if (budget == 0) return Truth::kUnknown;
  bool unknown = false;
  for (int k = 0; k < 8; ++k) {
    Eigen::Vector3d a, b;
    for (int i = 0; i < 3; ++i) {
      a[i] = (k >> i & 1) ? centre[i] : lo[i];
      b[i] = (k >> i & 1) ? hi[i] : centre[i];
    }
    const Truth t = touchesBox(shape, X_SW, a, b, budget - 1);
    if (t == Truth::kYes) return Truth::kYes;
    if (t == Truth::kUnknown) unknown = true;
  }
  return unknown ? Truth::kUnknown : Truth::kNo;
}

// Compares a built tree with (1) the library's own per-voxel rule at every voxel -- exactly, which
// checks that the descent's inside/outside verdicts above level 0 are sound -- and (2) the
// independent oracle for every voxel it can decide.
void checkAgainstBruteForce(const WorldGrid& grid, const Primitive& shape,
                            const Eigen::Isometry3d& X_WS, Rounding rounding, const Octree& tree,
                            std::size_t* undecided) {
  const DenseGrid dense = DenseGrid::fromTree(tree);
  const Eigen::Isometry3d X_SW = X_WS.inverse();
  const std::uint32_t side = grid.sideVoxels();
  std::size_t mismatches = 0;
  for (std::uint32_t z = 0; z < side; ++z) {
    for (std::uint32_t y = 0; y < side; ++y) {
      for (std::uint32_t x = 0; x < side; ++x) {
        const Voxel v{x, y, z};
        const bool black = dense.get(v);
        const Eigen::Vector3d centre = grid.voxelCenter(v);
        const double f = boundDistance(shape, X_SW * centre);
        // The library's own rule, exactly, wherever it could be in doubt (within two voxels of
        // the surface); further away the independent check below is exact anyway.
        if (std::abs(f) < 2 * kVoxel && black != voxelIsBlack(grid, shape, X_WS, rounding, v)) {
          if (++mismatches < 5) ADD_FAILURE() << "voxel " << x << "," << y << "," << z;
        }
        // Independent check. Cheap rejection first: the shape's bound at the centre is far.
        Truth truth;
        if (rounding == Rounding::kCenter) {
          truth = std::abs(f) < 1e-12 ? Truth::kUnknown : (f < 0 ? Truth::kYes : Truth::kNo);
        } else if (f > kVoxel) {
          truth = Truth::kNo;
        } else {
          // The object must reach into the voxel: its interior, shrunk by the 1e-6-voxel tie.
          Cube c{0, v};
          const Eigen::Vector3d tie = Eigen::Vector3d::Constant(1e-6 * kVoxel);
          truth = touchesBox(shape, X_SW, grid.cubeMin(c) + tie, grid.cubeMax(c) - tie);
        }
        if (truth == Truth::kUnknown) {
          ++*undecided;
        } else if (black != (truth == Truth::kYes)) {
          if (++mismatches < 5) {
            ADD_FAILURE() << "oracle disagrees at voxel " << x << "," << y << "," << z;
          }
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(Voxelize, PrimitivesMatchBruteForceBothModes) {
  std::mt19937_64 rng(1987);
  std::size_t undecided = 0, checked_voxels = 0;
  for (int depth = 3; depth <= 7; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    const int trials = depth <= 5 ? 16 : depth == 6 ? 8 : 4;
    for (int trial = 0; trial < trials; ++trial) {
      const Primitive shape = randomPrimitive(grid, rng, trial);
      const Eigen::Isometry3d X_WS = randomPose(grid, rng);
      for (Rounding rounding : {Rounding::kConservative, Rounding::kCenter}) {
        SCOPED_TRACE("depth " + std::to_string(depth) + " trial " + std::to_string(trial) + " " +
                     toString(rounding));
        const Octree tree = voxelize(grid, shape, X_WS, rounding);
        expectCompact(tree);
        checkAgainstBruteForce(grid, shape, X_WS, rounding, tree, &undecided);
        checked_voxels += std::size_t{grid.sideVoxels()} * grid.sideVoxels() * grid.sideVoxels();
      }
    }
  }
  // Grazing contacts closer than ~1e-9 voxel are vanishingly rare with random poses.
  EXPECT_LT(undecided, checked_voxels / 100000 + 5);
}

TEST(Voxelize, ConservativeNeverMissesAPointOfTheShape) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 24; ++trial) {
    const WorldGrid grid = gridOfDepth(trial % 2 ? 6 : 8);
    const Primitive shape = randomPrimitive(grid, rng, trial);
    const Eigen::Isometry3d X_WS = randomPose(grid, rng);
    const Octree tree = voxelize(grid, shape, X_WS, Rounding::kConservative);
    expectCompact(tree);
    // Points inside (rejection sampling in the shape's bounding box) and on the surface (the
    // Lipschitz bound is a distance on the faces we aim at: push points onto the boundary).
    Eigen::Vector3d half;
    if (const Box* b = std::get_if<Box>(&shape)) half = b->half_extents;
    if (const Sphere* s = std::get_if<Sphere>(&shape)) half.setConstant(s->radius);
    if (const Cylinder* c = std::get_if<Cylinder>(&shape)) {
      half = Eigen::Vector3d(c->radius, c->radius, 0.5 * c->length);
    }
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int tested = 0;
    for (int i = 0; i < 20000 && tested < 3000; ++i) {
      Eigen::Vector3d p_S(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
      if (i % 2) {
        // Snap to the surface along one axis-aligned direction of the shape frame.
        const int axis = i % 3;
        if (std::holds_alternative<Box>(shape)) {
          p_S[axis] = p_S[axis] < 0 ? -half[axis] : half[axis];
        } else if (std::holds_alternative<Sphere>(shape)) {
          p_S *= half.x() / p_S.norm();
        } else if (axis == 2) {
          p_S.z() = p_S.z() < 0 ? -half.z() : half.z();
        } else {
          p_S.head<2>() *= half.x() / p_S.head<2>().norm();
        }
      }
      if (boundDistance(shape, p_S) > 1e-12) continue;
      ++tested;
      const Eigen::Vector3d p_W = X_WS * p_S;
      Voxel v;
      if (!grid.voxelAt(p_W, &v)) continue;
      ASSERT_TRUE(tree.occupied(v))
          << "point " << p_W.transpose() << " of shape " << trial << " is in a white voxel";
    }
    EXPECT_GT(tested, 500);
  }
}

TEST(Voxelize, CenterModeIsPointInShapeAtVoxelCentres) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 9; ++trial) {
    const WorldGrid grid = gridOfDepth(6);
    const Primitive shape = randomPrimitive(grid, rng, trial);
    const Eigen::Isometry3d X_WS = randomPose(grid, rng);
    const Octree tree = voxelize(grid, shape, X_WS, Rounding::kCenter);
    expectCompact(tree);
    const Eigen::Isometry3d X_SW = X_WS.inverse();
    const std::uint32_t side = grid.sideVoxels();
    for (std::uint32_t z = 0; z < side; ++z)
      for (std::uint32_t y = 0; y < side; ++y)
        for (std::uint32_t x = 0; x < side; ++x) {
          const Eigen::Vector3d p_S = X_SW * grid.voxelCenter({x, y, z});
          if (std::abs(boundDistance(shape, p_S)) < 1e-12) continue;
          ASSERT_EQ(tree.occupied({x, y, z}), containsPoint(shape, p_S))
              << "trial " << trial << " voxel " << x << "," << y << "," << z;
        }
  }
}

TEST(Voxelize, CenterModeKeepsVolumeAndConservativeContainsIt) {
  // Weng & Ahuja §3: the centre rule roughly preserves volume; conservative over-covers.
  const WorldGrid grid = gridOfDepth(7);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 6; ++trial) {
    const Primitive shape = trial % 3 == 0   ? Primitive(Box{Eigen::Vector3d(1.1, 0.7, 2.3)})
                            : trial % 3 == 1 ? Primitive(Sphere{2.2})
                                             : Primitive(Cylinder{1.3, 3.1});
    Eigen::Isometry3d X_WS = randomPose(grid, rng);
    X_WS.translation() =
        grid.origin() + Eigen::Vector3d::Constant(grid.sideMetres() / 2);  // unclipped
    const Octree center = voxelize(grid, shape, X_WS, Rounding::kCenter);
    const Octree conservative = voxelize(grid, shape, X_WS, Rounding::kConservative);
    expectCompact(center);
    expectCompact(conservative);
    const double exact = trial % 3 == 0   ? 8 * 1.1 * 0.7 * 2.3
                         : trial % 3 == 1 ? 4.0 / 3.0 * M_PI * 2.2 * 2.2 * 2.2
                                          : M_PI * 1.3 * 1.3 * 3.1;
    EXPECT_NEAR(center.volume(), exact, 0.02 * exact) << trial;
    EXPECT_GT(conservative.volume(), exact);
    // Every centre-mode voxel is also a conservative one.
    for (const Voxel& v : center.blackVoxels()) ASSERT_TRUE(conservative.occupied(v));
  }
}

TEST(Voxelize, AxisAlignedBoxOnVoxelBoundaries) {
  // A box whose faces lie exactly on voxel faces: both modes give exactly the box's voxels
  // (conservative rounding asks for the voxel's interior, so the layer of voxels that only
  // touch the faces stays white). Moved by a thousandth of a voxel, it reaches into one layer.
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.25, 5);
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  X_WS.translation() =
      Eigen::Vector3d(2.0, 2.5, 3.0);  // box spans voxels [6,10) x [8,12) x [10,14)
  const Box box{Eigen::Vector3d(0.5, 0.5, 0.5)};
  const Octree center = voxelize(grid, box, X_WS, Rounding::kCenter);
  const Octree conservative = voxelize(grid, box, X_WS, Rounding::kConservative);
  expectCompact(center);
  expectCompact(conservative);
  EXPECT_EQ(center.blackVoxelCount(), 64u);
  EXPECT_TRUE(center.occupied({6, 8, 10}));
  EXPECT_TRUE(center.occupied({9, 11, 13}));
  EXPECT_FALSE(center.occupied({10, 11, 13}));
  EXPECT_EQ(conservative, center);
  EXPECT_FALSE(conservative.occupied({5, 8, 10}));
  EXPECT_FALSE(conservative.occupied({10, 8, 10}));
  X_WS.translation().x() += 1e-3 * grid.voxelSize();
  const Octree moved = voxelize(grid, box, X_WS, Rounding::kConservative);
  EXPECT_EQ(moved.blackVoxelCount(), 5u * 4u * 4u);
  EXPECT_TRUE(moved.occupied({10, 8, 10}));
  EXPECT_FALSE(moved.occupied({5, 8, 10}));
  // By less than the tie (1e-6 voxel) it does not.
  X_WS.translation().x() += -1e-3 * grid.voxelSize() + 1e-7 * grid.voxelSize();
  EXPECT_EQ(voxelize(grid, box, X_WS, Rounding::kConservative), center);
}

TEST(Voxelize, UniverseWideAndDisjointShapes) {
  const WorldGrid grid = gridOfDepth(4);
  const Eigen::Vector3d middle = grid.origin() + Eigen::Vector3d::Constant(grid.sideMetres() / 2);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = middle;
  for (Rounding r : {Rounding::kConservative, Rounding::kCenter}) {
    EXPECT_EQ(voxelize(grid, Sphere{10.0}, X, r), Octree::full(grid));
    EXPECT_EQ(voxelize(grid, Box{Eigen::Vector3d::Constant(0.8)}, X, r), Octree::full(grid));
    Eigen::Isometry3d far = X;
    far.translation().x() += 50.0;
    EXPECT_TRUE(voxelize(grid, Cylinder{1.0, 2.0}, far, r).empty());
  }
  // A shape far smaller than a voxel: conservative keeps it, the centre rule drops it.
  Eigen::Isometry3d tiny = X;
  tiny.translation() += Eigen::Vector3d(0.021, 0.033, 0.047);
  EXPECT_EQ(voxelize(grid, Sphere{0.001}, tiny, Rounding::kConservative).blackVoxelCount(), 1u);
  EXPECT_TRUE(voxelize(grid, Sphere{0.001}, tiny, Rounding::kCenter).empty());
  // A shape sticking out of the universe is clipped, not rejected.
  Eigen::Isometry3d corner = Eigen::Isometry3d::Identity();
  corner.translation() = grid.origin();
  const Octree clipped = voxelize(grid, Sphere{0.35}, corner, Rounding::kCenter);
  expectCompact(clipped);
  EXPECT_TRUE(clipped.occupied({0, 0, 0}));
  EXPECT_FALSE(clipped.occupied({4, 0, 0}));
}

TEST(Voxelize, CylinderOverApproximationIsBounded) {
  // The cylinder test is exact: every conservative voxel really is within reach of the solid.
  // Check directly with the branch-and-bound oracle at a finer tolerance.
  const WorldGrid grid = gridOfDepth(6);
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 4; ++trial) {
    const Cylinder cylinder{0.4 + 0.3 * trial, 1.7};
    const Eigen::Isometry3d X_WS = randomPose(grid, rng);
    const Octree tree = voxelize(grid, cylinder, X_WS, Rounding::kConservative);
    const Eigen::Isometry3d X_SW = X_WS.inverse();
    for (const Voxel& v : tree.blackVoxels()) {
      const Cube c{0, v};
      // Grow the voxel by 1e-9 voxel: anything touching the grown voxel counts.
      const Eigen::Vector3d pad = Eigen::Vector3d::Constant(1e-9 * kVoxel);
      ASSERT_NE(touchesBox(cylinder, X_SW, grid.cubeMin(c) - pad, grid.cubeMax(c) + pad),
                Truth::kNo)
          << "voxel " << v.x << "," << v.y << "," << v.z << " does not touch the cylinder";
    }
  }
}

TEST(Voxelize, RejectsBadShapesAndPoses) {
  const WorldGrid grid = gridOfDepth(4);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto message = [&](const Primitive& shape, const Eigen::Isometry3d& X) -> std::string {
    try {
      voxelize(grid, shape, X, Rounding::kCenter);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message(Box{Eigen::Vector3d(1, 0, 1)}, I).find("Box.half_extents.y"),
            std::string::npos);
  EXPECT_NE(message(Box{Eigen::Vector3d(1, 1, -2)}, I).find("Box.half_extents.z"),
            std::string::npos);
  EXPECT_NE(message(Sphere{std::nan("")}, I).find("Sphere.radius"), std::string::npos);
  EXPECT_NE(message(Sphere{INFINITY}, I).find("Sphere.radius"), std::string::npos);
  EXPECT_NE(message(Cylinder{1.0, 0.0}, I).find("Cylinder.length"), std::string::npos);
  EXPECT_NE(message(Cylinder{-1.0, 1.0}, I).find("Cylinder.radius"), std::string::npos);
  Eigen::Isometry3d nan_pose = I;
  nan_pose.translation().x() = std::nan("");
  EXPECT_NE(message(Sphere{1.0}, nan_pose).find("X_WS"), std::string::npos);
  Eigen::Isometry3d scaled = I;
  scaled.linear() *= 2.0;
  EXPECT_NE(message(Sphere{1.0}, scaled).find("rotation"), std::string::npos);
  Eigen::Isometry3d mirrored = I;
  mirrored.linear()(0, 0) = -1.0;
  EXPECT_NE(message(Sphere{1.0}, mirrored).find("rotation"), std::string::npos);
}

TEST(VoxelizePoints, MarksTheVoxelOfEveryPointInside) {
  std::mt19937_64 rng(99);
  for (int depth = 3; depth <= 7; ++depth) {
    const WorldGrid grid = gridOfDepth(depth);
    DenseGrid expected(depth);
    std::vector<Eigen::Vector3d> points;
    std::uniform_real_distribution<double> u(-0.2, 1.2);
    // Clusters (so that compaction happens) plus scattered points, some outside the universe.
    for (int i = 0; i < 4000; ++i) {
      Eigen::Vector3d f(u(rng), u(rng), u(rng));
      if (i % 2) f = Eigen::Vector3d(0.3, 0.4, 0.5) + 0.1 * f;
      const Eigen::Vector3d p = grid.origin() + grid.sideMetres() * f;
      points.push_back(p);
      Voxel v;
      if (grid.voxelAt(p, &v)) expected.set(v);
    }
    const Octree tree = voxelizePoints(grid, points);
    expectCompact(tree);
    EXPECT_EQ(DenseGrid::fromTree(tree), expected) << depth;
  }
  const WorldGrid grid = gridOfDepth(3);
  EXPECT_TRUE(voxelizePoints(grid, {}).empty());
  try {
    voxelizePoints(grid, {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, std::nan(""), 0)});
    FAIL() << "NaN point accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("points_W[1]"), std::string::npos);
  }
}

}  // namespace
}  // namespace octomotion
