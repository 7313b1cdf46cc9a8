// The free-flying bound of LinkMotionBound (robot/motion_bound.h): for random rigid bodies
// (primitives and meshes, the origin away from their centre) and random SE(3) edges, no point
// travels farther along OMPL's interpolation than its link's bound, which is at most the bound
// by the radius (|dt| + radius * theta); the axis tables hold every point's distance from
// random axes (bodies with fixed and with movable joints) and exceed the largest of them by at
// most a cell's angular radius times the radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <ompl/base/ScopedState.h>

#include "generated_meshes.h"
#include "link_points.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/robot/motion_bound.h"

namespace octomotion {
namespace {

const std::string kSource = OCTOMOTION_SOURCE_DIR;

Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  Eigen::Vector4d v;
  for (int i = 0; i < 4; ++i) v[i] = std::normal_distribution<double>()(rng);
  return Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized();
}

Eigen::Vector3d randomVector(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return {u(rng), u(rng), u(rng)};
}

// A random part: a box, a ball, a cylinder or a blob mesh written to `path`.
CollisionGeometry randomPart(std::mt19937_64& rng, const std::string& path) {
  switch (std::uniform_int_distribution<int>(0, 3)(rng)) {
    case 0:
      return Primitive{Box{randomVector(rng, 0.01, 0.8)}};
    case 1:
      return Primitive{Sphere{std::uniform_real_distribution<double>(0.02, 0.4)(rng)}};
    case 2:
      return Primitive{Cylinder{std::uniform_real_distribution<double>(0.02, 0.3)(rng),
                                std::uniform_real_distribution<double>(0.05, 1.5)(rng)}};
    default: {
      TriangleMesh mesh = test::blobMesh(0.4, 0.3, rng);
      // Stretched along one side: long bodies gain most from the axis.
      const Eigen::Vector3d stretch = randomVector(rng, 0.3, 2.5);
      for (Eigen::Vector3d& v : mesh.vertices) v = v.cwiseProduct(stretch);
      test::writeStl(path, mesh);
      return MeshRef{path, Eigen::Vector3d::Ones()};
    }
  }
}

// A random rigid body of 1 to 4 parts, each at a random pose, all shifted by an offset of up to
// 1.5 m so the origin is off-centre.
RobotModel randomBody(std::mt19937_64& rng, const std::filesystem::path& dir, int index) {
  std::vector<CollisionElement> elements;
  const Eigen::Vector3d offset = randomVector(rng, -1.5, 1.5);
  const int parts = std::uniform_int_distribution<int>(1, 4)(rng);
  for (int k = 0; k < parts; ++k) {
    Eigen::Isometry3d X_LE = Eigen::Isometry3d::Identity();
    X_LE.linear() = randomRotation(rng).toRotationMatrix();
    X_LE.translation() = offset + randomVector(rng, -0.6, 0.6);
    const std::string path =
        (dir / ("blob" + std::to_string(index) + "_" + std::to_string(k) + ".stl")).string();
    elements.push_back(CollisionElement{X_LE, randomPart(rng, path), "part"});
  }
  return RobotModel::rigidBody("body" + std::to_string(index), std::move(elements));
}

TEST(FreeFlyingBound, NoPointOfARandomBodyTravelsFartherThanItsBound) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "octomotion_free_flying_bound_test";
  std::filesystem::create_directories(dir);
  std::mt19937_64 rng(29);
  const Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-3), Eigen::Vector3d::Constant(3));
  constexpr int kSteps = 256;
  double new_sum = 0.0, old_sum = 0.0;
  for (int body = 0; body < 12; ++body) {
    const RobotModel robot = randomBody(rng, dir, body);
    const LinkMotionBound bound(robot);
    CollisionMeshes meshes(false, false);
    const std::vector<Eigen::Vector3d> points = test::linkPoints(robot.link(0), meshes, 100000);
    ASSERT_FALSE(points.empty());
    auto space = makeStateSpace(robot, &box);
    space->setup();
    ompl::base::ScopedState<> s1(space), s2(space), s(space);
    auto place = [&](ompl::base::State* state, const Eigen::Isometry3d& X) {
      configurationToState(robot, {}, X, state);
    };
    std::vector<double> q;
    for (int m = 0; m < 30; ++m) {
      Eigen::Isometry3d X1 = Eigen::Isometry3d::Identity(), X2 = X1;
      X1.linear() = randomRotation(rng).toRotationMatrix();
      X1.translation() = randomVector(rng, -2, 2);
      // Short and long turns, pure turns and pure translations, turns about an axis the
      // translation runs along.
      const int kind = m % 5;
      const double angle = kind == 0 ? 0.01 : std::uniform_real_distribution<double>(0, M_PI)(rng);
      const Eigen::Vector3d axis = randomVector(rng, -1, 1).normalized();
      const Eigen::Matrix3d turn = kind == 4 ? Eigen::Matrix3d::Identity()
                                             : Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      X2.linear() = X1.linear() * turn;
      const double length = kind == 3 ? 0.0 : std::uniform_real_distribution<double>(0, 2)(rng);
      const Eigen::Vector3d direction =
          kind == 2 ? Eigen::Vector3d(X1.linear() * axis) : randomVector(rng, -1, 1).normalized();
      X2.translation() = X1.translation() + length * direction;
      place(s1.get(), X1);
      place(s2.get(), X2);
      Eigen::Isometry3d Y1, Y2, X, previous;
      ASSERT_TRUE(stateToConfiguration(robot, s1.get(), q, Y1));
      ASSERT_TRUE(stateToConfiguration(robot, s2.get(), q, Y2));
      const LinkMotionBound::RootMotion root(Y1, Y2);
      const double limit = bound.freeFlyingBound(0, root);
      const double old_limit =
          (Y2.translation() - Y1.translation()).norm() + bound.radius() * root.angle;
      EXPECT_LE(limit, old_limit * (1 + 1e-6) + 1e-12) << "body " << body << " motion " << m;
      std::vector<double> travelled(points.size(), 0.0);
      for (int k = 0; k <= kSteps; ++k) {
        space->interpolate(s1.get(), s2.get(), static_cast<double>(k) / kSteps, s.get());
        ASSERT_TRUE(stateToConfiguration(robot, s.get(), q, X));
        for (std::size_t i = 0; k > 0 && i < points.size(); ++i) {
          travelled[i] += (X * points[i] - previous * points[i]).norm();
        }
        previous = X;
      }
      const double most = *std::max_element(travelled.begin(), travelled.end());
      EXPECT_LE(most, limit + 1e-9) << "body " << body << " motion " << m;
      // A part of the edge: the same motion scaled by its length.
      space->interpolate(s1.get(), s2.get(), 0.25, s.get());
      ASSERT_TRUE(stateToConfiguration(robot, s.get(), q, X));
      space->interpolate(s1.get(), s2.get(), 0.75, s.get());
      ASSERT_TRUE(stateToConfiguration(robot, s.get(), q, previous));
      EXPECT_NEAR(bound.freeFlyingBound(0, LinkMotionBound::RootMotion(X, previous)), 0.5 * limit,
                  1e-6 * limit + 1e-9);
      new_sum += limit;
      old_sum += old_limit;
    }
  }
  // The axis pays: on these bodies the bound is clearly below the radius's.
  EXPECT_LT(new_sum, 0.95 * old_sum);
  std::filesystem::remove_all(dir);
}

