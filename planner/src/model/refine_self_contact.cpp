// RefineMode::kExact's certain self contacts (internal/refine.h), element by element as FCL
// tests them. Two closed meshes are in contact for FCL when a point of one's surface (a vertex,
// or a point of a long edge) lies kCertainDepth inside the other and one of its vertices
// kCertainDepth outside: the first's surface is connected and has points on both sides of the
// second's, so the two surfaces cross, and FCL's mesh test (triangle against triangle) reports
// the crossing. A primitive is a solid for FCL: a point of a mesh's surface (on a triangle FCL
// tests) kCertainDepth inside it is a contact, so is a closed mesh crossing it
// (closedMeshCrossesPrimitive) or another primitive overlapping it (primitivesOverlap). Such a
// pair needs neither its voxels nor FCL, and the check stops there.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <utility>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "internal/refine.h"

namespace octomotion::detail {

namespace {

// A link's mesh in L with each vertex once, and its triangles over them; empty unless the link
// is one mesh element.
struct IndexedMesh {
  std::vector<Eigen::Vector3d> vertices_L;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

IndexedMesh indexedMesh(const fcl::CollisionGeometryd& geometry, const Eigen::Isometry3d& X_LE) {
  IndexedMesh out;
  if (geometry.getObjectType() != fcl::OT_BVH) return out;
  const auto* mesh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(&geometry);
  if (mesh == nullptr || mesh->vertices == nullptr || mesh->tri_indices == nullptr) return out;
  std::map<std::array<double, 3>, std::uint32_t> index;
  for (int t = 0; t < mesh->num_tris; ++t) {
    std::array<std::uint32_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p_L = X_LE * mesh->vertices[mesh->tri_indices[t][k]];
      const auto [it, added] = index.emplace(std::array<double, 3>{p_L.x(), p_L.y(), p_L.z()},
                                             static_cast<std::uint32_t>(out.vertices_L.size()));
      if (added) out.vertices_L.push_back(p_L);
      triangle[static_cast<std::size_t>(k)] = it->second;
    }
    out.triangles.push_back(triangle);
  }
  return out;
}

// Every edge in exactly two triangles (a closed surface) and every triangle reachable from the
// first across edges (one surface).
bool closedAndConnected(const IndexedMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t i = mesh.triangles[t][k], j = mesh.triangles[t][(k + 1) % 3];
      if (i == j) return false;
      edges[{std::min(i, j), std::max(i, j)}].push_back(t);
    }
  }
  std::vector<std::size_t> parent(mesh.triangles.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&](std::size_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  for (const auto& [edge, triangles] : edges) {
    if (triangles.size() != 2) return false;
    parent[root(triangles[0])] = root(triangles[1]);
  }
  for (std::size_t t = 0; t < parent.size(); ++t) {
    if (root(t) != root(0)) return false;
  }
  return true;
}

// The mesh's face planes with outward normals (n . p <= d inside each), when the triangles'
// windings agree (each directed edge once) and enclose a positive volume (flipped when
// negative); empty for a mesh with a triangle without area.
std::vector<Eigen::Vector4d> outwardPlanes(const IndexedMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::vector<Eigen::Vector4d> planes;
  double volume6 = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices_L[t[0]], &b = mesh.vertices_L[t[1]],
                          &c = mesh.vertices_L[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 1e-12)) return {};
    volume6 += a.dot(b.cross(c));
    n.normalize();
    planes.emplace_back(n.x(), n.y(), n.z(), n.dot(a));
    for (std::size_t k = 0; k < 3; ++k) {
      if (++directed[{t[k], t[(k + 1) % 3]}] != 1) return {};
    }
  }
  if (!(std::abs(volume6) > 0)) return {};
  if (volume6 < 0) {
    for (Eigen::Vector4d& plane : planes) plane = -plane;
  }
  return planes;
}

// p lies kCertainDepth inside every face plane, so inside the solid: were it outside, the
// closest surface point q would have an angle-weighted pseudonormal N with N . (p - q) > 0
// (Baerentzen & Aanaes 2005), so p would lie on the outer side of a face at q.
bool deepInsidePlanes(const std::vector<Eigen::Vector4d>& planes, const Eigen::Vector3d& p) {
  for (const Eigen::Vector4d& plane : planes) {
    if (plane.head<3>().dot(p) > plane.w() - kCertainDepth) return false;
  }
  return true;
}

