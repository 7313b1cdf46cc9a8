// RefineMode::kExact (internal/refine.h): the octree certifies freedom, witness points certain
// contacts with primitive obstacles, FCL decides the links and pairs left.
#include "internal/refine.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/distance.h>

#include "internal/collision_model_parts.h"
#include "octomotion/error.h"

namespace octomotion {

RefineScratchHolder::RefineScratchHolder() noexcept = default;
RefineScratchHolder::RefineScratchHolder(const RefineScratchHolder&) {}
RefineScratchHolder::RefineScratchHolder(RefineScratchHolder&&) noexcept = default;
RefineScratchHolder& RefineScratchHolder::operator=(const RefineScratchHolder& other) {
  if (this != &other) scratch_.reset();
  return *this;
}
RefineScratchHolder& RefineScratchHolder::operator=(RefineScratchHolder&&) noexcept = default;
RefineScratchHolder::~RefineScratchHolder() = default;
void RefineScratchHolder::reset(std::unique_ptr<detail::RefineScratch> scratch) {
  scratch_ = std::move(scratch);
}

namespace detail {

namespace {

void extend(fcl::AABBd& box, const fcl::AABBd& other, bool first) {
  if (first) {
    box = other;
  } else {
    box += other;
  }
}

// Up to kWitnessPoints of `points`, spread out: each next one the farthest from those taken.
std::vector<Eigen::Vector3d> spreadOut(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> taken;
  if (points.empty()) return taken;
  std::vector<double> gap(points.size(), std::numeric_limits<double>::infinity());
  std::size_t next = 0;
  while (taken.size() < std::min(points.size(), kWitnessPoints)) {
    taken.push_back(points[next]);
    std::size_t far = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      gap[i] = std::min(gap[i], (points[i] - taken.back()).squaredNorm());
      if (gap[i] > gap[far]) far = i;
    }
    if (gap[far] <= 0) break;  // every point taken (duplicates)
    next = far;
  }
  return taken;
}

// A robot element's witnesses in its frame: a mesh's vertices (on its triangles); none for
// anything else.
std::vector<Eigen::Vector3d> witnessesOf(const fcl::CollisionGeometryd& geometry) {
  if (geometry.getObjectType() == fcl::OT_BVH) {
    const auto* mesh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(&geometry);
    if (mesh == nullptr || mesh->vertices == nullptr || mesh->tri_indices == nullptr) return {};
    // Only vertices of triangles: FCL tests triangles, not loose points.
    std::vector<bool> used(static_cast<std::size_t>(mesh->num_vertices), false);
    for (int t = 0; t < mesh->num_tris; ++t) {
      for (int k = 0; k < 3; ++k) used[mesh->tri_indices[t][k]] = true;
    }
    std::vector<Eigen::Vector3d> vertices;
    for (std::size_t v = 0; v < used.size(); ++v) {
      if (used[v]) vertices.push_back(mesh->vertices[v]);
    }
    return spreadOut(vertices);
  }
  return {};  // primitive elements are tested as solids (primitivesOverlap)
}

// A mesh obstacle as pieces of nearby triangles, each with its own FCL model, box and hull
// (RefineObject): the pieces partition the triangles, so FCL's contact (with any piece) and
// distance (the least over the pieces) are the mesh's, and each piece's hull holds its triangles
// only, so a link beside one wall of a building is cleared (refineLinkHits) and bounded
// (refineClearancesPerLink) by that wall's hull, not by the whole mesh's, which holds the link.
// Pieces are split at the median of their triangles' centroids along the longest side of the
// centroids' box while they have more than max(kPieceTriangles, triangles / kMaxPieces)
// triangles, or more than one and a vertex box thicker than `thin` on every side (a hull that may
// span free space: a floor's triangle with a wall's) as long as there are fewer than kMaxPieces.
// A mesh of at most kPieceTriangles triangles within `thin` on a side stays one piece.
constexpr std::size_t kPieceTriangles = 16;
constexpr std::size_t kMaxPieces = 256;
std::vector<TriangleMesh> meshPieces(const TriangleMesh& mesh, double thin) {
  const std::size_t most = std::max(kPieceTriangles, mesh.triangles.size() / kMaxPieces);
  std::vector<Eigen::Vector3d> centroids;
  for (const auto& t : mesh.triangles) {
    centroids.push_back((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3);
  }
  std::vector<std::uint32_t> order(mesh.triangles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::vector<TriangleMesh> pieces;
  // [begin, end) of `order`, split until small enough.
  std::vector<std::pair<std::size_t, std::size_t>> todo = {{0, order.size()}};
  while (!todo.empty()) {
    const auto [begin, end] = todo.back();
    todo.pop_back();
    bool split = end - begin > most;
    if (!split && end - begin > 1 && pieces.size() + todo.size() + 2 <= kMaxPieces) {
      Eigen::AlignedBox3d vertices;
      for (std::size_t i = begin; i < end; ++i) {
        for (std::uint32_t v : mesh.triangles[order[i]]) vertices.extend(mesh.vertices[v]);
      }
      split = vertices.sizes().minCoeff() > thin;
    }
    if (split) {
      Eigen::AlignedBox3d box;
      for (std::size_t i = begin; i < end; ++i) box.extend(centroids[order[i]]);
      Eigen::Index axis = 0;
      box.sizes().maxCoeff(&axis);
      const std::size_t middle = begin + (end - begin) / 2;
      std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin),
                       order.begin() + static_cast<std::ptrdiff_t>(middle),
                       order.begin() + static_cast<std::ptrdiff_t>(end),
                       [&](std::uint32_t a, std::uint32_t b) {
                         return centroids[a][axis] < centroids[b][axis];
                       });
      todo.emplace_back(begin, middle);
      todo.emplace_back(middle, end);
      continue;
    }
    // The piece's triangles over its own vertices.
    TriangleMesh piece;
    std::unordered_map<std::uint32_t, std::uint32_t> index;
    for (std::size_t i = begin; i < end; ++i) {
      std::array<std::uint32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[order[i]][static_cast<std::size_t>(k)];
        const auto [it, added] =
            index.emplace(v, static_cast<std::uint32_t>(piece.vertices.size()));
        if (added) piece.vertices.push_back(mesh.vertices[v]);
        t[static_cast<std::size_t>(k)] = it->second;
      }
      piece.triangles.push_back(t);
    }
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

}  // namespace

bool deepInside(const Primitive& shape, const Eigen::Vector3d& p_O) {
  if (const auto* b = std::get_if<Box>(&shape)) {
    return (p_O.cwiseAbs() - b->half_extents).maxCoeff() <= -kCertainDepth;
  }
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    const double r = ball->radius - kCertainDepth;
    return r > 0 && p_O.squaredNorm() <= r * r;
  }
  const auto& c = std::get<Cylinder>(shape);
  const double r = c.radius - kCertainDepth;
  return r > 0 && std::abs(p_O.z()) <= c.length / 2 - kCertainDepth &&
         p_O.head<2>().squaredNorm() <= r * r;
}

RefineData::RefineData(const RobotModel& model, const EnvironmentGeometry& environment,
                       const WorldGrid& grid, const CollisionModelOptions& options)
    : robot(std::make_unique<const fcl_internal::RobotGeometry>(
          model, options.keep_mesh_root_transform, options.center_mesh_vertices)),
      link_elements(static_cast<std::size_t>(model.linkCount())) {
  for (std::size_t e = 0; e < robot->elementCount(); ++e) {
    link_elements[static_cast<std::size_t>(robot->elementLink(e))].push_back(e);
  }
  for (std::size_t i = 0; i < environment.size(); ++i) {
    const EnvironmentGeometry::Item& item = environment.items()[i];
    RefineObject object;
    auto add = [&](const fcl_internal::Geom& g, const Eigen::Isometry3d& X_WO) {
      object.shapes.emplace_back(g, X_WO.rotation(), X_WO.translation());
      fcl_internal::setTightAabb(object.shapes.back());
    };
    if (item.spec.kind == EnvironmentObject::Kind::kPrimitive) {
      add(fcl_internal::shapeOf(item.spec.primitive), item.spec.X_WO);
      object.primitive = item.spec.primitive;
      object.X_OW = item.spec.X_WO.inverse();
      object.hull_O = primitiveHull(item.spec.primitive);
      object.deep_O = deepPoints(item.spec.primitive);
      has_primitives = true;
    } else if (item.spec.kind == EnvironmentObject::Kind::kMesh) {
      const std::vector<TriangleMesh> pieces = meshPieces(item.mesh, 2 * grid.voxelSize());
      if (pieces.size() > 1) {
        // Each piece an object of its own, with its hull in W (X_OW stays the identity).
        for (const TriangleMesh& piece : pieces) {
          RefineObject part;
          part.shapes.emplace_back(fcl_internal::meshOf(piece), item.spec.X_WO.rotation(),
                                   item.spec.X_WO.translation());
          fcl_internal::setTightAabb(part.shapes.back());
          part.box_W = part.shapes.back().getAABB();
          std::vector<Eigen::Vector3d> points_W;
          for (const Eigen::Vector3d& v : piece.vertices) points_W.push_back(item.spec.X_WO * v);
          part.hull_W = ConvexPoints::hullOf(points_W);
          part.hull_O = part.hull_W;
          objects.push_back(std::move(part));
        }
        continue;
      }
      add(fcl_internal::meshOf(item.mesh), item.spec.X_WO);
    } else {
      // Point clouds and OctoMaps are voxels by definition: their exact geometry is their black
      // voxels on the model's grid, as the environment tree holds them.
      environment.voxelizeObject(i, grid, options.rounding).forEachBlackLeaf([&](const Cube& c) {
        const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
        const Eigen::Vector3d size = hi - lo;
        add(std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z()),
            Eigen::Isometry3d(Eigen::Translation3d((lo + hi) / 2)));
      });
    }
    for (std::size_t k = 0; k < object.shapes.size(); ++k) {
      extend(object.box_W, object.shapes[k].getAABB(), k == 0);
    }
    object.hull_W = objectHull(item.spec, item.mesh);
    objects.push_back(std::move(object));
  }
  fcl_internal::RobotScratch prototypes;
  robot->initScratch(model, prototypes);
  for (const fcl::CollisionObjectd& element : prototypes.objects) {
    element_witnesses_E.push_back(witnessesOf(*element.collisionGeometry()));
  }
  link_hulls_L = linkHulls(*robot, model, link_elements);
  for (const ConvexPoints& hull : link_hulls_L) {
    Eigen::AlignedBox3d box_L;
    for (std::size_t i = 0; i < hull.size(); ++i) box_L.extend(hull.point(i));
    link_hull_boxes_L.emplace_back(box_L.center(), box_L.isEmpty()
                                                       ? Eigen::Vector3d::Zero()
                                                       : Eigen::Vector3d(box_L.sizes() / 2));
  }
  self_elements = selfContactElements(*robot, model, link_elements);
}

