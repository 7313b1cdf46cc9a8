// robot.pose: the Panda mounted at a non-trivial pose, in a generated environment moved with it.
// Every checker takes the mount the same way (built in): the conservative octree misses no FCL
// contact and rejects no free state beyond its margin (docs/validation.md), mounted or not, and
// disagrees with FCL about as often mounted as unmounted; the exact FCL reference of the mounted
// scene gives the same answers as the unmounted one in the environment moved by the inverse
// mount; and FCL on an OctoMap of the mounted scene misses no exact contact either.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include <unistd.h>

#include "differential.h"

namespace octomotion::validation {
namespace {

namespace fs = std::filesystem;

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

std::string yamlPose(const Eigen::Isometry3d& X) {
  std::ostringstream out;
  out.precision(17);
  const Eigen::Quaterniond q(X.linear());
  out << "{xyz: [" << X.translation().x() << ", " << X.translation().y() << ", "
      << X.translation().z() << "], quat: [" << q.x() << ", " << q.y() << ", " << q.z() << ", "
      << q.w() << "]}";
  return out.str();
}

struct Object {
  std::string shape;       // "box: {...}" etc.
  Eigen::Isometry3d X_BO;  // in the robot's base frame
};

// Boxes, balls and cylinders of 3 to 15 cm within the Panda's reach (fixed seed).
std::vector<Object> generatedEnvironment(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  std::vector<Object> objects;
  for (int k = 0; k < 14; ++k) {
    Object o;
    const double a = 2 * M_PI * unit(rng), r = 0.25 + 0.5 * unit(rng);
    o.X_BO = Eigen::Isometry3d::Identity();
    o.X_BO.translation() = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 1.0 * unit(rng));
    o.X_BO.linear() = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
                          .normalized()
                          .toRotationMatrix();
    const double s = 0.03 + 0.12 * unit(rng);
    std::ostringstream shape;
    shape.precision(17);
    switch (k % 3) {
      case 0:
        shape << "box: {size: [" << s << ", " << 0.5 * s + 0.02 << ", " << 1.5 * s << "]}";
        break;
      case 1:
        shape << "sphere: {radius: " << s / 2 << "}";
        break;
      default:
        shape << "cylinder: {radius: " << s / 3 << ", length: " << 2 * s << "}";
    }
    o.shape = shape.str();
    objects.push_back(o);
  }
  return objects;
}

// The Panda at `mount` (none: unmounted), the objects at X_WE * X_BO.
std::string writeScene(const std::string& file, const std::vector<Object>& objects,
                       const std::optional<Eigen::Isometry3d>& mount,
                       const Eigen::Isometry3d& X_WE) {
  std::ofstream out(file);
  out << "robot:\n  urdf: " << kPanda << "/panda.urdf\n  srdf: " << kPanda << "/panda.srdf\n";
  if (mount) out << "  pose: " << yamlPose(*mount) << "\n";
  out << "environment:\n";
  for (const Object& o : objects)
    out << "  - {" << o.shape << ", pose: " << yamlPose(X_WE * o.X_BO) << "}\n";
  out << "octree: {resolution: 0.02, rounding: conservative, checker: octree-fused}\n";
  return file;
}

struct Tally {
  std::size_t states = 0, contacts = 0, missed = 0, extra = 0, extra_env = 0, beyond = 0;
  std::vector<bool> fcl;  // FCL's answer (environment or self) per state
};

// The octree (fused, conservative) against the scene's own exact reference.
Tally compare(const PlanningScene& scene, const std::vector<Sample>& samples) {
  const Resolutions r = resolutionsOf(*scene.model);
  const double s3 = std::sqrt(3.0);
  const double slack = kTieSlack * std::max(1.0, r.environment);
  const double delta_env = s3 * (r.environment + r.link) + slack;
  const double delta_self = 2 * s3 * r.self_link + slack;
  const OctreeBackend octree(scene.model, CheckerPath::kFused);
  const FclCollisionModel& fcl = *scene.fclModel();
  const auto scratch = octree.makeBackendScratch();
  const auto exact = fcl.makeBackendScratch();
  const differential_detail::Solids solids(scene);
  const RobotData& poses = octree.scratchOf(*scratch).check.robot;
  Tally t;
  for (const Sample& s : samples) {
    const Answers a = answersAt(s, fcl, *exact, octree, *scratch);
    ++t.states;
    t.fcl.push_back(a.fcl_env || a.fcl_self);
    t.contacts += a.fcl_env || a.fcl_self;
    t.missed += (a.fcl_env && !a.octree_env) + (a.fcl_self && !a.octree_self);
    if (a.octree_env && !a.fcl_env) {
      ++t.extra;
      ++t.extra_env;
      const double d = fcl.environmentDistance(fcl.scratchOf(*exact), 2 * delta_env);
      t.beyond += d > delta_env && !solids.environmentNested(poses);
    }
    if (a.octree_self && !a.fcl_self) {
      ++t.extra;
      const double d = fcl.selfDistance(fcl.scratchOf(*exact), 2 * delta_self);
      t.beyond += d > delta_self && !solids.selfNested(poses);
    }
  }
  return t;
}

TEST(Mount, EveryCheckerHonoursTheMount) {
  if (!fs::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  const fs::path dir =
      fs::temp_directory_path() / ("octomotion_mount_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<Object> objects = generatedEnvironment(0x6d6f756e74);
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.linear() = (Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.35, Eigen::Vector3d(1, -1, 0).normalized()))
                   .toRotationMatrix();
  M.translation() = Eigen::Vector3d(1.237, -0.613, 0.419);
  const PlanningScene unmounted = loadPlanningScene(writeScene(
      (dir / "unmounted.yaml").string(), objects, std::nullopt, Eigen::Isometry3d::Identity()));
  const PlanningScene mounted =
      loadPlanningScene(writeScene((dir / "mounted.yaml").string(), objects, M, M));
  EXPECT_TRUE(mounted.model->baseMount().isApprox(M, 1e-12));
  EXPECT_TRUE(mounted.fclModel()->baseMount().isApprox(M, 1e-12));

  // The same joint values for both; the base pose argument is the identity, which a fixed-base
  // robot ignores (the mount is built in).
  std::vector<Sample> samples = uniformSamples(unmounted, 1500, 0x5eed);
  for (Sample& s : samples) s.X_WB = Eigen::Isometry3d::Identity();
  const Tally a = compare(unmounted, samples);
  const Tally b = compare(mounted, samples);
  for (const Tally* t : {&a, &b}) {
    EXPECT_EQ(t->missed, 0u);
    EXPECT_EQ(t->beyond, 0u);
    EXPECT_GT(t->contacts, t->states / 20);  // not vacuous
    EXPECT_LT(t->contacts, t->states);
  }
  // The relative geometry is the same, so exact FCL answers the same; the octree's environment
  // voxels fall differently on the two grids (world-aligned), so its extra rejections of the
  // environment may differ a little, not in kind. (Self pairs are tested in link frames: the mount
  // cannot change them.)
  EXPECT_EQ(a.fcl, b.fcl);
  const double rate_a = static_cast<double>(a.extra_env) / static_cast<double>(a.states);
  const double rate_b = static_cast<double>(b.extra_env) / static_cast<double>(b.states);
  EXPECT_LE(rate_b, 1.5 * rate_a + 0.01) << "unmounted " << rate_a << ", mounted " << rate_b;
  std::cout << "FCL contacts " << a.contacts << " of " << a.states << "; octree extra rejections "
            << a.extra << " unmounted, " << b.extra << " mounted (environment " << a.extra_env
            << ", " << b.extra_env << ")\n";

  // FCL on an OctoMap (conservative voxels, exact robot) of the mounted scene: a superset of
  // the exact contacts, which it would not be if it put the robot at the origin.
  const FclOctomapCollisionModel& octomap = *mounted.fclOctomapModel();
  EXPECT_TRUE(octomap.baseMount().isApprox(M, 1e-12));
  const auto map_scratch = octomap.makeBackendScratch();
  std::size_t missed = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    if (b.fcl[i] && !octomap.inCollision(s.q.data(), s.q.size(), s.X_WB, *map_scratch)) ++missed;
  }
  EXPECT_EQ(missed, 0u);
  fs::remove_all(dir);
}

TEST(Mount, MountedFclEqualsUnmountedFclInTheInverselyMovedEnvironment) {
  if (!fs::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda at " << kPanda;
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.linear() =
      Eigen::AngleAxisd(-2.1, Eigen::Vector3d(0.2, 0.5, 1).normalized()).toRotationMatrix();
  M.translation() = Eigen::Vector3d(-0.4, 2.3, 0.8);
  std::vector<EnvironmentObject> world, moved;
  // Objects within reach, clear of the base.
  std::mt19937_64 rng(0x1a2b);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 12; ++k) {
    EnvironmentObject o;
    o.name = "object " + std::to_string(k);
    o.primitive =
        k % 2 ? Primitive(Sphere{0.06}) : Primitive(Box{Eigen::Vector3d(0.08, 0.04, 0.15)});
    const double a = 2 * M_PI * u(rng), r = 0.35 + 0.45 * u(rng);
    o.X_WO = M * Eigen::Translation3d(r * std::cos(a), r * std::sin(a), 0.2 + u(rng)) *
             Eigen::AngleAxisd(3 * u(rng), Eigen::Vector3d::UnitX());
    world.push_back(o);
    o.X_WO = M.inverse() * o.X_WO;
    moved.push_back(o);
  }
  const FclCollisionModel mounted(robot, EnvironmentGeometry::load(world), false, false, M);
  const FclCollisionModel unmounted(robot, EnvironmentGeometry::load(moved));
  auto sm = mounted.makeBackendScratch();
  auto su = unmounted.makeBackendScratch();
  std::mt19937_64 states(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int contacts = 0;
  for (int i = 0; i < 2000; ++i) {
    std::vector<double> q;
    for (const Variable& v : robot.variables())
      q.push_back(v.lower + (v.upper - v.lower) * unit(states));
    // Any base pose argument: a fixed-base robot stands at its mount.
    Eigen::Isometry3d ignored = Eigen::Isometry3d::Identity();
    ignored.translation() = Eigen::Vector3d(5 * unit(states), 0, 0);
    const bool hit = mounted.environmentInCollision(q.data(), q.size(), ignored, *sm);
    ASSERT_EQ(hit, unmounted.environmentInCollision(q.data(), q.size(), ignored, *su)) << i;
    EXPECT_NEAR(mounted.clearance(*sm), unmounted.clearance(*su), 1e-5) << i;
    contacts += hit;
  }
  EXPECT_GT(contacts, 100);
  EXPECT_LT(contacts, 1900);
}

}  // namespace
}  // namespace octomotion::validation