// Per link, axisRadius(l, u) against the largest distance from the axis u of the link's points
// over `poses` (root frame), for `axes` axes: at least it, and at most `slack` more.
void expectAxisRadiusHolds(const RobotModel& robot, const LinkMotionBound& bound,
                           const std::vector<std::vector<Eigen::Isometry3d>>& poses, double slack,
                           int axes, std::uint64_t seed) {
  CollisionMeshes meshes(false, false);
  std::mt19937_64 rng(seed);
  for (int l : bound.geometryLinks()) {
    const std::vector<Eigen::Vector3d> points = test::linkPoints(robot.link(l), meshes, 100000);
    for (int a = 0; a < axes; ++a) {
      // Random axes, and axes on the cells' borders (a coordinate equal to another, or 0).
      Eigen::Vector3d u = randomVector(rng, -1, 1);
      if (a % 4 == 1) u[a % 3] = u[(a + 1) % 3];
      if (a % 4 == 2) u[a % 3] = 0.0;
      if (a % 4 == 3) u = Eigen::Vector3d::Unit(a % 3) * (a % 2 ? 1.0 : -1.0);
      u.normalize();
      double most = 0.0;
      for (const std::vector<Eigen::Isometry3d>& X : poses) {
        for (const Eigen::Vector3d& p : points) {
          most = std::max(most, u.cross(X[static_cast<std::size_t>(l)] * p).norm());
        }
      }
      const double table = bound.axisRadius(l, u);
      EXPECT_GE(table, most) << robot.link(l).name << " axis " << u.transpose();
      EXPECT_LE(table, most + slack) << robot.link(l).name << " axis " << u.transpose();
      EXPECT_LE(table, bound.radius() * (1 + 1e-6));
    }
  }
}

