// The octree collision model of one scene, Pinocchio-style: a constant OctreeCollisionModel
// (robot, environment tree, one source tree per link) shared by every thread, and a
// CheckScratch per thread. Each link is voxelized once, in its own frame, into a source tree;
// every query derives the link's placement from that source tree and the link's pose (never from
// a previous placement), then tests it against the environment tree and against the other
// links' source trees (self-collision, in the other link's frame). Robots with many links find
// their self pairs with the N-objects octree broad phase (SelfBroadPhase), scenes with scattered
// objects pre-test links against the objects' boxes (EnvironmentPreTest), and clearance uses
// point octrees of the environment's black leaves (ClearanceMethod): docs/planner.md.
// The model's parts (environment, link models, self-collision, clearance) are private to the
// library (planner/src/model/internal/); this header declares what users need.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

// The broad phase's leaf capacity N (CollisionModelOptions::self_broad_phase_leaf_capacity) is
// in its terms (NObjectsOctree::kUnlimited); the scratch keeps the octree itself opaque.
#include "octomotion/motion/collides.h"
#include "octomotion/octree/octree.h"
#include "octomotion/octree/rounding.h"
#include "octomotion/planner/model/state_explanation.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/planner/scene/attached_object.h"
#include "octomotion/planner/scene/environment_geometry.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion::broadphase {
class NObjectsOctree;  // broadphase/n_objects_octree.h
}  // namespace octomotion::broadphase

namespace octomotion {

struct NearestObstacle;  // model/collision_backend.h

namespace detail {
struct CollisionModelParts;
struct ExplainData;
struct RefineData;
struct RefineScratch;
}  // namespace detail

// kMoveTree: moveTree places the source tree on the target's grid, then the parallel traversal
// tests the two trees; kFused: both at once, without materialising the moved tree.
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
// From this many self links the broad phase's box tests cost less than the all-pairs loop's
// sphere tests. Measured by bench/planner_selfcollision_bench.cpp.
inline constexpr int kSelfBroadPhaseAutoLinks = 20;
// Leaf capacity N of the self-collision broad phase: unlimited, one leaf and the octree's
// vectorised all-pairs box kernel: links jump at every check, so re-inserting them into smaller
// leaves costs more than the box tests it saves. Measured by bench/planner_selfcollision_bench.cpp.
// (broadphase::NObjectsOctree::kUnlimited.)
inline constexpr std::uint32_t kSelfBroadPhaseLeafCapacity =
    std::numeric_limits<std::uint32_t>::max();

// Which links the environment half of a check sends to the environment tree (docs/planner.md,
// "Many environment objects"): kEnvironmentBox: those whose bounding sphere meets the box of all
// black voxels; kObjectBoxes: those whose sphere meets some object's own box (a loop over the
// objects' boxes, so scattered objects no longer make every link test the tree); kAuto:
// kObjectBoxes for 2 ... kObjectBoxesMaxObjects objects. The tree stays one merged octree either
// way (per-object trees cost more per check).
enum class EnvironmentPreTest { kAuto, kEnvironmentBox, kObjectBoxes };
// Up to this many objects the loop over their boxes costs less than the tree queries it spares.
// Measured by bench/planner_environment_bench.cpp.
inline constexpr std::size_t kObjectBoxesMaxObjects = 128;

// The environment tree is built on universes whose origin is the lowest corner of the
// environment the robot can reach, or 1 .. kOriginShifts - 1 voxels below it, and the one with
// the fewest nodes is kept: which faces fall on the boundaries of large cells depends on the
// shift. Reported by CollisionModelReport::environment (octomotion info).
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
// they cost build time and memory, which stay small next to the environment's. Measured by
// bench/planner_check_breakdown_bench.cpp.
inline constexpr double kDefaultLinkResolutionRatio = 0.25;

// The voxel sizes of a model's link trees, for the environment queries and for the self pairs,
// with the defaults of CollisionModelOptions::link_resolution and ::self_link_resolution applied
// (the one place they are applied).
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
  // often). When it differs from link_resolution, each link in a self pair keeps a second tree
  // used only against the other links.
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
  // by default: classifying the tables takes seconds of CPU per model (on all cores; measured by
  // bench/planner_self_pair_tables_bench.cpp).
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
  // Model only what a state can change: on a fixed-base robot, links whose pose depends on no
  // joint variable (only fixed joints up to the root: a base, a held joint's links) are tested
  // against the environment once, at build time, instead of per state; self pairs whose relative
  // pose depends on no variable (no movable joint on the path between the two links; free-flying
  // robots too) are tested once and dropped from the per-state pairs. Same answers for every
  // state; when such a build-time test finds a contact, every state is in collision (and
  // CollisionModelReport::static_collisions says which). Off: every link and pair per state.
  bool fold_static = true;
  // The universe covers everything the robot can reach, whatever the environment, and keeps the
  // reach's corner as its origin (no origin search): for a world that changes between plans
  // (OctreeCollisionModel::addObject and the others), where an object added or moved anywhere
  // the robot reaches must fit. Default: the reach where it meets the environment's box, tighter
  // and with the best of kOriginShifts origins, but an update that reaches outside it is refused.
  bool fit_universe_to_reach = false;
  // RefineMode::kExact: the octree decides what it can certify, FCL the rest (see RefineMode).
  // The FCL geometry of the robot and of every object is built with the model. Certain contacts
  // (core_boxes) and static folding (fold_static) prove a shared voxel, not an exact contact, so
  // they are off in this mode. World updates are refused.
  // kAuto (the default; resolveRefineMode): kExact under conservative rounding, kNone under
  // centre rounding or with fit_universe_to_reach (a world that changes). A conservative 1 cm
  // model without it rejects free states up to two voxel diagonals from contact (a grasp a few
  // millimetres from an object, most of an arm's near self pairs): docs/trade-off.md.
  RefineMode refine = RefineMode::kAuto;
  // RefineMode::kExact: clearanceLowerBound returns FCL's exact distance to the environment when
  // the octree's bound is below this (metres), else the octree's bound.
  double refine_clearance_margin = 0.05;
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

// Least share of a self pair's joint space whose states reach the tree test for the pair to get
// a joint-space table (CollisionModelOptions::self_pair_tables): below it the table's build
// costs more than the tree tests it spares.
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
  // CollisionModelOptions::fold_static: the links tested against the environment once (instead
  // of per state), the self pairs tested once and dropped (names in robot order), and those of
  // them found in contact: when any is, every state is in collision.
  std::vector<std::string> static_links;
  std::vector<std::pair<std::string, std::string>> constant_pairs;
  std::vector<std::string> static_collisions;
  RefineMode refine = RefineMode::kNone;  // CollisionModelOptions::refine, resolved
  double refine_build_seconds = 0;        // the FCL geometry of RefineMode::kExact
  double build_seconds = 0;
  std::string toString() const;  // the human-readable "what was modelled" summary
};

