// Exact refine mode's hull filter (planner/src/model/refine_hulls.cpp): a checked link pair
// whose hulls (the convex hull of each link's mesh vertices, ConvexPoints) are apart is cleared
// without voxels or FCL. Property: on the real Panda at uniform random states (fixed seed),
// every checked pair the filter calls apart is one FCL's mesh test finds free (explain with
// every contact). Not vacuous: the filter clears pairs, FCL finds self contacts, and the refined
// model counts the pairs it cleared this way. Skipped without ../shared/data/panda.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "exact_and_fcl.h"
#include "octomotion/motion/convex_gap.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/robot/collision_meshes.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion {
namespace {

const std::string kPanda = std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";

// Each link's mesh vertices in its frame, as the refine mode takes them (default mesh
// conventions); empty for a link without meshes.
std::vector<ConvexPoints> meshHulls(const RobotModel& robot) {
  CollisionMeshes meshes(false, false);
  std::vector<ConvexPoints> hulls(static_cast<std::size_t>(robot.linkCount()));
  for (int l = 0; l < robot.linkCount(); ++l) {
    std::vector<Eigen::Vector3d> points_L;
    for (const CollisionElement& e : robot.link(l).collision) {
      const TriangleMesh& mesh = meshes.get(std::get<MeshRef>(e.geometry));
      for (const Eigen::Vector3d& v : mesh.vertices) points_L.push_back(e.X_LE * v);
    }
    if (!points_L.empty()) hulls[static_cast<std::size_t>(l)] = ConvexPoints(points_L);
  }
  return hulls;
}

TEST(RefineHulls, EveryPairApartIsFreeForFcl) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda";
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  const std::vector<ConvexPoints> hulls = meshHulls(robot);
  const FclCollisionModel fcl(robot, EnvironmentGeometry::load({}));
  const auto scratch = fcl.makeBackendScratch();
  RobotData data = robot.makeData();
  std::mt19937_64 rng(0x4e11);
  ExplainOptions every;
  every.all = true;
  every.check_limits = false;
  std::size_t apart = 0, fcl_contacts = 0, wrong = 0;
  for (int state = 0; state < 1500; ++state) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    robot.forwardKinematics(q.data(), q.size(), data, Eigen::Isometry3d::Identity());
    std::set<std::pair<std::string, std::string>> touching;
    for (const InvalidityReason& r :
         fcl.explain(q.data(), q.size(), Eigen::Isometry3d::Identity(), *scratch, every).reasons) {
      if (r.kind != InvalidityReason::Kind::kSelf) continue;
      touching.insert({r.link, r.other});
      touching.insert({r.other, r.link});
      ++fcl_contacts;
    }
    for (const auto& [a, b] : robot.checkedPairs()) {
      const ConvexPoints& ha = hulls[static_cast<std::size_t>(a)];
      const ConvexPoints& hb = hulls[static_cast<std::size_t>(b)];
      if (ha.empty() || hb.empty()) continue;
      const Eigen::Isometry3d X_AB = data.linkPose(a).inverse() * data.linkPose(b);
      // The refine mode's gap (kHullGap) or none at all: apart must mean free either way.
      for (const double gap : {1e-5, 0.0}) {
        if (!convexApart(ha, hb, X_AB, gap)) continue;
        ++apart;
        if (touching.count({robot.link(a).name, robot.link(b).name}) != 0) {
          ADD_FAILURE() << robot.link(a).name << " / " << robot.link(b).name << " state " << state;
          ++wrong;
        }
      }
    }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(apart, 1000u);
  EXPECT_GT(fcl_contacts, 50u);
}

// The refined model uses the filter: it counts pairs cleared by their hulls, and its self answer
// is FCL's on every state.
TEST(RefineHulls, RefinedModelClearsPairsByHullsAndAgreesWithFcl) {
  if (!std::filesystem::exists(kPanda + "/panda.urdf")) GTEST_SKIP() << "no Panda";
  RobotModel robot = RobotModel::fromUrdfFile(kPanda + "/panda.urdf");
  robot.loadSrdfFile(kPanda + "/panda.srdf");
  test::ExactAndFcl setup(robot);
  const OctreeCollisionModel& model = setup.model;
  const FclCollisionModel& fcl = setup.fcl;
  FclCollisionModel::ScratchPtr& exact = setup.exact;
  CheckScratch& scratch = setup.scratch;
  std::mt19937_64 rng(0x4e12);
  std::size_t disagreements = 0, contacts = 0;
  for (int state = 0; state < 1500; ++state) {
    std::vector<double> q;
    for (const Variable& v : robot.variables()) {
      q.push_back(std::uniform_real_distribution<double>(v.lower, v.upper)(rng));
    }
    fcl.setConfiguration(q.data(), q.size(), Eigen::Isometry3d::Identity(), *exact);
    const bool truth = fcl.selfInCollision(*exact);
    contacts += truth;
    disagreements += model.inCollision(q.data(), q.size(), Eigen::Isometry3d::Identity(),
                                       CheckerPath::kFused, scratch) != truth;
  }
  EXPECT_EQ(disagreements, 0u);
  EXPECT_GT(contacts, 0u);
  EXPECT_GT(model.refineCounts(scratch).hull_apart_pairs, 0u);
}

}  // namespace
}  // namespace octomotion
