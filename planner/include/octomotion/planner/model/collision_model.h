// The octree collision model of one scene, Pinocchio-style: a constant OctreeCollisionModel
// (robot, environment tree, one source tree per link) shared by every thread, and a
// CheckScratch per thread. Each link is voxelized once, in its own frame, into a source tree;
// every query derives the link's placement from that source tree and the link's pose (never from
// a previous placement), then tests it against the environment tree and against the other
// links' source trees (self-collision, in the other link's frame). Robots with many links find
// their self pairs with the N-objects octree broad phase (SelfBroadPhase), scenes with scattered
// objects pre-test links against the objects' boxes (EnvironmentPreTest), and clearance uses
// point octrees of the environment's black leaves (ClearanceMethod): docs/planner.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/broadphase/n_objects_octree.h"
#include "octomotion/motion/box_overlap.h"
#include "octomotion/motion/collides.h"
#include "octomotion/motion/pose.h"
#include "octomotion/motion/primitive_contact.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/model/joint_space_table.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/environment_geometry.h"
#include "octomotion/pointcloud/point_octree.h"

namespace octomotion {

struct TriangleMesh;

// (a) the mission's path: moveTree from the source tree, then the parallel traversal;
// (b) the fused query: both at once, without materialising the moved tree.
enum class CheckerPath { kMoveTree, kFused };

// How selfInCollision finds the link pairs worth a tree-vs-tree test:
// kPairs: every checked (SRDF-enabled) pair, each with a bounding-sphere pre-test;
// kNObjectsOctree: an N-objects octree broad phase (broadphase/n_objects_octree.h) over the
//   links' world boxes, rebuilt incrementally per check in the per-thread CheckScratch; only its
//   overlapping candidates that are checked pairs get the sphere and tree tests;
// kAuto: kNObjectsOctree when at least kSelfBroadPhaseAutoLinks links take part in self pairs,
//   else kPairs. Both give exactly the same answers (tests/planner/self_broadphase_test.cpp).
enum class SelfBroadPhase { kAuto, kPairs, kNObjectsOctree };
const char* selfBroadPhaseName(SelfBroadPhase strategy);
// Measured with bench/planner_selfcollision_bench.cpp (docs/planner.md, "Self-collision broad
// phase"): from 20 links the broad phase beats the all-pairs loop in every run (20 links: 1.05 vs
// 1.29 us, 100 links: 9.8 vs 36 us per check); at 16 they tie, at 6 the loop is 3x faster.
inline constexpr int kSelfBroadPhaseAutoLinks = 20;
// Leaf capacity N of the self-collision broad phase: unlimited, i.e. one leaf and the octree's
// vectorised all-pairs box kernel (report §1.4). Subdividing (N = 8, 16, 64) never paid off up to
// 100 links: with uniform random states every link jumps each check, so re-inserting costs more
// than the box tests it saves (100 links: N = 16 24.2 us, N = 64 16.6 us, unlimited 9.8 us).
inline constexpr std::uint32_t kSelfBroadPhaseLeafCapacity = broadphase::NObjectsOctree::kUnlimited;

// Which links the environment half of a check sends to the environment tree (docs/planner.md,
// "Many environment objects"): kEnvironmentBox: those whose bounding sphere meets the box of all
// black voxels; kObjectBoxes: those whose sphere meets some object's own box (a loop over the
// objects' boxes, so scattered objects no longer make every link test the tree); kAuto:
// kObjectBoxes for 2 ... kObjectBoxesMaxObjects objects. The tree stays one merged octree either
// way: per-object trees lost at every count from 50 objects on (bench/planner_environment_bench).
enum class EnvironmentPreTest { kAuto, kEnvironmentBox, kObjectBoxes };
// Measured: object boxes win up to 100 objects (10: 0.07 vs 1.5 us, 100: 1.7 vs 3.1 us per
// check), tie at 250 and lose at 500 (4.6 vs 3.2 us).
inline constexpr std::size_t kObjectBoxesMaxObjects = 128;

// The environment tree is built on universes whose origin is the lowest corner of the
// environment the robot can reach, or 1 .. kOriginShifts - 1 voxels below it, and the one with
// the fewest nodes is kept (collision_model.cpp, step 5).
inline constexpr int kOriginShifts = 4;

// How clearanceLowerBound finds each clearance sphere's nearest obstacle:
// kEnvironmentTree: branch and bound over the environment octree's black leaves (exact box
//   distance to the nearest black voxel);
// kPointOctree: nearest-point queries in PointOctrees of the black leaves' centres, one tree per
//   leaf level, minus that level's half cube diagonal (looser by at most that half diagonal:
//   0.87 voxel for single voxels). See docs/planner.md, "Clearance".
enum class ClearanceMethod { kEnvironmentTree, kPointOctree };

// A fresh process-unique id for a model (see OctreeCollisionModel::id).
std::uint64_t nextModelId();

// The links' source trees for the environment queries are this many times the environment's
// voxel unless CollisionModelOptions::link_resolution says otherwise. A link voxel's margin adds
// to the environment's, so finer link trees halve the false positives at the same environment
// resolution and, being tighter, make the checks faster too (fewer false contacts to descend);
// they cost build time and memory, which are small next to the environment's (bookshelf 5 mm:
// 0.25 s and 1.7 MB against 0.04 s and 0.7 MB at 1; docs/trade-off.md, "Finer link trees").
inline constexpr double kDefaultLinkResolutionRatio = 0.25;

// The voxel sizes of a model's link trees, for the environment queries and for the self pairs,
// with the defaults of CollisionModelOptions::link_resolution and ::self_link_resolution applied
// (the one place they are; the trade study resolves its ratios with it at resolution 1).
struct LinkTreeResolutions {
  double link, self;
};
inline LinkTreeResolutions linkTreeResolutions(double resolution,
                                               std::optional<double> link_resolution,
                                               std::optional<double> self_link_resolution) {
  const double link = link_resolution.value_or(resolution * kDefaultLinkResolutionRatio);
  return {link, self_link_resolution.value_or(link_resolution ? link : resolution)};
}

struct CollisionModelOptions {
  double resolution = 0.01;  // environment voxel size (metres)
  // Source-tree voxel size for the environment queries; default: resolution x
  // kDefaultLinkResolutionRatio.
  std::optional<double> link_resolution;
  // Source-tree voxel size for the self-collision pairs; default: link_resolution when that is
  // set, else resolution (finer self trees cost more than they save on robots that self-collide
  // often, such as octo6; docs/trade-off.md). When it differs from link_resolution, each link
  // in a self pair keeps a second tree used only against the other links.
  std::optional<double> self_link_resolution;
  Rounding rounding = Rounding::kConservative;
  // Fixed-base robots: the root link's pose. Free-flying robots: ignored.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  // Free-flying robots: where the body's origin may go (SE(3) position bounds). Required.
  std::optional<Eigen::AlignedBox3d> base_position_bounds;
  // Robot mesh conventions: URDF robots reset the mesh file's root transform (ROS/MoveIt);
  // OMPL.app rigid bodies keep it and are shifted so the mean of their vertices is the origin.
  bool keep_mesh_root_transform = false;
  bool center_mesh_vertices = false;
  // Building fails early (InvalidArgument naming the object and the resolution) when a tree's
  // surface, estimated from its bounding box, would exceed this many voxels: a typo such as a
  // micrometre resolution must not exhaust the machine. 2e8 surface voxels is about 0.5 GB.
  double max_surface_voxels = 2e8;
  SelfBroadPhase self_broad_phase = SelfBroadPhase::kAuto;
  ClearanceMethod clearance = ClearanceMethod::kPointOctree;
  EnvironmentPreTest environment_pre_test = EnvironmentPreTest::kAuto;
  std::uint32_t self_broad_phase_leaf_capacity = kSelfBroadPhaseLeafCapacity;  // N (>= 1)
  // Self pairs whose relative pose depends on at most self_pair_table_max_variables joint
  // variables (<= JointSpaceTable::kMaxDims; a joint that turns a link about an axis its solid
  // is symmetric about does not count), and whose tree test runs for at least
  // kSelfPairTableMinShare of their joint space, get a JointSpaceTable classified with FCL on
  // the exact geometry at build time: states in a certified cell skip the octree pair test, the
  // rest take it (docs/planner.md, "Self-pair tables"). Conservative rounding only (the tables
  // use conservative trees as their inside/outside oracle). The tolerance is the widest change
  // of the pair's distance within a finest cell: the band around contact left to the octree
  // test. 3-variable tables need far more cells than the budget to certify near contacts. Off
  // by default: classifying octo6's five tables costs ~20 s of CPU per model (in parallel: 10.5 s
  // on 2 cores; octo7's one table 0.06 s).
  bool self_pair_tables = false;
  double self_pair_table_tolerance = 5e-4;        // metres, > 0
  std::size_t self_pair_table_max_cells = 60000;  // FCL classifications per pair
  std::size_t self_pair_table_max_variables = 2;
  // Conservative rounding: each link's environment tree gets up to three boxes inside its black
  // voxels (innerBoxes), and a link that passes the pre-test is first tested for a certain
  // contact: one of those boxes overlapping a box obstacle (a box primitive of the scene: its
  // part inside the universe; a rotated one only when wholly inside). Same answers (both
  // voxelizations keep the voxels the two boxes overlap); the tree query is skipped where a link
  // crosses a board or a wall.
  bool core_boxes = true;
  // Conservative rounding: after the pre-tests and certain contacts, each link's black source
  // voxels are tested against the scene's primitives (boxes, balls, cylinders) themselves
  // (blackLeafMeetsPrimitive) instead of their voxels; the other objects (meshes, point clouds,
  // OctoMaps) are queried in a second tree of their own. The primitives' voxel margin (up to a
  // voxel diagonal beyond each) is gone; the link voxels' margin stays, so no contact FCL finds
  // is missed (docs/validation.md §2). Without primitives, or under centre rounding, it does not
  // apply (a warning; CollisionModelReport::exact_primitives is 0). Off by default: the
  // environment octree is the library's general path (docs/planner.md, "Exact primitives").
  bool exact_primitives = false;
  WarningSink warnings;
};

struct LinkReport {
  std::string name;
  bool modelled = false;  // false: no geometry, or it can neither touch the scene nor a link
  std::size_t source_internal_nodes = 0;
  std::size_t source_black_leaves = 0;
  std::size_t source_bytes = 0;
  std::size_t self_source_bytes = 0;  // the separate self-collision tree (0: none)
  int source_depth = 0;
  double radius = 0;  // bounding sphere of the source tree's black voxels (metres)
  double build_seconds = 0;
  // Share of kEnvironmentOrderSamples uniform joint states in which the link's tree meets the
  // environment's (arms; -1 when not sampled): the environment half tests links in decreasing
  // share, so a colliding state usually stops at its first tree query.
  double environment_hit_share = -1;
  int core_boxes = 0;  // CollisionModelOptions::core_boxes: boxes inside the environment tree
};

// Joint states sampled at build time to order the environment half's links (arms only).
inline constexpr int kEnvironmentOrderSamples = 512;

inline constexpr double kSelfPairTableMinShare = 0.01;

struct SelfPairTableReport {
  std::string link_a, link_b;
  int variables = 0;  // dimensions of the table
  int depth = 0;      // finest cells: 2^-depth of each variable's range
  std::size_t nodes = 0;
  std::size_t bytes = 0;
  std::size_t classified = 0;  // FCL classifications made
  // Share of the pair's joint space certified free / colliding (the rest: octree test).
  double free_fraction = 0;
  double colliding_fraction = 0;
  double build_seconds = 0;
};

struct CollisionModelReport {
  WorldGrid grid{Eigen::Vector3d::Zero(), 1.0, 1};
  double link_resolution = 0;
  double self_link_resolution = 0;  // equal to link_resolution unless set apart
  Eigen::AlignedBox3d reach_W;      // what the robot can reach
  EnvironmentReport environment;
  std::vector<LinkReport> links;
  std::size_t self_pairs = 0;
  std::size_t self_links = 0;  // links taking part in at least one self pair
  SelfBroadPhase self_broad_phase = SelfBroadPhase::kPairs;  // resolved (never kAuto)
  EnvironmentPreTest environment_pre_test = EnvironmentPreTest::kEnvironmentBox;  // resolved
  std::size_t environment_object_boxes = 0;  // object boxes the pre-test loops over
  std::size_t environment_solid_boxes = 0;   // inscribed boxes of primitives, for core boxes
  // CollisionModelOptions::exact_primitives in force: the primitives the links are tested
  // against (0: off, no primitives, or centre rounding), and the other objects, queried in a
  // tree of their own.
  std::size_t exact_primitives = 0;
  std::size_t exact_primitives_other_objects = 0;
  int environment_cell_grid_level = -1;  // BlackCellGrid of the environment (-1: none)
  std::size_t environment_cell_grid_bytes = 0;
  int environment_clearance_grid_level = -1;  // ClearanceGrid of the environment (-1: none)
  std::size_t environment_clearance_grid_bytes = 0;
  std::vector<std::string> environment_order;  // links in the order the environment half tests
  std::vector<SelfPairTableReport> self_pair_tables;
  double build_seconds = 0;
  std::string toString() const;  // the human-readable "what was modelled" summary
};

// Per-thread scratch for queries: FK results, the fused query's buffers and (kNObjectsOctree)
// the self-collision broad phase's octree, whose links move with every check. One per thread.
struct CheckScratch {
  RobotData robot;
  CollisionScratch fused;
  std::optional<broadphase::NObjectsOctree> self_broad_phase;
  std::vector<Eigen::Vector3d> centres_W;  // per modelled link: bounding-sphere centre in W
  std::uint64_t owner = 0;                 // id() of the model it was made for
};

class OctreeCollisionModel {
 public:
  // Builds the environment tree on a universe fitted to what the robot can reach (parts of the
  // environment it can never reach are not modelled) and one source tree per link.
  OctreeCollisionModel(RobotModel robot, const EnvironmentGeometry& environment,
                       const CollisionModelOptions& options);