// deepInsidePlanes on the mesh's planes, with its boxes answering first where they can.
bool deepInsideMesh(const ClosedLinkMesh& mesh, const Eigen::Vector3d& p) {
  if (!mesh.box_L.contains(p)) return false;
  if (mesh.inner_box_L.contains(p)) return true;
  return deepInsidePlanes(mesh.planes_L, p);
}

// p lies kCertainDepth beyond the mesh's vertices along a face normal or an axis (outside the
// vertices' box), so outside its hull.
bool deepOutsideHull(const ClosedLinkMesh& mesh, const Eigen::Vector3d& p) {
  if ((mesh.box_L.min() - p).maxCoeff() >= kCertainDepth ||
      (p - mesh.box_L.max()).maxCoeff() >= kCertainDepth) {
    return true;
  }
  if (mesh.inner_box_L.contains(p)) return false;
  for (std::size_t f = 0; f < mesh.planes_L.size(); ++f) {
    if (mesh.planes_L[f].head<3>().dot(p) >= mesh.supports_L[f] + kCertainDepth) return true;
  }
  return false;
}

// The mesh's vertex nearest p (farthest from p when `farthest`), by its clusters: the one whose
// centre is nearest (farthest) first, then only those that may hold a nearer (farther) vertex.
const Eigen::Vector3d& extremeVertex(const ClosedLinkMesh& mesh, const Eigen::Vector3d& p,
                                     bool farthest) {
  const double sign = farthest ? -1 : 1;
  std::size_t start = 0;
  double start_key = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < mesh.clusters.size(); ++k) {
    const double key = sign * (mesh.clusters[k].centre - p).squaredNorm();
    if (key < start_key) {
      start_key = key;
      start = k;
    }
  }
  std::size_t best = 0;
  double best2 = farthest ? -1 : std::numeric_limits<double>::infinity();
  auto scan = [&](const PointCluster& c) {
    for (std::uint32_t i = c.begin; i < c.end; ++i) {
      const double d2 = (mesh.vertices_L[i] - p).squaredNorm();
      if (farthest ? d2 > best2 : d2 < best2) {
        best2 = d2;
        best = i;
      }
    }
  };
  scan(mesh.clusters[start]);
  for (std::size_t k = 0; k < mesh.clusters.size(); ++k) {
    if (k == start) continue;
    const PointCluster& c = mesh.clusters[k];
    const double centre2 = (c.centre - p).squaredNorm();
    const double best_distance = std::sqrt(best2);
    // Every vertex of c lies within [|centre - p| - radius, |centre - p| + radius] of p.
    if (farthest) {
      const double reach = best_distance - c.radius;
      if (reach > 0 && centre2 < reach * reach) continue;
    } else {
      const double reach = best_distance + c.radius;
      if (centre2 > reach * reach) continue;
    }
    scan(c);
  }
  return mesh.vertices_L[best];
}

// The point of the mesh's long edges nearest p (in L): a point of its surface; p itself when
// it has none.
Eigen::Vector3d nearestOnLongEdges(const ClosedLinkMesh& mesh, const Eigen::Vector3d& p) {
  Eigen::Vector3d best = p;
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < mesh.edge_start_L.size(); ++i) {
    const Eigen::Vector3d& a = mesh.edge_start_L[i];
    const Eigen::Vector3d& d = mesh.edge_span_L[i];
    const double s = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector3d x = a + s * d;
    const double d2 = (x - p).squaredNorm();
    if (d2 < best2) {
      best2 = d2;
      best = x;
    }
  }
  return best;
}