// The self-collision broad phase's octree in a CheckScratch (kNObjectsOctree; empty otherwise),
// whose links move with every check: opaque here, made once per thread by makeScratch (or by the
// first check that needs it).
class SelfBroadPhaseScratch {
 public:
  SelfBroadPhaseScratch() noexcept;
  SelfBroadPhaseScratch(const SelfBroadPhaseScratch& other);
  SelfBroadPhaseScratch(SelfBroadPhaseScratch&& other) noexcept;
  SelfBroadPhaseScratch& operator=(const SelfBroadPhaseScratch& other);
  SelfBroadPhaseScratch& operator=(SelfBroadPhaseScratch&& other) noexcept;
  ~SelfBroadPhaseScratch();

  bool has_value() const { return octree_ != nullptr; }
  broadphase::NObjectsOctree* get() const { return octree_.get(); }
  void reset(broadphase::NObjectsOctree octree);

 private:
  std::unique_ptr<broadphase::NObjectsOctree> octree_;
};

// RefineMode::kExact: what one thread's refined queries decided how, counted from the scratch's
// first refined query (OctreeCollisionModel::refineCounts). Links and pairs the octree could
// not certify: contacts certain without FCL (a link's surface point deep inside a primitive
// obstacle), and the link-objects and link-link tests FCL ran.
struct RefineCounts {
  std::uint64_t certain_contacts = 0;
  std::uint64_t fcl_links = 0;
  std::uint64_t fcl_pairs = 0;
  // Link pairs cleared by their hulls (the convex hulls of their meshes' vertices apart), before
  // any voxel or FCL test.
  std::uint64_t hull_apart_pairs = 0;
  // Link pairs in contact for certain without voxels or FCL (two closed convex meshes whose
  // surfaces cross); the check stops at the first.
  std::uint64_t certain_self_contacts = 0;
  // Link-object pairs of links FCL decided, cleared by the link's hull apart from the object's
  // (a box's corners, a capsule about a cylinder, a mesh's vertices) before FCL.
  std::uint64_t hull_apart_objects = 0;
  // Links cleared of the environment by their hull apart from every object's hull that could
  // reach them, before their voxels (skipped for voxel objects, which have no hull).
  std::uint64_t hull_apart_links = 0;
  // Links cleared of the environment by the clearance grid (its bound at their bounding
  // sphere's centre above the sphere's radius), before their hull or voxels.
  std::uint64_t grid_clear_links = 0;
};