  const RobotModel& robot() const { return robot_; }
  const Octree& environment() const { return environment_; }
  const WorldGrid& grid() const { return environment_.grid(); }
  Rounding rounding() const { return options_.rounding; }
  const CollisionModelReport& report() const { return report_; }
  const Eigen::Isometry3d& baseMount() const { return options_.X_WB; }

  CheckScratch makeScratch() const;
  // Unique for the process's lifetime (addresses may be reused; ids are not), so per-thread
  // scratch can tell which model it belongs to.
  std::uint64_t id() const { return id_; }

  // Runs FK for q (and base pose X_WB for free-flying robots) into the scratch, then tests every
  // modelled link against the environment and every checked pair against each other, cheapest
  // tests first, stopping at the first contact. Throws InvalidArgument for a non-finite input.
  bool inCollision(const double* q, std::size_t q_size, const Eigen::Isometry3d& X_WB,
                   CheckerPath path, CheckScratch& scratch) const;
  // The same tests on link poses already in the scratch (after forwardKinematics).
  bool linksInCollision(CheckerPath path, CheckScratch& scratch) const;
  // Its two halves: links against the environment only, and the checked self pairs only.
  bool environmentInCollision(CheckerPath path, CheckScratch& scratch) const;
  bool selfInCollision(CheckerPath path, CheckScratch& scratch) const;
  // The strategy selfInCollision uses (options' choice, kAuto resolved by link count).
  SelfBroadPhase selfBroadPhase() const { return report_.self_broad_phase; }