TEST(FreeFlyingBound, AxisRadiusHoldsTheLinksOfARigidUrdf) {
  // Three links on fixed joints, the last far from the root: each link its own table.
  const std::string urdf = R"(<robot name="rod">
  <link name="a"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.6 0.1 0.1"/></geometry>
  </collision></link>
  <link name="b"><collision><origin xyz="0 0.2 0" rpy="0.3 0.2 0.1"/><geometry>
  <cylinder radius="0.05" length="0.4"/></geometry></collision></link>
  <link name="c"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0.6 0 0"/></joint>
  <joint name="bc" type="fixed"><parent link="b"/><child link="c"/>
  <origin xyz="0 0.4 0.2" rpy="0 0.5 0"/></joint>
</robot>)";
  RobotModelOptions options;
  options.base = BaseMotion::kFreeFlying;
  const RobotModel robot = RobotModel::fromUrdfString(urdf, "rod.urdf", kSource, options);
  ASSERT_TRUE(robot.isFreeFlying());
  ASSERT_EQ(robot.linkCount(), 3);
  const LinkMotionBound bound(robot);
  RobotData data = robot.makeData();
  robot.forwardKinematics(nullptr, 0, data, Eigen::Isometry3d::Identity());
  std::vector<Eigen::Isometry3d> X(data.X_WL.begin(), data.X_WL.end());
  // A cell's axes are at most 1.5 / kAxisCells radians from its centre, so at most twice that
  // from each other.
  expectAxisRadiusHolds(robot, bound, {X}, 3.0 / LinkMotionBound::kAxisCells * bound.radius(), 500,
                        7);
  // The sphere far out: its own table is below the whole robot's radius along most axes.
  const int c = robot.linkIndex("c");
  EXPECT_LT(bound.axisRadius(c, Eigen::Vector3d(0.6, 0.4, 0.2).normalized()), 0.5 * bound.radius());
}

TEST(FreeFlyingBound, AxisRadiusHoldsOverTheJointsOfAFreeFlyingArm) {
  RobotModelOptions options;
  options.package_paths = {kSource};
  options.base = BaseMotion::kFreeFlying;
  const RobotModel robot = RobotModel::fromUrdfFile(kSource + "/robots/octo7/octo7.urdf", options);
  ASSERT_GT(robot.variableCount(), 0);
  const LinkMotionBound bound(robot);
  std::mt19937_64 rng(5);
  RobotData data = robot.makeData();
  const auto n = static_cast<std::size_t>(robot.variableCount());
  std::vector<std::vector<Eigen::Isometry3d>> poses;
  std::vector<double> q(n);
  for (int k = 0; k < 50; ++k) {
    for (std::size_t v = 0; v < n; ++v) {
      const Variable& var = robot.variables()[v];
      q[v] = std::uniform_real_distribution<double>(var.lower, var.upper)(rng);
    }
    robot.forwardKinematics(q.data(), n, data, Eigen::Isometry3d::Identity());
    poses.emplace_back(data.X_WL.begin(), data.X_WL.end());
  }
  // Below a movable joint the table bounds through the joints' origins: sound, not tight.
  expectAxisRadiusHolds(robot, bound, poses, 2 * bound.radius(), 100, 9);
}

}  // namespace
}  // namespace octomotion