// A point of `mover`'s surface (placed in `other`'s frame by X_OM) deep inside `other` and one
// deep outside: mover's surface is connected, so it crosses other's, and two of their triangles
// meet. The inside candidates are mover's vertex nearest other's centroid, then the nearest
// point of its long edges; the outside one its vertex farthest from the centroid.
bool crosses(const ClosedLinkMesh& mover, const ClosedLinkMesh& other,
             const Eigen::Isometry3d& X_OM) {
  const Eigen::Vector3d c_M = X_OM.inverse() * other.centroid_L;
  if (!deepInsideMesh(other, X_OM * extremeVertex(mover, c_M, false)) &&
      (mover.edge_start_L.empty() ||
       !deepInsideMesh(other, X_OM * nearestOnLongEdges(mover, c_M)))) {
    return false;
  }
  return deepOutsideHull(other, X_OM * extremeVertex(mover, c_M, true));
}

// The mesh's longest edges into mesh.edge_*_L (ClosedLinkMesh::kLongEdges).
void longEdges(const IndexedMesh& indexed, ClosedLinkMesh& mesh) {
  const double shortest = mesh.box_L.diagonal().norm() / 3;
  std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> edges;
  for (const auto& t : indexed.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3];
      if (i > j) continue;  // each edge once: its two triangles run it in opposite directions
      const double length = (indexed.vertices_L[j] - indexed.vertices_L[i]).norm();
      if (length >= shortest) edges.push_back({length, {i, j}});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x > y; });
  edges.resize(std::min(edges.size(), ClosedLinkMesh::kLongEdges));
  for (const auto& [length, edge] : edges) {
    mesh.edge_start_L.push_back(indexed.vertices_L[edge.first]);
    mesh.edge_span_L.push_back(indexed.vertices_L[edge.second] - indexed.vertices_L[edge.first]);
  }
}

// Clusters the vertices (at most kClusterVertices each), reordering them so each cluster is
// contiguous.
constexpr std::size_t kClusterVertices = 16;
void clusterVertices(ClosedLinkMesh& mesh) {
  std::vector<std::uint32_t> order;
  mesh.clusters = clusterPoints(mesh.vertices_L, kClusterVertices, order);
  std::vector<Eigen::Vector3d> reordered;
  reordered.reserve(order.size());
  for (std::uint32_t i : order) reordered.push_back(mesh.vertices_L[i]);
  mesh.vertices_L = std::move(reordered);
}

// The primitive's solid shrunk by kCertainDepth (its points at least that deep), or nothing when
// it is thinner.
std::optional<Primitive> deepCore(const Primitive& shape) {
  if (const auto* box = std::get_if<Box>(&shape)) {
    const Eigen::Vector3d half = box->half_extents.array() - kCertainDepth;
    if (!(half.minCoeff() > 0)) return std::nullopt;
    return Box{half};
  }
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    if (!(ball->radius > kCertainDepth)) return std::nullopt;
    return Sphere{ball->radius - kCertainDepth};
  }
  const auto& c = std::get<Cylinder>(shape);
  if (!(c.radius > kCertainDepth && c.length > 2 * kCertainDepth)) return std::nullopt;
  return Cylinder{c.radius - kCertainDepth, c.length - 2 * kCertainDepth};
}

// The point of the primitive's solid nearest p_P (both in its frame P).
Eigen::Vector3d closestPoint(const Primitive& shape, const Eigen::Vector3d& p_P) {
  if (const auto* box = std::get_if<Box>(&shape)) {
    return p_P.cwiseMax(-box->half_extents).cwiseMin(box->half_extents);
  }
  if (const auto* ball = std::get_if<Sphere>(&shape)) {
    const double norm = p_P.norm();
    return norm > ball->radius ? Eigen::Vector3d(p_P * (ball->radius / norm)) : p_P;
  }
  const auto& c = std::get<Cylinder>(shape);
  Eigen::Vector3d q = p_P;
  q.z() = std::clamp(q.z(), -c.length / 2, c.length / 2);
  const double radial = q.head<2>().norm();
  if (radial > c.radius) q.head<2>() *= c.radius / radial;
  return q;
}