  // A lower bound on the distance between the robot (at the poses in the scratch) and the
  // environment's black voxels; 0 when in contact. See docs: it is loose by up to the link's
  // source-voxel diagonal plus the spread of the link's bounding spheres.
  // Uses options' ClearanceMethod; the two below force one (kPointOctree falls back to the tree
  // when the model was built with kEnvironmentTree, which does not build the point trees).
  double clearanceLowerBound(const CheckScratch& scratch) const;
  double clearanceLowerBoundTree(const CheckScratch& scratch) const;
  double clearanceLowerBoundPoints(const CheckScratch& scratch) const;

  // Read-only view of a modelled link's source tree (in its link frame L), for viewers and
  // exports: moveTree(*source, X_WL, grid(), rounding()) is the link's placement at pose X_WL.
  struct LinkSourceTree {
    int link = -1;                   // index in robot().links()
    const Octree* source = nullptr;  // owned by the model
    // The self pairs' tree when it has its own resolution (self_link_resolution), else null.
    const Octree* self_source = nullptr;
  };
  std::vector<LinkSourceTree> linkSourceTrees() const {
    std::vector<LinkSourceTree> trees;
    trees.reserve(links_.size());
    for (const LinkTree& lt : links_) {
      trees.push_back(
          {lt.link, &lt.voxels.source, lt.self_voxels ? &lt.self_voxels->source : nullptr});
    }
    return trees;
  }