// RefineMode::kExact: the posed FCL objects of one thread, opaque here, made by the first
// refined query. A copy starts empty (it is remade on use), so copies never share it.
class RefineScratchHolder {
 public:
  RefineScratchHolder() noexcept;
  RefineScratchHolder(const RefineScratchHolder& other);
  RefineScratchHolder(RefineScratchHolder&& other) noexcept;
  RefineScratchHolder& operator=(const RefineScratchHolder& other);
  RefineScratchHolder& operator=(RefineScratchHolder&& other) noexcept;
  ~RefineScratchHolder();

  detail::RefineScratch* get() const { return scratch_.get(); }
  void reset(std::unique_ptr<detail::RefineScratch> scratch);

 private:
  std::unique_ptr<detail::RefineScratch> scratch_;
};

// Per-thread scratch for queries: FK results, the fused query's buffers and (kNObjectsOctree)
// the self-collision broad phase's octree. One per thread.
struct CheckScratch {
  RobotData robot;
  CollisionScratch fused;
  SelfBroadPhaseScratch self_broad_phase;
  // RefineMode::kExact only; mutable because clearanceLowerBound (const scratch) poses FCL
  // objects in it.
  mutable RefineScratchHolder refine;
  std::vector<Eigen::Vector3d> centres_W;  // per modelled link: bounding-sphere centre in W
  std::uint64_t owner = 0;                 // id() of the model it was made for
};

// The constant model of one scene, shared by every thread; its parts are built once by the
// constructor (planner/src/model/internal/collision_model_builder.h).
class OctreeCollisionModel {
 public:
  // Builds the environment tree on a universe fitted to what the robot can reach (parts of the
  // environment it can never reach are not modelled) and one source tree per link.
  OctreeCollisionModel(RobotModel robot, const EnvironmentGeometry& environment,
                       const CollisionModelOptions& options);
  // The same, keeping `environment` (explainContacts names its objects) without a copy; the
  // constructor above keeps a copy.
  OctreeCollisionModel(RobotModel robot, std::shared_ptr<const EnvironmentGeometry> environment,
                       const CollisionModelOptions& options);
  OctreeCollisionModel(OctreeCollisionModel&& other) noexcept;
  OctreeCollisionModel& operator=(OctreeCollisionModel&& other) noexcept;
  ~OctreeCollisionModel();

  const RobotModel& robot() const { return robot_; }
  const Octree& environment() const;
  const WorldGrid& grid() const;
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
  // Why the link poses in the scratch collide (CollisionBackend::explain): each link whose
  // environment test hits, with each object whose own voxels (on the environment's grid, built on
  // first use and kept) or, with exact primitives, whose primitive its voxels meet; each checked
  // pair that meets. Whether the exact shapes touch is asked of FCL (meshes and primitives;
  // unknown for point clouds and OctoMaps); the margin is the voxel size. Appends to
  // explanation.reasons, the first contact only unless `all`. Agrees with linksInCollision.
  void explainContacts(CheckerPath path, CheckScratch& scratch, bool all,
                       StateExplanation& explanation) const;
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
  // RefineMode::kExact: the octree's bound when it is at least `margin`, else FCL's exact
  // distance between the robot's geometry and the environment's objects (point clouds and
  // OctoMaps: their voxels). Without kExact: clearanceLowerBound.
  double refinedClearance(const CheckScratch& scratch, double margin) const;
  RefineMode refine() const { return options_.refine; }
  // RefineMode::kExact, for the certified motion validator (refine_clearance.cpp): each link l
  // with caps[l] > 0 whose per_link[l] (a lower bound, e.g. clearanceLowerBoundGridPerLink's)
  // is below caps[l] and below two voxels gets a tighter lower bound on the distance from its
  // geometry to the environment's objects, or caps[l] when that is at least caps[l]: per object,
  // the distance between convex hulls holding both (boxes, balls, cylinders; docs/validation.md
  // §7), or FCL's exact distance where that hull bound is within an eighth of a voxel of contact
  // (a 64th against a primitive) or the object is not a primitive. And the same between two links'
  // geometry, or `cap` when at least `cap`. Without kExact: per_link unchanged, and 0.
  // `nearest`, when not null, receives for each link refined below its cap the slabs of its
  // nearest objects' hull distances, nearest first while each has one, and a bound on the
  // others (NearestObstacle); a link whose nearest object has no slab is left as it is.
  void refineClearancesPerLink(const CheckScratch& scratch, const double* caps, double* per_link,
                               NearestObstacle* nearest = nullptr) const;
  double refinedPairDistance(const CheckScratch& scratch, int link_a, int link_b, double cap) const;
  // RefineMode::kExact: what the scratch's refined queries decided how (zero before any).
  RefineCounts refineCounts(const CheckScratch& scratch) const;
  // A looser, much cheaper bound for certifying motions (CertifiedMotionValidator): the same
  // spheres against the environment's ClearanceGrid (one lookup each; loose by up to a grid
  // cell more). Never above clearanceLowerBoundTree's true target, the distance to the voxels.
  double clearanceLowerBoundGrid(const CheckScratch& scratch) const;
  // The same per robot link into per_link[robot().linkCount()], each less `slack` (floored at
  // 0); for links whose reach misses the environment's box, the gap between the two boxes.
  // Links with caps[l] <= 0 are not computed (their value is unspecified).
  void clearanceLowerBoundGridPerLink(const CheckScratch& scratch, const double* caps, double slack,
                                      double* per_link) const;