// The vertices' box shrunk about the centroid until its corners, so all its points (the region
// inside every face plane is convex), lie kCertainDepth inside every face plane; empty when the
// centroid does not.
Eigen::AlignedBox3d innerBox(const ClosedLinkMesh& mesh) {
  const Eigen::Vector3d c = mesh.centroid_L;
  auto boxAt = [&](double scale) {
    return Eigen::AlignedBox3d(c + scale * (mesh.box_L.min() - c),
                               c + scale * (mesh.box_L.max() - c));
  };
  auto inside = [&](const Eigen::AlignedBox3d& box) {
    for (int k = 0; k < 8; ++k) {
      if (!deepInsidePlanes(mesh.planes_L,
                            box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)))) {
        return false;
      }
    }
    return true;
  };
  if (!deepInsidePlanes(mesh.planes_L, c)) return {};
  double in = 0, out = 1;
  if (inside(boxAt(out))) return boxAt(out);
  for (int i = 0; i < 30; ++i) {
    const double middle = (in + out) / 2;
    (inside(boxAt(middle)) ? in : out) = middle;
  }
  return boxAt(in);
}

}  // namespace

DeepPoints deepPoints(const Primitive& shape) {
  DeepPoints out;
  out.core = deepCore(shape);
  if (!out.core) return out;
  std::vector<Eigen::Vector3d>& points = out.points;
  points.push_back(Eigen::Vector3d::Zero());
  if (const auto* box = std::get_if<Box>(&*out.core)) {
    const std::array<Eigen::Vector3d, 8> corners = boxCorners(box->half_extents);
    points.insert(points.end(), corners.begin(), corners.end());
  } else if (const auto* ball = std::get_if<Sphere>(&*out.core)) {
    for (int axis = 0; axis < 3; ++axis) {
      points.push_back(ball->radius * Eigen::Vector3d::Unit(axis));
      points.push_back(-ball->radius * Eigen::Vector3d::Unit(axis));
    }
  } else {
    const auto& c = std::get<Cylinder>(*out.core);
    for (int k = 0; k < 8; ++k) {
      const double angle = k * M_PI / 4;
      for (const double z : {-c.length / 2, c.length / 2}) {
        points.emplace_back(c.radius * std::cos(angle), c.radius * std::sin(angle), z);
      }
    }
  }
  return out;
}

bool primitivesOverlap(const Primitive& a, const DeepPoints& deep_a, const Primitive& b,
                       const DeepPoints& deep_b, const Eigen::Isometry3d& X_AB) {
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  // Each centre deep in the other, then each core's point nearest the other's centre.
  if (deepInside(b, X_BA.translation()) || deepInside(a, X_AB.translation())) return true;
  if (!deep_a.core || !deep_b.core) return false;
  return deepInside(b, X_BA * closestPoint(*deep_a.core, X_AB.translation())) ||
         deepInside(a, X_AB * closestPoint(*deep_b.core, X_BA.translation()));
}

bool closedMeshCrossesPrimitive(const ClosedLinkMesh& mesh, const DeepPoints& deep,
                                const Eigen::Isometry3d& X_PM) {
  if (!deep.core) return false;
  const Eigen::Isometry3d X_MP = X_PM.inverse();
  const Eigen::Vector3d q_M = X_MP * closestPoint(*deep.core, X_PM * mesh.centroid_L);
  if (!deepInsideMesh(mesh, q_M)) return false;
  for (const Eigen::Vector3d& p_P : deep.points) {
    if (deepOutsideHull(mesh, X_MP * p_P)) return true;
  }
  return false;
}

