// Private to the planner library: what RefineMode::kExact keeps besides the octree model. The
// octree certifies freedom (no shared voxel under conservative rounding); a link whose voxels
// meet the environment's, or a checked pair whose voxels meet, is decided by FCL on the original
// geometry: the robot's links as FCL objects (fcl_robot.h), each object of the scene as a posed
// FCL shape (meshes and primitives) or, for point clouds and OctoMaps, whose geometry is their
// voxels, one FCL box per black leaf on the model's grid. Before FCL, a link the octree cannot
// clear is tested for a certain contact (a witness point of its surface deep inside a
// primitive obstacle), and FCL runs only on the links left uncertain. Built once with the
// model, then constant and shared by threads; each thread poses the robot in its own
// RefineScratch, only the links it tests.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "../../robot/internal/fcl_robot.h"
#include "octomotion/motion/convex_gap.h"
#include "octomotion/motion/point_clusters.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/scene/environment_geometry.h"

namespace octomotion::detail {

// Points of a primitive's solid at least kCertainDepth deep (deepPoints): its solid shrunk by
// that depth (empty when the solid is thinner), the centre, and points on the shrunk solid's
// boundary (a box's corners, eight points on each rim of a cylinder, a ball's six poles), in
// the primitive's frame.
struct DeepPoints {
  std::optional<Primitive> core;
  std::vector<Eigen::Vector3d> points;
};

// One object of the scene, or one piece of a large mesh object (a few nearby triangles: its
// hull is then the piece's, not the whole mesh's).
struct RefineObject {
  std::vector<fcl::CollisionObjectd> shapes;  // one (primitive, mesh) or one box per voxel
  fcl::AABBd box_W;                           // of all shapes
  // A box, ball or cylinder obstacle: the shape in its frame O (FCL treats it as a solid).
  std::optional<Primitive> primitive;
  Eigen::Isometry3d X_OW = Eigen::Isometry3d::Identity();
  // In W, a convex set holding the object's solid (objectHull); empty for voxel objects. A
  // link whose hull is apart from it is free of it for FCL (refineLinkHits).
  ConvexPoints hull_W;
  // A primitive's exact or outer hull in O (primitiveHull); a piece of a large mesh's hull in W
  // (X_OW the identity; refine.cpp, meshPieces); empty for other objects, whose hull may hold
  // points far from them (a concave mesh around a link).
  ConvexPoints hull_O;
  // A primitive's deepPoints in O, for closedMeshCrossesPrimitive; empty for other objects.
  DeepPoints deep_O;
};

// A convex set holding `spec`'s solid in W: a box's corners, a ball's centre grown by its radius,
// a cylinder's end centres grown by its radius (a capsule holds it), a mesh's vertices (its
// triangles lie in their hull); empty for other objects.
ConvexPoints objectHull(const EnvironmentObject& spec, const TriangleMesh& mesh);

// A point of a robot element this deep inside a primitive obstacle makes FCL report a contact:
// far above FCL's GJK tolerance (micrometres), far below any obstacle's size.
inline constexpr double kCertainDepth = 1e-4;
// Witness points kept per mesh element: its vertices, spread out (farthest first).
inline constexpr std::size_t kWitnessPoints = 24;

// A closed mesh element in its link's frame L, for certain self contacts
// (certainPairContact): its vertices, its face planes with outward normals (n, d: n . p <= d
// on the inner side) and, per face, the largest n . v over the vertices (the hull's extent
// along n); empty otherwise.
struct ClosedLinkMesh {
  std::vector<Eigen::Vector3d> vertices_L;
  // Nearby vertices (clusterPoints, in L), contiguous in vertices_L, so the searches for the
  // vertex nearest or farthest from a point skip most clusters.
  std::vector<PointCluster> clusters;
  std::vector<Eigen::Vector4d> planes_L;
  std::vector<double> supports_L;
  Eigen::Vector3d centroid_L = Eigen::Vector3d::Zero();  // of the vertices
  // Shortcuts past the planes: the box of the vertices (a point outside it is outside the
  // solid), and a box whose points all lie kCertainDepth inside every face plane (empty when
  // the centroid does not).
  Eigen::AlignedBox3d box_L;
  Eigen::AlignedBox3d inner_box_L;
  // The longest edges (at most kLongEdges, each at least a third of the box's diagonal): their
  // points lie on the surface far from any vertex, as along a capsule's side, where another
  // link may cross it with no vertex inside (crosses).
  static constexpr std::size_t kLongEdges = 128;
  std::vector<Eigen::Vector3d> edge_start_L, edge_span_L;  // an edge: start + s * span, s in [0, 1]
  bool empty() const { return planes_L.empty(); }
};

// A robot element as the certain contacts see it (selfContactElements): a mesh's vertices in L
// (on the triangles FCL tests) and, when it is closed, its ClosedLinkMesh; or a primitive solid
// with its frame and its deepPoints in that frame E.
struct SelfContactElement {
  ClosedLinkMesh mesh;
  std::optional<Primitive> primitive;
  Eigen::Isometry3d X_EL = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> points_L;
  DeepPoints deep_E;
};

struct RefineData {
  RefineData(const RobotModel& robot, const EnvironmentGeometry& objects, const WorldGrid& grid,
             const CollisionModelOptions& options);

