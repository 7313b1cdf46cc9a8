// Exact primitives (CollisionModelOptions::exact_primitives): with every obstacle a primitive,
// the environment half answers "in collision" exactly when some link's black leaf meets some
// primitive (blackLeafMeetsPrimitive, tested against brute force in tests/motion). Here the
// model's pre-tests, certain contacts and link order must not change that answer: it is compared
// with a plain loop over every link and every object, on both checker paths, at three
// resolutions, with link trees finer and coarser than the environment's voxels. Meshes among the
// primitives are answered by a tree of their own; a scene without primitives, and centre
// rounding, keep the voxel answers and say so.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "environment_answers.h"
#include "joint_states.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/planner/model/collision_model.h"
#include "primitive_scenes.h"
#include "snake_robot.h"

namespace octomotion {
namespace {

RobotModel snake(int links, double limit) {
  return RobotModel::fromUrdfString(test::snakeUrdf(links, limit), "snake.urdf", ".");
}

// The rods, posts and balls of the core-box tests (poles reaching out of the universe) with half
// of their boards, tilted.
std::vector<EnvironmentObject> obstacles(std::uint64_t seed) {
  std::vector<EnvironmentObject> objects = test::rodsAndBalls(seed);
  const std::vector<EnvironmentObject> boards = test::boards(seed + 1, true);
  objects.insert(objects.end(), boards.begin() + 6, boards.begin() + 12);
  return objects;
}

// Every modelled link against every primitive, leaf by leaf, with no pre-test, and (when given)
// against a tree of the other objects on the model's grid.
class LeafOracle {
 public:
  LeafOracle(const OctreeCollisionModel& model, const std::vector<EnvironmentObject>& objects,
             const Octree* others = nullptr)
      : others_(others) {
    for (const auto& t : model.linkSourceTrees()) {
      links_.push_back(t.link);
      sources_.push_back(std::make_unique<MovableSource>(*t.source));
    }
    for (const EnvironmentObject& o : objects) {
      if (o.kind != EnvironmentObject::Kind::kPrimitive) continue;
      shapes_.emplace_back(o.primitive);
      X_OW_.push_back(o.X_WO.inverse());
    }
  }
  bool inCollision(const RobotData& data, CollisionScratch& scratch) const {
    for (std::size_t l = 0; l < links_.size(); ++l) {
      const Eigen::Isometry3d& X_WL = data.linkPose(links_[l]);
      for (std::size_t o = 0; o < shapes_.size(); ++o) {
        if (blackLeafMeetsPrimitive(*sources_[l], X_OW_[o] * X_WL, shapes_[o])) return true;
      }
      if (others_ && collides(*sources_[l], X_WL, *others_, Rounding::kConservative, scratch)) {
        return true;
      }
    }
    return false;
  }