std::vector<SelfContactElement> selfContactElements(
    const fcl_internal::RobotGeometry& robot, const RobotModel& model,
    const std::vector<std::vector<std::size_t>>& link_elements) {
  fcl_internal::RobotScratch prototypes;
  robot.initScratch(model, prototypes);
  std::vector<SelfContactElement> elements(robot.elementCount());
  for (std::size_t l = 0; l < link_elements.size(); ++l) {
    const std::vector<CollisionElement>& collision = model.link(static_cast<int>(l)).collision;
    // RobotGeometry makes one element per collision element, in order.
    if (link_elements[l].size() != collision.size()) continue;
    for (std::size_t k = 0; k < collision.size(); ++k) {
      const std::size_t e = link_elements[l][k];
      SelfContactElement& out = elements[e];
      const Eigen::Isometry3d& X_LE = collision[k].X_LE;
      if (const auto* primitive = std::get_if<Primitive>(&collision[k].geometry)) {
        out.primitive = *primitive;
        out.X_EL = X_LE.inverse();
        out.deep_E = deepPoints(*primitive);
        continue;
      }
      const IndexedMesh mesh = indexedMesh(*prototypes.objects[e].collisionGeometry(), X_LE);
      out.points_L = mesh.vertices_L;
      if (mesh.vertices_L.size() < 4 || !closedAndConnected(mesh)) continue;
      ClosedLinkMesh& closed = out.mesh;
      closed.planes_L = outwardPlanes(mesh);
      if (closed.planes_L.empty()) continue;
      closed.vertices_L = mesh.vertices_L;
      for (const Eigen::Vector3d& v : mesh.vertices_L) closed.centroid_L += v;
      closed.centroid_L /= static_cast<double>(mesh.vertices_L.size());
      for (const Eigen::Vector4d& plane : closed.planes_L) {
        double support = -std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& v : mesh.vertices_L) {
          support = std::max(support, plane.head<3>().dot(v));
        }
        closed.supports_L.push_back(support);
      }
      for (const Eigen::Vector3d& v : mesh.vertices_L) closed.box_L.extend(v);
      closed.inner_box_L = innerBox(closed);
      longEdges(mesh, closed);
      clusterVertices(closed);
    }
  }
  return elements;
}

namespace {

// The point of `element` nearest `primitive`'s centre (its vertex, or a point of a closed mesh's
// long edges) lies deep inside its solid. X_PL_EL takes the element's link frame to the
// primitive's.
bool pointInside(const SelfContactElement& element, const SelfContactElement& primitive,
                 const Eigen::Isometry3d& X_PL_EL) {
  if (element.points_L.empty()) return false;
  const Eigen::Isometry3d X_PE = primitive.X_EL * X_PL_EL;  // element's L to the primitive's E
  const Eigen::Vector3d c_L = X_PE.inverse().translation();
  // A closed mesh's vertices are its points, in clusters; its long edges' points are on its
  // surface too.
  if (!element.mesh.empty()) {
    const ClosedLinkMesh& mesh = element.mesh;
    return deepInside(*primitive.primitive, X_PE * extremeVertex(mesh, c_L, false)) ||
           (!mesh.edge_start_L.empty() &&
            deepInside(*primitive.primitive, X_PE * nearestOnLongEdges(mesh, c_L)));
  }
  std::size_t nearest = 0;
  double near2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < element.points_L.size(); ++i) {
    const double d2 = (element.points_L[i] - c_L).squaredNorm();
    if (d2 < near2) {
      near2 = d2;
      nearest = i;
    }
  }
  return deepInside(*primitive.primitive, X_PE * element.points_L[nearest]);
}

}  // namespace

bool certainPairContact(const RefineData& data, const RobotData& robot, int link_a, int link_b) {
  const std::vector<std::size_t>& elements_a = data.link_elements[static_cast<std::size_t>(link_a)];
  const std::vector<std::size_t>& elements_b = data.link_elements[static_cast<std::size_t>(link_b)];
  const Eigen::Isometry3d X_AB = robot.linkPose(link_a).inverse() * robot.linkPose(link_b);
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  for (std::size_t ea : elements_a) {
    const SelfContactElement& a = data.self_elements[ea];
    for (std::size_t eb : elements_b) {
      const SelfContactElement& b = data.self_elements[eb];
      if (!a.mesh.empty() && !b.mesh.empty() &&
          (crosses(b.mesh, a.mesh, X_AB) || crosses(a.mesh, b.mesh, X_BA))) {
        return true;
      }
      if (a.primitive && b.primitive) {
        if (primitivesOverlap(*a.primitive, a.deep_E, *b.primitive, b.deep_E,
                              a.X_EL * X_AB * b.X_EL.inverse())) {
          return true;
        }
        continue;
      }
      if (b.primitive &&
          (pointInside(a, b, X_BA) ||
           (!a.mesh.empty() && closedMeshCrossesPrimitive(a.mesh, b.deep_E, b.X_EL * X_BA)))) {
        return true;
      }
      if (a.primitive &&
          (pointInside(b, a, X_AB) ||
           (!b.mesh.empty() && closedMeshCrossesPrimitive(b.mesh, a.deep_E, a.X_EL * X_AB)))) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace octomotion::detail