RefineScratch& refineScratch(const RefineData& data, const RobotModel& model, std::uint64_t owner,
                             RefineScratchHolder& h) {
  if (h.get() == nullptr || h.get()->owner != owner) {
    auto scratch = std::make_unique<RefineScratch>();
    scratch->owner = owner;
    data.robot->initScratch(model, scratch->fcl);
    scratch->posed_at.assign(data.robot->elementCount(), 0);
    scratch->link_object_directions.assign(data.link_elements.size() * data.objects.size(),
                                           Eigen::Vector3d::Zero());
    scratch->link_object_apart = scratch->link_object_directions;
    h.reset(std::move(scratch));
  }
  RefineScratch& r = *h.get();
  ++r.query;
  return r;
}

void refinePoseLink(const RefineData& data, RefineScratch& r, const RobotData& robot, int link) {
  for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
    if (r.posed_at[e] == r.query) continue;
    data.robot->poseElement(robot, e, r.fcl);
    r.posed_at[e] = r.query;
  }
}

bool certainLinkContact(const RefineData& data, RefineScratch& r, const RobotData& robot,
                        int link) {
  if (!data.has_primitives) return false;
  refinePoseLink(data, r, robot, link);
  for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
    const std::vector<Eigen::Vector3d>& witnesses = data.element_witnesses_E[e];
    const SelfContactElement& kind = data.self_elements[e];
    const ClosedLinkMesh& closed = kind.mesh;
    if (witnesses.empty() && closed.empty() && !kind.primitive) continue;
    const fcl::CollisionObjectd& element = r.fcl.objects[e];
    for (const RefineObject& object : data.objects) {
      if (!object.primitive || !object.box_W.overlap(element.getAABB())) continue;
      const Eigen::Isometry3d X_OE = object.X_OW * element.getTransform();
      if (kind.primitive) {  // two solids
        if (primitivesOverlap(*object.primitive, object.deep_O, *kind.primitive, kind.deep_E,
                              X_OE)) {
          return true;
        }
        continue;
      }
      for (const Eigen::Vector3d& p_E : witnesses) {
        if (deepInside(*object.primitive, X_OE * p_E)) return true;
      }
      // A thin bar or board through the link holds none of its vertices, but crosses its mesh.
      if (!closed.empty() &&
          closedMeshCrossesPrimitive(closed, object.deep_O, object.X_OW * robot.linkPose(link))) {
        return true;
      }
    }
  }
  return false;
}