  std::unique_ptr<const fcl_internal::RobotGeometry> robot;
  std::vector<RefineObject> objects;
  // Per robot link: its elements (indices in RobotGeometry's order).
  std::vector<std::vector<std::size_t>> link_elements;
  // Per mesh element, in its frame E: points of its surface whose triangles FCL tests (its
  // vertices, spread out), for certain contacts with primitive obstacles; none for primitive
  // elements, which primitivesOverlap tests as solids.
  std::vector<std::vector<Eigen::Vector3d>> element_witnesses_E;
  bool has_primitives = false;  // some object is a primitive (certain contacts can exist)
  // Per robot link, in its frame: the hull of its elements' points (mesh vertices, box
  // corners); empty for a link with another shape. Two links whose hulls are apart cannot touch,
  // so a checked pair is cleared before any voxel or FCL test (refineHullsApart).
  std::vector<ConvexPoints> link_hulls_L;
  // Per robot link with a hull: the box of its hull's points in L (centre, half sides), tested
  // before GJK (refineHullsApart): tighter than the voxel boxes, and a few operations.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> link_hull_boxes_L;
  // Per robot element: what certain self contacts use (selfContactElements).
  std::vector<SelfContactElement> self_elements;
};

// Hulls closer than this are left to the octree and FCL: far above rounding in the poses,
// far below any gap that matters.
inline constexpr double kHullGap = 1e-5;

// The distance from p to the box (0 inside it).
inline double distanceToBox(const fcl::AABBd& box, const Eigen::Vector3d& p) {
  return (box.min_ - p).cwiseMax(p - box.max_).cwiseMax(0.0).norm();
}

// Which of two outcomes a thread saw lately: the counts halve when their sum reaches kWindow,
// so they follow the states it checks now (a planner's nearby states). Per self pair, its exact
// tests' verdicts (first: hulls apart, second: certain contact): a pair mostly in contact tries
// the certain-contact test before the hulls' (which cannot clear it). Per query, the half that
// found the contact (first: environment, second: self pairs): the half that found more runs its
// octree pass first (refinedLinksInCollision), so a contact found there spares the other's.
struct RecentOutcomes {
  static constexpr std::uint8_t kWindow = 32;
  std::uint8_t first = 0;
  std::uint8_t second = 0;
  bool secondLeads() const { return second > first; }
  void add(bool is_second) {
    ++(is_second ? second : first);
    if (first + second >= kWindow) {
      first /= 2;
      second /= 2;
    }
  }
};

struct RefineScratch {
  std::uint64_t owner = 0;  // id() of the model it was made for
  fcl_internal::RobotScratch fcl;
  // Elements are posed on first use in a query: posed_at[e] == query when e is at this query's
  // link poses (queries count up from 1).
  std::vector<std::uint64_t> posed_at;
  std::uint64_t query = 0;
  // What the octree could not certify, for FCL after the octree pass: robot links against
  // the environment, link pairs.
  std::vector<int> uncertain_links;
  std::vector<std::pair<int, int>> uncertain_pairs;
  // Per self pair (SelfCollision::pairs): the last direction that separated its hulls, tried
  // first (a planner's nearby states are often separated the same way).
  std::vector<Eigen::Vector3d> pair_directions;
  // Per self pair: its recent verdicts when its links' boxes meet, to order its two exact tests
  // (selfOctreePass). Both are sound, so the order changes the time, not the answer.
  std::vector<RecentOutcomes> pair_verdicts;
  RecentOutcomes half_contacts;    // second: the self pairs'
  std::vector<char> object_apart;  // refineLinkHits' per-object hull verdicts
  // Per link and object (link * objects + object): the direction of the last hull distance
  // between them (refine_clearance.cpp), tried first by the next (convexDistanceBelow); a stale
  // one costs a support pair, never the bound. Sized when the scratch is made: a model's refine
  // data never changes (world updates refuse exact refine).
  std::vector<Eigen::Vector3d> link_object_directions;
  // The same for linkApartFromObjects' separating directions (kept apart from the distances').
  std::vector<Eigen::Vector3d> link_object_apart;
  RefineCounts counts;
  // Distances for the certified motion validator (refine_clearance.cpp): link-object and
  // link-link distances answered by their hulls' bound, and FCL distance calls (one per element
  // and shape pair) for the others.
  std::uint64_t hull_distances = 0;
  std::uint64_t fcl_distances = 0;
};

// The thread's refine scratch for a new query at the link poses in `robot` (FK done), made on
// first use; elements are posed lazily (refinePoseLink).
RefineScratch& refineScratch(const RefineData& data, const RobotModel& model, std::uint64_t owner,
                             RefineScratchHolder& holder);
// Poses `link`'s elements for the current query unless done already.
void refinePoseLink(const RefineData& data, RefineScratch& r, const RobotData& robot, int link);

// Without FCL: a witness point of one of `link`'s elements lies kCertainDepth inside a primitive
// obstacle, so FCL finds a contact (its triangle, or its solid, meets the obstacle's solid); or
// a closed mesh element crosses the obstacle (closedMeshCrossesPrimitive).
bool certainLinkContact(const RefineData& data, RefineScratch& r, const RobotData& robot, int link);
// FCL: one of `link`'s elements touches one of the objects' shapes.
bool refineLinkHits(const RefineData& data, RefineScratch& r, const RobotData& robot, int link);
// FCL: an element of link_a touches one of link_b.
bool refinePairHits(const RefineData& data, RefineScratch& r, const RobotData& robot, int link_a,
                    int link_b);
// FCL on the links in r.uncertain_links, then the pairs in r.uncertain_pairs, each list in
// order, stopping at the first contact.
bool refineUncertainLinksHit(const RefineData& data, RefineScratch& r, const RobotData& robot);
bool refineUncertainPairsHit(const RefineData& data, RefineScratch& r, const RobotData& robot);
// Each link's hull in its frame (RefineData::link_hulls_L).
std::vector<ConvexPoints> linkHulls(const fcl_internal::RobotGeometry& robot,
                                    const RobotModel& model,
                                    const std::vector<std::vector<std::size_t>>& link_elements);
// The hull of `link` is kHullGap apart from the hull of every object that could reach it (its
// box within the link hull's ball) at the link's pose in `robot`: FCL finds no contact between
// the link and the environment, so its voxels need not be looked at. False when the link or
// such an object has no hull (voxel objects). Directions that separated them are kept in `r`.
bool linkApartFromObjects(const RefineData& data, RefineScratch& r, const RobotData& robot,
                          int link);
// The hull of `link` is kHullGap apart from `object`'s (both non-empty) at the link's pose in
// `robot`, so FCL finds no contact between the link's elements and the object.
bool linkApartFromObject(const RefineData& data, const RobotData& robot, int link,
                         const RefineObject& object);
// The hulls of link_a and link_b (both with one) are kHullGap apart at the poses in `robot`, so
// FCL finds no contact between their elements. `direction` starts the search and keeps the
// separating direction.
bool refineHullsApart(const RefineData& data, const RobotData& robot, int link_a, int link_b,
                      Eigen::Vector3d& direction);
// Per robot element, checked once at build time: its closed mesh (every edge in two triangles
// with windings that agree, one surface, triangles with area) or its primitive, and its points
// in L. Elements of links whose collision list does not match RobotGeometry's are left empty.
std::vector<SelfContactElement> selfContactElements(
    const fcl_internal::RobotGeometry& robot, const RobotModel& model,
    const std::vector<std::vector<std::size_t>>& link_elements);
// Without FCL: an element of link_a and one of link_b are certainly in contact, so FCL's
// element test reports a contact. Either both are closed meshes and a vertex of one lies
// kCertainDepth inside the other's every face plane (so inside its solid) while another lies
// kCertainDepth outside its hull, so their surfaces cross; or one is a primitive (a solid for
// FCL) with the other mesh's vertex nearest its centre kCertainDepth inside it, or crossed by
// the other's closed mesh (closedMeshCrossesPrimitive), or overlapping the other primitive
// (primitivesOverlap).
bool certainPairContact(const RefineData& data, const RobotData& robot, int link_a, int link_b);
// p_O lies at least kCertainDepth inside the primitive (in its frame O).
bool deepInside(const Primitive& shape, const Eigen::Vector3d& p_O);
DeepPoints deepPoints(const Primitive& shape);
// Without FCL: two primitive solids (frames A and B, X_AB placing B in A) overlap for FCL: the
// centre of one, or the point of its deep core nearest the other's centre, lies kCertainDepth
// inside the other.
bool primitivesOverlap(const Primitive& a, const DeepPoints& deep_a, const Primitive& b,
                       const DeepPoints& deep_b, const Eigen::Isometry3d& X_AB);
// Without FCL: a closed mesh (its frame M; X_PM places it in the primitive's frame P) and a
// primitive solid are in contact for FCL. The point of the solid's deep core nearest the mesh's
// vertex centroid lies kCertainDepth inside the mesh's every face plane (so inside its solid),
// and another of its deep points kCertainDepth outside the mesh's hull: the segment between
// them lies kCertainDepth deep in the convex solid and leaves the mesh's, so a point of the
// mesh's surface lies that deep in the primitive, which FCL's triangle test finds.
bool closedMeshCrossesPrimitive(const ClosedLinkMesh& mesh, const DeepPoints& deep,
                                const Eigen::Isometry3d& X_PM);
// The hull in its frame of a box, ball or cylinder (convex_gap.h): a distance to it is at most
// the distance to the solid.
ConvexPoints primitiveHull(const Primitive& shape);
// FCL's exact distance from the robot's elements to the objects (0 in contact).
double refineEnvironmentDistance(const RefineData& data, RefineScratch& r, const RobotData& robot);

}  // namespace octomotion::detail