  // Read-only view of a modelled link's source tree (in its link frame L), for viewers and
  // exports: moveTree(*source, X_WL, grid(), rounding()) is the link's placement at pose X_WL.
  struct LinkSourceTree {
    int link = -1;                   // index in robot().links()
    const Octree* source = nullptr;  // owned by the model
    // The self pairs' tree when it has its own resolution (self_link_resolution), else null.
    const Octree* self_source = nullptr;
  };
  std::vector<LinkSourceTree> linkSourceTrees() const;

  // ---- A world that changes between plans (docs/robots.md; world_updates.cpp). Each update
  // re-voxelizes only the region it touches (the old and new boxes of the object, from every
  // object that meets them) and keeps the link trees and self-pair data; the environment's grids,
  // boxes and clearance structures follow. Not concurrent with queries: update between plans,
  // then share the model read-only again. Each update gives the model a new id(), so scratch
  // made before it is remade by the next query (and OMPL planners' data must be cleared: their
  // checked motions are stale). Throws InvalidArgument for an unknown or duplicate name, an
  // object whose reachable part lies outside the universe (see fit_universe_to_reach), or a
  // model built with exact_primitives; the model is unchanged then.

  // Adds an object to the world (its file read as EnvironmentGeometry::load does).
  void addObject(const EnvironmentObject& object, const WarningSink& warnings = {});
  void addObject(EnvironmentGeometry::Item item);
  void removeObject(const std::string& name);
  // The object's new pose (primitives and meshes).
  void moveObject(const std::string& name, const Eigen::Isometry3d& X_WO);
  // Attaches a primitive or mesh to a link: it moves with the link, is tested against the
  // environment and against every other modelled link and attached object except the carrying
  // link, its touch_links and the objects on the same link. Only its own trees are built.
  void attachObject(const AttachedObject& object, const WarningSink& warnings = {});
  // Detaches it; with `leave_at_W` it stays in the world there (as addObject; see
  // attachedObjectPose for where the link holds it at a configuration).
  void detachObject(const std::string& name,
                    const std::optional<Eigen::Isometry3d>& leave_at_W = std::nullopt);
  // X_WO of an attached object with the robot at q (X_WB: free-flying robots' base pose).
  Eigen::Isometry3d attachedObjectPose(const std::string& name, const double* q, std::size_t q_size,
                                       const Eigen::Isometry3d& X_WB) const;
  // The world's objects now, and the attached objects' names.
  const EnvironmentGeometry& objects() const;
  std::vector<std::string> attachedObjects() const;

 private:
  void requireUpdatable() const;
  // The environment tree again inside the voxels the boxes touch, then everything derived.
  void updateEnvironment(const std::vector<Eigen::AlignedBox3d>& changed_W);
  void requireInUniverse(const EnvironmentGeometry::Item& item) const;

  std::uint64_t id_;
  RobotModel robot_;
  CollisionModelOptions options_;
  CollisionModelReport report_;
  void resetExplainData();

  std::unique_ptr<detail::CollisionModelParts> parts_;
  std::unique_ptr<detail::ExplainData> explain_;  // built on first use (octree_explain.cpp)
  // RefineMode::kExact: the FCL geometry (refine.cpp); null otherwise.
  std::unique_ptr<const detail::RefineData> refine_;
  bool refinedEnvironmentInCollision(CheckerPath path, CheckScratch& scratch) const;
  bool refinedSelfInCollision(CheckerPath path, CheckScratch& scratch) const;
  bool refinedLinksInCollision(CheckerPath path, CheckScratch& scratch) const;
};

}  // namespace octomotion