bool refineLinkHits(const RefineData& data, RefineScratch& r, const RobotData& robot, int link) {
  refinePoseLink(data, r, robot, link);
  fcl_internal::RobotScratch& s = r.fcl;
  // Per object: unknown (0), apart from the link's hull (1), not apart (2); decided on the
  // first element that reaches FCL with it.
  r.object_apart.assign(data.objects.size(), 0);
  for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
    const fcl::CollisionObjectd& element = s.objects[e];
    for (std::size_t o = 0; o < data.objects.size(); ++o) {
      const RefineObject& object = data.objects[o];
      if (object.shapes.empty() || !object.box_W.overlap(element.getAABB())) continue;
      if (r.object_apart[o] == 0) {
        r.object_apart[o] = linkApartFromObject(data, robot, link, object) ? 1 : 2;
        r.counts.hull_apart_objects += r.object_apart[o] == 1;
      }
      if (r.object_apart[o] == 1) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        if (fcl_internal::collidePair(element, shape, s.request, s.result)) return true;
      }
    }
  }
  return false;
}

bool refinePairHits(const RefineData& data, RefineScratch& r, const RobotData& robot, int link_a,
                    int link_b) {
  refinePoseLink(data, r, robot, link_a);
  refinePoseLink(data, r, robot, link_b);
  fcl_internal::RobotScratch& s = r.fcl;
  for (std::size_t a : data.link_elements[static_cast<std::size_t>(link_a)]) {
    for (std::size_t b : data.link_elements[static_cast<std::size_t>(link_b)]) {
      if (fcl_internal::collidePair(s.objects[a], s.objects[b], s.request, s.result)) return true;
    }
  }
  return false;
}