 private:
  const Octree* others_;
  std::vector<int> links_;
  std::vector<std::unique_ptr<MovableSource>> sources_;
  std::vector<PrimitiveShape> shapes_;
  std::vector<Eigen::Isometry3d> X_OW_;
};

TEST(ExactPrimitives, AnswerIsEveryLinkLeafAgainstEveryObject) {
  const RobotModel robot = snake(6, 1.6);
  const std::vector<EnvironmentObject> objects = obstacles(3);
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  const auto states = test::uniformJointStates(robot, 1500, 4);
  struct Setting {
    double res, link_res;
  };
  // Link trees at 1/4 of the voxel (the default), at the voxel, and coarser than it (the
  // pre-tests must then grow by the link's voxel, not the environment's).
  for (const Setting s :
       {Setting{0.02, 0.005}, Setting{0.01, 0.01}, Setting{0.005, 0.02}, Setting{0.005, 0.04}}) {
    CollisionModelOptions o;
    o.resolution = s.res;
    o.refine = RefineMode::kNone;  // the voxels' answers
    o.link_resolution = s.link_res;
    o.exact_primitives = true;
    std::vector<std::string> warnings;
    o.warnings = [&](const std::string& w) { warnings.push_back(w); };
    const OctreeCollisionModel exact(robot, env, o);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(exact.report().exact_primitives, objects.size());
    o.exact_primitives = false;
    const OctreeCollisionModel voxels(robot, env, o);
    const LeafOracle oracle(exact, objects);
    const std::string where =
        "resolution " + std::to_string(s.res) + ", link trees " + std::to_string(s.link_res);
    for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
      CheckScratch a = exact.makeScratch(), b = voxels.makeScratch();
      int hits = 0, voxel_only = 0;
      for (std::size_t i = 0; i < states.size(); ++i) {
        const std::vector<double>& q = states[i];
        robot.forwardKinematics(q.data(), q.size(), a.robot);
        robot.forwardKinematics(q.data(), q.size(), b.robot);
        const bool expected = oracle.inCollision(a.robot, a.fused);
        const bool got = exact.environmentInCollision(path, a);
        ASSERT_EQ(got, expected) << "state " << i << ", " << where;
        hits += got;
        voxel_only += !got && voxels.environmentInCollision(path, b);
      }
      EXPECT_GT(hits, 150) << where;  // both answers are exercised
      EXPECT_LT(hits, 1350) << where;
      // The obstacles' voxel margin is gone: some states the voxels reject are free now.
      EXPECT_GT(voxel_only, 0) << where;
    }
  }
}

EnvironmentObject meshCube(const Eigen::Vector3d& xyz) {
  EnvironmentObject cube;
  cube.name = "mesh_cube";
  cube.kind = EnvironmentObject::Kind::kMesh;
  cube.file = std::string(OCTOMOTION_TEST_DATA_DIR) + "/meshes/unit_cube.stl";
  cube.scale = Eigen::Vector3d::Constant(0.15);
  cube.X_WO.translation() = xyz;
  return cube;
}

// A mesh among the primitives: the primitives exact, the mesh in a tree of its own.
TEST(ExactPrimitives, OtherObjectsKeepTheirVoxels) {
  const RobotModel robot = snake(6, 1.6);
  std::vector<EnvironmentObject> objects = obstacles(3);
  objects.push_back(meshCube(Eigen::Vector3d(0.2, -0.2, 0.1)));
  objects.push_back(meshCube(Eigen::Vector3d(-0.25, 0.1, -0.15)));
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  const auto states = test::uniformJointStates(robot, 1500, 5);
  CollisionModelOptions o;
  o.resolution = 0.01;
  o.refine = RefineMode::kNone;  // the voxels' answers
  o.exact_primitives = true;
  std::vector<std::string> warnings;
  o.warnings = [&](const std::string& w) { warnings.push_back(w); };
  const OctreeCollisionModel exact(robot, env, o);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(exact.report().exact_primitives, objects.size() - 2);
  EXPECT_EQ(exact.report().exact_primitives_other_objects, 2u);
  const Octree cubes =
      EnvironmentGeometry::load(std::vector<EnvironmentObject>(objects.end() - 2, objects.end()))
          .voxelize(exact.grid(), Rounding::kConservative);
  const LeafOracle oracle(exact, objects, &cubes);
  const LeafOracle primitives_only(exact, objects);
  for (const CheckerPath path : {CheckerPath::kFused, CheckerPath::kMoveTree}) {
    CheckScratch a = exact.makeScratch();
    int hits = 0, by_cubes = 0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const std::vector<double>& q = states[i];
      robot.forwardKinematics(q.data(), q.size(), a.robot);
      const bool expected = oracle.inCollision(a.robot, a.fused);
      ASSERT_EQ(exact.environmentInCollision(path, a), expected) << "state " << i;
      hits += expected;
      by_cubes += expected && !primitives_only.inCollision(a.robot, a.fused);
    }
    EXPECT_GT(hits, 150);
    EXPECT_LT(hits, 1350);
    EXPECT_GT(by_cubes, 20);  // the cubes' tree answers for some states
  }
}

TEST(ExactPrimitives, WithoutPrimitivesOrUnderCentreRoundingTheVoxelsAnswer) {
  const RobotModel robot = snake(6, 1.6);
  const auto states = test::uniformJointStates(robot, 800, 5);
  const EnvironmentGeometry cubes = EnvironmentGeometry::load(
      {meshCube(Eigen::Vector3d(0.2, -0.2, 0.1)), meshCube(Eigen::Vector3d(-0.25, 0.1, -0.15))});
  const EnvironmentGeometry mixed = EnvironmentGeometry::load(obstacles(3));
  for (const Rounding rounding : {Rounding::kConservative, Rounding::kCenter}) {
    const EnvironmentGeometry& env = rounding == Rounding::kCenter ? mixed : cubes;
    CollisionModelOptions o;
    o.resolution = 0.01;
    o.refine = RefineMode::kNone;  // the voxels' answers
    o.rounding = rounding;
    o.exact_primitives = true;
    std::vector<std::string> warnings;
    o.warnings = [&](const std::string& w) { warnings.push_back(w); };
    const OctreeCollisionModel asked(robot, env, o);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("octree.exact_primitives: not applied"), std::string::npos);
    EXPECT_NE(warnings[0].find(rounding == Rounding::kCenter ? "centre rounding" : "no primitives"),
              std::string::npos)
        << warnings[0];
    EXPECT_EQ(asked.report().exact_primitives, 0u);
    o.exact_primitives = false;
    const OctreeCollisionModel plain(robot, env, o);
    const int hits =
        test::environmentHitsIfSame(asked, plain, states, CheckerPath::kFused, "not applied");
    EXPECT_GT(hits, 50);
  }
}

}  // namespace
}  // namespace octomotion