 private:
  // A link's black voxels at one resolution, in its own frame L, prepared for queries.
  struct LinkVoxels {
    Octree source{WorldGrid(Eigen::Vector3d::Zero(), 1.0, 1)};
    std::unique_ptr<const MovableSource> movable;        // the source prepared for the fused query
    Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  // bounding sphere of the black voxels
    double radius = 0;
    Eigen::Vector3d half_L = Eigen::Vector3d::Zero();  // their box: centre center_L, half-sides
    double source_diagonal = 0;                        // of one source voxel (metres)
    // Boxes inside the black voxels (CollisionModelOptions::core_boxes), shrunk by kSolidShrink.
    struct CoreBox {
      Eigen::Vector3d centre_L, half_L;
    };
    std::vector<CoreBox> core_boxes;
  };
  // A box inside a primitive obstacle (the box itself, a ball's inscribed cube, a cylinder's
  // square prism), shrunk by kSolidShrink: every voxel it overlaps is black in the environment.
  struct SolidBox {
    Eigen::Vector3d centre_W, half;
    Eigen::Matrix3d R_OW;      // world to the box's axes
    Eigen::Vector3d extent_W;  // half sides of its world AABB
  };
  // Boxes of a certain contact are shrunk by this share of the larger voxel size: a point of
  // both then has a ball about it in both boxes, so the target voxel holding it overlaps the
  // obstacle and a moved link voxel by far more than the colour rules' ties (1e-6 voxel).
  static constexpr double kSolidShrink = 1e-3;
  // One of the link's core boxes overlaps a solid box: the link's moved tree and the
  // environment share a black voxel.
  bool certainContact(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const;
  // CollisionModelOptions::exact_primitives: a primitive obstacle in its own frame P, and its
  // world AABB (EnvironmentGeometry::Item::bounds_W: centre_W, half sides extent_W). A link is
  // tested against it when the world box of the link's black voxels grown by kExactReachVoxels
  // link voxels meets that AABB: a link voxel's bounding sphere reaches (√3 - 1)/2 of a voxel
  // beyond the voxel.
  struct ExactPrimitive {
    PrimitiveShape shape;
    Eigen::Isometry3d X_PW;
    Eigen::Vector3d centre_W, extent_W;
  };
  static constexpr double kExactReachVoxels = 1.0;
  // A black voxel of the link's environment tree meets one of exact_primitives_.
  bool leavesMeetPrimitives(const LinkVoxels& v, const Eigen::Isometry3d& X_WL) const;
  struct LinkTree {
    int link = -1;
    LinkVoxels voxels;  // tested against the environment (and the other links, unless below)
    // At self_link_resolution when it differs from link_resolution: the self pairs' margin is
    // set by the link voxels alone, so finer trees here remove self false positives without
    // deepening the environment queries.
    std::unique_ptr<const LinkVoxels> self_voxels;
    const LinkVoxels& forSelf() const { return self_voxels ? *self_voxels : voxels; }
    bool touches_environment = true;         // false: cannot reach the modelled environment
    std::vector<Eigen::Vector4d> spheres_L;  // coarse cover of the black voxels (clearance)
  };

  static LinkVoxels voxelizeLink(const Link& link,
                                 const std::vector<const TriangleMesh*>& element_mesh,
                                 Eigen::AlignedBox3d box_L, double resolution,
                                 const CollisionModelOptions& options, bool for_self_pairs);
  // What the environment pre-test reads of a link, in one flat record per link that can touch
  // the environment (a rejected link touches nothing else).
  struct EnvironmentLinkTest {
    Eigen::Vector3d center_L;  // the link box's centre and half sides (LinkVoxels)
    Eigen::Vector3d half_L;
    double reach_squared = 0;         // (bounding radius + one environment voxel diagonal)^2
    double origin_reach_squared = 0;  // (that reach + |center_L|)^2, about the link's origin
    int link = -1;                    // robot link index
    std::size_t slot = 0;             // in links_
  };
  EnvironmentLinkTest environmentTest(std::size_t slot) const;
  // The link's bounding sphere, grown by a voxel diagonal, reaches `box` (inline: the first
  // stage of the environment pre-test, run for every link of every check).
  static bool sphereMeetsBox(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL,
                             const Eigen::AlignedBox3d& box);
  // For a link whose bounding sphere reaches the environment's box (sphereMeetsBox): false when its
  // oriented box meets neither the environment's box nor (kObjectBoxes) any object's box, so it
  // cannot meet an environment voxel.
  bool linkNearEnvironment(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL) const;
  // linkNearEnvironment, then the link's query against the environment tree.
  bool linkHitsEnvironment(const EnvironmentLinkTest& t, const Eigen::Isometry3d& X_WL,
                           CheckerPath path, CollisionScratch& fused) const;
  // The self-pair test in two stages, cheapest first. The bounding spheres (centres in W from
  // placeCentres) are close enough for B's voxels placed on A's grid to reach A when their
  // centres are within spheresReach of each other.
  static double spheresReach(const LinkVoxels& a, const LinkVoxels& b) {
    return a.radius + b.radius + a.source_diagonal;
  }
  // The boxes of A's and B's black voxels (B's rotation in A: R_AB) overlap.
  static bool boxesMeet(const LinkVoxels& a, const Eigen::Isometry3d& X_WA,
                        const Eigen::Matrix3d& R_AB, const LinkVoxels& b,
                        const Eigen::Vector3d& cb_W) {
    return boxesOverlap(a.center_L, a.half_L, R_AB,
                        X_WA.linear().transpose() * (cb_W - X_WA.translation()), b.half_L,
                        kMotionTieTolerance * a.source.grid().voxelSize());
  }
  // linksHit, for pairs whose spheres meet: the oriented boxes, then the trees.
  bool linksHit(const LinkVoxels& a, const Eigen::Isometry3d& X_WA, const LinkVoxels& b,
                const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& cb_W, CheckerPath path,
                CollisionScratch& fused) const;
  // Self pair `pair` (index into pairs_): the spheres (centres from placeCentres), then
  // pairStagesHit.
  bool pairHits(std::size_t pair, CheckerPath path, CheckScratch& scratch) const {
    const SelfPair& p = pairs_[pair];
    return spheresMeet(p, scratch.centres_W[p.a], scratch.centres_W[p.b]) &&
           pairStagesHit(p, path, scratch);
  }
  // scratch.centres_W[slot]: every modelled link's self-collision sphere centre.
  void placeCentres(CheckScratch& scratch) const;
  bool selfPairsInCollision(CheckerPath path, CheckScratch& scratch) const;
  bool selfBroadPhaseInCollision(CheckerPath path, CheckScratch& scratch) const;
  broadphase::NObjectsOctree makeSelfBroadPhase() const;

  std::uint64_t id_;
  RobotModel robot_;
  CollisionModelOptions options_;
  Octree environment_;
  // The environment's entirely black cells as a bit grid (conservative rounding; else null):
  // the fused query tries a few points of each link in it before any traversal.
  std::unique_ptr<const BlackCellGrid> environment_cells_;
  // Lower bounds on the distance to the environment per cell: the fused query drops the pieces
  // of a link that are clear of it before descending.
  std::unique_ptr<const ClearanceGrid> environment_clearance_;
  Eigen::AlignedBox3d environment_box_W_;  // world box of the environment's black voxels
  // kObjectBoxes: each object's box grown by a voxel (so it holds the object's black voxels).
  std::vector<Eigen::AlignedBox3d> object_boxes_W_;
  // The same boxes for the pre-test's first three axes, one array per axis (centre, and half
  // side plus the tie margin), precomputed: most boxes are rejected there.
  std::array<std::vector<double>, 3> object_centre_W_, object_reach_W_;
  // A rotated primitive's own box, grown by a voxel diagonal (it holds the object's black
  // voxels too, and is much tighter than the world box for a tilted bar): tested after the
  // world box. Parallel to object_boxes_W_; `tilted` false for the others.
  struct ObjectFrameBox {
    Eigen::Vector3d centre_W = Eigen::Vector3d::Zero(), half = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R_OW = Eigen::Matrix3d::Identity();  // world to the object's axes
    bool tilted = false;
  };
  std::vector<ObjectFrameBox> object_frame_boxes_;
  std::vector<SolidBox> solid_boxes_W_;
  std::vector<ExactPrimitive> exact_primitives_;
  // With exact primitives in a scene that also has other objects: their tree (on the
  // environment's grid) and its grids, queried like the environment tree.
  struct VoxelObjects {
    Octree tree;
    std::unique_ptr<const BlackCellGrid> cells;
    std::unique_ptr<const ClearanceGrid> clearance;
  };
  std::unique_ptr<const VoxelObjects> other_objects_;
  std::vector<LinkTree> links_;  // modelled links only
  // The links that can touch the environment, in the order environmentInCollision tests them:
  // most often hit first (LinkReport::environment_hit_share), ties in model order. Free states
  // test them all either way; colliding ones stop sooner.
  std::vector<EnvironmentLinkTest> environment_tests_;
  void orderEnvironmentLinks();
  std::vector<const LinkVoxels*> self_voxels_;  // per slot: links_[slot].forSelf(), one load
  std::vector<int> link_slot_;                  // robot link index -> index in links_, or -1
  struct SelfPair {
    std::size_t a, b;                        // slots in links_
    double reach_squared = 0;                // spheresReach(a, b)^2
    const JointSpaceTable* table = nullptr;  // in pair_tables_, or none
  };
  // The pair's bounding spheres, centred at ca_W and cb_W, are within reach of each other.
  static bool spheresMeet(const SelfPair& p, const Eigen::Vector3d& ca_W,
                          const Eigen::Vector3d& cb_W) {
    return (ca_W - cb_W).squaredNorm() <= p.reach_squared;
  }
  // A pair whose spheres meet: its joint-space table when it has one, then the boxes and trees
  // of the self trees.
  bool pairStagesHit(const SelfPair& p, CheckerPath path, CheckScratch& scratch) const;
  // Share of the pair's joint space (its variables `vars`, 256 samples) whose states reach the
  // tree test.
  double treeTestShare(const SelfPair& pair, const std::vector<int>& vars) const;
  std::vector<SelfPair> pairs_;
  std::vector<std::unique_ptr<const JointSpaceTable>> pair_tables_;
  // Self broad phase: object id i is links_[self_links_[i]] (increasing slots, so a < b ids keep
  // the pairs' order); self_pair_of_[a * self_links_.size() + b] for ids a < b: the index in
  // pairs_ of a checked pair, or -1.
  // Clearance (kPointOctree): the environment's black leaves of one level, as cube centres.
  struct ClearanceLevel {
    double half_diagonal = 0;  // of that level's cubes (metres)
    pointcloud::PointOctree centres;
  };
  std::vector<ClearanceLevel> clearance_levels_;
  double clearance_float_slack_ = 0;  // covers float rounding of centres and distances
  std::vector<int> self_links_;
  std::vector<std::int32_t> self_pair_of_;
  Eigen::AlignedBox3d self_root_box_W_;  // the broad phase's root: everything links can reach
  CollisionModelReport report_;
};

}  // namespace octomotion