bool refineUncertainLinksHit(const RefineData& data, RefineScratch& r, const RobotData& robot) {
  for (const int link : r.uncertain_links) {
    ++r.counts.fcl_links;
    if (refineLinkHits(data, r, robot, link)) return true;
  }
  return false;
}

bool refineUncertainPairsHit(const RefineData& data, RefineScratch& r, const RobotData& robot) {
  for (const auto& [a, b] : r.uncertain_pairs) {
    ++r.counts.fcl_pairs;
    if (refinePairHits(data, r, robot, a, b)) return true;
  }
  return false;
}

// The octree's pass over the environment half: true on a certain contact, else the links it
// cannot clear in r.uncertain_links.
bool environmentOctreePass(const CollisionModelParts& parts, const RefineData& data,
                           RefineScratch& r, CheckerPath path, CheckScratch& scratch) {
  const EnvironmentModel& environment = parts.environment;
  const LinkModels& links = parts.links;
  r.uncertain_links.clear();
  for (const EnvironmentLinkTest& t : links.environment_tests) {
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(t.link);
    // The answer is FCL's against the objects: a link whose hull is apart from theirs is free,
    // whatever its voxels meet.
    if (!sphereMeetsBox(t, X_WL, environment.box_W)) continue;
    if (environment.linkClearByGrid(links.links[t.slot].voxels, X_WL)) {
      ++r.counts.grid_clear_links;
      continue;
    }
    if (linkApartFromObjects(data, r, scratch.robot, t.link)) {
      ++r.counts.hull_apart_links;
      continue;
    }
    // A link the hulls leave (its hull meets an object's, or it could reach a voxel object) is
    // mostly in contact: a certain contact settles the state without the voxel query, which
    // costs more in contact than out of it. A certain contact is a real one, so the voxels
    // (conservative) would have met too.
    if (certainLinkContact(data, r, scratch.robot, t.link)) {
      ++r.counts.certain_contacts;
      return true;
    }
    if (environment.linkHits(t, links.links[t.slot].voxels, X_WL, path, scratch.fused)) {
      r.uncertain_links.push_back(t.link);
    }
  }
  return false;
}

// The octree's pass over the self half: true on a certain contact, else the checked pairs
// whose voxels meet in r.uncertain_pairs.
bool selfOctreePass(const CollisionModelParts& parts, const RefineData& data, RefineScratch& r,
                    CheckerPath path, CheckScratch& scratch) {
  using Verdict = SelfCollision::ExactVerdict;
  const LinkModels& links = parts.links;
  const std::vector<SelfPair>& pairs = parts.self.pairs;
  r.uncertain_pairs.clear();
  r.pair_directions.resize(pairs.size(), Eigen::Vector3d::Zero());
  r.pair_verdicts.resize(pairs.size());
  return parts.self.confirmedInCollision(
      links, path, scratch,
      [&](std::size_t i) {
        const int a = links.links[pairs[i].a].link, b = links.links[pairs[i].b].link;
        RecentOutcomes& seen = r.pair_verdicts[i];
        // A pair mostly in contact lately: its hulls would not be apart.
        const bool contact_first = seen.secondLeads();
        if (contact_first && certainPairContact(data, scratch.robot, a, b)) {
          seen.add(true);
          ++r.counts.certain_self_contacts;
          return Verdict::kContact;
        }
        if (refineHullsApart(data, scratch.robot, a, b, r.pair_directions[i])) {
          seen.add(false);
          ++r.counts.hull_apart_pairs;
          return Verdict::kFree;
        }
        if (!contact_first && certainPairContact(data, scratch.robot, a, b)) {
          seen.add(true);
          ++r.counts.certain_self_contacts;
          return Verdict::kContact;
        }
        return Verdict::kUnknown;
      },
      [&](const SelfPair& p) {
        r.uncertain_pairs.emplace_back(links.links[p.a].link, links.links[p.b].link);
        return false;
      });
}

double refineEnvironmentDistance(const RefineData& data, RefineScratch& r, const RobotData& robot) {
  for (std::size_t link = 0; link < data.link_elements.size(); ++link) {
    refinePoseLink(data, r, robot, static_cast<int>(link));
  }
  const fcl_internal::RobotScratch& s = r.fcl;
  double best = std::numeric_limits<double>::infinity();
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  for (const fcl::CollisionObjectd& element : s.objects) {
    for (const RefineObject& object : data.objects) {
      if (object.shapes.empty() || object.box_W.distance(element.getAABB()) >= best) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        if (shape.getAABB().distance(element.getAABB()) >= best) continue;
        result.clear();
        fcl::distance(&element, &shape, request, result);
        best = std::min(best, std::max(0.0, result.min_distance));
        if (best <= 0) return 0;
      }
    }
  }
  return best;
}

}  // namespace detail

bool OctreeCollisionModel::refinedEnvironmentInCollision(CheckerPath path,
                                                         CheckScratch& scratch) const {
  detail::RefineScratch& r = detail::refineScratch(*refine_, robot_, id_, scratch.refine);
  return detail::environmentOctreePass(*parts_, *refine_, r, path, scratch) ||
         detail::refineUncertainLinksHit(*refine_, r, scratch.robot);
}

bool OctreeCollisionModel::refinedSelfInCollision(CheckerPath path, CheckScratch& scratch) const {
  detail::RefineScratch& r = detail::refineScratch(*refine_, robot_, id_, scratch.refine);
  return detail::selfOctreePass(*parts_, *refine_, r, path, scratch) ||
         detail::refineUncertainPairsHit(*refine_, r, scratch.robot);
}

// The two halves in one query, so a link's FCL objects are posed once. FCL runs after both
// octree passes found no certain contact, the environment's links before the self pairs. The
// half that recently found more contacts makes its octree pass first (RecentOutcomes): a
// certain contact there spares the other half's pass. Every test is sound, so the order changes
// the time, not the answer.
bool OctreeCollisionModel::refinedLinksInCollision(CheckerPath path, CheckScratch& scratch) const {
  detail::RefineScratch& r = detail::refineScratch(*refine_, robot_, id_, scratch.refine);
  auto found = [&](bool in_self) {
    r.half_contacts.add(in_self);
    return true;
  };
  if (r.half_contacts.secondLeads()) {
    if (detail::selfOctreePass(*parts_, *refine_, r, path, scratch)) return found(true);
    if (detail::environmentOctreePass(*parts_, *refine_, r, path, scratch)) return found(false);
  } else {
    if (detail::environmentOctreePass(*parts_, *refine_, r, path, scratch)) return found(false);
    // The environment's FCL tests before the self pass: a contact FCL finds there spares it.
    if (detail::refineUncertainLinksHit(*refine_, r, scratch.robot)) return found(false);
    r.uncertain_links.clear();
    if (detail::selfOctreePass(*parts_, *refine_, r, path, scratch)) return found(true);
  }
  if (detail::refineUncertainLinksHit(*refine_, r, scratch.robot)) return found(false);
  if (detail::refineUncertainPairsHit(*refine_, r, scratch.robot)) return found(true);
  return false;
}

RefineCounts OctreeCollisionModel::refineCounts(const CheckScratch& scratch) const {
  const detail::RefineScratch* r = scratch.refine.get();
  return r != nullptr && r->owner == id_ ? r->counts : RefineCounts{};
}

double OctreeCollisionModel::refinedClearance(const CheckScratch& scratch, double margin) const {
  const double bound = options_.clearance == ClearanceMethod::kPointOctree
                           ? clearanceLowerBoundPoints(scratch)
                           : clearanceLowerBoundTree(scratch);
  if (!refine_ || bound >= margin) return bound;
  return detail::refineEnvironmentDistance(
      *refine_, detail::refineScratch(*refine_, robot_, id_, scratch.refine), scratch.robot);
}

}  // namespace octomotion
